"""No import cycles: every import counts, at module level, inside a function or under
``TYPE_CHECKING``, so a cycle cannot hide behind a deferred import.

import-linter (tests/test_architecture.py) checks the layers between subpackages; this checks
the modules within them, e.g. inside :mod:`rollspring.analysis`: ``report`` (the sign
conventions) <- ``linear`` (equilibrium, modes, the result type and its JSON form) <- ``checks``
<- ``modal`` (``analyze``).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"


def import_graph(root: Path, package: str) -> dict[str, set[str]]:
    """Module -> the modules of ``package`` it imports (anywhere in its source)."""
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
    assert graph["rollspring.analysis.report"] == set()
    assert graph["rollspring.analysis.banded"] == set()  # sparse linear algebra: a leaf
    assert graph["rollspring.analysis.linear"] == {
        "rollspring.analysis.banded",
        "rollspring.analysis.report",
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
