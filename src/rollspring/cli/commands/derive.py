"""``rollspring derive SYSTEM``: the equations of motion derived step by step (SymPy).

``--method newton|conservation|lagrange|natural-frequencies|hamilton|all`` (repeatable),
``--format text|markdown|latex``, ``--symbols`` (masses, radii, stiffnesses as symbols: the
default) or ``--numbers`` (exact numbers throughout),
``-o FILE`` (written atomically; default stdout). The command is added to an app by
:func:`register`.
"""

from __future__ import annotations

from typing import Annotated

import typer

from rollspring.cli.common import add_command, confirm_cost, load, print_text, say, write_text
from rollspring.cli.options import Formats, SystemArg, out_option, yes_option

# The derivation engine (SymPy) is imported when the command runs, not when the CLI starts.
#: The names of the methods and formats, for the help text (a test checks them against the
#: engine's METHODS, ALL and FORMATS).
METHOD_NAMES = ("newton", "conservation", "lagrange", "natural-frequencies", "hamilton", "all")
FORMAT_NAMES = Formats("text", "markdown", "latex")

__all__ = ["derive_command", "register"]


def derive_command(
    system: SystemArg,
    method: Annotated[
        list[str] | None,
        typer.Option(
            "--method",
            "-m",
            help=f"Method(s): {', '.join(METHOD_NAMES[:-1])} or {METHOD_NAMES[-1]} (repeatable).",
            show_default=False,
        ),
    ] = None,
    format: Annotated[str, FORMAT_NAMES.option("latex: a full document")] = "text",  # noqa: A002
    symbols: Annotated[
        bool,
        typer.Option(
            "--symbols/--numbers",
            help="--symbols (the default): masses, radii, stiffnesses and heights as symbols "
            "(m_1, R, k, ...), the numbers only in the notation table and in each method's "
            "final 'with your values' step; --numbers: exact numbers throughout.",
        ),
    ] = True,
    out: Annotated[
        str | None, out_option("Write to this file (atomically) instead of stdout.")
    ] = None,
    yes: Annotated[bool, yes_option("time", " (many bodies)")] = False,
) -> None:
    """Derive the equations of motion step by step by Newton, conservation laws, Lagrange,
    subsystem frequencies and Hamilton; check that they agree (symbolically)."""
    # the derivation engine itself, not rollspring.service.documents: that module brings the
    # paper's claims and the worksheets, start-up this command never uses
    from rollspring.analysis.derivation import ALL, DerivationError
    from rollspring.analysis.derivation.derive import derivation_request, run_derivation
    from rollspring.service.costs import derivation_cost

    FORMAT_NAMES.check(format, DerivationError)
    try:  # the arguments checked once, in the library; its words with the option's dashes
        request = derivation_request(method or ALL, symbols=symbols)
    except DerivationError as exc:
        raise DerivationError(f"--{exc}") from None
    if out is not None:
        from rollspring.outputs.atomic import writable_file

        writable_file(out)  # an unwritable --out fails now, not after the derivation
    model = load(system)
    confirm_cost(derivation_cost(model), yes=yes)  # estimated once: the run estimates nothing
    derivation = run_derivation(model, request)
    rendered, check = derivation.render(format), derivation.cross_check
    if out is None:
        print_text(rendered)
    else:
        write_text(out, rendered, DerivationError)
    if not check.agree:
        say(
            "warning: the methods do not all agree: "
            + "; ".join(f"{c.method}: {c.what}" for c in check.failures)
        )


def register(app: typer.Typer) -> None:
    """Add the ``derive`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, derive_command, "derive", extras="report")
