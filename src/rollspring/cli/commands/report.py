"""``rollspring report SYSTEM -o report.html``: one self-contained offline page about a system.

The page (made by :func:`rollspring.service.documents.build_report`, rendered by
:mod:`rollspring.outputs.report`) holds the parameters, the modal table, X̂, the friction needed
against μs, the derivations and paper checks, the plots and an animation; with ``--format pdf``
headless Chromium prints the same page. The command is added to an app by
:func:`register`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rollspring.cli.common import ProgressBar, add_command, confirm_cost, load, say
from rollspring.cli.options import Formats, SystemArg, out_option, yes_option
from rollspring.model import DEFAULT_PRESET

__all__ = ["FORMATS", "register", "report"]

#: Formats ``--format`` accepts (as :data:`rollspring.outputs.report.FORMATS`, which is imported
#: only when the command runs: it brings Matplotlib, and every other command starts faster).
FORMATS = Formats("html", "pdf")


def report(
    system: SystemArg = DEFAULT_PRESET,
    out: Annotated[
        str | None,
        out_option("Output file (default report.html, or report.pdf with --format pdf)."),
    ] = None,
    format: Annotated[  # noqa: A002 - the option is called --format
        str | None,
        FORMATS.option(
            text="html (default; pdf when --out ends in .pdf) or pdf (printed by headless "
            "Chromium).",
            show_default=False,
        ),
    ] = None,
    duration: Annotated[
        float | None,
        typer.Option(
            "--duration",
            "-T",
            help="Simulated time, s (default: four periods of the slowest mode, 1 to 20 s).",
            show_default=False,
        ),
    ] = None,
    derivation: Annotated[
        bool,
        typer.Option(
            "--derivation/--no-derivation",
            help="Include the symbolic derivation by the five "
            "methods and the paper's claims (SymPy; the slowest part for large systems).",
        ),
    ] = True,
    chromium: Annotated[
        str | None,
        typer.Option(
            help="Chromium executable for --format pdf (default: $ROLLSPRING_CHROMIUM, then "
            "chromium on PATH).",
            show_default=False,
        ),
    ] = None,
    data: Annotated[
        str | None,
        typer.Option(
            "--data",
            help="A measured table (track CSV, plain CSV, Tracker file): adds a lab section, "
            "the system fitted to it.",
            show_default=False,
        ),
    ] = None,
    free: Annotated[
        list[str] | None,
        typer.Option(
            "--free",
            help="With --data: a PATH to fit (default: every spring's stiffness and damping).",
            show_default=False,
        ),
    ] = None,
    mapping: Annotated[
        list[str] | None,
        typer.Option("--map", help="With --data: TRACK=BODY.", show_default=False),
    ] = None,
    yes: Annotated[bool, yes_option()] = False,
) -> None:
    """Write a self-contained report (HTML, or PDF through headless Chromium): diagram,
    parameters, modes, X̂, friction needed vs μs, derivations, paper checks, plots, animation."""
    from rollspring.outputs.report import (
        ReportError,
        check_report_name,
        find_chromium,
        write_report,
    )
    from rollspring.service.costs import report_cost
    from rollspring.service.documents import report_request, run_report

    if format is None:
        format = "pdf" if out is not None and out.lower().endswith(".pdf") else "html"  # noqa: A001
    FORMATS.check(format, ReportError)
    try:  # the arguments checked once, in the library; in the command line's words
        request = report_request(duration=duration, derivation=derivation)
    except ReportError:
        raise ReportError(
            f"--duration: must be a positive number of seconds, got {duration:g}"
        ) from None
    target = Path(out if out is not None else f"report.{format}")
    if data is None and (free or mapping):
        option = "--free" if free else "--map"
        raise ReportError(f"{option}: only with --data (the measured table to fit)")
    from rollspring.outputs.atomic import writable_file

    writable_file(target)  # an unwritable --out fails now, not after the work
    check_report_name(target, format)  # the bytes written are the format's
    if format == "pdf":
        find_chromium(chromium)  # fail before the work when Chromium is missing
    model = load(system)
    if data is not None:
        import dataclasses

        from rollspring.service.fitting import lab_request, parse_mapping

        lab = lab_request(model, data, free, parse_mapping(mapping or ()), confirm=yes)
        request = dataclasses.replace(request, lab=lab)
    # estimated once, as a whole: the report's analysis, run and derivation estimate nothing
    confirm_cost(report_cost(model, duration=duration, derivation=derivation), yes=yes)
    with ProgressBar("building the report") as progress:
        built = run_report(model, request, progress)
        written = write_report(built, target, format=format, chromium=chromium)
    for failure in built.math_failures:
        say(f"warning: shown as LaTeX source: {failure}")
    say(f"wrote {written}")


def register(app: typer.Typer) -> None:
    """Add the ``report`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, report, "report", extras="report")
