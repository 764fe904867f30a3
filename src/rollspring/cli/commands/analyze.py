"""``rollspring analyze SYSTEM``: the linear analysis — equilibrium, M and K, normal modes,
stationary point and the friction each body needs (:func:`rollspring.analyze`).

``--json`` prints one JSON object (:func:`rollspring.service.runs.analysis_payload`); otherwise
Rich tables (:mod:`rollspring.cli.tables`, or summaries for a long chain:
:mod:`rollspring.cli.long_tables`). ``--modes`` picks the lowest K modes or a band.
"""

from __future__ import annotations

from typing import Annotated

import typer

from rollspring.cli.common import add_command, confirm_cost, load, print_json, say, stdout_console
from rollspring.cli.options import JsonOpt, SystemArg, YesOpt
from rollspring.model import DEFAULT_PRESET

__all__ = ["analyze", "register"]


def analyze(
    system: SystemArg = DEFAULT_PRESET,
    as_json: JsonOpt = False,
    yes: YesOpt = False,
    modes: Annotated[
        str | None,
        typer.Option(
            "--modes",
            help="Which normal modes: K (the lowest K) or FIRST-LAST (1-based, a band); "
            "default every mode up to 2000 bodies, the lowest 20 beyond.",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Linear analysis: equilibrium, M and K, normal modes, stationary point, friction needed."""
    from rollspring.analysis.modal import analysis_request, run_analysis
    from rollspring.errors import AnalysisError
    from rollspring.service.costs import analysis_cost
    from rollspring.service.runs import analysis_payload

    chosen = _mode_selection(modes, AnalysisError)
    model = load(system)
    request = analysis_request(model, modes=chosen)  # the arguments checked once
    # estimated once: the analysis estimates nothing again
    confirm_cost(analysis_cost(model, modes=chosen), yes=yes, stoppable=False)
    if as_json:
        payload, warnings = analysis_payload(model, request)
        for warning in warnings:
            say(f"warning: {warning}")
        print_json(payload)
        return
    from rollspring.model.chains import LONG_CHAIN

    result = run_analysis(model, request)
    if len(model.bodies) > LONG_CHAIN:  # summaries, not a row per body
        from rollspring.cli.long_tables import print_long_analysis

        print_long_analysis(stdout_console(), result)
    else:
        from rollspring.cli.tables import print_analysis

        print_analysis(stdout_console(), result)


def _mode_selection(text: str | None, error: type[Exception]) -> int | tuple[int, int] | None:
    """``--modes``: "K" -> K, "FIRST-LAST" -> (FIRST, LAST); checked against the system by
    :func:`rollspring.analyze` (the numbers' range), here their form."""
    if text is None:
        return None
    first, dash, last = text.strip().partition("-")
    try:
        if dash:
            return int(first), int(last)
        return int(first)
    except ValueError:
        raise error(
            f"--modes: a count K or a band FIRST-LAST of whole numbers, got {text!r}"
        ) from None


def register(app: typer.Typer) -> None:
    """Add the ``analyze`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, analyze, "analyze")
