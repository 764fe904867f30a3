"""``rollspring fit DATA --system SYSTEM --free PATH ...``: a measured table of a real
experiment becomes a fitted model (:func:`rollspring.fit`, run by
:func:`rollspring.service.fitting.run_fit`).

DATA is a ``track`` CSV, a plain CSV (``t``, ``x_<body id>``, optional ``phi_<body id>``) or a
Tracker data file; ``--free`` names the PATHs to fit (``springs.0.stiffness``,
``springs.0.damping``, ``bodies.hoop.mass``, ...), besides each body's initial position and
velocity (or, with ``--fix-initial``, the start time ``t0``). ``-o fitted.toml`` writes the fitted
system and ``--figure fit.png`` the data over the model, as a set; ``--json`` prints one JSON
object (``parameters`` keyed by PATH with ``value`` and ``stderr``, ``residual_rms`` per body,
``status``, ``claims`` for two bodies). Bad input is one line and exit code 2; a fit that does
not converge prints its status and best values and exits with code 1. Before any work the fit
is estimated (:func:`rollspring.service.fitting.fit_estimate`: tiny on the exact linear motion,
a simulation of the recording per evaluation on the simulated one) and refused above 5 minutes
or 2 GiB unless ``--yes``, which also confirms a long ``--posterior``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer

from rollspring.cli.common import (
    ProgressBar,
    add_command,
    confirm_cost,
    load,
    print_json,
    say,
    stdout_console,
)
from rollspring.cli.options import JsonOpt, out_option, yes_option

if TYPE_CHECKING:
    from rollspring.lab.fit import FitResult

__all__ = ["fit", "register"]


def fit(
    data: Annotated[
        str,
        typer.Argument(
            help="The measured table: a track CSV, a plain CSV (t, x_<id>, phi_<id>) or a "
            "Tracker data file.",
            show_default=False,
        ),
    ],
    system: Annotated[
        str,
        typer.Option(
            "--system",
            "-s",
            help="The system: a file (.toml, .json) or a preset name.",
            show_default=False,
        ),
    ],
    free: Annotated[
        list[str] | None,
        typer.Option(
            "--free",
            help="A number of the system to fit, as a PATH (springs.0.stiffness, "
            "springs.0.damping, bodies.<id>.mass, ...); repeat for more.",
            show_default=False,
        ),
    ] = None,
    mapping: Annotated[
        list[str] | None,
        typer.Option(
            "--map",
            help="Match a track to a body: TRACK=BODY (default: by name); repeat.",
            show_default=False,
        ),
    ] = None,
    fix_initial: Annotated[
        bool,
        typer.Option(
            "--fix-initial",
            help="Hold the system's initial state and fit the data's time t0 at which it holds.",
        ),
    ] = False,
    posterior: Annotated[
        bool, typer.Option("--posterior", help="Sample the posterior by MCMC (emcee).")
    ] = False,
    out: Annotated[str | None, out_option("Write the fitted system here (TOML).")] = None,
    figure: Annotated[
        str | None,
        typer.Option(
            "--figure", help="Write the data over the model here (PNG or SVG).", show_default=False
        ),
    ] = None,
    as_json: JsonOpt = False,
    yes: Annotated[
        bool,
        yes_option(
            note=": a fit on the simulated motion (rolling resistance, slip, off-centre "
            "springs: one simulation of the recording per evaluation) or its --posterior"
        ),
    ] = False,
) -> None:
    """Fit a system to a measured table: values ± standard errors, residuals, the paper's claims."""
    from rollspring.service.fitting import (
        FitRequest,
        check_fit_places,
        fit_estimate,
        fit_table,
        parse_mapping,
        run_fit,
        write_fit_outputs,
    )

    check_fit_places(out, figure, data)
    if figure is not None:
        from rollspring.errors import require_extra

        require_extra("plot", "rollspring fit --figure")
    if posterior:  # emcee, of the lab extra (checked alone: the fit itself needs no extra)
        from importlib.util import find_spec

        from rollspring.errors import MissingExtraError

        if find_spec("emcee") is None:
            raise MissingExtraError("rollspring fit --posterior", ("lab",))
    request = FitRequest(
        data=data,
        free=tuple(free or ()),
        mapping=parse_mapping(mapping or ()),
        fix_initial=fix_initial,
        posterior=posterior,
        confirm=yes,
    )
    model = load(system)
    table = fit_table(model, request)
    confirm_cost(fit_estimate(model, request, table), yes=yes)
    with ProgressBar("fitting") as progress:
        result = run_fit(model, request, progress, table=table)
    for written in write_fit_outputs(result, system_path=out, figure_path=figure):
        say(f"wrote {written}")
    for warning in result.warnings:
        say(f"warning: {warning}")
    if not result.converged:
        say(f"error: {result.message}")
    if as_json:
        print_json(result.to_dict())
    else:
        _print_table(result)
    if not result.converged:
        raise typer.Exit(1)


def _print_table(result: FitResult) -> None:
    from rich.table import Table

    from rollspring.outputs.lab import format_value

    console = stdout_console()
    out = result.to_dict()
    table = Table(title=f"fit to {result.data.source}: {result.message}", title_justify="left")
    table.add_column("parameter")
    table.add_column("value", justify="right")
    table.add_column("unit")
    for name, p in out["parameters"].items():
        table.add_row(name, format_value(p["value"], p["stderr"]), p["unit"])
    console.print(table)
    rms = ", ".join(f"{body} {1e3 * v:.3g} mm" for body, v in out["residual_rms"].items())
    console.print(f"residual RMS: {rms}  ({out['motion']}, {out['points']} points)")
    claims = out["claims"]
    if claims:
        console.print("the paper's claims measured:")
        for name in ("cm_peak_to_peak", "stationary_peak_to_peak", "friction_ratio"):
            entry = claims.get(name)
            if entry is not None:
                unit = "" if name == "friction_ratio" else " m"
                console.print(f"  {name}: {format_value(entry['value'], entry['stderr'])}{unit}")
        for body, check in claims.get("rolled", {}).items():
            verdict = "rolled" if check["rolled"] else "did NOT roll (slipped)"
            console.print(
                f"  {body} {verdict}: slip {1e3 * check['slip_rms']:.2g} mm RMS against noise "
                f"{1e3 * check['noise']:.2g} mm"
            )
    if out.get("posterior"):
        console.print("95% credible intervals (MCMC):")
        for name, c in out["posterior"]["credible_intervals"].items():
            console.print(f"  {name}: {c['median']:.6g} [{c['low']:.6g}, {c['high']:.6g}]")


def register(app: typer.Typer) -> None:
    """Add the ``fit`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, fit, "fit")
