"""Sections of the report about the system as given: at a glance, the diagram, the parameters,
and the equilibrium with the equations of motion (M and K).
"""

from __future__ import annotations

import numpy as np

from rollspring.outputs import figures
from rollspring.outputs.numbers import attachment_words
from rollspring.outputs.report._html import Markup, Num, esc, fmt, table
from rollspring.outputs.report._page import Page, _figure, _tex_id, _tex_matrix


def section_overview(page: Page) -> Markup:
    a, arrays = page.analysis, page.arrays
    items = []
    if not a.equilibrium.found:
        items.append(Markup(f"<strong>no equilibrium</strong>: {esc(a.equilibrium.reason)}"))
    osc = a.oscillating
    if osc:
        low = osc[0]
        items.append(
            Markup(f"lowest frequency ω = {fmt(low.omega)} rad/s (period {fmt(low.period)} s)")
        )
    if a.stationary_weights is not None:
        is_cm = bool(
            np.allclose(
                a.stationary_weights, arrays.mass / arrays.mass.sum(), rtol=1e-9, atol=1e-12
            )
        )
        items.append(
            Markup(
                "a stationary point X̂ exists; it "
                + (
                    "is the centre of mass"
                    if is_cm
                    else "is <strong>not</strong> the centre of mass"
                )
            )
        )
    if a.required_mu is not None:
        rolling = [m <= mu for m, mu in zip(a.required_mu, arrays.mu_static, strict=True)]
        items.append(
            Markup(
                "linear motion: every body rolls"
                if all(rolling)
                else "linear motion: <strong>friction is not enough</strong> for "
                + ", ".join(esc(b) for b, r in zip(arrays.ids, rolling, strict=True) if not r)
            )
        )
    status = page.trajectory.status
    items.append(
        Markup(
            f"simulation over {fmt(float(page.trajectory.t[-1]))} s: "
            + (
                esc(status)
                if status == "finished"
                else f"<strong>{esc(status)}</strong>: {esc(page.trajectory.message)}"
            )
        )
    )
    return page.section(
        "overview",
        "At a glance",
        Markup("<ul>" + "".join(f"<li>{i}</li>" for i in items) + "</ul>"),
    )


def section_diagram(page: Page) -> Markup:
    a = page.analysis
    initial = _figure(
        figures.plot_system(a, at="initial"),
        "The system as placed at the start (▲ centre of mass, ◆ X̂).",
        "figure-system",
    )
    parts: list[object] = [initial]
    if a.equilibrium.found:
        parts.append(
            _figure(
                figures.plot_system(a, at="equilibrium", forces=True),
                "At equilibrium, with the friction, normal forces and spring tensions there.",
                "figure-equilibrium",
            )
        )
    return page.section(
        "diagram", "The system", Markup('<div class="grid2">'), *parts, Markup("</div>")
    )


def section_parameters(page: Page) -> Markup:
    system, arrays = page.system, page.arrays
    # the rolling resistance coefficient, a column only when a body has it
    resisted_header = ["C_rr"] if arrays.resisted else []
    bodies = table(
        [
            "body",
            "shape",
            "m (kg)",
            "R (m)",
            "γ = I/(mR²)",
            "J = (1+γ)mR² (kg m²)",
            "track height (m)",
            "x₀ (m)",
            "v₀ (m/s)",
            "μs",
            "μk",
            *resisted_header,
        ],
        [
            [
                b.id,
                b.shape,
                Num(b.mass),
                Num(b.radius),
                Num(b.gamma),
                Num(float(arrays.inertia[i])),
                Num(b.track_height),
                Num(b.x),
                Num(b.v),
                Num(b.mu_static) if b.rolls else "–",
                Num(b.mu_kinetic_value) if b.rolls else "–",
                *([Num(b.rolling_resistance) if b.rolls else "–"] if resisted_header else []),
            ]
            for i, b in enumerate(system.bodies)
        ],
        caption="Bodies",
        table_id="bodies",
    )
    springs = (
        table(
            ["spring", "ends", "attachments", "k (N/m)", "rest length (m)", "damping (N s/m)"],
            [
                [
                    name,
                    " – ".join(s.ends),
                    " ; ".join(attachment_words(at) for at in s.attachments),
                    Num(s.stiffness),
                    Num(float(arrays.rest_length[k])),
                    Num(s.damping),
                ]
                for k, (name, s) in enumerate(zip(arrays.spring_names, system.springs, strict=True))
            ],
            caption="Springs",
            table_id="springs",
        )
        if system.springs
        else ""
    )
    anchors = (
        table(
            ["anchor", "x (m)", "y (m)"],
            [[a.id, Num(a.x), Num(a.y)] for a in system.anchors],
            caption="Anchors (fixed points)",
            table_id="anchors",
        )
        if system.anchors
        else ""
    )
    forces = (
        table(
            ["body", "point", "Fx (N)", "Fy (N)"],
            [[f.body, attachment_words(f.at), Num(f.fx), Num(f.fy)] for f in system.forces],
            caption="Constant forces",
            table_id="forces",
        )
        if system.forces
        else ""
    )
    gravity = Markup(
        f'<p>Gravity g = <span id="gravity" data-value="{system.gravity!r}">'
        f"{fmt(system.gravity)}</span> m/s².</p>"
    )
    return page.section("parameters", "Parameters", gravity, bodies, springs, anchors, forces)


def section_equilibrium(page: Page) -> Markup:
    a, arrays = page.analysis, page.arrays
    q = a.equilibrium.q
    x_eq = arrays.x0 + arrays.scale * q
    found = Markup(
        "" if a.equilibrium.found else f'<p class="verdict-bad">{esc(a.equilibrium.reason)}</p>'
    )
    bodies = table(
        ["body", "x (m)", "φ (rad)", "f (N)", "N (N)"],
        [
            [
                b,
                Num(float(x_eq[i])),
                Num(float(arrays.rolls[i] * q[i])),
                Num(float(a.equilibrium_friction[i])),
                Num(float(a.equilibrium_normal[i])),
            ]
            for i, b in enumerate(arrays.ids)
        ],
        caption="Equilibrium (the configuration the motion oscillates about)",
        table_id="equilibrium",
    )
    springs = (
        table(
            ["spring", "length (m)", "tension (N)", "tilt (°)"],
            [
                [
                    name,
                    Num(float(a.spring_length[k])),
                    Num(float(a.spring_tension[k])),
                    Num(float(a.spring_tilt_deg[k])),
                ]
                for k, name in enumerate(arrays.spring_names)
            ],
            caption="Springs at equilibrium",
            table_id="spring-state",
        )
        if arrays.n_springs
        else ""
    )
    coords = ", ".join(
        (r"\varphi_{" if arrays.rolls[i] else "x_{") + _tex_id(b) + "}"
        for i, b in enumerate(arrays.ids)
    )
    equations = Markup(
        "<p>Linearised about the equilibrium (docs/physics.md (M12)), with the coordinates "
        + page.math(r"q = (" + coords + ")", display=False)
        + " (rad for rolling bodies, m for sliders):</p>"
        + '<div class="formula">'
        + page.math(
            r"\mathbf{M}\,\ddot{q} + \mathbf{K}\,q = 0,\qquad \mathbf{M} = "
            + _tex_matrix(a.mass)
            + r"\ \mathrm{kg\,m^2},\qquad \mathbf{K} = "
            + _tex_matrix(a.stiffness)
            + r"\ \mathrm{N\,m}"
        )
        + "</div>"
    )
    return page.section(
        "equilibrium", "Equilibrium and equations of motion", found, bodies, springs, equations
    )
