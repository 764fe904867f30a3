r"""Notebook display: HTML (a diagram, tables) and LaTeX (math) for rollspring's objects.

Matplotlib is imported only when something is drawn, so registering is cheap. Nothing here
edits the classes of the lower layers: :func:`register_formatters` registers the
functions below with IPython's display formatters (``formatters['text/html'].for_type``), so a
:class:`~rollspring.model.System`, a :class:`~rollspring.analysis.LinearAnalysis` (the normal
modes), a :class:`~rollspring.analysis.Mode` and a :class:`~rollspring.simulate.Trajectory`
render as rich output in Jupyter.

Public functions
----------------
* :func:`system_html` ``(system) -> str``: the diagram and tables of bodies, springs, anchors.
* :func:`analysis_html` ``(analysis) -> str``: the mode figure, a modes table, :math:`\hat X`,
  the matrices :math:`M`, :math:`K` (LaTeX, typeset by the notebook), warnings.
* :func:`analysis_latex` ``(analysis) -> str``: :math:`M\ddot u + Ku = 0` with the matrices and
  :math:`\omega`.
* :func:`mode_html` ``(mode) -> str``: one mode's frequency and shape.
* :func:`trajectory_html` ``(trajectory) -> str``: the summary table and the positions plot.
* :func:`register_formatters` ``(ipython=None) -> bool``.
* :func:`animate_inline` ``(trajectory, **options) -> IPython.display.HTML``: the JS animation.
* :func:`trajectory_to_pandas` ``(trajectory) -> pandas.DataFrame`` (index ``t``, the CSV
  columns, units in ``.attrs["units"]``).
* :func:`trajectory_to_xarray` ``(trajectory) -> xarray.Dataset`` (dimensions ``time``,
  ``body``, ``spring``; a ``units`` attribute on every variable).
"""

from __future__ import annotations

import base64
import html
from typing import Any

import numpy as np

from rollspring.analysis import LinearAnalysis, Mode
from rollspring.model import System
from rollspring.outputs.numbers import attachment_words, integrator_words
from rollspring.outputs.numbers import short_number as _g
from rollspring.simulate import Trajectory

__all__ = [
    "analysis_html",
    "analysis_latex",
    "animate_inline",
    "mode_html",
    "register_formatters",
    "system_html",
    "trajectory_html",
    "trajectory_to_pandas",
    "trajectory_to_xarray",
]

#: Resolution of the figures embedded in notebook output (a 6.4-inch figure is 640 px wide).
NOTEBOOK_DPI = 100

_TABLE = (
    '<table style="border-collapse: collapse; margin: 0.3em 0; font-size: 0.92em">'
    "{head}{rows}</table>"
)
_CELL = 'style="padding: 0.15em 0.6em; text-align: {align}; border-bottom: 1px solid #ddd"'


def _table(header: list[str], rows: list[list[Any]], caption: str = "") -> str:
    def cells(values: list[Any], tag: str) -> str:
        out = []
        for k, value in enumerate(values):
            align = "left" if k == 0 else "right"
            out.append(f"<{tag} {_CELL.format(align=align)}>{value}</{tag}>")
        return "<tr>" + "".join(out) + "</tr>"

    head = cells([html.escape(h) for h in header], "th")
    body = "".join(cells(row, "td") for row in rows)
    title = (
        f'<div style="font-weight: bold; margin-top: 0.6em">{html.escape(caption)}</div>'
        if caption
        else ""
    )
    return title + _TABLE.format(head=head, rows=body)


def _image(fig: Any) -> str:
    from rollspring.outputs.figures import figure_png

    data = base64.b64encode(figure_png(fig, dpi=NOTEBOOK_DPI)).decode("ascii")
    width = round(fig.get_figwidth() * NOTEBOOK_DPI)
    return (
        f'<img src="data:image/png;base64,{data}" width="{width}" '
        'style="max-width: 100%; height: auto" alt="rollspring figure">'
    )


def _heading(system: System, kind: str) -> str:
    name = html.escape(system.name or "system")
    text = (
        f'<div style="font-size: 1.1em"><b>{name}</b> '
        f'<span style="color: #666">({kind})</span></div>'
    )
    if system.description:
        text += f'<div style="color: #444; max-width: 48em">{html.escape(system.description)}</div>'
    return text


def system_html(system: System) -> str:
    """The system as HTML: its diagram (initial placement, CM on the floor) and tables of the
    bodies, springs, anchors and applied forces, as given in the file (SI units)."""
    from rollspring.outputs.figures import plot_system

    parts = [_heading(system, "system"), _image(plot_system(system, title=False).figure)]
    rows = []
    for body in system.bodies:
        rows.append(
            [
                html.escape(body.id),
                body.shape,
                _g(body.mass, 4),
                _g(body.radius, 4),
                _g(body.track_height, 4),
                _g(body.x, 6),
                _g(body.v, 6),
                _g(body.mu_static, 3) if body.rolls else "–",
            ]
        )
    parts.append(
        _table(
            ["body", "shape", "m (kg)", "R (m)", "track (m)", "x (m)", "v (m/s)", "μs"],
            rows,
            "Bodies",
        )
    )
    if system.springs:
        rows = []
        for spring, rest in zip(system.springs, system.rest_lengths, strict=True):
            a, b = spring.attachments
            rows.append(
                [
                    html.escape(" – ".join(spring.ends)),
                    _g(spring.stiffness, 6),
                    _g(rest, 6),
                    _g(spring.damping, 4),
                    f"{attachment_words(a)}; {attachment_words(b)}",
                ]
            )
        parts.append(
            _table(["spring", "k (N/m)", "L₀ (m)", "c (N s/m)", "attached at"], rows, "Springs")
        )
    if system.anchors:
        parts.append(
            _table(
                ["anchor", "x (m)", "y (m)"],
                [[html.escape(a.id), _g(a.x), _g(a.y)] for a in system.anchors],
                "Anchors",
            )
        )
    if system.forces:
        parts.append(
            _table(
                ["force on", "at", "Fx (N)", "Fy (N)"],
                [
                    [html.escape(f.body), attachment_words(f.at), _g(f.fx), _g(f.fy)]
                    for f in system.forces
                ],
                "Applied forces",
            )
        )
    parts.append(f'<div style="color: #666">g = {_g(system.gravity)} m/s²</div>')
    return "<div>" + "".join(parts) + "</div>"


def _matrix_latex(matrix: np.ndarray, digits: int = 6) -> str:
    rows = [" & ".join(_g(v, digits).replace("∞", r"\infty") for v in row) for row in matrix]
    return r"\begin{pmatrix}" + r" \\ ".join(rows) + r"\end{pmatrix}"


def analysis_latex(analysis: LinearAnalysis) -> str:
    r"""The linearised equations as LaTeX: :math:`M\ddot u + K u = 0` with the numbers of
    :math:`M = \mathrm{diag}(J_i)` and the exact Hessian :math:`K` (docs/physics.md (M12)), the
    coordinates, and the frequencies :math:`\omega_n`."""
    coordinates = ", ".join(
        (r"\varphi" if rolls else "x") + r"_{\mathrm{" + name.replace("_", r"\_") + "}}"
        for name, rolls in zip(analysis.ids, analysis.arrays.rolls > 0, strict=True)
    )
    omegas = ", ".join(_g(m.omega, 6) for m in analysis.modes)
    return (
        r"$$M\ddot u + K u = 0,\qquad u = ("
        + coordinates
        + r") - u^*,\qquad M = "
        + _matrix_latex(analysis.mass)
        + r",\quad K = "
        + _matrix_latex(analysis.stiffness)
        + r",\qquad \omega = ("
        + omegas
        + r")\ \mathrm{rad/s}$$"
    )


def _mode_label(number: int, mode: Mode) -> str:
    return {"zero": f"{number} (zero)", "unstable": f"{number} (unstable)"}.get(
        mode.kind, str(number)
    )


def analysis_html(analysis: LinearAnalysis) -> str:
    r"""The normal modes as HTML: one panel per mode (arrows on the diagram, with
    :math:`\omega`), a table of frequencies and shapes, the stationary point, the matrices and
    the warnings."""
    from rollspring.outputs.figures import plot_modes

    ids = analysis.ids
    parts = [_heading(analysis.system, "normal modes"), _image(plot_modes(analysis))]
    rows = []
    for n, mode in enumerate(analysis.modes, 1):
        rows.append(
            [_mode_label(n, mode), _g(mode.omega, 8), _g(mode.frequency), _g(mode.period)]
            + [_g(float(v), 4) for v in mode.shape_x]
            + [_g(float(v), 4) for v in mode.friction]
        )
    header = (
        ["mode", "ω (rad/s)", "f (Hz)", "period (s)"]
        + [f"x {i}" for i in ids]
        + [f"f {i} (N)" for i in ids]
    )
    parts.append(
        _table(
            [html.escape(h) for h in header],
            rows,
            "Normal modes: centre displacement x (largest = 1) and friction f along it",
        )
    )
    if analysis.stationary_weights is not None:
        weights = " + ".join(
            f"{w:.6g}·x<sub>{html.escape(i)}</sub>"
            for i, w in zip(ids, analysis.stationary_weights, strict=True)
        )
        mass = analysis.arrays.mass
        is_cm = bool(np.allclose(analysis.stationary_weights, mass / mass.sum()))
        parts.append(
            f"<p>Stationary point X̂ = {weights} = "
            f"{_g(analysis.stationary_position)} m "
            f"({'the centre of mass' if is_cm else 'not the centre of mass'})</p>"
        )
    else:
        parts.append("<p>No stationary point (no single zero mode).</p>")
    if (
        analysis.required_mu is not None
        and analysis.amplitude is not None
        and analysis.friction_amplitude is not None
    ):
        parts.append(
            _table(
                ["body", "amplitude (m)", "|f| max (N)", "μ needed", "μs"],
                [
                    [
                        html.escape(i),
                        _g(analysis.amplitude[k]),
                        _g(analysis.friction_amplitude[k]),
                        _g(analysis.required_mu[k], 4),
                        _g(analysis.system.bodies[k].mu_static, 3),
                    ]
                    for k, i in enumerate(ids)
                ],
                "Linear response",
            )
        )
    parts.append(f"<div>{analysis_latex(analysis)}</div>")
    for warning in analysis.warnings:
        parts.append(f'<p style="color: #a50026">warning: {html.escape(warning)}</p>')
    return "<div>" + "".join(parts) + "</div>"


def mode_html(mode: Mode) -> str:
    """One normal mode: kind, ω, frequency, period and its shape (largest displacement 1)."""
    rows = [
        [str(k + 1), _g(float(x), 4), _g(float(q), 4), _g(float(f), 4)]
        for k, (x, q, f) in enumerate(zip(mode.shape_x, mode.shape_q, mode.friction, strict=True))
    ]
    head = (
        f"<p><b>{mode.kind} mode</b>: ω = {_g(mode.omega, 8)} rad/s, "
        f"f = {_g(mode.frequency)} Hz, period {_g(mode.period)} s</p>"
    )
    return "<div>" + head + _table(["body #", "x", "φ or x", "f (N)"], rows) + "</div>"


def trajectory_html(trajectory: Trajectory) -> str:
    r"""A run as HTML: status, integrator, energy error, periods, first slip and lift-off,
    per-body extremes, and the plot of centre positions with the CM and :math:`\hat X`."""
    from rollspring.outputs.figures import plot_positions

    summary = trajectory.summary
    parts = [_heading(trajectory.system, "trajectory")]

    def event(kind: str) -> str:
        found = summary.get(kind)
        if not found:
            return "none"
        return f"{html.escape(str(found['body']))} at {_g(found['time'])} s"

    rows = [
        [
            "status",
            html.escape(trajectory.status)
            + (f" – {html.escape(trajectory.message)}" if trajectory.message else ""),
        ],
        ["time", f"0 … {_g(float(trajectory.t[-1]))} s, {trajectory.t.size} outputs"],
        [
            "integrator",
            html.escape(
                integrator_words(
                    trajectory.steps_by_integrator, trajectory.step, trajectory.integrator
                )
            ),
        ],
        [
            "energy (J)",
            f"{_g(summary.get('energy'))}, relative error {_g(summary.get('energy_error'), 3)}",
        ],
        [
            "period (s)",
            f"measured {_g(summary.get('period_measured'), 12)}, linear "
            f"{_g(summary.get('period_linear'), 12)}",
        ],
        ["first slip", event("first_slip")],
        ["first lift-off", event("first_liftoff")],
    ]
    parts.append(_table(["", ""], rows, "Run"))
    ratio = summary.get("max_friction_ratio", {})
    normal = summary.get("min_normal_force", {})
    body_rows = []
    for i, name in enumerate(trajectory.ids):
        body_rows.append(
            [
                html.escape(name),
                _g(ratio.get(name)),
                _g(normal.get(name)),
                _g(float(trajectory.x[-1, i])),
                _g(float(trajectory.v[-1, i])),
                _g(float(trajectory.phi[-1, i])),
            ]
        )
    parts.append(
        _table(
            ["body", "max |f|/N", "min N (N)", "final x (m)", "final v (m/s)", "final φ (rad)"],
            body_rows,
            "Bodies",
        )
    )
    parts.append(_image(plot_positions(trajectory).figure))
    return "<div>" + "".join(parts) + "</div>"


def register_formatters(ipython: Any = None) -> bool:
    """Register the HTML (and LaTeX) display of System, LinearAnalysis, Mode and Trajectory
    with ``ipython`` (default: the running IPython, if any). Returns False when there is none."""
    if ipython is None:
        try:
            from IPython import get_ipython
        except ImportError:
            return False
        ipython = get_ipython()
        if ipython is None:
            return False
    formatters = ipython.display_formatter.formatters
    html_formatter = formatters["text/html"]
    html_formatter.for_type(System, system_html)
    html_formatter.for_type(LinearAnalysis, analysis_html)
    html_formatter.for_type(Mode, mode_html)
    html_formatter.for_type(Trajectory, trajectory_html)
    formatters["text/latex"].for_type(LinearAnalysis, analysis_latex)
    return True


def animate_inline(trajectory: Trajectory, **options: Any) -> Any:
    """The trajectory's animation as an ``IPython.display.HTML`` object (Matplotlib's JS
    player, self-contained); ``options`` as for
    :func:`~rollspring.outputs.animation.animation_html` (duration, speed, fps, dpi, forces)."""
    try:
        from IPython.display import HTML
    except ImportError as exc:  # pragma: no cover - IPython comes with every notebook
        raise ImportError("animate_inline needs IPython (pip install ipython)") from exc
    from rollspring.outputs.animation import animation_html

    return HTML(animation_html(trajectory, **options))


def _columns(trajectory: Trajectory) -> dict[str, tuple[str, np.ndarray]]:
    columns = dict(trajectory.columns())
    columns.pop("t")
    return columns


def trajectory_to_pandas(trajectory: Trajectory) -> Any:
    """The trajectory as a ``pandas.DataFrame``: index ``t`` (s), one column per output named as
    in ``trajectory.csv`` (``<body>.x``, ``<spring>.tension``, ``energy``, ...), the
    ``slipping`` columns boolean; ``.attrs["units"]`` maps every column to its unit."""
    try:
        import pandas as pd
    except ImportError as exc:
        raise ImportError("trajectory_to_pandas needs pandas: pip install pandas") from exc
    columns = _columns(trajectory)
    data = {
        name: (values > 0.5 if name.endswith(".slipping") else values)
        for name, (_, values) in columns.items()
    }
    frame = pd.DataFrame(data, index=pd.Index(trajectory.t, name="t"))
    frame.attrs["units"] = {"t": "s", **{name: unit for name, (unit, _) in columns.items()}}
    frame.attrs["system"] = trajectory.system.name
    frame.attrs["status"] = trajectory.status
    return frame


def trajectory_to_xarray(trajectory: Trajectory) -> Any:
    """The trajectory as an ``xarray.Dataset`` with dimensions ``time``, ``body`` and
    ``spring``: per body ``x``, ``phi``, ``v``, ``omega``, ``friction``, ``normal``,
    ``friction_ratio``, ``slipping``; per spring ``length`` and ``tension``; ``kinetic``,
    ``potential``, ``energy``, ``cm_x`` and ``stationary_x`` (when the system has one); the body
    coordinates carry ``shape``, ``mass`` and ``radius``. Every variable has a ``units``
    attribute."""
    try:
        import xarray as xr
    except ImportError as exc:
        raise ImportError("trajectory_to_xarray needs xarray: pip install xarray") from exc
    tr = trajectory
    per_body = {
        "x": ("m", tr.x, "centre position"),
        "phi": ("rad", tr.phi, "rotation from the initial placement, clockwise positive"),
        "v": ("m/s", tr.v, "centre velocity"),
        "omega": ("rad/s", tr.omega, "angular velocity, clockwise positive"),
        "friction": ("N", tr.friction, "friction on the body, positive along +x"),
        "normal": ("N", tr.normal, "normal force"),
        "friction_ratio": ("1", tr.friction_ratio, "|f| / (mu_s N)"),
        "slipping": ("1", np.asarray(tr.slipping, dtype=bool), "the body slips"),
    }
    variables: dict[str, Any] = {}
    for name, (unit, values, text) in per_body.items():
        variables[name] = (("time", "body"), values, {"units": unit, "long_name": text})
    for name, unit, values, text in (
        ("length", "m", tr.spring_length, "spring length"),
        ("tension", "N", tr.spring_tension, "spring tension, positive when stretched"),
    ):
        variables[name] = (("time", "spring"), values, {"units": unit, "long_name": text})
    for name, unit, series, text in (
        ("kinetic", "J", tr.kinetic, "kinetic energy"),
        ("potential", "J", tr.potential, "potential energy"),
        ("energy", "J", tr.energy, "total energy"),
        ("cm_x", "m", tr.cm_x, "centre of mass"),
        ("stationary_x", "m", tr.stationary_x, "stationary point X-hat"),
    ):
        if series is not None:
            variables[name] = (("time",), series, {"units": unit, "long_name": text})
    bodies = tr.system.bodies
    coords = {
        "time": ("time", tr.t, {"units": "s"}),
        "body": ("body", list(tr.ids)),
        "spring": ("spring", list(tr.spring_names)),
        "shape": ("body", [b.shape for b in bodies]),
        "mass": ("body", [b.mass for b in bodies], {"units": "kg"}),
        "radius": ("body", [b.radius for b in bodies], {"units": "m"}),
    }
    attrs = {"system": tr.system.name, "status": tr.status, "integrator": str(tr.integrator)}
    return xr.Dataset(variables, coords=coords, attrs=attrs)
