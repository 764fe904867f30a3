"""Documents about a system: the report, the derivation, the paper's claims and the worksheets.

Each function computes what its document shows, in order (analysis → simulation → derivation →
the paper's claims), and hands the results to a renderer of :mod:`rollspring.outputs`, which
computes nothing itself. The CLI (``rollspring report``, ``derive``, ``paper-check``,
``worksheet``) and the web API (``POST /api/derive``, ``/api/report``) call these functions.

Public API::

    build_report(system, duration=None, derivation=True, progress=None)  # -> Report
    run_report(system, report_request(duration=None), progress=None)  # checked, not estimated
    derivation_document(system, ["newton"], format="markdown")    # -> (text, CrossCheck)
    derivation_payload(system, "all")                             # the JSON of POST /api/derive
    paper_checks()                                                # every claim, with its verdict
    figure_claims(system)                                         # (label, checks) or None
    claims_json(checks)                                           # as paper-check --json
    worksheet(level, seed)                                        # -> Worksheet
"""

from __future__ import annotations

import dataclasses
import functools
import math
import numbers
import os
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rollspring.analysis import analyze
from rollspring.analysis.derivation import ALL, CrossCheck, derive
from rollspring.analysis.derivation.derive import derivation_request, run_derivation
from rollspring.analysis.exercises import LEVELS, Worksheet
from rollspring.analysis.modal import analysis_request, run_analysis
from rollspring.analysis.paper import (
    ClaimCheck,
    check_claims,
    check_paper,
    paper_claims,
    paper_figure,
)
from rollspring.analysis.waves import travelling_wave
from rollspring.errors import ReportError, RollspringError, WorksheetError
from rollspring.model import System, as_system, system_from_dict
from rollspring.service import exercises

if TYPE_CHECKING:
    from rollspring.outputs.report import Report
    from rollspring.service.fitting import FitRequest

# The report's renderer (Matplotlib) and the simulation (Numba, SciPy) are imported by the
# functions that use them: the worksheets and the paper's claims need neither.

__all__ = [
    "ReportRequest",
    "build_report",
    "claims_json",
    "derivation_document",
    "derivation_payload",
    "figure_claims",
    "paper_checks",
    "paper_runs",
    "report_request",
    "run_report",
    "worksheet",
]


# -- the report -----------------------------------------------------------------------------------


def build_report(
    system: System | dict[str, Any] | str | os.PathLike[str],
    *,
    duration: float | None = None,
    rtol: float = 1e-8,
    derivation: bool = True,
    progress: Callable[[float], None] | None = None,
    confirm: bool = False,
    data: str | os.PathLike[str] | None = None,
    free: Sequence[str] | None = None,
    mapping: Mapping[str, str] | None = None,
) -> Report:
    """Analyse and simulate ``system``, derive it, check the paper's claims about it, and render
    its self-contained report page (:func:`rollspring.outputs.report.render_report`).

    With ``data`` (a measured table: a ``track`` CSV, a plain CSV or a Tracker file) the page
    has a lab section: the system fitted to it (:func:`rollspring.fit`, the PATHs ``free``;
    default every spring's stiffness and damping; ``mapping`` matches tracks to bodies), the
    data over the fitted model, the fitted values and the paper's claims measured.

    ``duration`` is the simulated time (default
    :func:`~rollspring.outputs.report.default_duration`); ``derivation=False`` leaves out the
    symbolic part (the derivation by the five methods and the paper's claims: SymPy, the slowest
    part for large systems); ``progress`` is called with the fraction done (0..1) after each
    stage. ``Report.timings`` holds the seconds each stage took, and their ``total``.

    A long chain (more than :data:`~rollspring.model.chains.LONG_CHAIN` bodies) gets a
    summary instead (:func:`~rollspring.outputs.report.render_chain_report`): no modal
    analysis or derivation; the run (``duration`` default :data:`CHAIN_DURATION` s,
    :data:`CHAIN_ROWS` output rows) and its waves
    (:func:`~rollspring.analysis.waves.travelling_wave`: the energy centroid's speed beside
    the group velocity).

    ``system`` is a :class:`~rollspring.model.System`, its JSON form (a dict) or a file path or
    preset name. Every bad argument is a one-line :class:`~rollspring.errors.RollspringError`,
    raised before any work; a report estimated at more than 5 minutes or 2 GiB
    (:func:`rollspring.service.costs.report_cost`) is refused with its estimate
    (:class:`~rollspring.errors.CostTooHigh`) unless ``confirm=True`` (``--yes`` on the command
    line).

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    duration, rtol
        The simulated time (s; None: the default) and the run's relative accuracy.
    derivation
        Include the derivations and the paper's claims (SymPy).
    progress
        Called with the fraction done (0..1) after each stage.
    confirm
        Start even when the estimated time or memory is above the bound.

    Returns
    -------
    Report
        The page (``html``), its parts and ``timings``; ``write_report`` saves it.
    """
    from rollspring.service.costs import CONFIRM, check_cost, report_cost

    system = as_system(system)
    request = report_request(duration=duration, rtol=rtol, derivation=derivation)
    if not isinstance(confirm, bool):
        raise ReportError(f"confirm: must be True or False, got {confirm!r}")
    if data is not None:
        from rollspring.service.fitting import lab_request

        lab = lab_request(system, data, free, mapping, confirm=confirm, flag=CONFIRM)
        request = dataclasses.replace(request, lab=lab)
    cost = report_cost(
        system, duration=request.duration, derivation=request.derivation, flag=CONFIRM
    )
    check_cost(cost, confirmed=confirm, flag=CONFIRM)
    return run_report(system, request, progress)


@dataclass(frozen=True, slots=True)
class ReportRequest:
    """The checked arguments of one :func:`build_report` of a system (see there)."""

    #: the simulated time (s, > 0 and finite), None for the default
    duration: float | None
    #: the run's relative accuracy, within :data:`~rollspring.analysis.costs.RTOL_RANGE`
    rtol: float
    #: include the derivations and the paper's claims
    derivation: bool
    #: a recording to fit the system to, shown in the lab section (None: no lab section)
    lab: FitRequest | None = None


def report_request(
    *, duration: Any = None, rtol: Any = 1e-8, derivation: Any = True
) -> ReportRequest:
    """The arguments of :func:`build_report` checked, in this order (the first bad one is the
    error, a one-line :class:`~rollspring.errors.RollspringError` naming it): ``duration``,
    ``rtol``, ``derivation``."""
    from rollspring.simulate.arguments import check_rtol_range

    if duration is not None and (
        isinstance(duration, bool)
        or not isinstance(duration, numbers.Real)
        or not math.isfinite(duration)
        or duration <= 0
    ):
        raise ReportError(f"duration: must be a positive number of seconds, got {duration!r}")
    rtol = check_rtol_range(rtol)
    if not isinstance(derivation, bool):
        raise ReportError(f"derivation: must be True or False, got {derivation!r}")
    return ReportRequest(None if duration is None else float(duration), rtol, derivation)


def run_report(
    system: System,
    request: ReportRequest,
    progress: Callable[[float], None] | None = None,
) -> Report:
    """The report :func:`build_report` makes of a request checked already
    (:func:`report_request`), without estimating its cost (the caller's: :func:`build_report`,
    or an interface that estimated it once): the analysis, the run and the derivation inside
    are not estimated again either."""
    from rollspring.model.chains import LONG_CHAIN
    from rollspring.outputs.report import animation_frames, default_duration, render_report
    from rollspring.simulate.request import simulation_request
    from rollspring.simulate.run import run_request

    duration, rtol, derivation = request.duration, request.rtol, request.derivation
    timings: dict[str, float] = {}
    started = clock = time.perf_counter()

    def done(stage: str, fraction: float) -> None:
        nonlocal clock
        now = time.perf_counter()
        timings[stage] = now - clock
        clock = now
        if progress is not None:
            progress(fraction)

    if len(system.bodies) > LONG_CHAIN:
        return _chain_report(system, duration, rtol, done, timings, started)
    analysis = run_analysis(system, analysis_request(system))
    if duration is None:
        duration = default_duration(analysis)
    done("analyze", 0.05)
    frames, rows = animation_frames(float(duration))
    run = simulation_request(float(duration), rtol=rtol, n_output=rows)
    trajectory = run_request(system, run)
    computed = 0.2
    done("simulate", computed)
    fitted = None
    if request.lab is not None:
        from rollspring.service.fitting import run_fit

        fitted = run_fit(system, request.lab)
        done("fit the recording", computed)
    derived = error = paper = None
    if derivation:
        try:
            derived = run_derivation(system, derivation_request(symbols=True))
        except RollspringError as exc:
            error = str(exc)
        done("derive", 0.5)
        paper = figure_claims(system)
        computed = 0.6
        done("check the paper's claims", computed)
    report = render_report(
        system,
        analysis,
        trajectory,
        frames=frames,
        derivation=derived,
        derivation_error=error,
        paper=paper,
        lab=fitted,
        stage=lambda name, f: done(name, computed + (1.0 - computed) * f),
    )
    timings["total"] = time.perf_counter() - started
    report.timings = timings
    return report


#: A long chain's report: the simulated time (s) by default and the run's output rows.
CHAIN_DURATION = 20.0
CHAIN_ROWS = 801


def _chain_report(
    system: System,
    duration: float | None,
    rtol: float,
    done: Callable[[str, float], None],
    timings: dict[str, float],
    started: float,
) -> Report:
    """A long chain's report: simulate, measure the waves, render the summary."""
    from rollspring.outputs.report import render_chain_report
    from rollspring.simulate.request import simulation_request
    from rollspring.simulate.run import run_request

    duration = CHAIN_DURATION if duration is None else float(duration)
    run = simulation_request(duration, rtol=rtol, n_output=CHAIN_ROWS)
    trajectory = run_request(system, run)
    done("simulate", 0.6)
    waves = travelling_wave(system, trajectory.t, trajectory.x, trajectory.v)
    done("waves", 0.7)
    report = render_chain_report(
        system, trajectory, waves, stage=lambda name, f: done(name, 0.7 + 0.3 * f)
    )
    timings["total"] = time.perf_counter() - started
    report.timings = timings
    return report


# -- the derivation -------------------------------------------------------------------------------


def derivation_document(
    system: System | dict[str, Any] | str | os.PathLike[str],
    methods: str | Sequence[str] = ALL,
    *,
    format: str = "text",  # noqa: A002 - mirrors --format
    symbols: bool = True,
    confirm: bool = False,
) -> tuple[str, CrossCheck]:
    """``system`` derived step by step by ``methods`` (``"all"`` or names of
    :data:`rollspring.analysis.derivation.METHODS`; with ``symbols`` the parameters are symbols),
    rendered as ``format`` (``text``, ``markdown`` or ``latex``, a complete document), and the
    cross-check of the methods. ``confirm``: as :func:`rollspring.derive`'s."""
    derivation = derive(as_system(system), methods, symbols=symbols, confirm=confirm)
    return derivation.render(format), derivation.cross_check


def derivation_payload(
    system: System, method: str | Sequence[str] = ALL, *, symbols: bool = True
) -> dict[str, Any]:
    """The derivation of ``system`` by ``method`` as plain JSON data (``POST /api/derive``).

    ``{"title", "subtitle", "sections": [{"title", "note", "steps": [{"words", "latex",
    "mathml", "ref"}]}], "cross_check": {"agree", "applied", "not_applicable", "checks":
    [{"method", "what", "agree", "residual"}]}, "claims"}``: ``note`` says why a section has
    no steps (a method that does not apply), ``not_applicable`` maps each such method to the
    reason; the sections are those the report shows as steps (its symbols, by default;
    ``symbols=False`` for exact numbers), ``mathml`` the report's MathML of the LaTeX (None
    where latex2mathml cannot convert it); in ``checks`` ``agree`` is None where SymPy ran out
    of time and ``residual`` is the SymPy text of the difference (0 when they agree).
    ``claims``: the paper's claims about the system with their verdicts, as
    ``rollspring paper-check --json`` gives them, when the system is one of the paper's
    (:func:`figure_claims`), each with its quote as HTML with MathML (``quote_html``) and its
    formula and correction as MathML (``claim_mathml``, ``correction_mathml``); otherwise None.
    """
    from rollspring.outputs.report import derivation_sections

    system = as_system(system)
    derivation = derive(system, method, symbols=symbols)
    check = derivation.cross_check
    paper = figure_claims(system)
    return {
        "title": derivation.title,
        "subtitle": derivation.subtitle,
        "sections": [
            {
                "title": section.title,
                "note": section.note,
                "steps": [
                    {
                        "words": step.words,
                        "latex": step.latex,
                        "mathml": _mathml(step.latex),
                        "ref": step.ref,
                    }
                    for step in section.steps
                ],
            }
            for section in derivation_sections(derivation)
        ],
        "cross_check": {
            "agree": check.agree,
            "applied": list(check.applied),
            "not_applicable": dict(check.not_applicable),
            "checks": [
                {"method": c.method, "what": c.what, "agree": c.agrees, "residual": str(c.residual)}
                for c in check.checks
            ],
        },
        "claims": None if paper is None else _claims_shown(paper[1]),
    }


def _claims_shown(checks: Sequence[ClaimCheck]) -> list[dict[str, Any]]:
    """The claims as :func:`claims_json` gives them, and as the report shows them:
    ``quote_html`` (the paper's words, text and MathML), ``claim_mathml``, ``correction_mathml``
    (None when there is no correction)."""
    from rollspring.outputs.report import claim_html

    shown = []
    for check, data in zip(checks, claims_json(checks), strict=True):
        html = claim_html(check)
        shown.append(
            data
            | {
                "quote_html": str(html["quote"]),
                "claim_mathml": str(html["claim"]),
                "correction_mathml": str(html["correction"]) if check.correction else None,
            }
        )
    return shown


def _mathml(latex: str) -> str | None:
    """The MathML of ``latex`` as the report shows it, or None where it cannot be converted."""
    from rollspring.outputs.report import MathConversionError, latex_to_mathml

    try:
        return str(latex_to_mathml(latex))
    except MathConversionError:
        return None


# -- the paper's claims ---------------------------------------------------------------------------


def paper_checks() -> tuple[ClaimCheck, ...]:
    """Every quantitative claim of the paper with its computed verdict (once per process)."""
    return check_paper()


def figure_claims(system: System) -> tuple[str, tuple[ClaimCheck, ...]] | None:
    """The paper's claims about ``system`` with their verdicts, as ``(label of the paper's
    figure, checks)``, when ``system`` is one of the paper's systems
    (:func:`rollspring.analysis.paper.paper_figure`); None otherwise."""
    figure = paper_figure(system)
    if figure is None:
        return None
    label, keys = figure
    claims = [c for c in paper_claims() if keys & {key.strip() for key in c.system.split(",")}]
    return label, check_claims(claims)


def claims_json(
    checks: Iterable[ClaimCheck], runs: Mapping[str, Any] | None = None
) -> list[dict[str, Any]]:
    """The checks as ``rollspring paper-check --json`` prints them: ``key``, ``location``,
    ``claim`` (LaTeX), ``quote``, ``verdict``, ``assumption``, ``correction`` (LaTeX or None),
    ``reason``, ``counterexample`` (None, or the system the engine runs to show the verdict; with
    ``runs`` (:func:`paper_runs`, by claim key) also what the run measured, whether it disagrees
    with the paper's statement, and its details)."""
    out = []
    for check in checks:
        record = check.to_dict()
        if runs is not None and check.claim.key in runs:
            record["counterexample"] = runs[check.claim.key].to_dict()
        out.append(record)
    return out


def paper_runs(checks: Iterable[ClaimCheck]) -> dict[str, Any]:
    """Each claim's counterexample, run (:mod:`rollspring.service.paper_runs`), by claim key."""
    from rollspring.service.paper_runs import run_counterexamples

    return run_counterexamples(list(checks))


# -- worksheets -----------------------------------------------------------------------------------


def worksheet(level: int, seed: int) -> Worksheet:
    """The exercise sheet of ``level`` (1-4) drawn with ``seed`` (a non-negative integer; the
    same seed gives the same sheet): a random system of the level, its analysis, questions and
    answers; the derivation its solutions show (Lagrange, the parameters as symbols) is made
    when the solutions first need it."""
    if isinstance(level, bool) or not isinstance(level, numbers.Integral) or level not in LEVELS:
        raise WorksheetError(f"--level: must be 1, 2, 3 or 4 (got {level})")
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
        raise WorksheetError(f"--seed: must be a non-negative integer (got {seed})")
    level, seed = int(level), int(seed)
    variant, data, setting = exercises.draw(level, seed)
    system = system_from_dict(data)
    analysis = analyze(system)
    questions, answers, notes = exercises.questions_and_answers(level, analysis)
    return Worksheet(
        level,
        seed,
        variant,
        f"Level {level}: {LEVELS[level]}",
        data,
        system,
        setting,
        questions,
        answers,
        analysis,
        functools.partial(derive, system, ["lagrange"], symbols=True),
        notes,
    )
