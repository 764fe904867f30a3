"""Sections of the report from the linear analysis: the normal modes, the stationary point X̂
and the friction each body needs against μs (with what the simulation saw).
"""

from __future__ import annotations

import numpy as np

from rollspring.outputs import figures
from rollspring.outputs.report._html import Markup, Num, esc, fmt, table
from rollspring.outputs.report._page import Page, _figure, _tex_id, _tex_number, _verdict


def section_modes(page: Page) -> Markup:
    a, ids = page.analysis, page.arrays.ids
    damped = any(m.damping_ratio for m in a.modes)
    headers = ["mode", "kind", "ω (rad/s)", "f (Hz)", "period (s)", "ω² (1/s²)"]
    if damped:
        headers.append("damping ratio ζ")
    rows = []
    for n, m in enumerate(a.modes, 1):
        row: list[object] = [
            str(n),
            m.kind,
            Num(m.omega),
            Num(m.frequency),
            Num(m.period),
            Num(m.eigenvalue),
        ]
        if damped:
            row.append(Num(m.damping_ratio))
        rows.append(row)
    modes = table(headers, rows, caption="Normal modes  K v = ω² M v", table_id="modes")
    shape_headers: list[object] = ["body"]
    for n in range(1, len(a.modes) + 1):
        shape_headers += [f"x, mode {n}", f"f (N), mode {n}", f"N (N), mode {n}"]
    shape_rows = []
    for i, b in enumerate(ids):
        row = [b]
        for m in a.modes:
            row += [
                Num(float(m.shape_x[i])),
                Num(float(m.friction[i])),
                Num(float(m.normal_force[i])),
            ]
        shape_rows.append(row)
    shapes = table(
        shape_headers,
        shape_rows,
        caption="Mode shapes: centre displacement (largest = 1 m) and the friction "
        "and normal-force changes along it",
        table_id="mode-shapes",
    )
    ratio = ""
    if len(ids) == 2 and a.oscillating:
        f = a.oscillating[0].friction
        if f[1] != 0:
            value = float(f[0] / f[1])
            ratio = Markup(
                "<p>Friction ratio in the mode, signed (positive along +x): "
                + page.math(
                    rf"f_{{{_tex_id(ids[0])}}}/f_{{{_tex_id(ids[1])}}} = " + _tex_number(value),
                    display=False,
                )
                + f' <span id="friction-ratio" data-value="{value!r}"></span>'
                + (
                    "; the frictions point opposite ways (the paper's f1/f2 = 3/2 is a ratio "
                    "of magnitudes)."
                    if value < 0
                    else "."
                )
                + "</p>"
            )
    split = ""
    if a.spring_split is not None:
        s = a.spring_split
        split = table(
            ["body", "Ω_i clamped (rad/s)", "share of the deformation", "k_i (N/m)"],
            [
                [
                    b,
                    Num(float(s["clamped_omega"][i])),
                    Num(float(s["share"][i])),
                    Num(float(s["k"][i])),
                ]
                for i, b in enumerate(ids)
            ],
            caption="The spring split about X̂ (paper's k1, k2; Ω² = Ω1² + Ω2², 1/k = 1/k1 + 1/k2)",
            table_id="spring-split",
        )
    picture = (
        _figure(figures.plot_modes(a), "The normal modes drawn on the system.", "figure-modes")
        if a.modes
        else ""
    )
    return page.section("modes", "Normal modes", modes, shapes, ratio, split, picture)


def section_stationary_point(page: Page) -> Markup:
    a, arrays = page.analysis, page.arrays
    ids = arrays.ids
    parts: list[object] = []
    if a.stationary_weights is None:
        zeros = sum(1 for m in a.modes if m.kind == "zero")
        parts.append(
            Markup(
                "<p>No stationary point: "
                + (
                    "the system has no zero mode (walls hold it), so nothing moves freely."
                    if zeros == 0
                    else f"{zeros} zero modes, no single conserved combination."
                )
                + "</p>"
            )
        )
    else:
        w = a.stationary_weights
        cm = arrays.mass / arrays.mass.sum()
        is_cm = bool(np.allclose(w, cm, rtol=1e-9, atol=1e-12))
        terms = " + ".join(
            rf"{_tex_number(float(wi))}\,x_{{{_tex_id(b)}}}" for wi, b in zip(w, ids, strict=True)
        )
        parts.append(
            Markup(
                "<p>The zero mode v₀ conserves Σ wᵢ ẋᵢ with wᵢ = Jᵢ v₀ᵢ / sᵢ "
                "(docs/physics.md (M14)); for centre springs wᵢ ∝ (1+γᵢ) mᵢ, "
                "the paper's eq. (c):</p>"
                + '<div class="formula">'
                + page.math(r"\hat{X} = \frac{\sum_i w_i x_i}{\sum_i w_i} = " + terms)
                + "</div>"
            )
        )
        parts.append(
            table(
                ["body", "weight of X̂", "weight of the CM"],
                [[b, Num(float(w[i])), Num(float(cm[i]))] for i, b in enumerate(ids)],
                caption="Weights (normalised to sum 1)",
                table_id="stationary-weights",
            )
        )
        rows: list[list[object]] = [
            ["X̂ at the start (m)", Num(a.stationary_position)],
            ["X̂ velocity (m/s)", Num(a.stationary_velocity)],
            ["X̂ is the centre of mass", "yes" if is_cm else "no"],
        ]
        if a.stationary_amplitude is not None:
            rows.append(["X̂ amplitude, linear (m)", Num(a.stationary_amplitude)])
        if a.cm_amplitude is not None:
            rows.append(["CM amplitude, linear (m)", Num(a.cm_amplitude)])
        run = page.trajectory
        if run.stationary_x is not None and run.t.size > 1:
            rows.append(["X̂ range in the simulation (m)", Num(float(np.ptp(run.stationary_x)))])
        if run.t.size > 1:
            rows.append(["CM range in the simulation (m)", Num(float(np.ptp(run.cm_x)))])
        parts.append(
            table(
                ["quantity", "value"],
                rows,
                caption="The stationary point",
                table_id="stationary-point-values",
            )
        )
    return page.section("stationary-point", "The stationary point X̂", *parts)


def section_friction(page: Page) -> Markup:
    a, arrays, run = page.analysis, page.arrays, page.trajectory
    ids = arrays.ids
    simulated = run.summary.get("max_friction_ratio") or {}
    intro = Markup(
        "<p>Rolling needs the static friction f (M8) within the normal force N (M9):</p>"
        + '<div class="formula">'
        + page.math(
            r"f_i = \frac{Q_i}{(1+\gamma_i) R_i} - F_{ix},\qquad N_i = m_i g - "
            r"F_{iy},\qquad |f_i| \le \mu_s N_i,\quad N_i \ge 0"
        )
        + "</div>"
    )
    rows: list[list[object]] = []
    for i, b in enumerate(ids):
        if not arrays.rolls[i]:
            rows.append([b, "slider (no friction)", "–", "–", "–", "–", "–", "–"])
            continue
        mu = float(arrays.mu_static[i])
        needed = None if a.required_mu is None else float(a.required_mu[i])
        sim = simulated.get(b)
        amplitude = None if a.friction_amplitude is None else float(a.friction_amplitude[i])
        low, high = (
            (None, None)
            if a.normal_force_range is None
            else (float(a.normal_force_range[i][0]), float(a.normal_force_range[i][1]))
        )
        ok = None if needed is None else needed <= mu
        rows.append(
            [
                b,
                Num(amplitude),
                Num(low),
                Num(high),
                Num(needed),
                Num(None if sim is None else float(sim)),
                Num(mu),
                _verdict(ok, "rolls", "slips"),
            ]
        )
    friction = table(
        [
            "body",
            "|f| amplitude, linear (N)",
            "N min (N)",
            "N max (N)",
            "μ needed = max |f|/N, linear",
            "max |f|/N, simulated",
            "μs",
            "verdict",
        ],
        rows,
        caption="Friction needed against the static friction coefficient μs",
        table_id="friction",
    )
    events = []
    for key, label in (("first_slip", "first slip"), ("first_liftoff", "first lift-off")):
        event = run.summary.get(key)
        events.append(
            f"{label}: "
            + ("none" if not event else f"'{event['body']}' at t = {fmt(event['time'])} s")
        )
    plots: list[object] = []
    if run.t.size > 1:
        plots = [
            Markup('<div class="grid2">'),
            _figure(
                figures.plot_friction_ratio(run),
                "The friction each body needs relative to what it can have, "
                "|f|/(μs N), in the simulated motion (slip at 1).",
                "figure-friction-ratio",
            ),
            _figure(
                figures.plot_contact_forces(run),
                "Friction f with the ±μs N band, and the normal force N.",
                "figure-contact-forces",
            ),
            Markup("</div>"),
        ]
    return page.section(
        "friction",
        "Friction needed vs μs",
        intro,
        friction,
        Markup(f'<p class="note">In the simulation: {esc("; ".join(events))}.</p>'),
        *plots,
    )
