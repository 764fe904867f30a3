r"""``simulate_batch``: one topology, arrays of parameter values, many runs at once.

Every run is the exact rolling motion :math:`J_i\ddot\varphi_i = Q_i(\varphi)` (PHYSICS.md (M7))
of the same system with some scalar parameters changed (masses, radii, friction coefficients,
initial positions and velocities, stiffnesses, rest lengths, gravity). The runs are integrated
by an explicit symplectic kick-drift-kick composition (valid because the mass matrix
:math:`\mathrm{diag}(J_i)` is constant, (M6)) with one fixed step for all runs, compiled with
Numba and spread over all cores. Each run keeps a handful of summary metrics, not its
trajectory (unless asked): the measured period, the amplitudes of the centre of mass and of the
stationary point :math:`\hat X`, the largest :math:`|f|/N` each body needed, the smallest normal
force, the energy error, and the first slip or lift-off with its instant.

How it works
------------
Runs are processed in blocks of :data:`BLOCK` (256) lanes, one block per task of a ``prange``
(all cores). Inside a block the state (per body the centre displacement :math:`y_i = s_i q_i`
and velocity :math:`\dot y_i`) and the running metrics are rows of a flat array, and every loop
runs over the 256 lanes with straight-line code that LLVM vectorises (AVX2: four runs per
instruction). That code is *generated* for the system (and cached, below): which spring ends
sit at a centre (no sine or cosine), which springs stay horizontal (length :math:`|dx|`, no
square root, constant normal forces), which bodies' slip test reduces to one threshold on a
spring's tension (a body on one horizontal centre spring: :math:`|f| = \gamma/(1+\gamma)|T|`,
(M10)), and which fields are per run (those that depend on the given parameter keys, loaded per
lane) or common (held in registers). Sine and cosine are evaluated by a vectorisable
polynomial (:data:`_SINCOS`) since ``math.sin`` would keep a loop scalar.

Each step checks every run (PHYSICS.md section 5): slip (:math:`|f_i| \ge \mu_s N_i`, compared
without division) and lift-off (:math:`N_i < 0`). An OR over the block says whether anything
happened; only then a scalar pass finds the lane, the body and the instant, interpolating the
margins linearly between the step and the previous one (reconstructed by a step backwards: the
compositions are time-reversible). The summary metrics (extremes, energy, period crossings) are
sampled every ``metric_every`` steps, chosen so that the fastest linear mode turns by at most
:data:`METRIC_PHASE` rad between samples (or every step, when one step turns it further): a
sampled extreme of a sinusoid is then within a factor
:math:`\cos(\text{METRIC_PHASE}/2) \approx 1 - 1.1\cdot10^{-4}` of the true one. A sample
costs several stages (:data:`SAMPLE_COST`), so runs with long steps (Yoshida-6 at moderate
tolerances) are dominated by it. A run's motion does not depend on this sampling (nor on the
other runs).

The generated module is written once, named by its hash, to ``$ROLLSPRING_KERNEL_DIR`` (else
``$XDG_CACHE_HOME/rollspring/batch-kernels``, else ``~/.cache/rollspring/batch-kernels``, else a
temporary directory), so Numba's ``cache=True`` keeps the compiled code between processes: the
first call for a new system or set of parameter keys compiles for several seconds, later ones
load in a fraction of a second. Nothing prunes that directory.
"""

from __future__ import annotations

import hashlib
import importlib.util
import math
import os
import re
import sys
import tempfile
import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rollspring.errors import ModelError, SimulationError
from rollspring.model import System
from rollspring.physics import system_arrays
from rollspring.physics.arrays import FloatArray

__all__ = [
    "BLOCK",
    "CHECK_COST",
    "INTEGRATORS",
    "METRIC_PHASE",
    "PARAMETER_QUANTITIES",
    "SAMPLE_COST",
    "SCHEMES",
    "STATUS_FINISHED",
    "STATUS_LIFTOFF",
    "STATUS_NAMES",
    "STATUS_NONFINITE",
    "STATUS_SLIP",
    "BatchResult",
    "run_cost",
    "simulate_batch",
]

#: Runs per block (lanes of the vectorised inner loops).
BLOCK = 256
_RS = BLOCK + 8  # row stride of the block-local arrays; padding avoids 4 KiB store/load aliasing

STATUS_FINISHED = 0
STATUS_NONFINITE = 1
STATUS_SLIP = 2
STATUS_LIFTOFF = 3
#: Status code -> name.
STATUS_NAMES = {STATUS_FINISHED: "finished", STATUS_NONFINITE: "nonfinite",
                STATUS_SLIP: "slip", STATUS_LIFTOFF: "liftoff"}

_Y4 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
_Y6 = (0.784513610477560, 0.235573213359357, -1.17767998417887)  # Yoshida 1990, solution A

#: name -> (order p, stage weights w_k, C_p): the relative frequency error of the composition is
#: C_p (omega h)^p (Verlet's 1/24 exact; the others measured on the harmonic oscillator).
SCHEMES: dict[str, tuple[int, tuple[float, ...], float]] = {
    "verlet": (2, (1.0,), 1.0 / 24.0),
    "yoshida4": (4, (_Y4, 1.0 - 2.0 * _Y4, _Y4), 0.0662),
    "yoshida6": (6, (*_Y6, 1.0 - 2.0 * sum(_Y6), *_Y6[::-1]), 0.00377),
}
#: Accepted values of ``integrator``.
INTEGRATORS = ("auto", *SCHEMES)
#: Largest omega*h any scheme may use (inside every scheme's stability interval, and at least
#: 12 steps per period of the fastest mode for the per-step checks).
_MAX_OMEGA_STEP = 0.5
#: Costs, in stages (force evaluations), of a step's slip and lift-off checks and of a metric
#: sample, measured on the hoop-cylinder kernel (0.66 ns a lane for a stage, 0.58-0.8 with the
#: checks, 3.3 for a sample; with sines and square roots the stage dominates more):
#: ``integrator="auto"`` takes the scheme of least
#: ``n_steps * (stages + CHECK_COST) + n_samples * SAMPLE_COST`` (:func:`run_cost`).
CHECK_COST = 0.25
SAMPLE_COST = 4.0
#: Largest phase (rad) of the fastest linear mode between two samples of the summary metrics.
METRIC_PHASE = 0.03

#: Quantities a parameter path may name: ``bodies.<id>.<q>``, ``springs.<index>.<q>``, ``gravity``.
PARAMETER_QUANTITIES = {
    "bodies": ("mass", "radius", "mu_static", "mu_kinetic", "x", "v"),
    "springs": ("stiffness", "rest_length"),
    "gravity": (),
}


# --------------------------------------------------------------------------------------------
# result


@dataclass
class BatchResult:
    r"""Per-run summary of a batch (arrays of length ``n_runs``; per body: ``(n_runs, n_bodies)``,
    columns in the order of ``ids``). SI units.

    * ``status`` (int8): :data:`STATUS_FINISHED` (0: rolled throughout), :data:`STATUS_SLIP` (2)
      or :data:`STATUS_LIFTOFF` (3) (the run's first event), :data:`STATUS_NONFINITE` (1: the
      state overflowed, which overrides an earlier event); ``status_names`` gives the names.
    * ``first_slip_time``, ``first_slip_body``: instant (s) and body index of the first slip
      or lift-off (whichever ``status`` says; the margin :math:`|f| - \mu_s N` or :math:`-N`
      interpolated linearly between steps); NaN and -1 if none. With ``stop_on_slip`` the run
      stops there and its metrics cover the motion up to the end of the step in which it
      happened (so ``max_friction_ratio`` may exceed :math:`\mu_s` and ``min_normal_force`` be
      negative by that step's overshoot); without, the run continues with rolling enforced.
    * ``period_measured``: mean interval between upward zero crossings of the rate of change of
      the first spring's length (the instants of its minima; for a single-mode motion the same
      as the upward crossings of the length through its mean), linearly interpolated between
      samples; NaN with fewer than two crossings or no spring.
    * ``cm_amplitude``: half of max - min of the centre-of-mass position
      :math:`X = \sum m_i x_i/\sum m_i` over the run.
    * ``stationary_amplitude``: the same for :math:`\hat X - \hat V t`,
      :math:`\hat X = \sum w_i x_i/\sum w_i`, :math:`w_i = (1+\gamma_i) m_i` (a slider: m), with
      its uniform motion :math:`\hat V = \sum w_i v_{i0}/\sum w_i` removed. Exactly stationary
      when every spring joins two centres and there are no anchors or forces (M11); for other
      systems it is this weighted mean, not the zero mode of (M14).
    * ``max_friction_ratio``: max over the samples of :math:`|f_i|/N_i` ((M8), (M9); 0 for a
      slider, inf if :math:`N_i` reached 0 with :math:`f_i \ne 0`); ``min_normal_force``: min
      :math:`N_i`.
    * ``energy_error``: max over the samples of :math:`|E - E_0|/|E_0|`,
      :math:`E = \sum \tfrac12 J_i\dot\varphi_i^2 + \sum\tfrac12 k(l-L_0)^2 - \sum F\cdot(P-P_0)`
      (0 if E stayed exactly at :math:`E_0 = 0`, inf if it left it).
    * ``final_x``, ``final_v``: centre positions and velocities at the end (for a run that
      stopped: at the end of the step in which it stopped).
    * ``t`` (n_output,) and ``x`` (n_runs, n_output, n_bodies) with ``keep_trajectories``:
      centre positions at evenly spaced times (NaN after a run stopped); otherwise None.

    ``parameters`` holds the broadcast parameter arrays; ``integrator``, ``step`` (s),
    ``n_steps`` and ``metric_every`` (steps between metric samples) describe the integration;
    ``omega_max`` is the highest linear frequency over the runs (rad/s) the step was chosen for;
    ``timings`` (s): ``prepare`` (parameters, plan, step), ``compile`` (generating, compiling or
    loading the kernel), ``integrate``, ``total``. :meth:`columns`, :meth:`to_dict` and
    :meth:`summary_table` give flat, JSON and text views.
    """

    ids: tuple[str, ...]
    parameters: dict[str, FloatArray]
    duration: float
    integrator: str
    step: float
    n_steps: int
    metric_every: int
    omega_max: float
    status: np.ndarray
    first_slip_time: FloatArray
    first_slip_body: np.ndarray
    period_measured: FloatArray
    cm_amplitude: FloatArray
    stationary_amplitude: FloatArray
    max_friction_ratio: FloatArray
    min_normal_force: FloatArray
    energy_error: FloatArray
    final_x: FloatArray
    final_v: FloatArray
    t: FloatArray | None = None
    x: FloatArray | None = None
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.status.shape[0])

    @property
    def status_names(self) -> np.ndarray:
        """``status`` as names (``finished``, ``slip``, ``liftoff``, ``nonfinite``)."""
        names = np.array([STATUS_NAMES[k] for k in sorted(STATUS_NAMES)], dtype=object)
        return names[self.status]

    def columns(self) -> dict[str, np.ndarray]:
        """Every per-run quantity as a flat column (per-body quantities as ``<id>.<name>``),
        parameters first; the rows are the runs."""
        out: dict[str, np.ndarray] = dict(self.parameters)
        out["status"] = self.status_names
        out["first_slip_time"] = self.first_slip_time
        out["first_slip_body"] = np.array(
            [self.ids[b] if b >= 0 else "" for b in self.first_slip_body], dtype=object)
        out["period_measured"] = self.period_measured
        out["cm_amplitude"] = self.cm_amplitude
        out["stationary_amplitude"] = self.stationary_amplitude
        out["energy_error"] = self.energy_error
        for i, name in enumerate(self.ids):
            out[f"{name}.max_friction_ratio"] = self.max_friction_ratio[:, i]
            out[f"{name}.min_normal_force"] = self.min_normal_force[:, i]
            out[f"{name}.final_x"] = self.final_x[:, i]
            out[f"{name}.final_v"] = self.final_v[:, i]
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the integration settings and every column as a list."""
        def plain(values: np.ndarray) -> list[Any]:
            """Numbers as floats/ints (None where not finite), names as strings."""
            if values.dtype.kind in "iu":
                return [int(v) for v in values]
            if values.dtype.kind == "f":
                return [float(v) if math.isfinite(v) else None for v in values]
            return [str(v) for v in values]

        return {
            "ids": list(self.ids),
            "n_runs": self.n_runs,
            "duration": self.duration,
            "integrator": self.integrator,
            "step": self.step,
            "n_steps": self.n_steps,
            "metric_every": self.metric_every,
            "omega_max": self.omega_max,
            "columns": {name: plain(np.asarray(values)) for name, values in self.columns().items()},
        }

    def summary_table(self, max_rows: int = 20) -> str:
        """A plain-text table of the first ``max_rows`` runs (parameters, status, period,
        amplitudes, friction ratios, energy error)."""
        cols = self.columns()
        keep = [*self.parameters, "status", "first_slip_time", "period_measured",
                "cm_amplitude", "stationary_amplitude",
                *(f"{i}.max_friction_ratio" for i in self.ids), "energy_error"]
        rows = min(self.n_runs, max_rows)

        def cell(v: Any) -> str:
            return v if isinstance(v, str) else f"{v:.6g}"

        table = [keep] + [[cell(cols[k][r]) for k in keep] for r in range(rows)]
        widths = [max(len(row[c]) for row in table) for c in range(len(keep))]
        lines = ["  ".join(s.rjust(w) for s, w in zip(row, widths, strict=True)) for row in table]
        if rows < self.n_runs:
            lines.append(f"... {self.n_runs - rows} more runs")
        return "\n".join(lines)


# --------------------------------------------------------------------------------------------
# parameters -> per-run arrays


def _bad(key: str, reason: str) -> ModelError:
    return ModelError(f"parameters[{key!r}]: {reason}")


@dataclass
class _Runs:
    """The per-run values of every parameter (each ``(n_runs,)`` or ``(n_runs, n)``)."""

    n_runs: int
    mass: FloatArray
    radius: FloatArray
    mu_static: FloatArray
    mu_kinetic: FloatArray
    x: FloatArray
    v: FloatArray
    stiffness: FloatArray
    rest_length: FloatArray  # NaN where the spring's rest length is its initial length
    gravity: FloatArray
    parameters: dict[str, FloatArray]
    targets: dict[str, tuple[str, int]]  # key -> (quantity, body or spring index)


def _parse_parameters(system: System, parameters: Mapping[str, ArrayLike]) -> _Runs:
    """Check the parameter paths and values, broadcast them to one run count."""
    if not isinstance(parameters, Mapping):
        raise ModelError(f"parameters: must be a mapping of paths to arrays, got "
                         f"{type(parameters).__name__}")
    index = {b.id: i for i, b in enumerate(system.bodies)}
    n_springs = len(system.springs)
    targets: dict[str, tuple[str, int]] = {}
    values: dict[str, FloatArray] = {}
    for key, raw in parameters.items():
        if not isinstance(key, str):
            raise ModelError(f"parameters: keys must be strings like 'bodies.<id>.mass', "
                             f"got {key!r}")
        parts = key.split(".")
        if parts == ["gravity"]:
            targets[key] = ("gravity", 0)
        elif len(parts) == 3 and parts[0] == "bodies":
            _, ident, quantity = parts
            if ident not in index:
                raise _bad(key, f"no body '{ident}' (bodies: {', '.join(index)})")
            if quantity not in PARAMETER_QUANTITIES["bodies"]:
                raise _bad(key, f"unknown body quantity '{quantity}' (one of "
                           f"{', '.join(PARAMETER_QUANTITIES['bodies'])})")
            targets[key] = (quantity, index[ident])
        elif len(parts) == 3 and parts[0] == "springs":
            _, number, quantity = parts
            if not number.isdigit() or int(number) >= n_springs:
                raise _bad(key, f"no spring '{number}' (springs are numbered 0 to "
                           f"{n_springs - 1} in file order)" if n_springs else
                           f"no spring '{number}' (the system has no springs)")
            if quantity not in PARAMETER_QUANTITIES["springs"]:
                raise _bad(key, f"unknown spring quantity '{quantity}' (one of "
                           f"{', '.join(PARAMETER_QUANTITIES['springs'])})")
            targets[key] = (quantity, int(number))
        else:
            raise _bad(key, "unknown parameter path (use 'bodies.<id>.<quantity>', "
                       "'springs.<index>.<quantity>' or 'gravity')")
        same = [other for other, target in targets.items() if other != key
                and target == targets[key]]
        if same:
            raise _bad(key, f"names the same parameter as {same[0]!r}")
        try:
            array = np.asarray(raw, dtype=np.float64)
        except (TypeError, ValueError):
            raise _bad(key, "must be a number or a 1-D array of numbers") from None
        if array.ndim > 1:
            raise _bad(key, f"must be a number or a 1-D array, got shape {array.shape}")
        values[key] = array
    lengths = {key: a.shape[0] for key, a in values.items() if a.ndim == 1}
    sizes = set(lengths.values()) - {1}
    if len(sizes) > 1:
        first = next(key for key, size in lengths.items() if size != 1)
        for key, size in lengths.items():
            if size not in (1, lengths[first]):
                raise _bad(key, f"has {size} values but '{first}' has {lengths[first]}: "
                           "all arrays must have one length (or one value)")
    n_runs = sizes.pop() if sizes else 1
    if n_runs == 0:
        raise _bad(next(iter(lengths)), "is empty: a batch needs at least one run")
    broadcast = {key: np.broadcast_to(a, (n_runs,)).copy() for key, a in values.items()}

    arrays = system_arrays(system)
    n = arrays.n_bodies

    def per_body(base: FloatArray) -> FloatArray:
        return np.repeat(np.asarray(base, dtype=np.float64)[None, :], n_runs, axis=0)

    runs = _Runs(
        n_runs=n_runs,
        mass=per_body(arrays.mass), radius=per_body(arrays.radius),
        mu_static=per_body(arrays.mu_static),
        mu_kinetic=per_body([b.mu_kinetic if b.mu_kinetic is not None else np.nan
                             for b in system.bodies]),
        x=per_body(arrays.x0), v=per_body(arrays.v0),
        stiffness=per_body(arrays.stiffness).reshape(n_runs, n_springs),
        rest_length=per_body([s.rest_length if s.rest_length is not None else np.nan
                              for s in system.springs]).reshape(n_runs, n_springs),
        gravity=np.full(n_runs, float(arrays.gravity)),
        parameters=broadcast,
        targets=targets,
    )
    for key, value in broadcast.items():
        quantity, i = targets[key]
        _check_values(key, quantity, value)
        if quantity == "gravity":
            runs.gravity[:] = value
        else:
            getattr(runs, quantity)[:, i] = value
    # mu_kinetic may not exceed mu_static (its default is mu_static, or 0 when that is inf)
    default_k = np.where(np.isfinite(runs.mu_static), runs.mu_static, 0.0)
    runs.mu_kinetic = np.where(np.isnan(runs.mu_kinetic), default_k, runs.mu_kinetic)
    over = runs.mu_kinetic > runs.mu_static
    if np.any(over):
        run, i = (int(v[0]) for v in np.nonzero(over))
        key = next((k for k, (q, j) in targets.items() if q in ("mu_static", "mu_kinetic")
                    and j == i), f"bodies.{system.bodies[i].id}.mu_kinetic")
        raise _bad(key, f"mu_kinetic ({runs.mu_kinetic[run, i]:g}) exceeds mu_static "
                   f"({runs.mu_static[run, i]:g}) in run {run}")
    return runs


def _check_values(key: str, quantity: str, value: FloatArray) -> None:
    def first(mask: np.ndarray) -> str:
        run = int(np.flatnonzero(mask)[0])
        return f"run {run} has {float(value[run])!r}"

    if quantity == "mu_static":
        bad = np.isnan(value) | (value < 0)
        if np.any(bad):
            raise _bad(key, f"must be >= 0 (inf allowed) ({first(bad)})")
        return
    if not np.all(np.isfinite(value)):
        raise _bad(key, f"must be finite ({first(~np.isfinite(value))})")
    if quantity in ("mass", "radius", "stiffness") and np.any(value <= 0):
        raise _bad(key, f"must be > 0 ({first(value <= 0)})")
    if quantity in ("mu_kinetic", "rest_length", "gravity") and np.any(value < 0):
        raise _bad(key, f"must be >= 0 ({first(value < 0)})")


# --------------------------------------------------------------------------------------------
# the plan: per-run fields and the topology the kernel is generated for
#
# The kernel's state per body is the centre displacement y_i = s_i q_i (R phi for a rolling
# body, x - x0 for a slider) and its rate u_i (the centre velocity). The per-run numbers the
# generated code reads are "fields" (each an array over the runs): per body
#   x0 (initial centre x), cy (centre height h + R), is (1/s), xa (s^2/J: centre acceleration
#   per unit of Q/s), m (mass), ku (J/(2 s^2): kinetic energy per u^2), nn (normal force when it
#   is constant), mu (mu_s), mn (mu_s nn), wt (m g), u0 (initial velocity), cq (m/M), xq (w/W),
#   efx, efy (constant external force);
# per spring k, L (rest length), dx (x-offset of the ends at rest, for ends at fixed heights),
# dy (their height difference), r, al (off-centre ends), ax, ay (anchors); per force Fx, Fy,
# fr, fal, frs, frc (r sin alpha, r cos alpha); vhat; and tth (per spring: the tension at
# which one of the bodies it alone acts on starts to slip).


@dataclass(frozen=True)
class _SpringPlan:
    ends: tuple[int, int]  # body index, -1 for an anchor
    kinds: tuple[str, str]  # 'centre', 'off' (off-centre attachment), 'anchor'
    geometry: str  # 'flat' (horizontal for ever), 'fixed' (ends at fixed heights), 'general'


@dataclass
class _Plan:
    n: int
    rolls: tuple[bool, ...]
    springs: tuple[_SpringPlan, ...]
    forces: tuple[tuple[int, bool], ...]  # (body, off-centre)
    normal_const: tuple[bool, ...]
    slip_check: tuple[bool, ...]
    fields: dict[str, FloatArray]  # name -> (n_runs,), read by the kernel
    scale: FloatArray  # (n_runs, n) s_i, for the linear frequencies
    inertia: FloatArray  # (n_runs, n) J_i
    simple: dict[int, list[int]]  # spring -> bodies whose slip test is on its tension


def _attachment_polar(at, radius: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(r, alpha) of an attachment per run (a ``height`` attachment depends on the radius)."""
    if at.height is not None:
        dy = at.height - radius
        return np.abs(dy), np.where(dy >= 0, 0.0, math.pi)
    if at.radius is not None:
        return (np.full_like(radius, at.radius),
                np.full_like(radius, math.radians(at.angle or 0.0)))
    return np.zeros_like(radius), np.zeros_like(radius)


def _make_plan(system: System, runs: _Runs) -> _Plan:
    arrays = system_arrays(system)
    n = arrays.n_bodies
    index = {b.id: i for i, b in enumerate(system.bodies)}
    anchors = system.anchor_map
    rolls = tuple(bool(b.rolls) for b in system.bodies)
    rolling = np.array(rolls)
    gamma = np.asarray(arrays.gamma)
    m, R = runs.mass, runs.radius
    s = np.where(rolling, R, 1.0)
    J = np.where(rolling, (1.0 + gamma) * m * R**2, m)
    cy = arrays.track + R
    w = (1.0 + gamma) * m  # X-hat weights (M11)
    f: dict[str, FloatArray] = {}
    for i in range(n):
        f[f"x0_{i}"] = runs.x[:, i]
        f[f"cy_{i}"] = cy[:, i]
        f[f"is_{i}"] = 1.0 / s[:, i]
        f[f"xa_{i}"] = s[:, i] ** 2 / J[:, i]
        f[f"m_{i}"] = m[:, i]
        f[f"ku_{i}"] = 0.5 * J[:, i] / s[:, i] ** 2
        f[f"wt_{i}"] = m[:, i] * runs.gravity
        f[f"mu_{i}"] = runs.mu_static[:, i]
        f[f"u0_{i}"] = runs.v[:, i]
        f[f"cq_{i}"] = m[:, i] / m.sum(axis=1)
        f[f"xq_{i}"] = w[:, i] / w.sum(axis=1)
    f["vhat"] = np.sum(w * runs.v, axis=1) / w.sum(axis=1)

    springs = []
    for k, spring in enumerate(system.springs):
        kinds, ends, px, py = [], [], [], []
        for e, (end, at) in enumerate(zip(spring.ends, spring.attachments, strict=True)):
            if end in index:
                i = index[end]
                r, alpha = _attachment_polar(at, R[:, i])
                off = bool(np.any(r != 0.0))
                if off and not rolls[i]:
                    run = int(np.flatnonzero(r != 0.0)[0])
                    raise ModelError(
                        f"springs[{k}].at[{e}]: '{end}' is a slider (it does not rotate) and "
                        f"this height is off its centre in run {run} (radius "
                        f"{float(R[run, i])!r})")
                kinds.append("off" if off else "centre")
                ends.append(i)
                if off:
                    f[f"r_{k}_{e}"] = r
                    f[f"al_{k}_{e}"] = alpha
                px.append(runs.x[:, i] + r * np.sin(alpha))
                py.append(cy[:, i] + r * np.cos(alpha))
            else:
                kinds.append("anchor")
                ends.append(-1)
                a = anchors[end]
                f[f"ax_{k}_{e}"] = np.full(runs.n_runs, float(a.x))
                f[f"ay_{k}_{e}"] = np.full(runs.n_runs, float(a.y))
                px.append(np.full(runs.n_runs, float(a.x)))
                py.append(np.full(runs.n_runs, float(a.y)))
        length = np.hypot(px[1] - px[0], py[1] - py[0])
        bad = ~np.isfinite(length) | (length == 0.0)
        if np.any(bad):
            run = int(np.flatnonzero(bad)[0])
            raise ModelError(f"springs[{k}]: its two ends coincide in the initial placement of "
                             f"run {run} (length {length[run]:g})")
        rest = runs.rest_length[:, k]
        f[f"L_{k}"] = np.where(np.isnan(rest), length, rest)
        f[f"k_{k}"] = runs.stiffness[:, k]
        if "off" in kinds:
            geometry = "general"
        else:
            dy = py[1] - py[0]
            geometry = "flat" if np.all(dy == 0.0) else "fixed"
            f[f"dx_{k}"] = px[1] - px[0]
            if geometry == "fixed":
                f[f"dy_{k}"] = dy
        springs.append(_SpringPlan((ends[0], ends[1]), (kinds[0], kinds[1]), geometry))

    forces = []
    efx = np.zeros((runs.n_runs, n))
    efy = np.zeros((runs.n_runs, n))
    for j, force in enumerate(system.forces):
        i = index[force.body]
        r, alpha = _attachment_polar(force.at, R[:, i])
        off = bool(np.any(r != 0.0))
        if off and not rolls[i]:
            run = int(np.flatnonzero(r != 0.0)[0])
            raise ModelError(f"forces[{j}].at: '{force.body}' is a slider (it does not rotate) "
                             f"and this height is off its centre in run {run} (radius "
                             f"{float(R[run, i])!r})")
        forces.append((i, off))
        f[f"Fx_{j}"] = np.full(runs.n_runs, float(force.fx))
        f[f"Fy_{j}"] = np.full(runs.n_runs, float(force.fy))
        if off:
            f[f"fr_{j}"] = r
            f[f"fal_{j}"] = alpha
            f[f"frs_{j}"] = r * np.sin(alpha)
            f[f"frc_{j}"] = r * np.cos(alpha)
        efx[:, i] += force.fx
        efy[:, i] += force.fy
    normal_const = []
    for i in range(n):
        normal_const.append(all(sp.geometry == "flat" for sp in springs if i in sp.ends))
        f[f"efx_{i}"] = efx[:, i]
        f[f"efy_{i}"] = efy[:, i]
        nn = f[f"wt_{i}"] - efy[:, i]
        f[f"nn_{i}"] = nn
        mu = f[f"mu_{i}"]
        with np.errstate(invalid="ignore", over="ignore"):
            f[f"mn_{i}"] = np.where(np.isinf(mu), np.inf, mu * nn)
    slip_check = tuple(bool(rolls[i] and np.any(np.isfinite(runs.mu_static[:, i])))
                       for i in range(n))
    # A body on one horizontal centre spring and nothing else needs the friction
    # f = (m s^2/J - 1) F_x = -(gamma/(1+gamma)) (+-T) (M10): its slip test is |T| >= mu N /
    # |m s^2/J - 1|, one threshold per spring for all such bodies (the cheapest per-step check).
    ends_on = [[k for k, sp in enumerate(springs) for e in sp.ends if e == i] for i in range(n)]
    simple: dict[int, list[int]] = {}
    for i in range(n):
        on = ends_on[i]
        if (slip_check[i] and len(on) == 1 and springs[on[0]].geometry == "flat"
                and all(b != i for b, _ in forces)):
            simple.setdefault(on[0], []).append(i)
    for k, members in simple.items():
        with np.errstate(divide="ignore", invalid="ignore"):
            limits = [f[f"mn_{i}"] / np.abs(f[f"m_{i}"] * f[f"xa_{i}"] - 1.0) for i in members]
        f[f"tth_{k}"] = np.minimum.reduce(limits)
    return _Plan(n=n, rolls=rolls, springs=tuple(springs), forces=tuple(forces),
                 normal_const=tuple(normal_const), slip_check=slip_check, fields=f,
                 scale=s, inertia=J, simple=simple)


def _parameter_fields(system: System, runs: _Runs) -> set[str]:
    """The fields that depend on the given parameters: those that change in probe runs, the
    first run with one given parameter changed, up and down. The kernel reads them per lane
    whatever their values, so a sweep compiles once per set of keys, not per set of values."""
    keys = list(runs.targets)
    m = 1 + 2 * len(keys)

    def rows(a: FloatArray) -> FloatArray:
        return np.repeat(a[:1], m, axis=0)

    probe = _Runs(n_runs=m, mass=rows(runs.mass), radius=rows(runs.radius),
                  mu_static=rows(runs.mu_static), mu_kinetic=rows(runs.mu_kinetic),
                  x=rows(runs.x), v=rows(runs.v), stiffness=rows(runs.stiffness),
                  rest_length=rows(runs.rest_length), gravity=rows(runs.gravity),
                  parameters={}, targets={})
    for r, key in enumerate(keys):
        quantity, i = runs.targets[key]
        values = probe.gravity if quantity == "gravity" else getattr(probe, quantity)[:, i]
        old = values[0]
        if quantity in ("x", "v"):
            values[2 * r + 1], values[2 * r + 2] = old + 0.125, old - 0.25
        elif not math.isfinite(old):
            values[2 * r + 1], values[2 * r + 2] = 1.0, 0.5
        else:
            values[2 * r + 1], values[2 * r + 2] = 1.25 * old + 0.125, 0.5 * old
    try:
        fields = _make_plan(system, probe).fields
    except ModelError:  # a changed value made a degenerate system: the values decide alone
        return set()
    changed = set()
    with np.errstate(invalid="ignore"):
        for name, v in fields.items():
            same = (v == v[0]) | (np.isnan(v) & np.isnan(v[0]))
            if not np.all(same):
                changed.add(name)
    return changed


# --------------------------------------------------------------------------------------------
# the highest linear frequency and the step


def _omega_max(plan: _Plan, chunk: int = 1 << 15) -> float:
    r"""Highest linear frequency over the runs (rad/s): the largest :math:`|\lambda|` of
    :math:`K v = \lambda M v` at the initial placement, for the full stiffness (M12) and for its
    elastic part :math:`\sum k b b^T` alone (the stiffness at a tension-free equilibrium)."""
    f = plan.fields
    n = plan.n
    n_runs = plan.scale.shape[0]
    best = 0.0
    for lo in range(0, n_runs, chunk):
        sl = slice(lo, min(lo + chunk, n_runs))
        c = sl.stop - sl.start
        s = plan.scale[sl]
        k_full = np.zeros((c, n, n))
        k_elastic = np.zeros((c, n, n))
        for k, sp in enumerate(plan.springs):
            pos, first, second = [], [], []
            for e, (i, kind) in enumerate(zip(sp.ends, sp.kinds, strict=True)):
                if kind == "anchor":
                    pos.append(np.stack([f[f"ax_{k}_{e}"][sl], f[f"ay_{k}_{e}"][sl]], -1))
                    first.append(np.zeros((c, 2)))
                    second.append(np.zeros((c, 2)))
                    continue
                r = f[f"r_{k}_{e}"][sl] if kind == "off" else np.zeros(c)
                al = f[f"al_{k}_{e}"][sl] if kind == "off" else np.zeros(c)
                sn, cs = r * np.sin(al), r * np.cos(al)
                pos.append(np.stack([f[f"x0_{i}"][sl] + sn, f[f"cy_{i}"][sl] + cs], -1))
                first.append(np.stack([s[:, i] + cs, -sn], -1))  # (M2)
                second.append(np.stack([-sn, -cs], -1))  # (M3)
            d = pos[1] - pos[0]
            length = np.hypot(d[:, 0], d[:, 1])
            e_vec = d / length[:, None]
            stiffness = f[f"k_{k}"][sl]
            tension = stiffness * (length - f[f"L_{k}"][sl])
            delta, curve = {}, {}
            for e, sign in ((0, -1.0), (1, 1.0)):
                i = sp.ends[e]
                if i >= 0:
                    delta[i] = sign * first[e]
                    curve[i] = sign * second[e]
            for i in delta:
                bi = np.sum(e_vec * delta[i], -1)
                for j in delta:
                    bj = np.sum(e_vec * delta[j], -1)
                    k_elastic[:, i, j] += stiffness * bi * bj
                    geometric = (np.sum(delta[i] * delta[j], -1) - bi * bj) / length  # (M13)
                    if i == j:
                        geometric = geometric + np.sum(e_vec * curve[i], -1)
                    k_full[:, i, j] += stiffness * bi * bj + tension * geometric
        for j, (i, off) in enumerate(plan.forces):
            if off:
                k_full[:, i, i] += (f[f"Fx_{j}"][sl] * f[f"frs_{j}"][sl]
                                    + f[f"Fy_{j}"][sl] * f[f"frc_{j}"][sl])
        scale = 1.0 / np.sqrt(plan.inertia[sl])
        for matrix in (k_full, k_elastic):
            scaled = matrix * scale[:, :, None] * scale[:, None, :]
            scaled = 0.5 * (scaled + np.swapaxes(scaled, 1, 2))
            if np.all(np.isfinite(scaled)):
                best = max(best, float(np.max(np.abs(np.linalg.eigvalsh(scaled)))))
    return math.sqrt(best)


def _choose_step(omega: float, duration: float, rtol: float, integrator: str,
                 step: float | None) -> tuple[str, int]:
    r"""Scheme and number of steps: the accumulated phase error :math:`C_p(\omega h)^p\,\omega T`
    at most ``rtol`` (``omega h <= 0.5``), the cheapest scheme for ``auto``."""
    if step is not None:
        name = "yoshida4" if integrator == "auto" else integrator
        return name, max(1, math.ceil(duration / step * (1 - 1e-12)))
    names = list(SCHEMES) if integrator == "auto" else [integrator]
    best: tuple[str, int, float] | None = None
    for name in names:
        order, weights, constant = SCHEMES[name]
        if omega > 0:
            radians = max(omega * duration, 2 * math.pi)
            omega_step = min((rtol / (constant * radians)) ** (1.0 / order), _MAX_OMEGA_STEP)
            n_steps = max(1, math.ceil(duration * omega / omega_step * (1 - 1e-12)))
        else:
            n_steps = 1
        cost = run_cost(name, n_steps, _metric_every(omega, duration / n_steps, n_steps))
        if best is None or cost < best[2]:
            best = (name, n_steps, cost)
    assert best is not None
    return best[0], best[1]


def _metric_every(omega: float, h: float, n_steps: int) -> int:
    """Steps between metric samples: the fastest mode turns by at most METRIC_PHASE."""
    return max(1, int(METRIC_PHASE / (omega * h))) if omega > 0 else n_steps


def run_cost(integrator: str, n_steps: int, metric_every: int) -> float:
    """The work of a run in stages: ``n_steps (stages + CHECK_COST)`` plus ``SAMPLE_COST`` per
    metric sample (one every ``metric_every`` steps, and the last step)."""
    samples = n_steps // metric_every + (n_steps % metric_every != 0)
    return n_steps * (len(SCHEMES[integrator][1]) + CHECK_COST) + samples * SAMPLE_COST


# --------------------------------------------------------------------------------------------
# code generation

_MAX = "{dst} = {x} if {x} > {old} else {old} + 0.0"  # +0.0: an unconditional store (no masks)
_MIN = "{dst} = {x} if {x} < {old} else {old} + 0.0"
_FASTMATH = '{"contract"}'


class _Source:
    """The generated kernel module for one plan (topology, varying fields, stop mode).

    Every loop over the lanes is a small compiled function of its own (LLVM vectorises each
    cleanly); ``block`` strings them together for one block of runs and ``run`` spreads the
    blocks over the cores.
    """

    def __init__(self, plan: _Plan, varying: list[str], constant: list[str], stop: bool):
        self.p = plan
        self.n = plan.n
        self.varying = {name: r for r, name in enumerate(varying)}
        self.constant = {name: c for c, name in enumerate(constant)}
        self.stop = stop
        n = self.n
        rows = [f"y{i}" for i in range(n)] + [f"u{i}" for i in range(n)]
        rows += ["E0", "DE", "CMLO", "CMHI", "XHLO", "XHHI", "CP", "CF", "CL", "CN", "ACT",
                 "LIVE"]
        for i in range(n):
            rows += [f"FB{i}", f"NB{i}", f"NMIN{i}"]
        # a body on one horizontal centre spring: |f| = |m s^2/J - 1| |T|, so the largest |T|
        # of that spring gives its largest |f| (N is constant)
        self.tension_of = {i: k for k, members in plan.simple.items() for i in members}
        rows += [f"TM{k}" for k in sorted(plan.simple)]
        self.rows = {name: r * _RS for r, name in enumerate(rows)}
        self.n_rows = len(rows)
        self.used: set[str] = set()
        self.used_const: set[str] = set()
        self.period = bool(plan.springs)
        # bodies whose generalised force has a torque about the centre (off-centre points)
        self.torqued = {i for sp in plan.springs for i, kind in zip(sp.ends, sp.kinds,
                                                                    strict=True) if kind == "off"}
        self.torqued |= {i for i, off in plan.forces if off}

    # -- helpers -------------------------------------------------------------------------
    def fld(self, name: str) -> str:
        """A per-run field: a block constant, or this lane's value (loaded at the loop top)."""
        if name in self.constant:
            self.used_const.add(name)
            return f"c_{name}"
        self.used.add(name)
        return f"p_{name}"

    def row(self, name: str, lane: str) -> str:
        return f"S[{self.rows[name]} + {lane}]"

    def function(self, name: str, args: str, body: list[str], returns: str | None = None
                 ) -> list[str]:
        """A compiled function: the block constants it uses, then ``body``."""
        consts = [f"c_{c} = C[{self.constant[c]}]" for c in sorted(self.used_const)]
        self.used_const = set()
        lines = ["", "", f'@njit(cache=True, error_model="numpy", fastmath={_FASTMATH})',
                 f"def {name}({args}):", *_indent(consts + body)]
        if returns is not None:
            lines.append(f"    return {returns}")
        return lines

    def lane_loop(self, body: list[str]) -> list[str]:
        """``for j in range(B)`` over ``body`` (straight-line code for lane ``j``), after the
        loads of this lane's varying fields."""
        return ["for j in range(B):", *_indent(self.loads("j") + body)]

    def loads(self, lane: str) -> list[str]:
        lines = [f"p_{name} = Pl[{self.varying[name] * _RS} + {lane}]"
                 for name in sorted(self.used)]
        self.used = set()
        return lines

    # -- physics -------------------------------------------------------------------------
    def forces(self, y: list[str], energy: bool, lever: bool, acc: bool = True) -> list[str]:
        """Lines defining, for the displacements named in ``y``: gx{i} (:math:`Q_i/s_i`, (M7)),
        acc{i} (centre acceleration :math:`\\ddot y_i = (s_i^2/J_i)\\,Q_i/s_i`, with ``acc``),
        fx{i} (horizontal applied force),
        fy{i} (vertical; bodies whose normal force varies), U (potential energy, with
        ``energy``) and lba/lbb (rate of the first spring's length per unit centre velocity of
        its ends, with ``lever``)."""
        p, F = self.p, self.fld
        n = self.n
        lines: list[str] = []
        fx: dict[int, list[str]] = {i: [] for i in range(n)}
        fy: dict[int, list[str]] = {i: [] for i in range(n)}
        tau: dict[int, list[str]] = {i: [] for i in range(n)}  # clockwise torque about centre
        energy_terms: list[str] = []
        for k, sp in enumerate(p.springs):
            stiff, rest = F(f"k_{k}"), F(f"L_{k}")
            # per end: x, y, arm (x, y of P - C, for torques) and velocity factors (wx, wy)
            ends = []
            general = sp.geometry == "general"  # (positions needed; else offsets at rest)
            for e, (i, kind) in enumerate(zip(sp.ends, sp.kinds, strict=True)):
                if kind == "anchor":
                    ends.append((F(f"ax_{k}_{e}") if general else None,
                                 F(f"ay_{k}_{e}") if general else None, None, None, "0.0", "0.0"))
                elif kind == "centre":
                    ends.append((f"({F(f'x0_{i}')} + {y[i]})" if general else None,
                                 F(f"cy_{i}") if general else None, None, None, "1.0", "0.0"))
                else:
                    r = F(f"r_{k}_{e}")
                    lines += [f"sn, cs = sincos({F(f'al_{k}_{e}')} + {y[i]} * {F(f'is_{i}')})",
                              f"ox{k}_{e} = {r} * sn", f"oy{k}_{e} = {r} * cs"]
                    ends.append((f"({F(f'x0_{i}')} + {y[i]} + ox{k}_{e})",
                                 f"({F(f'cy_{i}')} + oy{k}_{e})", f"ox{k}_{e}", f"oy{k}_{e}",
                                 f"(1.0 + oy{k}_{e} * {F(f'is_{i}')})",
                                 f"(-ox{k}_{e} * {F(f'is_{i}')})"))
            (ax, ay, aox, aoy, awx, awy), (bx, by, box, boy, bwx, bwy) = ends
            ia, ib = sp.ends
            if sp.geometry == "general":
                lines.append(f"d{k} = {bx} - {ax}")
            else:  # ends at centres or anchors: the x-offset at rest plus the displacements
                shift = " ".join(t for t in (f"+ {y[ib]}" if ib >= 0 else "",
                                             f"- {y[ia]}" if ia >= 0 else "") if t)
                lines.append(f"d{k} = {F(f'dx_{k}')} {shift}")
            if sp.geometry == "flat":
                lines.append(f"tx{k} = {stiff} * (d{k} - math.copysign({rest}, d{k}))")
                ty = None
                if energy:
                    lines.append(f"ext{k} = abs(d{k}) - {rest}")
                if lever and k == 0:
                    lines.append(f"ex{k} = math.copysign(1.0, d{k})")
                    ex, ey = f"ex{k}", None
            else:
                dy = F(f"dy_{k}") if sp.geometry == "fixed" else f"({by} - {ay})"
                lines += [f"e{k} = {dy}",
                          f"l{k} = math.sqrt(d{k} * d{k} + e{k} * e{k})",
                          f"ext{k} = l{k} - {rest}",
                          f"tl{k} = {stiff} * ext{k} / l{k}",
                          f"tx{k} = tl{k} * d{k}", f"ty{k} = tl{k} * e{k}"]
                ty = f"ty{k}"
                if lever and k == 0:
                    lines += [f"ex{k} = d{k} / l{k}", f"ey{k} = e{k} / l{k}"]
                    ex, ey = f"ex{k}", f"ey{k}"
            if energy:
                energy_terms.append(f"+ 0.5 * {stiff} * ext{k} * ext{k}")
            # force on end a: +T e, on end b: -T e (PHYSICS.md section 2)
            for i, sign, ox, oy in ((ia, "+", aox, aoy), (ib, "-", box, boy)):
                if i < 0:
                    continue
                fx[i].append(f"{sign} tx{k}")
                if ty is not None:
                    fy[i].append(f"{sign} {ty}")
                if ox is not None:  # clockwise torque of (tx, ty) at arm (ox, oy): oy tx - ox ty
                    tau[i].append(f"{sign} ({oy} * tx{k} - {ox} * {ty})")
            if lever and k == 0:
                for i, sign, wx, wy, name in ((ia, "-", awx, awy, "a"), (ib, "", bwx, bwy, "b")):
                    if i < 0:
                        continue
                    term = f"{ex} * {wx}"
                    if ey is not None:
                        term += f" + {ey} * {wy}"
                    lines.append(f"lb{name} = {sign}({term})")
        for j, (i, off) in enumerate(p.forces):
            fxj, fyj = F(f"Fx_{j}"), F(f"Fy_{j}")
            if off:
                r = F(f"fr_{j}")
                lines += [f"sn, cs = sincos({F(f'fal_{j}')} + {y[i]} * {F(f'is_{i}')})",
                          f"fox{j} = {r} * sn", f"foy{j} = {r} * cs"]
                tau[i].append(f"+ ({fxj} * foy{j} - {fyj} * fox{j})")
                if energy:
                    energy_terms.append(f"- ({fxj} * ({y[i]} + fox{j} - {F(f'frs_{j}')})"
                                        f" + {fyj} * (foy{j} - {F(f'frc_{j}')}))")
            elif energy:
                energy_terms.append(f"- {fxj} * {y[i]}")
        has_force = {i for i, _ in p.forces}
        for i in range(n):
            ext_x = [F(f"efx_{i}")] if i in has_force else []
            lines.append(f"fx{i} = {_sum(ext_x + fx[i])}")
            if not p.normal_const[i]:
                ext_y = [F(f"efy_{i}")] if i in has_force else []
                lines.append(f"fy{i} = {_sum(ext_y + fy[i])}")
            if tau[i]:  # Q/s = F_x + tau/s (M7)
                lines.append(f"gx{i} = fx{i} + ({_sum(tau[i])}) * {F(f'is_{i}')}")
            else:
                lines.append(f"gx{i} = fx{i}")
            if acc:
                lines.append(f"acc{i} = {F(f'xa_{i}')} * gx{i}")
        if energy:
            lines.append(f"U = {_sum(energy_terms)}")
        return lines

    def contact(self) -> list[str]:
        """f{i} (friction needed, (M8): m a - F_x) and N{i} (normal force, (M9))."""
        F, lines = self.fld, []
        for i in range(self.n):
            if self.p.rolls[i]:
                lines.append(f"f{i} = {F(f'm_{i}')} * acc{i} - fx{i}")
            else:
                lines.append(f"f{i} = 0.0")
            if self.p.normal_const[i]:
                lines.append(f"N{i} = {F(f'nn_{i}')}")
            else:
                lines.append(f"N{i} = {F(f'wt_{i}')} - fy{i}")
        return lines

    def condition(self) -> str:
        """The per-step event condition (slip or lift-off), a bool expression."""
        F, terms = self.fld, []
        simple = {i for members in self.p.simple.values() for i in members}
        for k in sorted(self.p.simple):
            terms.append(f"(abs(tx{k}) >= {F(f'tth_{k}')})")
        for i in range(self.n):
            if self.p.slip_check[i] and i not in simple:
                if self.p.normal_const[i]:
                    terms.append(f"(abs(f{i}) >= {F(f'mn_{i}')})")
                else:
                    terms.append(f"(abs(f{i}) >= {F(f'mu_{i}')} * N{i})")
            if not self.p.normal_const[i]:
                terms.append(f"(N{i} < 0.0)")
        return " | ".join(terms) if terms else "False"

    def energy(self, ve: list[str]) -> str:
        F = self.fld
        return "E = U + " + " + ".join(f"{F(f'ku_{i}')} * {ve[i]} * {ve[i]}"
                                       for i in range(self.n))

    def ldot(self, ve: list[str]) -> str:
        ia, ib = self.p.springs[0].ends
        terms = []
        if ia >= 0:
            terms.append(f"lba * {ve[ia]}")
        if ib >= 0:
            terms.append(f"lbb * {ve[ib]}")
        return " + ".join(terms)

    def metrics(self, lane: str, ve: list[str], y: list[str], crossing: bool) -> list[str]:
        """Update the sampled metrics of ``lane`` (needs forces, contact, E, t, dT)."""
        F, S = self.fld, (lambda name: self.row(name, lane))
        lines = [f"dE = abs(E - {S('E0')})", f"o = {S('DE')}",
                 _MAX.format(dst=S("DE"), x="dE", old="o")]
        cm = " + ".join(f"{F(f'cq_{i}')} * {y[i]}" for i in range(self.n))
        xh = " + ".join(f"{F(f'xq_{i}')} * {y[i]}" for i in range(self.n))
        lines += [f"cm = {cm}", f"xh = {xh} - {F('vhat')} * t"]
        for name, x, fmt in (("CMLO", "cm", _MIN), ("CMHI", "cm", _MAX), ("XHLO", "xh", _MIN),
                             ("XHHI", "xh", _MAX)):
            lines += [f"o = {S(name)}", fmt.format(dst=S(name), x=x, old="o")]
        for k in sorted(self.p.simple):
            lines += [f"at = abs(tx{k})", f"o = {S(f'TM{k}')}",
                      _MAX.format(dst=S(f"TM{k}"), x="at", old="o")]
        for i in range(self.n):
            if self.p.rolls[i] and i not in self.tension_of:
                lines.append(f"af = abs(f{i})")
                if self.p.normal_const[i]:
                    lines += [f"o = {S(f'FB{i}')}", _MAX.format(dst=S(f"FB{i}"), x="af", old="o")]
                else:  # the best |f|/N as a pair: compare by cross-multiplication
                    lines += [f"fb = {S(f'FB{i}')}", f"nb = {S(f'NB{i}')}",
                              f"better = (N{i} >= 0.0) & (af * nb > fb * N{i})",
                              f"{S(f'FB{i}')} = af if better else fb + 0.0",
                              f"{S(f'NB{i}')} = N{i} if better else nb + 0.0"]
            if not self.p.normal_const[i]:
                lines += [f"o = {S(f'NMIN{i}')}",
                          _MIN.format(dst=S(f"NMIN{i}"), x=f"N{i}", old="o")]
        if crossing and self.period:
            lines += [f"ld = {self.ldot(ve)}", f"pv = {S('CP')}", "up = (pv < 0.0) & (ld >= 0.0)",
                      "tc = t - dT * ld / (ld - pv)", f"cn = {S('CN')}", f"cf = {S('CF')}",
                      f"cl = {S('CL')}",
                      f"{S('CF')} = tc if (up & (cn == 0.0)) else cf + 0.0",
                      f"{S('CL')} = tc if up else cl + 0.0",
                      f"{S('CN')} = cn + 1.0 if up else cn + 0.0",
                      f"{S('CP')} = ld"]
        return lines

    # -- functions -----------------------------------------------------------------------
    def _drift(self) -> list[str]:
        lines = []
        for i in range(self.n):
            lines += [f"u{i} = {self.row(f'u{i}', 'j')}",
                      f"y{i} = {self.row(f'y{i}', 'j')} + dk * u{i}"]
        return lines

    def _kicks(self, coefficient: str) -> tuple[list[str], list[str]]:
        """``u{i} + coefficient * acc{i}`` for every body, with ``coefficient * xa`` hoisted out
        of the lane loop where ``xa`` is a block constant: (lines before the loop, kicked
        velocity expressions)."""
        before, kicked = [], []
        for i in range(self.n):
            if f"xa_{i}" in self.constant:
                before.append(f"kx{i} = {coefficient} * {self.fld(f'xa_{i}')}")
                kicked.append(f"u{i} + kx{i} * gx{i}")
            else:
                kicked.append(f"u{i} + {coefficient} * acc{i}")
        return before, kicked

    def stage(self) -> list[str]:
        """One inner stage of the composition for every lane: drift, forces, merged kick."""
        n = self.n
        body = self._drift()
        body += self.forces([f"y{i}" for i in range(n)], energy=False, lever=False)
        before, kicked = self._kicks("ck")
        for i in range(n):
            body += [f"{self.row(f'u{i}', 'j')} = {kicked[i]}",
                     f"{self.row(f'y{i}', 'j')} = y{i}"]
        loop = [*before, *self.lane_loop(body)]
        return self.function("stage", "S, Pl, C, dk, ck", loop)

    def last(self, sample: bool) -> list[str]:
        """The last stage of a step: drift, forces, the closing half-kick merged with the next
        step's opening one, the event checks; with ``sample`` the half-kicks are separate (the
        velocities at the step's end) and the metrics are sampled. Returns the OR of the lanes'
        event conditions."""
        n = self.n
        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]
        body = self._drift()
        body += self.forces(y, energy=sample, lever=sample and self.period)
        # the stored velocity is the same in both (a run's motion does not depend on when the
        # metrics are sampled, hence on the other runs); ve is the velocity at the step's end
        before, kicked = self._kicks("ck")
        for i in range(n):
            if sample:
                body.append(f"ve{i} = u{i} + kl * acc{i}")
            body += [f"{self.row(f'u{i}', 'j')} = {kicked[i]}",
                     f"{self.row(f'y{i}', 'j')} = y{i}"]
        body += self.contact()
        cond = self.condition()
        if sample:
            body.append(self.energy(ve))
            body += self.metrics("j", ve, y, crossing=True)
        # (a lane that overflows to NaN meets no condition: it is found at the end)
        if self.stop:
            body.append(f"ev |= {cond}")
        else:
            body.append(f"ev |= ({cond}) & ({self.row('ACT', 'j')} > 0.0)")
        loop = ["ev = 0", *before, *self.lane_loop(body)]
        if sample:
            return self.function("last_sample", "S, Pl, C, dk, ck, kl, t, dT", loop, "ev")
        return self.function("last_check", "S, Pl, C, dk, ck", loop, "ev")

    def prologue(self) -> list[str]:
        """Initial state, first metric sample and checks at t = 0, opening half-kick."""
        n, F = self.n, self.fld
        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]
        S = lambda name: self.row(name, "j")  # noqa: E731
        body = [f"y{i} = 0.0" for i in range(n)] + [f"ve{i} = {F(f'u0_{i}')}" for i in range(n)]
        body += self.forces(y, energy=True, lever=self.period)
        body += self.contact()
        body.append(self.energy(ve))
        for i in range(n):
            body += [f"{S(f'y{i}')} = 0.0", f"{S(f'u{i}')} = ve{i} + k0 * acc{i}"]
        body += [f"{S('E0')} = E", f"{S('DE')} = 0.0", f"{S('CMLO')} = 0.0",
                 f"{S('CMHI')} = 0.0", f"{S('XHLO')} = 0.0", f"{S('XHHI')} = 0.0",
                 f"{S('CF')} = np.nan", f"{S('CL')} = np.nan", f"{S('CN')} = 0.0",
                 f"{S('ACT')} = 1.0", f"{S('LIVE')} = 1.0"]
        body.append(f"{S('CP')} = {self.ldot(ve)}" if self.period else f"{S('CP')} = 0.0")
        for i in range(n):
            body += [f"{S(f'FB{i}')} = abs(f{i})", f"{S(f'NB{i}')} = N{i}",
                     f"{S(f'NMIN{i}')} = N{i}"]
        body += [f"{S(f'TM{k}')} = abs(tx{k})" for k in sorted(self.p.simple)]
        # at t = 0 every body is checked, lift-off included
        terms = [f"(N{i} < 0.0)" for i in range(n)]
        terms += [f"(abs(f{i}) >= {F(f'mu_{i}')} * N{i})" for i in range(n) if self.p.rolls[i]]
        terms.append("(not (abs(E) <= 1e308))")
        body.append(f"ev |= {' | '.join(terms)}")
        loop = ["ev = 0", "for j in range(B):", *_indent(self.loads("j") + body)]
        return self.function("prologue", "S, Pl, C, k0", loop, "ev")

    def _outputs(self, suffix: str = "") -> str:
        n = self.n
        names = [f"acc{i}" for i in range(n)] + [f"f{i}" for i in range(n)]
        names += [f"N{i}" for i in range(n)] + [f"tx{k}" for k in sorted(self.p.simple)] + ["U"]
        return ", ".join(_rename_names(names, suffix))

    def lane_state(self) -> list[str]:
        """One lane's centre accelerations, needed frictions, normal forces and potential
        energy at displacements y (scalar code for the cold paths)."""
        n = self.n
        y = [f"y{i}" for i in range(n)]
        body = self.forces(y, energy=True, lever=False) + self.contact()
        body = self.loads("jj") + body
        return self.function("lane_state", "Pl, C, jj, " + ", ".join(y), body,
                             self._outputs())

    def events(self) -> list[str]:
        """The scalar pass over the lanes of a block after a step in which some lane met the
        event condition: classify, locate the instant, record, stop. Returns the number of
        lanes stopped."""
        n, F = self.n, self.fld
        S = lambda name: self.row(name, "jj")  # noqa: E731
        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]
        ys = ", ".join(y)
        body = [f"if not ({S('LIVE')} > 0.0):", "    continue"]
        inner = [f"y{i} = {S(f'y{i}')}" for i in range(n)]
        inner.append(f"{self._outputs()} = lane_state(Pl, C, jj, {ys})")
        inner += [f"ve{i} = {S(f'u{i}')} - k0 * acc{i}" for i in range(n)]
        inner.append(self.energy(ve))
        # a lane's first event (the conditions are recomputed here, so lanes that did not
        # trigger the pass are left alone): of the bodies whose condition holds (lift-off
        # N < 0, slip 0 <= mu_s N <= |f|), the one whose margin crossed zero first in this step, the
        # margins interpolated linearly between this step and the previous one, reconstructed
        # by a step backwards (the compositions are time-reversible)
        candidates = []  # (condition, margin now, margin before, status, body)
        for i in range(n):
            candidates.append((f"N{i} < 0.0", f"-N{i}", f"-Nb{i}", STATUS_LIFTOFF, i))
            if self.p.rolls[i]:
                mu = F(f"mu_{i}")
                candidates.append((f"(N{i} >= 0.0 and abs(f{i}) >= {mu} * N{i})",
                                   f"abs(f{i}) - {mu} * N{i}",
                                   f"abs(fb{i}) - {mu} * Nb{i}", STATUS_SLIP, i))
        inner += ["kind = 0", "who = -1", "tev = np.inf",
                  f"if not (abs(E - {S('E0')}) <= 1e308):",
                  f"    kind = {STATUS_NONFINITE}",
                  "    tev = t",
                  f"elif {S('ACT')} > 0.0 and ({' or '.join(c[0] for c in candidates)}):"]
        yb = ", ".join(f"yb{i}" for i in range(n))
        back = [f"yb{i} = y{i}" for i in range(n)]
        back += [f"vb{i} = ve{i} - k0 * acc{i}" for i in range(n)]
        back += [f"accb{i} = acc{i}" for i in range(n)]
        back += [f"fb{i} = f{i}" for i in range(n)] + [f"Nb{i} = N{i}" for i in range(n)]
        loop = [f"yb{i} = yb{i} - dr[kk] * vb{i}" for i in range(n)]
        loop.append(f"{self._outputs('b')} = lane_state(Pl, C, jj, {yb})")
        loop += [f"vb{i} = vb{i} - kc[kk] * accb{i}" for i in range(n)]
        back += ["for kk in range(nst):", *_indent(loop)]
        pick = ["if t > 0.0:", *_indent(back)]
        for cond, now, before, code, i in candidates:
            pick += [f"if {cond}:",
                     "    tc = 0.0",
                     "    if t > 0.0:",
                     f"        now = {now}",
                     f"        before = {before}",
                     "        tc = t",
                     "        if before < 0.0 and now > before:",
                     "            tc = t - h * (now / (now - before))",
                     "    if tc < tev:",
                     "        tev = tc", f"        kind = {code}", f"        who = {i}"]
        inner += _indent(pick)
        inner += ["if kind == 0:", "    continue"]
        inner += [f"if kind == {STATUS_NONFINITE}:", "    OUTI[lo + jj, 0] = kind",
                  "else:", "    OUTI[lo + jj, 0] = kind", "    OUTI[lo + jj, 1] = who",
                  f"    OUT[lo + jj, {_C_TEV}] = tev"]
        stop = [f"if kind != {STATUS_NONFINITE}:",
                *_indent(self.metrics("jj", ve, y, crossing=False))]
        stop += self.write_out("jj")
        for i in range(n):
            stop += [f"{S(f'y{i}')} = np.nan", f"{S(f'u{i}')} = np.nan"]
        stop += [f"{S('ACT')} = 0.0", f"{S('LIVE')} = 0.0", "stopped += 1"]
        if self.stop:
            inner += stop
        else:
            inner += [f"if kind == {STATUS_NONFINITE}:", *_indent(stop),
                      "else:", f"    {S('ACT')} = 0.0"]
        body += self.loads("jj") + inner
        loop = ["nst = dr.shape[0]", "k0 = 0.5 * dr[0]", "stopped = 0",
                "for jj in range(B):", *_indent(body)]
        return self.function("events", "lo, S, Pl, C, dr, kc, h, t, OUT, OUTI", loop, "stopped")

    def write_out(self, lane: str) -> list[str]:
        """Copy the metrics of ``lane`` and its final state (needs y{i}, ve{i}) to OUT."""
        S = lambda name: self.row(name, lane)  # noqa: E731
        F = self.fld
        lines = [f"OUT[lo + {lane}, {col}] = {S(name)}" for name, col in _OUT_ROWS.items()]
        for i in range(self.n):
            base = _C_BODY + 5 * i
            if i in self.tension_of:
                k = self.tension_of[i]
                lines.append(f"{S(f'FB{i}')} = abs({F(f'm_{i}')} * {F(f'xa_{i}')} - 1.0) * "
                             f"{S(f'TM{k}')}")
            lines += [f"OUT[lo + {lane}, {base}] = {S(f'FB{i}')}",
                      f"OUT[lo + {lane}, {base + 1}] = {S(f'NB{i}')}",
                      f"OUT[lo + {lane}, {base + 2}] = {S(f'NMIN{i}')}",
                      f"OUT[lo + {lane}, {base + 3}] = {F(f'x0_{i}')} + y{i}",
                      f"OUT[lo + {lane}, {base + 4}] = ve{i}"]
        return lines

    def epilogue(self) -> list[str]:
        """Undo the last opening half-kick and copy every live lane's results to OUT."""
        n = self.n
        S = lambda name: self.row(name, "jj")  # noqa: E731
        inner = [f"y{i} = {S(f'y{i}')}" for i in range(n)]
        inner.append(f"{self._outputs()} = lane_state(Pl, C, jj, "
                     f"{', '.join(f'y{i}' for i in range(n))})")
        inner += [f"ve{i} = {S(f'u{i}')} - k0 * acc{i}" for i in range(n)]
        state = " + ".join(f"abs(y{i}) + abs(ve{i})" for i in range(n))
        inner += [f"if not ({state} <= 1e308):", f"    OUTI[lo + jj, 0] = {STATUS_NONFINITE}"]
        inner += self.write_out("jj")
        body = [f"if {S('LIVE')} > 0.0:", *_indent(self.loads("jj") + inner)]
        loop = ["for jj in range(B):", *_indent(body)]
        return self.function("epilogue", "lo, S, Pl, C, k0, OUT, OUTI", loop)

    def sample(self) -> list[str]:
        """Centre positions of every lane into row ``row`` of the trajectories."""
        F = self.fld
        body = [f"traj[lo + j, row, {i}] = {F(f'x0_{i}')} + {self.row(f'y{i}', 'j')}"
                for i in range(self.n)]
        loop = ["for j in range(B):", *_indent(self.loads("j") + body)]
        return self.function("sample", "lo, row, S, Pl, C, traj", loop)

    # -- the module ----------------------------------------------------------------------
    def module(self) -> str:
        nv = max(len(self.varying), 1)
        block = [
            "lo = blk * B",
            f"Pl = np.empty({nv * _RS})",
            f"for r in range({len(self.varying)}):",
            "    for j in range(B):",
            f"        Pl[r * {_RS} + j] = P[r, lo + j]",
            f"S = np.empty({self.n_rows * _RS})",
            "nst = dr.shape[0]",
            "k0 = 0.5 * dr[0]",
            "kl = 0.5 * dr[nst - 1]",
            "n_live = B",
            "if prologue(S, Pl, C, k0) != 0:",
            "    n_live -= events(lo, S, Pl, C, dr, kc, dt, 0.0, OUT, OUTI)",
            "if stride > 0:",
            "    sample(lo, 0, S, Pl, C, traj)",
            "last = 0",
            "for step in range(n_steps):",
            "    for kk in range(nst - 1):",
            "        stage(S, Pl, C, dr[kk], kc[kk])",
            "    t = (step + 1) * dt",
            "    if (step + 1) % every == 0 or step + 1 == n_steps:",
            "        ev = last_sample(S, Pl, C, dr[nst - 1], kl + k0, kl, t,",
            "                         (step + 1 - last) * dt)",
            "        last = step + 1",
            "    else:",
            "        ev = last_check(S, Pl, C, dr[nst - 1], kl + k0)",
            "    if ev != 0:",
            "        n_live -= events(lo, S, Pl, C, dr, kc, dt, t, OUT, OUTI)",
            "    if stride > 0 and (step + 1) % stride == 0:",
            "        sample(lo, (step + 1) // stride, S, Pl, C, traj)",
            "    if n_live == 0:",
            "        break",
            "epilogue(lo, S, Pl, C, k0, OUT, OUTI)",
        ]
        parts = [
            '"""Generated by rollspring.simulate.batch (source hash in the file name). '
            'Do not edit."""',
            "import math",
            "import numpy as np",
            "from numba import njit, prange",
            f"B = {BLOCK}",
            _SINCOS,
            *self.stage(), *self.last(sample=False), *self.last(sample=True),
            *self.prologue(), *self.lane_state(), *self.events(), *self.epilogue(),
            *self.sample(),
            "",
            "",
            '@njit(cache=True, error_model="numpy")',
            "def block(blk, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI):",
            *_indent(block),
            "",
            "",
            '@njit(parallel=True, cache=True, error_model="numpy")',
            "def run(n_blocks, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI):",
            "    for blk in prange(n_blocks):",
            "        block(blk, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI)",
            "",
        ]
        return "\n".join(parts)


#: sin and cos in straight-line code LLVM can vectorise (``math.sin`` is a libm call, which
#: keeps a loop scalar without Intel's SVML): reduction by the nearest multiple of pi/2 in three
#: parts (Cody-Waite, exact for |x| < 2^20 pi/2) and fdlibm's minimax polynomials on
#: [-pi/4, pi/4] (errors of about one unit in the last place).
_SINCOS = '''

@njit(error_model="numpy", fastmath={"contract"})
def sincos(x):
    k = np.floor(x * 0.6366197723675814 + 0.5)
    r = ((x - k * 1.57079632673412561417e+00) - k * 6.07710050630396597660e-11) \\
        - k * 2.02226624871116645580e-21
    z = r * r
    sn = r + r * z * (-1.66666666666666324348e-01 + z * (8.33333333332248946124e-03
         + z * (-1.98412698298579493134e-04 + z * (2.75573137070700676789e-06
         + z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))))
    cs = 1.0 - 0.5 * z + z * z * (4.16666666666666019037e-02 + z * (-1.38888888888741095749e-03
         + z * (2.48015872894767294178e-05 + z * (-2.75573143513906633035e-07
         + z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))))
    quadrant = k - 4.0 * np.floor(0.25 * k)
    odd = (quadrant == 1.0) | (quadrant == 3.0)
    s = cs if odd else sn
    c = sn if odd else cs
    s = -s if quadrant >= 2.0 else s
    c = -c if (quadrant == 1.0) | (quadrant == 2.0) else c
    return s, c'''


def _sum(terms: list[str]) -> str:
    """Terms (each optionally led by '+ ' or '- ') as one expression; '0.0' for none."""
    if not terms:
        return "0.0"
    first = terms[0]
    if first.startswith("+ "):
        first = first[2:]
    elif first.startswith("- "):
        first = f"-({first[2:]})"
    return " ".join([first, *terms[1:]])


def _indent(lines: list[str], by: str = "    ") -> list[str]:
    return [by + line for line in lines]


def _rename_names(names: list[str], suffix: str) -> list[str]:
    """``acc0`` -> ``accb0`` for suffix ``b`` (``U`` -> ``Ub``)."""
    return [re.sub(r"^([A-Za-z]+)(\d*)$", rf"\1{suffix}\2", name) for name in names]


# columns of OUT: event time, E0, max |E - E0|, CM and X-hat extremes, crossings, then per body
# (best |f|, its N, min N, final x, final v)
_C_TEV = 0
_OUT_ROWS = {"E0": 1, "DE": 2, "CMLO": 3, "CMHI": 4, "XHLO": 5, "XHHI": 6, "CF": 7, "CL": 8,
             "CN": 9}
_C_BODY = 10


# --------------------------------------------------------------------------------------------
# loading generated kernels

_KERNELS: dict[str, Any] = {}
_KERNELS_LOCK = threading.Lock()


def _kernel_dir() -> Path:
    env = os.environ.get("ROLLSPRING_KERNEL_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "rollspring" / "batch-kernels"


def _load_kernel(source: str) -> Any:
    """The compiled ``run`` of a generated module (written once, named by its hash, so Numba's
    on-disk cache applies)."""
    digest = hashlib.sha256(source.encode()).hexdigest()[:20]
    with _KERNELS_LOCK:
        if digest in _KERNELS:
            return _KERNELS[digest]
        name = f"rollspring_batch_{digest}"
        path = None
        for folder in (_kernel_dir(),
                       Path(tempfile.gettempdir()) / f"rollspring-batch-kernels-{os.getuid()}"):
            try:
                folder.mkdir(parents=True, exist_ok=True)
                candidate = folder / f"{name}.py"
                if not candidate.exists() or candidate.read_text() != source:
                    tmp = folder / f".{name}.{os.getpid()}.tmp"
                    tmp.write_text(source)
                    os.replace(tmp, candidate)
                path = candidate
                break
            except OSError:
                continue
        if path is None:
            raise SimulationError("cannot write the generated batch kernel: no writable cache "
                                  "directory (set ROLLSPRING_KERNEL_DIR)")
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[name]
            raise
        _KERNELS[digest] = module.run
        return module.run


# --------------------------------------------------------------------------------------------
# the entry point


def _check_arguments(duration, rtol, integrator, step, n_output) -> None:
    def bad(name: str, reason: str) -> SimulationError:
        return SimulationError(f"{name}: {reason}")

    if isinstance(duration, bool) or not isinstance(duration, int | float) \
            or not math.isfinite(duration) or duration <= 0:
        raise bad("duration", f"must be a positive number of seconds, got {duration!r}")
    if isinstance(rtol, bool) or not isinstance(rtol, int | float) or not math.isfinite(rtol) \
            or not 0 < rtol < 1:
        raise bad("rtol", f"must be a number in (0, 1), got {rtol!r}")
    if integrator not in INTEGRATORS:
        raise bad("integrator", f"unknown integrator {integrator!r}; choose one of "
                  f"{', '.join(INTEGRATORS)}")
    if step is not None and (isinstance(step, bool) or not isinstance(step, int | float)
                             or not math.isfinite(step) or not 0 < step <= duration):
        raise bad("step", f"must be a positive number of seconds up to the duration, got {step!r}")
    if isinstance(n_output, bool) or not isinstance(n_output, int) or n_output < 2:
        raise bad("n_output", f"must be an integer >= 2, got {n_output!r}")


def simulate_batch(
    system: System,
    parameters: Mapping[str, ArrayLike],
    duration: float,
    *,
    rtol: float = 1e-8,
    integrator: str = "auto",
    step: float | None = None,
    keep_trajectories: bool = False,
    n_output: int = 201,
    stop_on_slip: bool = True,
) -> BatchResult:
    r"""Run ``system`` once per set of parameter values, all runs in parallel, for ``duration`` s.

    ``parameters`` maps paths to numbers or 1-D arrays, broadcast to one run count:
    ``"bodies.<id>.mass"``, ``.radius``, ``.mu_static``, ``.mu_kinetic``, ``.x`` (initial centre
    position), ``.v`` (initial centre velocity); ``"springs.<index>.stiffness"``,
    ``.rest_length`` (springs numbered in file order); ``"gravity"``. Every one may vary,
    radii included: a radius moves the centre height, the ``height`` attachments (their distance
    from the centre) and the inertia. A spring without a ``rest_length`` in the system keeps its
    default, the initial length, in every run. The topology (bodies, shapes, springs, anchors,
    attachments, forces) is the system's. Unknown paths, wrong lengths and invalid values raise
    :class:`~rollspring.errors.ModelError` naming the key; damped springs are refused (the
    batch integrators are symplectic: use :func:`rollspring.simulate`).

    Each run starts at the system's placement (``phi = 0``) with its velocities and follows the
    rolling equations (M7) with the integrator ``"verlet"`` (order 2), ``"yoshida4"`` or
    ``"yoshida6"``; ``"auto"`` picks the cheapest for the accuracy. The step is common to all
    runs, chosen from the highest linear frequency over the runs :math:`\omega` so that the phase
    error :math:`C_p(\omega h)^p\,\omega T` is at most ``rtol`` (:math:`\omega h\le 0.5`), and
    rounded so that ``duration`` is a whole number of steps; ``step`` fixes it instead (``auto``
    then means Yoshida-4). Every step checks every run for slip (:math:`|f_i|\ge\mu_s N_i`) and
    lift-off (:math:`N_i < 0`); with ``stop_on_slip`` a run stops at its first event, without it
    the run continues with rolling enforced (the event is still reported). A run whose state
    overflows (a step far too long, a diverging system) ends with status ``nonfinite`` and
    meaningless metrics.

    ``keep_trajectories`` also returns the centre positions at ``n_output`` evenly spaced times
    (the number of steps is then rounded up to a multiple of ``n_output - 1``). Returns a
    :class:`BatchResult` of per-run metrics.

    The kernel is generated for the system, the set of parameter keys (not their values) and
    ``stop_on_slip``; the first call for a new combination compiles it (several seconds, see
    ``timings["compile"]``), later calls, in this process or another, load it from the cache.

    Example::

        system = rollspring.load_system("hoop-cylinder")
        k = np.linspace(50.0, 150.0, 100_000)
        result = simulate_batch(system, {"springs.0.stiffness": k,
                                         "bodies.hoop.mu_static": 0.04}, 10.0)
        result.period_measured, result.first_slip_time, result.status_names
    """
    clock = time.perf_counter()
    _check_arguments(duration, rtol, integrator, step, n_output)
    if not isinstance(system, System):
        raise ModelError(f"system: must be a rollspring System, got {type(system).__name__}")
    duration = float(duration)
    damped = [k for k, s in enumerate(system.springs) if s.damping > 0]
    if damped:
        raise ModelError(f"springs[{damped[0]}].damping: batch runs need undamped springs "
                         "(symplectic integrators); use rollspring.simulate")
    runs = _parse_parameters(system, parameters)
    plan = _make_plan(system, runs)
    omega = _omega_max(plan)
    name, n_steps = _choose_step(omega, duration, float(rtol), integrator, step)
    if keep_trajectories:
        n_steps = math.ceil(n_steps / (n_output - 1)) * (n_output - 1)
    h = duration / n_steps
    every = _metric_every(omega, h, n_steps)
    weights = np.array(SCHEMES[name][1])
    drift = weights * h
    kick = np.append(0.5 * (weights[:-1] + weights[1:]) * h, 0.5 * weights[-1] * h)

    n_runs = runs.n_runs
    n_blocks = -(-n_runs // BLOCK)
    n_pad = n_blocks * BLOCK
    given = _parameter_fields(system, runs)
    varying, constant = [], []
    for key in sorted(plan.fields):
        values = plan.fields[key]
        (varying if key in given or np.any(values != values[0]) else constant).append(key)
    P = np.empty((len(varying), n_pad))
    for r, key in enumerate(varying):
        P[r, :n_runs] = plan.fields[key]
        P[r, n_runs:] = plan.fields[key][-1]
    C = np.array([plan.fields[key][0] for key in constant], dtype=np.float64)
    source = _Source(plan, varying, constant, bool(stop_on_slip)).module()
    prepared = time.perf_counter()
    kernel = _load_kernel(source)

    n = plan.n
    out = np.full((n_pad, _C_BODY + 5 * n), np.nan)
    outi = np.zeros((n_pad, 2), dtype=np.int64)
    outi[:, 1] = -1
    stride = n_steps // (n_output - 1) if keep_trajectories else 0
    traj = np.full((n_pad, n_output, n) if keep_trajectories else (1, 1, 1), np.nan)
    args = (n_blocks, P, C, drift, kick, h, n_steps, every, stride, traj, out, outi)
    if not kernel.signatures:
        import numba

        kernel.compile(tuple(numba.typeof(a) for a in args))
    compiled = time.perf_counter()
    kernel(*args)
    finished = time.perf_counter()

    out, outi = out[:n_runs], outi[:n_runs]
    with np.errstate(divide="ignore", invalid="ignore"):
        count = out[:, 9]
        period = np.where(count >= 2, (out[:, 8] - out[:, 7]) / np.maximum(count - 1, 1), np.nan)
        e0, de = np.abs(out[:, 1]), out[:, 2]
        energy_error = np.where(e0 > 0, de / np.where(e0 > 0, e0, 1.0),
                                np.where(de == 0, 0.0, np.inf))
        energy_error = np.where(np.isnan(de), np.nan, energy_error)
        fb = out[:, _C_BODY::5][:, :n]
        nb = out[:, _C_BODY + 1::5][:, :n]
        ratio = np.where(fb == 0, 0.0, np.where(nb > 0, fb / np.where(nb > 0, nb, 1.0), np.inf))
        ratio = np.where(np.isnan(fb) | np.isnan(nb), np.nan, ratio)
        ratio[:, ~np.array(plan.rolls)] = 0.0
    status = outi[:, 0].astype(np.int8)
    t_out = np.linspace(0.0, duration, n_output) if keep_trajectories else None
    return BatchResult(
        ids=tuple(b.id for b in system.bodies),
        parameters=runs.parameters,
        duration=duration,
        integrator=name,
        step=h,
        n_steps=n_steps,
        metric_every=every,
        omega_max=omega,
        status=status,
        first_slip_time=out[:, _C_TEV].copy(),
        first_slip_body=outi[:, 1].copy(),
        period_measured=period,
        cm_amplitude=0.5 * (out[:, 4] - out[:, 3]),
        stationary_amplitude=0.5 * (out[:, 6] - out[:, 5]),
        max_friction_ratio=ratio,
        min_normal_force=out[:, _C_BODY + 2::5][:, :n].copy(),
        energy_error=energy_error,
        final_x=out[:, _C_BODY + 3::5][:, :n].copy(),
        final_v=out[:, _C_BODY + 4::5][:, :n].copy(),
        t=t_out,
        x=traj[:n_runs] if keep_trajectories else None,
        timings={"prepare": prepared - clock, "compile": compiled - prepared,
                 "integrate": finished - compiled, "total": time.perf_counter() - clock},
    )
