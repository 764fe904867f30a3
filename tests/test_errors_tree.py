"""One home for the exception tree (issue 12): every exception class rollspring defines lives in
``rollspring.errors``, its docstring draws the whole tree, and every class survives pickling
(errors cross process boundaries: the web API's workers, Dask's).
"""

from __future__ import annotations

import ast
import builtins
import importlib
import inspect
import json
import pickle
import re
import subprocess
import sys
from pathlib import Path

import pytest

from rollspring import errors

SRC = Path(errors.__file__).resolve().parent
ERRORS_PY = SRC / "errors.py"

#: the classes of the tree: the exception classes rollspring.errors exports
TREE = {
    name: value
    for name in errors.__all__
    if isinstance(value := getattr(errors, name), type) and issubclass(value, BaseException)
}

#: where each class used to be defined, and stays importable from (tests and users import it there)
OLD_HOMES = {
    "rollspring.web.workers": ["Overloaded", "OverBudget", "JobFailed"],
    "rollspring.outputs.report._html": ["ReportError", "MathConversionError"],
    "rollspring.outputs.report": ["ReportError", "MathConversionError"],
    "rollspring.outputs.animation": ["AnimationError"],
    "rollspring.outputs.maps": ["MapError"],
    "rollspring.outputs.mjcf": ["ExportError"],
    "rollspring.outputs.worksheet": ["WorksheetError"],
    "rollspring.cli.commands.sweep_plot": ["SweepPlotError"],
    "rollspring.cli.commands.paper_check": ["PaperCheckError"],
    "rollspring.cli.commands.worksheet": ["WorksheetOptionError"],
    "rollspring.cli.commands.serve": ["ServeError"],
    "rollspring.service.sweeps.grid": ["SweepError"],
    "rollspring.service.sweeps.store": ["StoreMismatchError"],
    "rollspring.service.sweeps": ["SweepError", "StoreMismatchError"],
    "rollspring.analysis.derivation.derive": ["DerivationError"],
    "rollspring.analysis.derivation": ["DerivationError"],
    "rollspring.analysis.derivation.frequencies": ["BudgetExceeded"],
}

#: constructor arguments of the classes that do not take a single message
ARGUMENTS: dict[str, tuple[object, ...]] = {
    "MissingExtraError": ("rollspring report", ("plot", "symbolic")),
    "JobFailed": ("invalid", "duration: must be positive", ("body", "duration")),
}


# ------------------------------------------------------------------------ (a) one home


def _builtin_exceptions() -> set[str]:
    return {
        name
        for name, value in vars(builtins).items()
        if isinstance(value, type) and issubclass(value, BaseException)
    }


def _exception_bases(node: ast.ClassDef, exceptions: set[str]) -> list[str]:
    """The bases of ``node`` that name an exception (``Exception``, ``errors.ModelError``, any
    name ending in Error/Exception/Warning)."""
    names = []
    for base in node.bases:
        name = ast.unparse(base).rpartition(".")[2]
        if name in exceptions or name.endswith(("Error", "Exception", "Warning")):
            names.append(name)
    return names


def _exception_classes(path: Path, exceptions: set[str]) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    return [
        node.name
        for node in ast.walk(tree)
        if isinstance(node, ast.ClassDef) and _exception_bases(node, exceptions)
    ]


def test_no_exception_class_is_defined_outside_errors_py() -> None:
    exceptions = _builtin_exceptions() | set(TREE)
    modules = sorted(SRC.rglob("*.py"))
    assert len(modules) > 50  # the scan sees the whole package
    elsewhere = {
        str(path.relative_to(SRC)): found
        for path in modules
        if path != ERRORS_PY and (found := _exception_classes(path, exceptions))
    }
    assert elsewhere == {}, f"move these to rollspring/errors.py: {elsewhere}"


def test_the_scan_finds_every_class_of_errors_py() -> None:
    """The detector of the test above sees exactly the tree in errors.py (it is not blind)."""
    found = _exception_classes(ERRORS_PY, _builtin_exceptions() | set(TREE))
    assert sorted(found) == sorted(TREE)
    assert len(TREE) >= 24  # 6 before issue 12, 17 moved in, WebError


def test_all_lists_every_exception_class_of_the_module() -> None:
    defined = {
        name
        for name, value in vars(errors).items()
        if inspect.isclass(value)
        and issubclass(value, BaseException)
        and value.__module__ == errors.__name__
    }
    assert defined == set(TREE)
    assert {"EXTRAS", "require_extra"} <= set(errors.__all__)
    assert all(hasattr(errors, name) for name in errors.__all__)


@pytest.mark.parametrize("module", sorted(OLD_HOMES))
def test_the_old_homes_still_export_the_same_classes(module: str) -> None:
    try:
        imported = importlib.import_module(module)
    except ModuleNotFoundError as exc:  # an optional extra that is not installed
        if (exc.name or "").startswith("rollspring"):
            raise
        pytest.skip(str(exc))
    for name in OLD_HOMES[module]:
        assert getattr(imported, name) is TREE[name], f"{module}.{name}"
        if hasattr(imported, "__all__"):
            assert name in imported.__all__, f"{module}.__all__ lacks {name}"


def test_errors_stays_the_lowest_layer() -> None:
    """errors.py imports nothing from rollspring and nothing heavy."""
    tree = ast.parse(ERRORS_PY.read_text(encoding="utf-8"))
    imported = {
        alias.name
        for node in ast.walk(tree)
        if isinstance(node, ast.Import)
        for alias in node.names
    } | {node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    assert not {name for name in imported if name.partition(".")[0] == "rollspring"}
    assert imported <= {"__future__", "importlib.util"}
    code = (
        "import sys, json; before = set(sys.modules); import rollspring.errors; "
        "print(json.dumps(sorted(set(sys.modules) - before)))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    # the package root (the composition root) also fills the presenters' registry, a module that
    # imports nothing
    allowed = {"rollspring", "rollspring.errors", "rollspring.presenters", "__future__"}
    assert set(json.loads(done.stdout)) <= allowed


# ---------------------------------------------------------------- (b) the docstring's tree


def _drawn_tree() -> list[tuple[int, str, str]]:
    """The docstring's diagram: ``(depth, class name, meaning)`` per class line, in order."""
    doc = errors.__doc__ or ""
    block = doc.partition("::\n")[2]
    rows = []
    for line in block.splitlines():
        if line and not line.startswith("    "):  # the end of the indented literal block
            break
        match = re.match(r"^    ([│├└─ ]*)([A-Z]\w*)(.*)$", line)
        if match:
            prefix, name, meaning = match.groups()
            assert len(prefix) % 4 == 0, line
            rows.append((len(prefix) // 4, name, meaning.strip()))
    return rows


def test_the_docstring_tree_draws_every_class_once_with_its_meaning() -> None:
    rows = _drawn_tree()
    names = [name for _, name, _ in rows]
    assert len(names) == len(set(names)), "a class drawn twice"
    assert set(names) == set(TREE), (
        f"missing from the tree: {sorted(set(TREE) - set(names))}; "
        f"drawn but not in errors.__all__: {sorted(set(names) - set(TREE))}"
    )
    for _, name, meaning in rows:
        assert len(meaning.split()) >= 3, f"{name}: no one-line meaning"
    assert rows[0][:2] == (0, "RollspringError")


def test_the_docstring_tree_matches_the_inheritance() -> None:
    """Each class is drawn under its own parent in the tree."""
    parents: list[str] = []
    for depth, name, _ in _drawn_tree():
        del parents[depth:]
        if depth:
            parent = TREE[parents[-1]]
            in_tree = [base for base in TREE[name].__bases__ if base.__name__ in TREE]
            assert in_tree == [parent], f"{name} is drawn under {parent.__name__}"
        parents.append(name)


def test_the_docstring_groups_the_tree_by_layer() -> None:
    doc = errors.__doc__ or ""
    layers = re.findall(r"^    │ ([a-z ]+)$", doc, re.M)
    assert layers == [
        "model",
        "analysis",
        "simulate",
        "lab",
        "outputs",
        "service",
        "web",
        "cli",
        "any layer",
    ]


# ------------------------------------------------------------------ (c) one root


@pytest.mark.parametrize("name", sorted(set(TREE) - {"RollspringError"}))
def test_every_class_derives_from_rollspring_error(name: str) -> None:
    assert issubclass(TREE[name], errors.RollspringError)
    assert TREE[name] is not errors.RollspringError


def test_the_root_is_a_plain_exception() -> None:
    assert errors.RollspringError.__bases__ == (Exception,)


def test_the_classes_that_were_plain_exceptions_are_not_value_errors() -> None:
    """A ValueError handler (a library's, or the web jobs' numerical-failure branch) must not
    swallow a budget signal or turn a web failure into another answer."""
    for name in ("BudgetExceeded", "WebError", "Overloaded", "OverBudget", "JobFailed"):
        assert not issubclass(TREE[name], ValueError), name
    assert issubclass(errors.Overloaded, errors.WebError)
    assert issubclass(errors.StoreMismatchError, errors.SweepError)
    assert issubclass(errors.MathConversionError, errors.ReportError)
    assert issubclass(errors.DerivationError, errors.AnalysisError)


# ------------------------------------------------------------------ (d) pickling


def _instance(name: str) -> BaseException:
    return TREE[name](*ARGUMENTS.get(name, (f"{name}: a one-line reason",)))


@pytest.mark.parametrize("name", sorted(TREE))
def test_every_class_survives_a_pickle_round_trip(name: str) -> None:
    original = _instance(name)
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        copy = pickle.loads(pickle.dumps(original, protocol=protocol))
        assert type(copy) is type(original)
        assert str(copy) == str(original)
        assert copy.args == original.args
        assert vars(copy) == vars(original)


def test_a_pickled_job_failure_keeps_its_fields() -> None:
    failure = errors.JobFailed("invalid", "rtol: must be positive", ("body", "rtol"))
    copy = pickle.loads(pickle.dumps(failure))
    assert (copy.kind, copy.message, copy.loc) == (
        "invalid",
        "rtol: must be positive",
        ("body", "rtol"),
    )
    assert str(copy) == "rtol: must be positive"
    assert repr(copy) == (
        "JobFailed(kind='invalid', message='rtol: must be positive', loc=('body', 'rtol'))"
    )
    assert errors.JobFailed("crash", "died").loc == ()


def test_a_pickled_missing_extra_keeps_its_message_and_extras() -> None:
    missing = errors.MissingExtraError("rollspring report", ("report",))
    copy = pickle.loads(pickle.dumps(missing))
    assert (copy.what, copy.extras) == ("rollspring report", ("report",))
    assert (
        str(copy) == "rollspring report needs the 'report' extra: pip install 'rollspring[report]'"
    )
    assert isinstance(copy, ImportError)
