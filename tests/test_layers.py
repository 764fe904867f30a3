"""No import cycles: every import counts, at module level, inside a function or under
``TYPE_CHECKING``, and so does an import by name (``importlib.import_module("rollspring.x")``,
``__import__``; an f-string counts as every module its literal prefix names), so a cycle cannot
hide behind a deferred or a string import. Only the composition root (``rollspring/__init__.py``)
imports rollspring's modules by name at all.

import-linter (tests/test_architecture.py) checks the layers between subpackages; this checks
the modules within them, e.g. inside :mod:`rollspring.analysis`: ``conventions`` (the sign
conventions) <- ``linear`` (equilibrium, modes, the result type and its JSON form) <- ``checks``
<- ``modal`` (``analyze``).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tests.code_reading import called_name

SRC = Path(__file__).resolve().parents[1] / "src"


#: The functions that import a module named by a string.
_BY_NAME = ("import_module", "__import__")


def imported_by_name(call: ast.Call) -> tuple[str, bool] | None:
    """What a call of ``importlib.import_module``/``import_module``/``__import__`` imports:
    (the name, False) for a literal; (the literal prefix, True) for an f-string that starts
    with one; None for any other call (or a name made otherwise: a variable)."""
    name = called_name(call)
    if name not in _BY_NAME or not call.args:
        return None
    argument = call.args[0]
    if isinstance(argument, ast.Constant) and isinstance(argument.value, str):
        return argument.value, False
    if isinstance(argument, ast.JoinedStr):
        prefix = ""
        for part in argument.values:
            if not (isinstance(part, ast.Constant) and isinstance(part.value, str)):
                break
            prefix += part.value
        return prefix, True
    return None


def import_graph(root: Path, package: str) -> dict[str, set[str]]:
    """Module -> the modules of ``package`` it imports (anywhere in its source): by import
    statements and by name (:func:`imported_by_name`: a literal is the module it names, an
    f-string every module whose name starts with its literal prefix)."""
    modules: dict[str, Path] = {}
    for path in (root / package.replace(".", "/")).rglob("*.py"):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        modules[".".join(parts)] = path

    def resolve(name: str) -> str | None:
        """The module that holds ``name`` (a module, or a name defined in one)."""
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        here = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        imported: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                source = node.module or ""
                if node.level:
                    anchor = here[: len(here) - node.level + 1]
                    source = ".".join([*anchor, source] if source else anchor)
                # ``from a import b``: the submodule a.b if there is one, else the module a
                targets = [
                    f"{source}.{alias.name}" if f"{source}.{alias.name}" in modules else source
                    for alias in node.names
                ]
            elif isinstance(node, ast.Call) and (by_name := imported_by_name(node)):
                text, is_prefix = by_name
                targets = (
                    [m for m in modules if text and m.startswith(text)] if is_prefix else [text]
                )
            else:
                continue
            imported |= {target for t in targets if (target := resolve(t)) not in (None, name)}
        graph[name] = imported
    return graph


def import_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(module: str) -> None:
        index[module] = low[module] = len(index)
        stack.append(module)
        on_stack.add(module)
        for other in sorted(graph[module]):
            if other not in index:
                visit(other)
                low[module] = min(low[module], low[other])
            elif other in on_stack:
                low[module] = min(low[module], index[other])
        if low[module] == index[module]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == module:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    return found


@pytest.mark.parametrize("package", ["rollspring.analysis", "rollspring"])
def test_no_import_cycles(package: str) -> None:
    graph = import_graph(SRC, package)
    assert len(graph) > 10
    assert not import_cycles(graph), "\n".join(
        " <-> ".join(cycle) for cycle in import_cycles(graph)
    )


def test_the_analysis_modules_build_one_way() -> None:
    graph = import_graph(SRC, "rollspring.analysis")
    assert graph["rollspring.analysis.conventions"] == set()
    assert graph["rollspring.analysis.banded"] == set()  # sparse linear algebra: a leaf
    assert graph["rollspring.analysis.linear"] == {
        "rollspring.analysis.banded",
        "rollspring.analysis.conventions",
    }
    assert graph["rollspring.analysis.checks"] == {"rollspring.analysis.linear"}
    assert graph["rollspring.analysis.costs"] == set()  # the cost guard: a leaf
    assert graph["rollspring.analysis.modal"] == {
        "rollspring.analysis.banded",
        "rollspring.analysis.checks",
        "rollspring.analysis.costs",
        "rollspring.analysis.linear",
    }


def test_deferred_imports_count(tmp_path: Path) -> None:
    """A cycle through an import inside a function or under TYPE_CHECKING is found."""
    package = tmp_path / "pkg"
    (package / "sub").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "sub" / "__init__.py").write_text("")
    (package / "a.py").write_text("def f():\n    from pkg.b import g\n    return g\n")
    (package / "b.py").write_text("import pkg.a\n\ndef g():\n    pass\n")
    (package / "c.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .sub.d import D\n"
    )
    (package / "sub" / "d.py").write_text("from .. import c\n\nclass D:\n    pass\n")
    graph = import_graph(tmp_path, "pkg")
    assert graph["pkg.a"] == {"pkg.b"}
    assert graph["pkg.sub.d"] == {"pkg.c"}
    assert import_cycles(graph) == [["pkg.a", "pkg.b"], ["pkg.c", "pkg.sub.d"]]


def test_string_imports_count(tmp_path: Path) -> None:
    """A cycle through ``importlib.import_module`` or ``__import__`` of a literal name, or of an
    f-string (every module under its literal prefix), is found: planted here, one of each."""
    package = tmp_path / "pkg"
    (package / "plugins").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "plugins" / "__init__.py").write_text("")
    # a literal, through importlib
    (package / "a.py").write_text(
        "import importlib\n\ndef f():\n    return importlib.import_module('pkg.b')\n"
    )
    (package / "b.py").write_text("from pkg import a\n")
    # an f-string: every module under pkg.plugins.
    (package / "c.py").write_text(
        "from importlib import import_module\n\n"
        "def load(name):\n    return import_module(f'pkg.plugins.{name}')\n"
    )
    (package / "plugins" / "d.py").write_text("def g():\n    from pkg.c import load\n")
    (package / "plugins" / "e.py").write_text("X = 1\n")
    # __import__ of a literal
    (package / "f.py").write_text("def h():\n    return __import__('pkg.g')\n")
    (package / "g.py").write_text("import pkg.f\n")
    # a name that is not known before run time: no edge (the test below forbids these)
    (package / "h.py").write_text("import importlib\n\ndef k(x):\n    importlib.import_module(x)\n")
    graph = import_graph(tmp_path, "pkg")
    assert graph["pkg.a"] == {"pkg.b"}
    assert graph["pkg.c"] == {"pkg.plugins.d", "pkg.plugins.e"}
    assert graph["pkg.f"] == {"pkg.g"}
    assert graph["pkg.h"] == set()
    assert import_cycles(graph) == [
        ["pkg.a", "pkg.b"],
        ["pkg.c", "pkg.plugins.d"],
        ["pkg.f", "pkg.g"],
    ]


#: The composition root: the one module that imports rollspring's modules by name (the public
#: names, loaded on first use).
COMPOSITION_ROOT = SRC / "rollspring" / "__init__.py"


def test_only_the_composition_root_imports_rollspring_modules_by_name() -> None:
    """No ``importlib.import_module``/``__import__`` of a rollspring module (a literal or
    f-string naming one, or a name made at run time, which could be one) anywhere in src but
    the package root: a module another imports is imported by an import statement, which the
    layers contract and the cycle test above see."""
    found = []
    modules = sorted((SRC / "rollspring").rglob("*.py"))
    assert len(modules) > 50
    for path in modules:
        if path == COMPOSITION_ROOT:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if not isinstance(node, ast.Call):
                continue
            by_name = imported_by_name(node)
            if by_name is None and called_name(node) not in _BY_NAME:
                continue
            text = by_name[0] if by_name is not None else None
            if text is None or text.startswith(("rollspring", ".")) or text == "":
                found.append(f"{path.relative_to(SRC)}:{node.lineno}: {ast.unparse(node)}")
    assert not found, "import these with an import statement:\n" + "\n".join(found)


def test_the_checks_see_the_commands_import_only_the_shared_cli_modules() -> None:
    """The command modules import what the commands share (rollspring.cli.common) and the
    terminal helpers, never rollspring.cli.app, which imports them all."""
    graph = import_graph(SRC, "rollspring")
    commands = {m for m in graph if m.startswith("rollspring.cli.commands.")}
    assert len(commands) >= 15
    assert graph["rollspring.cli.app"] >= commands
    for module in sorted(commands):
        assert "rollspring.cli.app" not in graph[module], module
        assert "rollspring.cli" not in graph[module], module  # its __init__ imports the app
