"""Sections of the report about the simulated motion: the facts of the run with the animation
player and its frame data (:func:`animation_data`), and the time plots.
"""

from __future__ import annotations

import math

import numpy as np

from rollspring.analysis import LinearAnalysis
from rollspring.outputs import figures
from rollspring.outputs.numbers import integrator_words
from rollspring.outputs.report._html import Markup, esc, fmt, table
from rollspring.outputs.report._page import Page, _figure, _json_script, _round
from rollspring.simulate import Trajectory


def section_animation(page: Page, frames: int) -> Markup:
    data = animation_data(page.analysis, page.trajectory, frames)
    run = page.trajectory
    options = "".join(
        f'<option value="{m:g}"{" selected" if m == data["magnify"] else ""}>×{m:g}</option>'
        for m in data["magnify_options"]
    )
    speeds = "".join(
        f'<option value="{s:g}"{" selected" if s == 1 else ""}>{s:g}×</option>'
        for s in (0.1, 0.25, 0.5, 1, 2, 4)
    )
    readout_rows = "".join(
        f'<tr id="readout-{esc(b)}"><td>{esc(b)}</td><td class="num"></td>'
        '<td class="num"></td><td class="num"></td><td class="num"></td></tr>'
        for b in page.arrays.ids
    )
    summary = run.summary
    facts = table(
        ["", ""],
        [
            ["status", run.status + (f": {run.message}" if run.message else "")],
            [
                "integrator",
                integrator_words(run.steps_by_integrator, run.step, run.integrator),
            ],
            [
                "energy (J), max relative error",
                Markup(f"{fmt(summary.get('energy'))}, {fmt(summary.get('energy_error'))}"),
            ],
            *(
                [
                    [
                        "energy dissipated (J): by damping, kinetic friction, rolling resistance",
                        Markup(
                            ", ".join(
                                fmt(summary["dissipated_by"].get(kind))
                                for kind in ("damping", "kinetic_friction", "rolling_resistance")
                            )
                        ),
                    ]
                ]
                if summary.get("energy_dissipated")
                else []
            ),
            [
                "period (s): measured, linear",
                Markup(
                    f"{fmt(summary.get('period_measured'))}, {fmt(summary.get('period_linear'))}"
                ),
            ],
        ],
        caption="The simulation (exact nonlinear motion)",
        table_id="simulation",
    )
    player = Markup(
        '<div id="player">'
        '<svg id="scene" xmlns="http://www.w3.org/2000/svg" role="img" '
        'aria-label="animation of the system"></svg>'
        '<div class="controls">'
        '<button id="play" type="button" aria-pressed="false">Play</button>'
        f'<label>speed <select id="speed">{speeds}</select></label>'
        '<input id="frame" type="range" min="0" max="0" step="1" value="0" '
        'aria-label="frame">'
        '<span id="clock">t = 0.000 s</span>'
        f'<label>displacements <select id="magnify">{options}</select></label>'
        "</div>"
        '<div class="legend"><span>▲ centre of mass</span>'
        + ("<span>◆ stationary point X̂</span>" if data["xhat"] is not None else "")
        + "<span>arrows: the friction on each body (dark red when |f| ≥ μs N)</span>"
        "<span>dots: spring attachments off the centre</span></div>"
        '<table id="readout"><thead><tr><th>body</th><th>x − x_eq (mm)</th><th>f (N)</th>'
        f"<th>N (N)</th><th>|f|/N</th></tr></thead><tbody>{readout_rows}</tbody></table>"
        "</div>"
    )
    note = Markup(
        f'<p class="note">{data["t"].__len__()} frames over {fmt(float(run.t[-1]))} s of the '
        "simulated motion; the player interpolates between them. Displacements from "
        "equilibrium are drawn magnified by the factor chosen (×"
        f"{data['magnify']:g} by default, so small oscillations can be seen); sizes, the "
        "spring's geometry at equilibrium and the forces are drawn to scale.</p>"
    )
    return page.section(
        "animation",
        "Simulation and animation",
        facts,
        player,
        note,
        _json_script("animation-data", data),
    )


def section_plots(page: Page) -> Markup:
    run = page.trajectory
    if run.t.size < 2:
        return page.section(
            "plots",
            "Plots",
            Markup("<p>The simulation stopped at its start, so there is no motion to plot.</p>"),
        )
    return page.section(
        "plots",
        "Plots",
        Markup('<div class="grid2">'),
        _figure(
            figures.plot_positions(run),
            "Centre positions about their start, with the centre of mass and X̂.",
            "figure-positions",
        ),
        _figure(figures.plot_energy(run), "Kinetic, potential and total energy.", "figure-energy"),
        _figure(
            figures.plot_phase_portraits(run),
            "Phase portraits: displacement against velocity.",
            "figure-phase",
        ),
        Markup("</div>"),
    )


def animation_data(analysis: LinearAnalysis, trajectory: Trajectory, frames: int) -> dict:
    """What the player draws: per frame time, centre x, angle, friction, normal force, the
    friction ratio |f|/(μs N), the CM and X̂; per body its shape, size, track and reference
    (equilibrium) position; per spring its ends (a body point or an anchor). Frames are evenly
    spaced in time, linearly interpolated from the trajectory's rows."""
    arrays = analysis.arrays
    run = trajectory
    t = np.asarray(run.t, dtype=float)
    n_frames = frames if t.size > 1 else 1
    times = np.linspace(t[0], t[-1], n_frames) if t.size > 1 else t.copy()

    def resample(values: np.ndarray) -> np.ndarray:
        values = np.asarray(values, dtype=float)
        if t.size == 1:
            return values.reshape(1, -1) if values.ndim > 1 else values.reshape(1)
        if values.ndim == 1:
            return np.interp(times, t, values)
        return np.column_stack([np.interp(times, t, values[:, k]) for k in range(values.shape[1])])

    q_eq = analysis.equilibrium.q
    x_ref = arrays.x0 + arrays.scale * q_eq
    phi_ref = arrays.rolls * q_eq
    ratio = np.nan_to_num(np.asarray(run.friction_ratio, dtype=float), nan=0.0, posinf=1e3)
    marks: list[list[list[float]]] = [[] for _ in arrays.ids]
    springs = []
    for s in range(arrays.n_springs):
        ends = []
        for j in range(2):
            b = int(arrays.end_body[s, j])
            if b < 0:
                ends.append({"anchor": arrays.end_anchor[s, j].tolist()})
            else:
                r, alpha = float(arrays.end_r[s, j]), float(arrays.end_alpha[s, j])
                ends.append({"body": b, "r": r, "alpha": alpha})
                if r > 0:
                    marks[b].append([r, alpha])
        springs.append({"ends": ends})
    friction = resample(run.friction)
    normal = resample(run.normal)
    # friction arrows: the largest friction of the run, or 5% of the largest normal force if
    # that is more (so rounding noise of a friction that vanishes is not blown up), is drawn
    # 1.5 R_max long
    f_ref = max(
        float(np.max(np.abs(friction), initial=0.0)),
        0.05 * float(np.max(np.abs(normal), initial=0.0)),
    )
    r_max = float(np.max(arrays.radius))
    cm_ref = float(arrays.mass @ x_ref / arrays.mass.sum())
    xhat_ref = (
        float(analysis.stationary_weights @ x_ref)
        if analysis.stationary_weights is not None
        else None
    )
    # magnify so that the largest displacement from equilibrium is about 0.6 R_max
    displacement = float(np.max(np.abs(np.asarray(run.x) - x_ref), initial=0.0))
    options = [1, 2, 5, 10, 20, 50, 100]
    magnify = 1
    for m in options:
        if displacement * m <= 0.6 * r_max:
            magnify = m
    return {
        "t": _round(times, 12),
        "x": _round(resample(run.x)),
        "phi": _round(resample(run.phi)),
        "f": _round(friction),
        "N": _round(normal),
        "ratio": _round(resample(ratio), 4),
        "cm": _round(resample(run.cm_x)),
        "xhat": (
            _round(resample(run.stationary_x))
            if run.stationary_x is not None and xhat_ref is not None
            else None
        ),
        "bodies": [
            {
                "id": b,
                "shape": body.shape,
                "R": float(arrays.radius[i]),
                "track": float(arrays.track[i]),
                "x_ref": float(x_ref[i]),
                "phi_ref": float(phi_ref[i]),
                "mu": float(arrays.mu_static[i]) if math.isfinite(arrays.mu_static[i]) else None,
                "marks": marks[i],
            }
            for i, (b, body) in enumerate(zip(arrays.ids, analysis.system.bodies, strict=True))
        ],
        "springs": springs,
        "anchors": [{"id": a.id, "x": a.x, "y": a.y} for a in analysis.system.anchors],
        "R_max": r_max,
        "floor": float(np.min(arrays.track)),
        "cm_ref": cm_ref,
        "xhat_ref": xhat_ref,
        "f_scale": 1.5 * r_max / f_ref if f_ref > 0 else 0.0,
        "magnify": magnify,
        "magnify_options": options,
        "colors": dict(figures.COLORS),
    }
