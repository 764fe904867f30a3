r"""The report of a long chain (more than :data:`~rollspring.model.chains.LONG_CHAIN`
bodies): a summary instead of one row, curve or matrix entry per body.

The page holds the chain in a few lines (the kinds of bodies and springs, with their counts),
the wave measured against the lattice (:class:`~rollspring.analysis.waves.Waves`: the energy
centroid's speed beside the group velocity :math:`d\omega/dq` of the packet's wavenumber and
branch, or a struck end's front beside :math:`\max|v_g|`), space–time images of the
displacement, of the friction the rolling needs against :math:`\mu_s N` and of the energy with
its centroid and the group-velocity line (:func:`~rollspring.outputs.figures.plot_space_time`),
the chain animated with its friction pattern (:class:`~rollspring.outputs.animation.
ChainAnimation`, Matplotlib's JS player), the energy against time, notes, and the summary and
wave numbers as embedded JSON. Computed by :func:`rollspring.service.documents.build_report`.
"""

from __future__ import annotations

import base64
import json
import math
from collections.abc import Callable
from typing import Any

from rollspring.analysis.waves import Waves
from rollspring.model import System
from rollspring.outputs import figures
from rollspring.outputs.report._build import Report
from rollspring.outputs.report._html import Markup, Num, esc, fmt, table
from rollspring.outputs.report._page import _figure, _json_script, page_document
from rollspring.outputs.trajectory import summary_json
from rollspring.simulate import Trajectory

__all__ = ["CHAIN_FRAMES", "render_chain_report"]

#: Frames of the embedded chain animation (the whole run, played in about 5 s at 10 fps).
CHAIN_FRAMES = 50
_FPS = 10


def render_chain_report(
    system: System,
    trajectory: Trajectory,
    waves: Waves,
    *,
    frames: int | None = None,
    stage: Callable[[str, float], None] | None = None,
) -> Report:
    """The self-contained report page of a long chain from its ``trajectory`` and ``waves``
    (module docstring), with ``frames`` animation frames (default :data:`CHAIN_FRAMES`);
    ``stage`` is called after each stage with its name and the fraction of
    the rendering done (0..1)."""

    def done(name: str, fraction: float) -> None:
        if stage is not None:
            stage(name, fraction)

    titles: list[tuple[str, str]] = []

    def section(section_id: str, title: str, *parts: object) -> Markup:
        titles.append((section_id, title))
        return Markup(
            f'<section id="{section_id}"><h2>{esc(title)}</h2>'
            + "".join(esc(p) for p in parts if p)
            + "</section>"
        )

    sections = [
        section("overview", "At a glance", _overview(system, trajectory, waves)),
        section("chain", "The chain", *_chain_tables(system)),
        section("waves", "The wave against the lattice", *_wave_parts(waves)),
    ]
    done("tables", 0.1)
    if trajectory.t.size >= 2:
        sections.append(
            section(
                "space-time",
                "Space–time",
                _figure(
                    figures.plot_space_time(trajectory, waves),
                    "Displacement, the friction the rolling needs against μs N (signed) and the "
                    "energy per body, against rest position and time; the energy centroid and "
                    "the group-velocity line on the energy; the dash-dotted line ends the clear "
                    "window.",
                    "figure-space-time",
                ),
            )
        )
        done("space-time images", 0.3)
        count = CHAIN_FRAMES if frames is None else int(frames)
        sections.append(section("animation", "Animation", _animation(trajectory, waves, count)))
        done("animation", 0.9)
        sections.append(
            section(
                "energy",
                "Energy",
                _figure(
                    figures.plot_energy(trajectory),
                    "Kinetic, potential and total energy.",
                    "figure-energy",
                ),
            )
        )
    notes = [
        "A long chain's report summarises: the modal analysis, the matrices M and K, the "
        "per-body tables, the derivation and the trajectory CSV are left out "
        "(rollspring analyze, simulate --out and dispersion give them).",
        *waves.notes,
    ]
    sections.append(
        section(
            "warnings",
            "Notes",
            Markup(
                '<ul class="warnings">' + "".join(f"<li>{esc(n)}</li>" for n in notes) + "</ul>"
            ),
        )
    )
    sections.append(section("data", "Data", *_data(trajectory, waves)))
    html = page_document(system, titles, sections)
    done("assemble", 1.0)
    return Report(
        system=system,
        analysis=None,
        trajectory=trajectory,
        html=html,
        sections=[sid for sid, _ in titles],
    )


def _overview(system: System, trajectory: Trajectory, waves: Waves) -> Markup:
    items = [f"{len(system.bodies)} bodies, {len(system.springs)} springs"]
    if math.isfinite(waves.cell_length):
        items.append(f"read as a periodic lattice with a cell of {fmt(waves.cell_length)} m")
    status = trajectory.status
    items.append(
        f"simulation over {fmt(float(trajectory.t[-1]))} s: "
        + (status if status == "finished" else f"{status}: {trajectory.message}")
    )
    items.append(_verdict_words(waves))
    return Markup("<ul>" + "".join(f"<li>{esc(i)}</li>" for i in items) + "</ul>")


def _verdict_words(waves: Waves) -> str:
    if waves.kind == "packet":
        words = (
            f"a wave packet (q = {fmt(waves.wavenumber)} rad/m, branch {waves.branch}): its "
            f"energy centroid travels at {fmt(waves.speed)} m/s"
        )
        if math.isfinite(waves.group_velocity):
            words += (
                f", the group velocity dω/dq is {fmt(waves.group_velocity)} m/s "
                f"({100 * waves.relative_difference:+.2f} %)"
            )
        return words
    if waves.kind == "front":
        words = f"a struck end: the front travels at {fmt(waves.speed)} m/s"
        if math.isfinite(waves.max_group_velocity):
            words += (
                f", the largest group velocity is {fmt(waves.max_group_velocity)} m/s "
                f"({100 * waves.relative_difference:+.2f} %)"
            )
        return words
    return "the energy starts neither clear of the ends nor at one end: no speed measured"


def _chain_tables(system: System) -> list[object]:
    kinds: dict[tuple[Any, ...], int] = {}
    for b in system.bodies:
        key = (b.shape, b.mass, b.radius, b.track_height, b.mu_static if b.rolls else None)
        kinds[key] = kinds.get(key, 0) + 1
    bodies = table(
        ["shape", "m (kg)", "R (m)", "track height (m)", "μs", "count"],
        [
            [shape, Num(m), Num(r), Num(h), "–" if mu is None else Num(mu), str(count)]
            for (shape, m, r, h, mu), count in kinds.items()
        ],
        caption="Bodies, by kind",
        table_id="body-kinds",
    )
    rests = system.rest_lengths
    springs: dict[tuple[Any, ...], int] = {}
    for spring, rest in zip(system.springs, rests, strict=True):
        anchored = any(end not in system.body_map for end in spring.ends)
        kind = (spring.stiffness, round(float(rest), 12), spring.damping, anchored)
        springs[kind] = springs.get(kind, 0) + 1
    spring_table = table(
        ["k (N/m)", "rest length (m)", "damping (N s/m)", "to a wall", "count"],
        [
            [Num(k), Num(rest), Num(c), "yes" if wall else "no", str(count)]
            for (k, rest, c, wall), count in springs.items()
        ],
        caption="Springs, by kind",
        table_id="spring-kinds",
    )
    x = [b.x for b in system.bodies]
    span = Markup(
        f"<p>The bodies' centres start from x = {fmt(min(x))} m to {fmt(max(x))} m; "
        f"gravity g = {fmt(system.gravity)} m/s².</p>"
    )
    return [span, bodies, spring_table]


def _wave_parts(waves: Waves) -> list[object]:
    explain = Markup(
        "<p>Each body carries its kinetic energy ½J q̇² and half of the potential energy of "
        "each spring it shares (all of a spring to a wall); these sum to the total energy. The "
        "energy centroid X_E = Σ xᵢeᵢ / Σ eᵢ is fitted by a straight line (least squares) over "
        "the <em>clear window</em>: from the start while X_E ± 3σ_E (σ_E the energy's spread) "
        "is inside the chain, before the packet reaches an end. In a linear lattice a packet's "
        "energy travels at the group velocity dω/dq of its wavenumber q and branch (found from "
        "the motion at the start: the peak of its Bloch spectrum and the branch nearest its "
        "frequency); a struck end sends a front that no part of the disturbance outruns at the "
        "largest group velocity.</p>"
    )
    rows: list[list[object]] = [
        ["kind", waves.kind],
        ["clear window ends at (s)", Num(waves.window_end)],
        ["output rows in the window", str(waves.window)],
    ]
    if waves.kind == "packet":
        rows += [
            ["wavenumber q (rad/m)", Num(waves.wavenumber)],
            ["branch", str(waves.branch)],
            ["centroid speed, measured (m/s)", Num(waves.speed)],
            ["group velocity dω/dq (m/s)", Num(waves.group_velocity)],
        ]
    elif waves.kind == "front":
        rows += [["front speed, measured (m/s)", Num(waves.speed)]]
    rows += [
        ["largest group velocity over the zone (m/s)", Num(waves.max_group_velocity)],
        ["relative difference", Num(waves.relative_difference)],
        ["rms distance from the fitted line (m)", Num(waves.residual)],
    ]
    numbers = table(["quantity", "value"], rows, caption="The wave", table_id="wave-numbers")
    return [explain, numbers]


def _animation(trajectory: Trajectory, waves: Waves, frames: int) -> Markup:
    from rollspring.outputs.animation import animation_html

    duration = float(trajectory.t[-1] - trajectory.t[0])
    speed = max(duration / (max(frames - 1, 1) / _FPS), 1e-6)
    markup = animation_html(trajectory, speed=speed, fps=_FPS, dpi=60, waves=waves)
    note = Markup(
        "<p>Every body is a point at its rest position raised by its displacement, coloured by "
        "the friction it needs against μs N (signed: orange along +x); the strip below repeats "
        "the colours, the friction pattern travelling with the wave. The energy centroid and "
        f"X_E(0) + v_g t are the vertical lines. Played at {fmt(speed)}× real time.</p>"
    )
    return Markup(note + f'<div class="chain-animation">{markup}</div>')


def _data(trajectory: Trajectory, waves: Waves) -> list[object]:
    summary = json.dumps(summary_json(trajectory), indent=2, ensure_ascii=False, allow_nan=False)
    wave = json.dumps(waves.to_dict(), indent=2, ensure_ascii=False, allow_nan=False)

    def link(name: str, text: str) -> str:
        data = base64.b64encode(text.encode("utf-8")).decode("ascii")
        return f'<a download="{name}" href="data:application/json;base64,{data}">{name}</a>'

    return [
        Markup(
            '<p class="download">Embedded in this file: '
            f"{link('summary.json', summary)} (as <code>rollspring simulate --out</code>) and "
            f"{link('waves.json', wave)} (the wave's numbers).</p>"
        ),
        _json_script("wave-data", waves.to_dict()),
    ]
