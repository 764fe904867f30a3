"""The model document and the documentation site's generated pages.

Every equation tag (M1)…(M23) and every section the code cites resolves in ``docs/physics.md``;
the generated API reference covers every public name and the CLI reference every command. The
site itself is built by ``make docs`` (Sphinx, warnings as errors); these checks are the fast,
deterministic part of it and need none of the documentation tools.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PHYSICS = ROOT / "docs" / "physics.md"
CITING = [ROOT / "src", ROOT / "tests", ROOT / "bench", ROOT / "README.md"]


def _sources() -> list[Path]:
    files: list[Path] = []
    for place in CITING:
        if place.is_file():
            files.append(place)
            continue
        for pattern in ("*.py", "*.js"):
            files += [p for p in place.rglob(pattern) if "node_modules" not in p.parts]
    return files


def _physics_text() -> str:
    return PHYSICS.read_text(encoding="utf-8")


def test_every_tag_is_defined_once() -> None:
    tags = re.findall(r"\\tag\{(M\d+)\}", _physics_text())
    assert sorted(tags, key=lambda t: int(t[1:])) == [f"M{n}" for n in range(1, 24)]


def test_every_cited_tag_resolves() -> None:
    defined = set(re.findall(r"\\tag\{(M\d+)\}", _physics_text()))
    cited: dict[str, list[str]] = {}
    for path in _sources():
        for tag in re.findall(r"\((M\d+)\)", path.read_text(encoding="utf-8")):
            cited.setdefault(tag, []).append(path.relative_to(ROOT).as_posix())
    assert cited, "no citations found"
    missing = {tag: sorted(set(where)) for tag, where in cited.items() if tag not in defined}
    assert not missing


def test_every_cited_section_exists() -> None:
    headings = set(re.findall(r"^#{2,3} (\d+(?:\.\d+)?)\.? ", _physics_text(), re.MULTILINE))
    pattern = re.compile(r"docs/physics\.md(?:\s+(?:section|Sec\.)\s*|\s*§\s*|\s+)(\d+(?:\.\d+)?)")
    cited: set[str] = set()
    for path in _sources():
        cited |= set(pattern.findall(path.read_text(encoding="utf-8")))
    assert cited
    assert cited <= headings, f"cited sections missing from docs/physics.md: {cited - headings}"


def _docs_extension():
    spec = importlib.util.spec_from_file_location(
        "rollspring_docs", ROOT / "docs" / "_ext" / "rollspring_docs.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_api_reference_lists_every_public_name() -> None:
    import rollspring

    page = _docs_extension().api_page()
    for name in rollspring.__all__:
        assert re.search(rf"\.\. auto\w+:: rollspring\.(\w+\.)?{name}$", page, re.MULTILINE), name


def test_cli_reference_lists_every_command() -> None:
    import typer.main

    import rollspring.cli

    command = typer.main.get_command(rollspring.cli.app)
    context = command.make_context("rollspring", [], resilient_parsing=True)
    page = _docs_extension().cli_page()
    names = command.list_commands(context)
    assert {"analyze", "simulate"} <= set(names)
    for name in names:
        assert f"## `rollspring {name}`" in page


@pytest.mark.parametrize(
    "example", sorted((ROOT / "examples").glob("*/plot_*.py")), ids=lambda p: p.name
)
def test_gallery_example_has_a_title(example: Path) -> None:
    """sphinx-gallery needs each example to open with a docstring whose first line is a title."""
    text = example.read_text(encoding="utf-8")
    match = re.match(r'r?"""\n(.+)\n(=+)\n', text)
    assert match and len(match.group(2)) >= len(match.group(1)), example.name
