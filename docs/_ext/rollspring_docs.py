"""Pages of the documentation site generated at build time from the software itself.

* ``_generated/api.rst``: the API reference, one autodoc entry for every public name in
  ``rollspring.__all__`` (a name added to ``__all__`` appears in the reference by itself).
* ``_generated/paper_check.md``: the table of the paper's claims with their verdicts, from
  ``rollspring.check_paper()``, the same records ``rollspring paper-check`` prints.
* ``_generated/cli.md``: the command-line reference, from the commands themselves
  (``typer.main.get_command(rollspring.cli.app)``): each command's help, usage, arguments and
  options with their defaults, exactly as ``rollspring COMMAND --help`` states them. (A small
  generator rather than ``sphinx-click``: Typer 0.29 builds its commands on its own copy of
  Click, which ``sphinx-click`` does not recognise as Click commands.)

Files are rewritten only when their text changes, so an unchanged page is not rebuilt.
"""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Any

import typer.main

import rollspring
import rollspring.cli

GENERATED = Path(__file__).resolve().parent.parent / "_generated"

#: Sections of the API reference: (title, one line of words, predicate on the module name).
SECTIONS: list[tuple[str, str, tuple[str, ...]]] = [
    (
        "Systems",
        "What a system is: bodies, springs, anchors, forces; files and presets.",
        ("rollspring.model",),
    ),
    (
        "Exact physics",
        "Pure vectorised functions of the system arrays and a state `q (..., n_bodies)`: "
        "positions, energies, generalised forces, contact forces, the exact stiffness matrix.",
        ("rollspring.physics",),
    ),
    (
        "Analysis",
        "Equilibrium, normal modes, the stationary point, the linear response.",
        ("rollspring.analysis.linear", "rollspring.analysis"),
    ),
    (
        "Simulation",
        "The exact nonlinear motion, single runs and batches.",
        ("rollspring.simulate",),
    ),
    (
        "The lab",
        "A real experiment's recording: a video tracked (OpenCV, the `lab` extra).",
        ("rollspring.lab",),
    ),
    (
        "Derivations, the paper check, reports and sweeps",
        "Loaded on first use (SymPy, Matplotlib, Zarr): `import rollspring` stays light.",
        (
            "rollspring.analysis.derivation",
            "rollspring.analysis.paper",
            "rollspring.service",
            "rollspring.outputs",
        ),
    ),
    ("Errors", "Every error rollspring raises on purpose.", ("rollspring.errors",)),
]


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _resolve(name: str) -> tuple[str, Any]:
    """(the dotted path autodoc documents, the object) for a public name of rollspring."""
    obj = getattr(rollspring, name)
    if inspect.ismodule(obj):  # rollspring.simulate: the subpackage, callable as simulate()
        return f"{obj.__name__}.{name}", getattr(obj, name)
    return f"rollspring.{name}", obj


def _section_of(obj: Any) -> int:
    module = getattr(obj, "__module__", "") or ""
    best, best_length = len(SECTIONS) - 1, -1
    for index, (_title, _blurb, prefixes) in enumerate(SECTIONS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best_length:
                best, best_length = index, len(prefix)
    return best


def api_page() -> str:
    """The API reference as reStructuredText: autodoc renders RST, so the page is RST too."""
    entries: dict[int, list[str]] = {i: [] for i in range(len(SECTIONS))}
    for name in sorted(rollspring.__all__, key=str.lower):
        target, obj = _resolve(name)
        if inspect.isclass(obj):
            if issubclass(obj, BaseException):
                block = f".. autoexception:: {target}\n   :no-members:\n"
            else:
                block = f".. autoclass:: {target}\n"
        else:
            block = f".. autofunction:: {target}\n"
        entries[_section_of(obj)].append(block)
    title = "API reference"
    lines = [
        title,
        "=" * len(title),
        "",
        "Every public name of the package (``rollspring.__all__``), generated from the docstrings "
        "at build time. Equation tags (M1)…(M20) refer to :doc:`the model <../physics>`; units "
        "are SI, with x to the right, y up and φ clockwise positive.",
        "",
        ".. code-block:: python",
        "",
        "   import rollspring",
        "",
    ]
    for index, (heading, words, _prefixes) in enumerate(SECTIONS):
        if not entries[index]:
            continue
        text = words.replace("`", "``")
        lines += [heading, "-" * len(heading), "", text, ""]
        lines += entries[index]
    return "\n".join(lines)


def _cell(text: str | None) -> str:
    return "" if not text else " ".join(str(text).split())


def _words(text: str | None) -> str:
    """Plain words in a Markdown cell: characters Markdown would read as markup escaped."""
    out = _cell(text)
    for char in "\\*_`[]<>|$":
        out = out.replace(char, "\\" + char)
    return out


def paper_check_page() -> str:
    from rollspring.analysis.paper import verdict_counts
    from rollspring.cli.commands.paper_check import run_text
    from rollspring.service.documents import paper_runs

    checks = rollspring.check_paper()
    runs = paper_runs(checks)
    lines = [
        "# The paper, claim by claim",
        "",
        "Every quantitative statement of G. Nyitray, *On the edge of complexity: the simplest "
        "not simple coupled mechanical system* (arXiv 2508.01379) — abstract, sections, "
        "appendices, displayed formulas, figure captions — quoted from its LaTeX source and "
        "compared by the derivation engine with what it derives from the exact model. Generated "
        "at build time from `rollspring.check_paper()` (the same records "
        "`rollspring paper-check` prints): "
        f"**{len(checks)} claims: {verdict_counts(c.verdict for c in checks)}.**",
        "",
        "Verdicts: *verified* — the paper's expression equals the derived one; *holds under the "
        "paper's stated assumption* — it holds under an assumption the paper itself states "
        "(released from rest, magnitudes, small angles, the centres level; the paper's words "
        "are quoted); *holds only if* — it holds only under a condition the paper does not state "
        "(the reason names it; a correction gives the form that holds without it); *wrong* — it "
        "does not hold, and the correction is the right expression in the paper's own terms. "
        "A *run* is a counterexample the engine simulates (the exact motion of one of the "
        "paper's systems, or a variant of it), measured against what the paper's statement "
        f"gives: {len(runs)} claims name one.",
        "",
    ]
    for check in checks:
        claim = check.claim
        lines += [
            f"* **{_words(claim.location)}** — *{check.verdict.mark} {check.verdict.words}*. "
            f"{_words(claim.statement)}: {{math}}`{_cell(claim.latex)}`",
            "",
            f"  The paper: “{_words(claim.quote)}”",
            "",
        ]
        for assumption in claim.assumptions if check.assumption else ():
            lines += [
                f"  Stated ({_words(assumption.location)}): “{_words(assumption.quote)}”",
                "",
            ]
        if check.correction:
            lines += [f"  Corrected: {{math}}`{_cell(check.correction)}`", ""]
        lines += [f"  Why: {_words(check.reason)}", ""]
        if claim.key in runs:
            lines += [f"  Run: {_words(run_text(runs[claim.key]))}", ""]
    return "\n".join(lines)


def cli_page() -> str:
    command = typer.main.get_command(rollspring.cli.app)
    root = command.make_context("rollspring", [], resilient_parsing=True)
    lines = [
        f"{_words(command.help)}",
        "",
        "```text",
        "rollspring [OPTIONS] COMMAND [ARGS]...",
        "```",
        "",
    ]
    for name in command.list_commands(root):
        sub = command.get_command(root, name)
        if sub is None or getattr(sub, "hidden", False):
            continue
        ctx = sub.make_context(name, [], parent=root, resilient_parsing=True)
        usage = " ".join(["rollspring", name, *sub.collect_usage_pieces(ctx)])
        lines += [f"## `rollspring {name}`", "", _words(sub.help), "", "```text", usage, "```", ""]
        for param in sub.get_params(ctx):
            record = param.get_help_record(ctx)
            if record is None or getattr(param, "hidden", False):
                continue
            names, text = record
            lines += [f"`{names}`", f": {_words(text) or '(no description)'}", ""]
    return "\n".join(lines)


def _generate(app: Any) -> None:
    _write(GENERATED / "api.rst", api_page())
    _write(GENERATED / "paper_check.md", paper_check_page())
    _write(GENERATED / "cli.md", cli_page())


def _rst_text(text: str) -> str:
    out = " ".join(text.split()).replace("\\", "\\\\")
    for char in "*|_":
        out = out.replace(char, "\\" + char)
    return out.replace("`", "``")  # the descriptions' Markdown code spans, as RST literals


def _is_model(obj: Any) -> bool:
    import pydantic

    return inspect.isclass(obj) and issubclass(obj, pydantic.BaseModel)


def _model_signature(
    app: Any, what: str, name: str, obj: Any, options: Any, signature: Any, return_annotation: Any
) -> tuple[str, None] | None:
    """A pydantic model's signature as its field names only (its fields are listed below it)."""
    if what == "class" and _is_model(obj):
        return "(*, " + ", ".join(obj.model_fields) + ")", None
    return None


def _model_fields(app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    """Append a pydantic model's fields with their defaults and descriptions (the system file's
    keys: the same words as ``rollspring schema``)."""
    if what != "class" or not _is_model(obj):
        return
    lines += ["", "Fields (the keys of a system file):", ""]
    for field_name, info in obj.model_fields.items():
        default = "" if info.is_required() else f" (default ``{info.default!r}``)"
        lines.append(f"* ``{field_name}``{default}: {_rst_text(info.description or '')}")
    lines.append("")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _generate)
    app.connect("autodoc-process-signature", _model_signature)
    app.connect("autodoc-process-docstring", _model_fields)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
