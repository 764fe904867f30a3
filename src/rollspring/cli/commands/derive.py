"""``rollspring derive SYSTEM``: the equations of motion derived step by step (SymPy).

``--method newton|conservation|lagrange|natural-frequencies|hamilton|all`` (repeatable),
``--format text|markdown|latex``, ``--symbols`` (masses, radii, stiffnesses as symbols),
``-o FILE`` (written atomically; default stdout). The command is added to an app by
:func:`register`.
"""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from rollspring.cli.common import (
    SystemArg,
    add_command,
    format_option,
    load,
    out_option,
    say,
    yes_option,
)

# The derivation engine (SymPy) is imported when the command runs, not when the CLI starts.
#: The names of the methods and formats, for the help text (a test checks them against the
#: engine's METHODS, ALL and FORMATS).
METHOD_NAMES = ("newton", "conservation", "lagrange", "natural-frequencies", "hamilton", "all")
FORMAT_NAMES = ("text", "markdown", "latex")

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
    format: Annotated[  # noqa: A002 - the option is called --format
        str, format_option(f"Output format: {', '.join(FORMAT_NAMES)} (latex: a full document).")
    ] = "text",
    symbols: Annotated[
        bool,
        typer.Option(
            "--symbols",
            help="Masses, radii, stiffnesses and heights as symbols (m_1, R, k, ...) "
            "instead of exact numbers.",
        ),
    ] = False,
    out: Annotated[
        str | None, out_option("Write to this file (atomically) instead of stdout.")
    ] = None,
    yes: Annotated[bool, yes_option("time", " (many bodies)")] = False,
) -> None:
    """Derive the equations of motion step by step by Newton, conservation laws, Lagrange,
    subsystem frequencies and Hamilton; check that they agree (symbolically)."""
    # the derivation engine itself, not rollspring.service.documents: that module brings the
    # paper's claims and the worksheets, start-up this command never uses
    from rollspring.analysis.derivation import ALL, FORMATS, METHODS, DerivationError, derive

    if format not in FORMATS:
        raise DerivationError(
            f"--format: unknown format '{format}' (formats: {', '.join(FORMATS)})"
        )
    methods = method or [ALL]
    for name in methods:
        if name != ALL and name not in METHODS:
            raise DerivationError(
                f"--method: unknown method '{name}' (methods: {', '.join(METHODS)}, {ALL})"
            )
    if out is not None:
        from rollspring.outputs.atomic import writable_file

        writable_file(out)  # an unwritable --out fails now, not after the derivation
    from rollspring.service.costs import check_cost, derivation_cost

    model = load(system)
    cost = derivation_cost(model)
    check_cost(cost, confirmed=yes)
    if cost.long:
        say(f"note: the derivation will take {cost.describe()}; Ctrl-C stops it")
    derivation = derive(model, methods, symbols=symbols, confirm=True)  # checked above (--yes)
    rendered, check = derivation.render(format), derivation.cross_check
    if out is None:
        sys.stdout.write(rendered)
        sys.stdout.flush()
    else:
        from rollspring.outputs.atomic import atomic_write_text

        try:
            atomic_write_text(out, rendered)
        except OSError as exc:
            raise DerivationError(f"--out: {out}: cannot write ({exc.strerror or exc})") from None
        say(f"wrote {out}")
    if not check.agree:
        say(
            "warning: the methods do not all agree: "
            + "; ".join(f"{c.method}: {c.what}" for c in check.failures)
        )


def register(app: typer.Typer) -> None:
    """Add the ``derive`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, derive_command, "derive", extras="report")
