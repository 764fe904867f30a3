r"""Assemble the report page from results already computed (an analysis, a simulation, a
derivation, the paper's claims checked) and their pictures.

Each ``_Page.section_*`` method returns one ``<section>`` of the page (Markup);
:func:`render_report` puts the sections in order. What the page shows is computed by
:func:`rollspring.service.documents.build_report`, which calls it.
"""

from __future__ import annotations

import base64
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from rollspring.analysis import LinearAnalysis
from rollspring.analysis.derivation import Derivation, Section
from rollspring.analysis.paper import (
    HOLDS_ONLY_IF,
    HOLDS_STATED,
    VERDICTS,
    VERIFIED,
    WRONG,
    ClaimCheck,
)
from rollspring.analysis.report import CONVENTIONS
from rollspring.model import System
from rollspring.outputs import figures
from rollspring.outputs.files import atomic_write_text
from rollspring.outputs.numbers import attachment_words, integrator_words
from rollspring.outputs.report._assets import CSS, PLAYER_JS
from rollspring.outputs.report._html import (
    Markup,
    Num,
    ReportError,
    esc,
    fmt,
    math_or_source,
    table,
)
from rollspring.outputs.report._pdf import html_to_pdf
from rollspring.outputs.trajectory import json_ready, summary_json, trajectory_csv
from rollspring.simulate import Trajectory

__all__ = [
    "FORMATS",
    "Report",
    "animation_data",
    "animation_frames",
    "default_duration",
    "derivation_sections",
    "render_report",
    "write_report",
]

#: Values of ``format`` that :func:`write_report` accepts.
FORMATS = ("html", "pdf")
#: Stored animation frames per simulated second (the player interpolates between them).
FRAMES_PER_SECOND = 60
_MAX_FRAMES = 1200
#: Output rows of the simulation per animation frame (the plots use every row).
_ROWS_PER_FRAME = 4


@dataclass
class Report:
    """A finished report: the page (``html``), what it was made from, and how long each stage
    took (``timings``, s). ``math_failures`` lists formulas shown as LaTeX source because
    latex2mathml could not convert them (empty when every formula is MathML)."""

    system: System
    #: None for a long chain's report (:func:`~rollspring.outputs.report.render_chain_report`)
    analysis: LinearAnalysis | None
    trajectory: Trajectory
    html: str
    sections: list[str] = field(default_factory=list)
    math_failures: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)


def default_duration(analysis: LinearAnalysis) -> float:
    """Simulated time of a report: four periods of the slowest oscillating mode, within
    [1, 20] s; 2 s when nothing oscillates."""
    periods = [m.period for m in analysis.oscillating if math.isfinite(m.period)]
    if not periods:
        return 2.0
    return float(min(max(4.0 * max(periods), 1.0), 20.0))


def animation_frames(duration: float) -> tuple[int, int]:
    """``(frames, rows)`` for a report of ``duration`` simulated seconds: the frames the player
    stores (:data:`FRAMES_PER_SECOND`, 50 to 1200) and the output rows the simulation needs
    for them (the plots use every row)."""
    frames = int(min(max(math.ceil(duration * FRAMES_PER_SECOND), 50), _MAX_FRAMES))
    return frames, _ROWS_PER_FRAME * (frames - 1) + 1


def derivation_sections(derivation: Derivation) -> list[Section]:
    """The sections of ``derivation`` shown as steps: every one but the cross-check's own
    (shown as a table of verdicts instead)."""
    own_table = derivation.cross_check.section().title
    return [s for s in derivation.sections if s.title != own_table]


def render_report(
    system: System,
    analysis: LinearAnalysis,
    trajectory: Trajectory,
    *,
    frames: int,
    derivation: Derivation | None = None,
    derivation_error: str | None = None,
    paper: tuple[str, Sequence[ClaimCheck]] | None = None,
    stage: Callable[[str, float], None] | None = None,
) -> Report:
    """The self-contained report page of ``system`` from its ``analysis`` and ``trajectory``.

    ``frames``: animation frames the player stores (:func:`animation_frames`); ``derivation``:
    the symbolic derivation to show, or ``derivation_error`` (why there is none) — with neither
    the page has no derivation; ``paper``: ``(label of the paper's figure, its claims checked)``
    when the system is one of the paper's; ``stage`` is called after each stage of the
    rendering with its name and the fraction of the rendering done (0..1).
    """

    def done(name: str, fraction: float) -> None:
        if stage is not None:
            stage(name, fraction)

    failures: list[str] = []
    page = _Page(system, analysis, trajectory, failures)
    sections = [
        page.section_overview(),
        page.section_diagram(),
        page.section_parameters(),
        page.section_equilibrium(),
        page.section_modes(),
        page.section_stationary_point(),
        page.section_friction(),
    ]
    done("tables and figures", 0.5)
    sections.append(page.section_animation(frames))
    sections.append(page.section_plots())
    done("animation and plots", 0.75)
    if derivation is not None or derivation_error is not None:
        sections.append(page.section_derivation(derivation, derivation_error))
        done("derivation", 0.9)
    if paper is not None:
        sections.append(page.section_paper_check(*paper))
        done("paper check", 0.95)
    sections.append(page.section_warnings())
    sections.append(page.section_data())
    html = page.document([s for s in sections if s])
    done("assemble", 1.0)
    return Report(
        system=system,
        analysis=analysis,
        trajectory=trajectory,
        html=html,
        sections=page.section_ids,
        math_failures=failures,
    )


def write_report(
    report: Report,
    path: str | Path,
    *,
    format: str = "html",  # noqa: A002
    chromium: str | None = None,
) -> Path:
    """Write the report to ``path`` atomically: the HTML page, or (``format="pdf"``) the same
    page printed by headless Chromium (:func:`~rollspring.outputs.report.find_chromium`)."""
    if format not in FORMATS:
        raise ReportError(f"--format: unknown format '{format}' (formats: {', '.join(FORMATS)})")
    target = Path(path)
    if format == "pdf":
        return html_to_pdf(report.html, target, chromium=chromium)
    try:
        atomic_write_text(target, report.html)
    except OSError as exc:
        raise ReportError(f"{target}: cannot write ({exc.strerror or exc})") from None
    return target


# -- numbers in LaTeX ---------------------------------------------------------------------------


def _tex_number(value: float, digits: int = 6) -> str:
    if math.isinf(value):
        return r"\infty" if value > 0 else r"-\infty"
    if value == 0:
        return "0"
    text = f"{value:.{digits}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        return rf"{mantissa}\times 10^{{{int(exponent)}}}"
    return text


def _tex_id(name: str) -> str:
    """A body id as a LaTeX subscript text."""
    return r"\text{" + name.replace("_", r"\_") + "}"


def _tex_matrix(matrix: np.ndarray, digits: int = 6) -> str:
    rows = [" & ".join(_tex_number(float(v), digits) for v in row) for row in matrix]
    return r"\begin{pmatrix}" + r"\\".join(rows) + r"\end{pmatrix}"


def _json_script(element_id: str, data: Any) -> Markup:
    text = json.dumps(json_ready(data), ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    text = text.replace("<", "\\u003c")  # no "</script" or "<!--" inside the script element
    return Markup(f'<script type="application/json" id="{element_id}">{text}</script>')


def _round(values: Any, digits: int = 7) -> list:
    """Values rounded to ``digits`` significant digits (small JSON, plenty for drawing);
    non-finite values become 0."""
    array = np.asarray(values, dtype=float)
    array = np.where(np.isfinite(array), array, 0.0)
    flat = [float(f"{v:.{digits}g}") for v in array.ravel().tolist()]
    return np.array(flat).reshape(array.shape).tolist()


def _figure(figure: Any, caption: str, figure_id: str) -> Markup:
    """A Matplotlib figure (or the figure of an Axes) as an embedded SVG image."""
    figure = getattr(figure, "figure", figure)
    svg = figures.figure_svg(figure)
    data = base64.b64encode(svg.encode("utf-8")).decode("ascii")
    return Markup(
        f'<figure id="{esc(figure_id)}"><img alt="{esc(caption)}" '
        f'src="data:image/svg+xml;base64,{data}"><figcaption>{esc(caption)}'
        "</figcaption></figure>"
    )


def _verdict(ok: bool | None, yes: str, no: str) -> Markup:
    if ok is None:
        return Markup('<span class="verdict-other">–</span>')
    return Markup(f'<span class="verdict-{"ok" if ok else "bad"}">{esc(yes if ok else no)}</span>')


# -- the page -------------------------------------------------------------------------------------


class _Page:
    """The sections of one report (they share the analysis, the run and the list of MathML
    conversion failures)."""

    def __init__(
        self, system: System, analysis: LinearAnalysis, trajectory: Trajectory, failures: list[str]
    ) -> None:
        self.system = system
        self.analysis = analysis
        self.trajectory = trajectory
        self.arrays = analysis.arrays
        self.failures = failures
        self.section_ids: list[str] = []
        self.titles: list[tuple[str, str]] = []

    def math(self, latex: str, *, display: bool = True) -> Markup:
        return math_or_source(latex, display=display, failures=self.failures)

    def section(self, section_id: str, title: str, *parts: object) -> Markup:
        self.section_ids.append(section_id)
        self.titles.append((section_id, title))
        return Markup(
            f'<section id="{section_id}"><h2>{esc(title)}</h2>'
            + "".join(esc(p) for p in parts if p)
            + "</section>"
        )

    # -- header and overview -----------------------------------------------------------------

    def section_overview(self) -> Markup:
        a, arrays = self.analysis, self.arrays
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
        status = self.trajectory.status
        items.append(
            Markup(
                f"simulation over {fmt(float(self.trajectory.t[-1]))} s: "
                + (
                    esc(status)
                    if status == "finished"
                    else f"<strong>{esc(status)}</strong>: {esc(self.trajectory.message)}"
                )
            )
        )
        return self.section(
            "overview",
            "At a glance",
            Markup("<ul>" + "".join(f"<li>{i}</li>" for i in items) + "</ul>"),
        )

    # -- the diagram -------------------------------------------------------------------------

    def section_diagram(self) -> Markup:
        a = self.analysis
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
        return self.section(
            "diagram", "The system", Markup('<div class="grid2">'), *parts, Markup("</div>")
        )

    # -- parameters ----------------------------------------------------------------------------

    def section_parameters(self) -> Markup:
        system, arrays = self.system, self.arrays
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
                    for k, (name, s) in enumerate(
                        zip(arrays.spring_names, system.springs, strict=True)
                    )
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
        return self.section("parameters", "Parameters", gravity, bodies, springs, anchors, forces)

    # -- equilibrium and matrices ------------------------------------------------------------

    def section_equilibrium(self) -> Markup:
        a, arrays = self.analysis, self.arrays
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
            + self.math(r"q = (" + coords + ")", display=False)
            + " (rad for rolling bodies, m for sliders):</p>"
            + '<div class="formula">'
            + self.math(
                r"\mathbf{M}\,\ddot{q} + \mathbf{K}\,q = 0,\qquad \mathbf{M} = "
                + _tex_matrix(a.mass)
                + r"\ \mathrm{kg\,m^2},\qquad \mathbf{K} = "
                + _tex_matrix(a.stiffness)
                + r"\ \mathrm{N\,m}"
            )
            + "</div>"
        )
        return self.section(
            "equilibrium", "Equilibrium and equations of motion", found, bodies, springs, equations
        )

    # -- modes ---------------------------------------------------------------------------------

    def section_modes(self) -> Markup:
        a, ids = self.analysis, self.arrays.ids
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
                    + self.math(
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
                caption="The spring split about X̂ (paper's k1, k2; Ω² = Ω1² + Ω2², "
                "1/k = 1/k1 + 1/k2)",
                table_id="spring-split",
            )
        picture = (
            _figure(figures.plot_modes(a), "The normal modes drawn on the system.", "figure-modes")
            if a.modes
            else ""
        )
        return self.section("modes", "Normal modes", modes, shapes, ratio, split, picture)

    # -- stationary point ----------------------------------------------------------------------

    def section_stationary_point(self) -> Markup:
        a, arrays = self.analysis, self.arrays
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
                rf"{_tex_number(float(wi))}\,x_{{{_tex_id(b)}}}"
                for wi, b in zip(w, ids, strict=True)
            )
            parts.append(
                Markup(
                    "<p>The zero mode v₀ conserves Σ wᵢ ẋᵢ with wᵢ = Jᵢ v₀ᵢ / sᵢ "
                    "(docs/physics.md (M14)); for centre springs wᵢ ∝ (1+γᵢ) mᵢ, "
                    "the paper's eq. (c):</p>"
                    + '<div class="formula">'
                    + self.math(r"\hat{X} = \frac{\sum_i w_i x_i}{\sum_i w_i} = " + terms)
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
            run = self.trajectory
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
        return self.section("stationary-point", "The stationary point X̂", *parts)

    # -- friction --------------------------------------------------------------------------------

    def section_friction(self) -> Markup:
        a, arrays, run = self.analysis, self.arrays, self.trajectory
        ids = arrays.ids
        simulated = run.summary.get("max_friction_ratio") or {}
        intro = Markup(
            "<p>Rolling needs the static friction f (M8) within the normal force N (M9):</p>"
            + '<div class="formula">'
            + self.math(
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
        return self.section(
            "friction",
            "Friction needed vs μs",
            intro,
            friction,
            Markup(f'<p class="note">In the simulation: {esc("; ".join(events))}.</p>'),
            *plots,
        )

    # -- animation -------------------------------------------------------------------------------

    def section_animation(self, frames: int) -> Markup:
        data = animation_data(self.analysis, self.trajectory, frames)
        run = self.trajectory
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
            for b in self.arrays.ids
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
                [
                    "period (s): measured, linear",
                    Markup(
                        f"{fmt(summary.get('period_measured'))}, "
                        f"{fmt(summary.get('period_linear'))}"
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
        return self.section(
            "animation",
            "Simulation and animation",
            facts,
            player,
            note,
            _json_script("animation-data", data),
        )

    # -- plots -------------------------------------------------------------------------------

    def section_plots(self) -> Markup:
        run = self.trajectory
        if run.t.size < 2:
            return self.section(
                "plots",
                "Plots",
                Markup(
                    "<p>The simulation stopped at its start, so there is no motion to plot.</p>"
                ),
            )
        return self.section(
            "plots",
            "Plots",
            Markup('<div class="grid2">'),
            _figure(
                figures.plot_positions(run),
                "Centre positions about their start, with the centre of mass and X̂.",
                "figure-positions",
            ),
            _figure(
                figures.plot_energy(run), "Kinetic, potential and total energy.", "figure-energy"
            ),
            _figure(
                figures.plot_phase_portraits(run),
                "Phase portraits: displacement against velocity.",
                "figure-phase",
            ),
            Markup("</div>"),
        )

    # -- the derivation by the five methods -------------------------------------------------

    def section_derivation(self, derivation: Derivation | None, error: str | None) -> Markup:
        title = "Derivation by the paper's five methods"
        if derivation is None:
            return self.section(
                "derivation",
                title,
                Markup(f'<p class="verdict-bad">No derivation for this system: {esc(error)}</p>'),
            )
        return self.section("derivation", title, *self._derivation_parts(derivation))

    def _derivation_parts(self, derivation: Derivation) -> list[object]:
        check = derivation.cross_check
        parts: list[object] = [
            Markup(
                f"<p>{esc(derivation.subtitle)} SymPy derives the equations of motion by each "
                "method (the paper's Sec. 2 to 4 and appendices) and the cross-check compares them "
                "with the structure route (exact Q = −∂V/∂φ, K, det(K − Ω²M) = 0).</p>"
                '<p id="cross-check-verdict">Cross-check: '
                + _verdict(check.agree, "all methods that apply agree", "the methods differ")
                + f" ({esc(', '.join(check.applied))} applied"
                + (
                    f"; not applicable: {esc(', '.join(check.not_applicable))}"
                    if check.not_applicable
                    else ""
                )
                + ").</p>"
            )
        ]
        undecided = Markup('<span class="verdict-other">undecided (time budget)</span>')
        rows = [
            [
                c.method,
                c.what,
                undecided if c.agrees is None else _verdict(c.agrees, "agrees", "differs"),
            ]
            for c in check.checks
        ]
        rows += [
            [name, reason, Markup('<span class="verdict-other">not applicable</span>')]
            for name, reason in check.not_applicable.items()
        ]
        parts.append(
            table(
                ["method", "compared", "verdict"],
                rows,
                caption="Cross-check of the methods",
                table_id="cross-check",
            )
        )
        for number, section in enumerate(derivation_sections(derivation), 1):
            steps = []
            for step in section.steps:
                ref = f' <span class="ref">[{esc(step.ref)}]</span>' if step.ref else ""
                steps.append(
                    Markup(
                        f'<div class="step"><p class="why">{esc(step.words)}{ref}'
                        f'</p><div class="formula">{self.math(step.latex)}</div>'
                        "</div>"
                    )
                )
            note = f'<p class="note">{esc(section.note)}</p>' if section.note else ""
            parts.append(
                Markup(
                    f'<div class="method" id="derivation-{number}">'
                    f"<h3>{esc(section.title)}</h3>{note}" + "".join(steps) + "</div>"
                )
            )
        return parts

    # -- the paper's claims ----------------------------------------------------------------

    def section_paper_check(self, label: str, checks: Sequence[ClaimCheck]) -> Markup:
        words = {
            VERIFIED: ("✔ verified", "ok"),
            HOLDS_STATED: ("☑ holds under the paper's stated assumption", "ok"),
            HOLDS_ONLY_IF: ("⚠ holds only if", "other"),
            WRONG: ("✘ wrong", "bad"),
        }
        rows = []
        for check in checks:
            text, css = words[check.verdict]
            rows.append(
                [
                    check.claim.location,
                    Markup(
                        f"{esc(check.claim.statement)}<br>"
                        f'<span class="cellmath">{self.math(check.claim.latex, display=False)}'
                        f"</span><br><q>{esc(check.claim.quote)}</q>"
                    ),
                    Markup(
                        f'<span class="verdict-{css}" data-verdict="{esc(check.verdict)}">'
                        f"{esc(text)}</span>"
                    ),
                    Markup(
                        f'<span class="cellmath">{self.math(check.correction, display=False)}'
                        "</span>"
                    )
                    if check.correction
                    else "–",
                    check.reason,
                ]
            )
        counts = {v: sum(1 for c in checks if c.verdict == v) for v in VERDICTS}
        intro = Markup(
            f"<p>This system is the paper's {esc(label)}. Each quantitative statement the paper "
            "makes about it (quoted from its source) is derived again by rollspring's derivation "
            "engine, on the paper's system with its parameters as symbols (m₁, m₂, R, k …), and "
            "compared with <code>simplify(paper − derived) == 0</code>: "
            f"{counts[VERIFIED]} verified, {counts[HOLDS_STATED]} hold under an assumption the "
            f"paper states, {counts[HOLDS_ONLY_IF]} hold only under a condition the paper does "
            f"not state, {counts[WRONG]} wrong. "
            "(<code>rollspring paper-check</code> lists every statement of the paper.)</p>"
        )
        return self.section(
            "paper-check",
            "The paper's claims, checked",
            intro,
            table(
                ["where", "claim", "verdict", "correction", "reason"],
                rows,
                caption=f"Claims about the paper's {label}",
                table_id="paper-claims",
            ),
        )

    # -- warnings, conventions, data ---------------------------------------------------------

    def section_warnings(self) -> Markup:
        warnings = self.analysis.warnings
        body = (
            Markup(
                '<ul class="warnings">' + "".join(f"<li>{esc(w)}</li>" for w in warnings) + "</ul>"
            )
            if warnings
            else Markup("<p>None.</p>")
        )
        conventions = Markup(
            "<dl>"
            + "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in CONVENTIONS.items())
            + "</dl>"
        )
        return self.section(
            "warnings",
            "Warnings and conventions",
            body,
            Markup("<h3>Conventions</h3>"),
            conventions,
        )

    def section_data(self) -> Markup:
        def encoded(text: str) -> str:
            return base64.b64encode(text.encode("utf-8")).decode("ascii")

        def as_json(data: Any) -> str:
            return json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False)

        csv = encoded(trajectory_csv(self.trajectory))
        summary = encoded(as_json(summary_json(self.trajectory)))
        analysis = encoded(as_json(self.analysis.to_dict()))
        links = Markup(
            '<p class="download">Embedded in this file: '
            f'<a download="analysis.json" href="data:application/json;base64,{analysis}">'
            "analysis.json</a> (as <code>rollspring analyze --json</code>), "
            f'<a download="trajectory.csv" href="data:text/csv;base64,{csv}">trajectory.csv</a>'
            f' and <a download="summary.json" href="data:application/json;base64,{summary}">'
            "summary.json</a> (as <code>rollspring simulate --out</code>).</p>"
        )
        return self.section(
            "data", "Data", links, _json_script("analysis-data", self.analysis.to_dict())
        )

    # -- the document ------------------------------------------------------------------------

    def document(self, sections: list[Markup]) -> str:
        return page_document(self.system, self.titles, sections)


def page_document(system: System, titles: list[tuple[str, str]], sections: list[Markup]) -> str:
    """The whole page: head (no request allowed), title, table of contents and ``sections``."""
    from rollspring._version import version

    __version__ = version()
    title = system.name or "system"
    toc = " ".join(f'<a href="#{sid}">{esc(t)}</a>' for sid, t in titles)
    description = f"<p>{esc(system.description)}</p>" if system.description else ""
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        # nothing may be fetched: images and data are embedded, scripts and styles inline
        '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
        "img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'\">"
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f'<meta name="generator" content="rollspring {esc(__version__)}">'
        '<link rel="icon" href="data:,">'
        f"<title>rollspring report: {esc(title)}</title><style>{CSS}</style></head><body>"
        f'<main><header class="page"><h1>{esc(title)}</h1>{description}'
        f'<nav class="toc">{toc}</nav></header>'
        + "".join(sections)
        + f"<footer>Made by rollspring {esc(__version__)}. One file, no network: every "
        "image, formula (MathML) and data set is in it.</footer></main>"
        f"<script>{PLAYER_JS}</script></body></html>\n"
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
