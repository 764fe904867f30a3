"""Analyses and simulations as the interfaces deliver them.

:func:`analysis_payload` is the object ``rollspring analyze --json`` prints and
``POST /api/analyze`` answers; :func:`run_simulation` starts a run the way an interface asks
for it (from the file's placement, or displaced along a normal mode; :func:`run_request` from
arguments checked already) and :func:`simulation_payload` is the web API's form of the result:
the summary ``rollspring simulate --json`` prints plus every output array.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from rollspring.analysis import LinearAnalysis, analyze, linear_motion
from rollspring.analysis.modal import AnalysisRequest, analysis_request, run_analysis
from rollspring.errors import SimulationError
from rollspring.model import System, rolled

if TYPE_CHECKING:  # the simulation (compiled kernels) loads only when a run is asked for
    from rollspring.simulate import Trajectory
    from rollspring.simulate.request import SimulationRequest

__all__ = [
    "ModeStart",
    "SimulationRun",
    "analysis_payload",
    "mode_start",
    "run_request",
    "run_simulation",
    "simulation_payload",
    "whole_system",
]


def analysis_payload(
    system: System, request: AnalysisRequest | None = None
) -> tuple[dict[str, Any], list[str]]:
    """The linear analysis of ``system`` as JSON (``analyze --json``) and its warnings.
    ``request``: its arguments checked already
    (:func:`~rollspring.analysis.modal.analysis_request`; None: the default modes); the cost is
    not estimated (the interfaces check it themselves: ``--yes``, the web's bounds)."""
    result = run_analysis(system, analysis_request(system) if request is None else request)
    return result.to_dict(), list(result.warnings)


@dataclass(frozen=True)
class ModeStart:
    """Start at rest in the equilibrium displaced along mode ``mode`` (an index into the
    analysis' ``modes``, sorted by ω) so that the largest centre displacement is ``amplitude``
    metres."""

    mode: int
    amplitude: float


@dataclass
class SimulationRun:
    """A finished run: the system as it was started (``system``: the file's placement, or the
    displaced one of a :class:`ModeStart`), its ``trajectory`` and, when asked for, the
    ``linear`` motion from the same start (centre positions over ``trajectory.t``)."""

    system: System
    trajectory: Trajectory
    linear: np.ndarray | None


def mode_start(system: System, start: ModeStart, analysis: LinearAnalysis | None = None) -> System:
    r"""``system`` placed at rest at :math:`q^* + a\,v_n` — the equilibrium displaced along the
    oscillating mode :math:`v_n` (shape normalised to a largest centre displacement of 1 m)
    with amplitude :math:`a` — by rolling the bodies there (:func:`rollspring.model.rolled`)."""
    analysis = analyze(system) if analysis is None else analysis
    modes = analysis.modes
    if not 0 <= start.mode < len(modes):
        raise SimulationError(
            f"start.mode: no mode {start.mode} (the system has modes 0 to {len(modes) - 1})"
        )
    mode = modes[start.mode]
    if mode.kind != "oscillating":
        raise SimulationError(
            f"start.mode: mode {start.mode} is a {mode.kind} mode; only an "
            "oscillating mode can be played"
        )
    if not analysis.equilibrium.found:
        raise SimulationError(f"start.mode: {analysis.equilibrium.reason}")
    q = analysis.equilibrium.q + start.amplitude * mode.shape_q
    return rolled(system, q, velocities=np.zeros(len(system.bodies)))


def run_simulation(
    system: System,
    duration: float,
    *,
    rtol: float = 1e-8,
    outputs: int = 2001,
    on_slip: str = "stop",
    integrator: str = "auto",
    start: ModeStart | None = None,
    linear: bool = False,
    progress: Callable[[float], None] | None = None,
) -> SimulationRun:
    """Simulate ``system`` for ``duration`` s (:func:`rollspring.simulate`), from its file's
    placement or from a :class:`ModeStart`; with ``linear``, also the linear motion from the
    same start (:func:`rollspring.analysis.linear_motion`; None where the system has no
    equilibrium). The arguments are checked as :func:`rollspring.simulate` checks them
    (:func:`~rollspring.simulate.request.simulation_request`), then :func:`run_request` runs
    them: the cost is not estimated (the interfaces check it themselves: ``--yes``, the web's
    bounds)."""
    from rollspring.simulate.request import simulation_request

    request = simulation_request(
        duration, rtol=rtol, integrator=integrator, on_slip=on_slip, n_output=outputs
    )
    return run_request(system, request, start=start, linear=linear, progress=progress)


def run_request(
    system: System,
    request: SimulationRequest,
    *,
    start: ModeStart | None = None,
    linear: bool = False,
    progress: Callable[[float], None] | None = None,
) -> SimulationRun:
    """:func:`run_simulation` of a request whose arguments are checked already (an interface
    that checked them and estimated the cost once:
    :func:`~rollspring.simulate.request.simulation_request`,
    :func:`~rollspring.simulate.costs.request_cost`): nothing is checked or estimated again."""
    from rollspring.simulate.run import run_request as run

    analysis = _analysis(system) if start is not None or linear else None
    if start is not None:
        system = mode_start(system, start, analysis)
        analysis = _analysis(system) if linear else None
    trajectory = run(system, request, progress)
    line = None
    if linear and analysis is not None and analysis.equilibrium.found:
        line = linear_motion(analysis, trajectory.t)
    return SimulationRun(system=system, trajectory=trajectory, linear=line)


def _analysis(system: System) -> LinearAnalysis:
    """The analysis a run starts from or is compared with (every mode by size): not estimated,
    as the run it serves is not."""
    return run_analysis(system, analysis_request(system))


def simulation_payload(run: SimulationRun) -> dict[str, Any]:
    """The run as the web API gives it (docs/web-api.md): the summary (JSON-ready), then every
    output over ``t`` (SI units) as contiguous NumPy arrays — per body, per spring, energies,
    the CM and X̂. :func:`rollspring.outputs.json_ready` turns it into plain JSON values (an
    infinite friction ratio, N <= 0, becomes ``null``); orjson writes it directly."""
    from rollspring.outputs import summary_json

    trajectory = run.trajectory

    def column(values: np.ndarray, i: int) -> np.ndarray:
        return np.ascontiguousarray(values[:, i])

    bodies = {}
    for i, name in enumerate(trajectory.ids):
        bodies[name] = {
            "x": column(trajectory.x, i),
            "phi": column(trajectory.phi, i),
            "v": column(trajectory.v, i),
            "omega": column(trajectory.omega, i),
            "friction": column(trajectory.friction, i),
            "normal": column(trajectory.normal, i),
            "friction_ratio": column(trajectory.friction_ratio, i),
            "slipping": column(trajectory.slipping, i),
        }
    whole = whole_system(trajectory)
    return {
        "summary": summary_json(trajectory),
        "t": trajectory.t,
        "bodies": bodies,
        "springs": [
            {
                "length": column(trajectory.spring_length, s),
                "tension": column(trajectory.spring_tension, s),
            }
            for s in range(len(trajectory.spring_names))
        ],
        "energy": {
            "kinetic": trajectory.kinetic,
            "potential": trajectory.potential,
            "total": trajectory.energy,
            "translational": whole["translational"],
            "rotational": whole["rotational"],
        },
        "cm_x": trajectory.cm_x,
        "cm_a": whole["cm_a"],
        "friction_x": whole["friction_x"],
        "other_external_x": whole["other_external_x"],
        "total_mass": whole["total_mass"],
        "stationary_x": trajectory.stationary_x,
        "initial": {body.id: {"x": body.x, "v": body.v} for body in run.system.bodies},
        "linear": None
        if run.linear is None
        else {name: column(run.linear, i) for i, name in enumerate(trajectory.ids)},
    }


def whole_system(trajectory: Trajectory) -> dict[str, Any]:
    r"""The whole system's Newton's second law and its kinetic energy split, over ``t``.

    ``cm_a``: the centre of mass's acceleration :math:`a_{CM} = \sum m_i\ddot x_i/\sum m_i`
    (m/s²) from the exact rolling equations of motion (:func:`rollspring.physics.accelerations`,
    :math:`\ddot x_i = s_i\ddot q_i`, at each output's positions and velocities); NaN (JSON
    ``null``) at an output where a body slips. ``friction_x``: :math:`\sum f_i` (N), the
    frictions, the only horizontal external forces of bodies joined to each other alone;
    ``other_external_x``: the rest of :math:`\sum F_{ix}` (N; wall springs, external forces; the
    springs between bodies cancel), so that
    :math:`(\sum m)\,a_{CM} = \sum f + \text{other}`. ``translational``
    :math:`\sum\tfrac12 m_i v_i^2` and ``rotational`` :math:`\sum\tfrac12 I_i\omega_i^2` (J),
    whose sum is the kinetic energy. ``total_mass``: :math:`\sum m_i` (kg)."""
    import dataclasses

    from rollspring.physics import accelerations, body_forces, system_arrays

    arrays = system_arrays(trajectory.system)
    rolls = arrays.rolls > 0
    x, phi = trajectory.x, trajectory.phi
    # the rolling coordinate q (the angle of a rolling body, the displacement of a slider) and
    # the reference positions x0 = x - s q it is measured from: the file's placement until a
    # body slips, shifted by each slip (constant while every body rolls)
    q = np.where(rolls, phi, x - arrays.x0)
    qdot = np.where(rolls, trajectory.omega, trajectory.v)
    offsets = x - arrays.scale * q
    n = len(trajectory.t)
    cm_a = np.full(n, np.nan)
    other = np.full(n, np.nan)
    rolling = ~trajectory.slipping.any(axis=1)
    mass = arrays.mass
    total_mass = float(np.sum(mass))
    if rolling.any():
        keys = np.round(offsets[rolling] / 1e-9).astype(np.int64)
        _, first, group = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        rows = np.flatnonzero(rolling)
        for g, start in enumerate(first):
            pick = rows[group.reshape(-1) == g]
            here = dataclasses.replace(arrays, x0=offsets[rows[start]])
            qddot = accelerations(here, q[pick], qdot[pick])
            cm_a[pick] = (arrays.scale * qddot) @ mass / total_mass
            other[pick] = np.sum(body_forces(here, q[pick], qdot[pick])[..., 0], axis=-1)
    central = arrays.gamma * mass * arrays.radius**2
    return {
        "cm_a": cm_a,
        "friction_x": np.sum(trajectory.friction, axis=1),
        "other_external_x": other,
        "total_mass": total_mass,
        "translational": 0.5 * (trajectory.v**2) @ mass,
        "rotational": 0.5 * (trajectory.omega**2) @ central,
    }
