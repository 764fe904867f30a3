"""The plan of a batch: per-run fields, the topology the kernel is generated for, each run's
linear frequency, which runs a common step can integrate, and the step itself."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rollspring.errors import ModelError
from rollspring.model import Attachment, System
from rollspring.physics import system_arrays
from rollspring.physics.arrays import FloatArray
from rollspring.simulate.batch.parameters import Runs, fill_defaults, system_runs
from rollspring.simulate.integrators import INTEGRATORS, MAX_OMEGA_STEP

__all__ = [
    "AUTO_SCHEMES",
    "CHECK_COST",
    "MAX_STEPS",
    "METRIC_PHASE",
    "SAMPLE_COST",
    "Plan",
    "SpringPlan",
    "batch_schedule",
    "check_runs",
    "choose_step",
    "distinct_rows",
    "make_plan",
    "metric_every_for",
    "omega_inputs",
    "omega_limit",
    "probe",
    "run_cost",
    "run_omegas",
    "steps_needed",
]

#: Costs, in stages (force evaluations), of a step's slip and lift-off checks and of a metric
#: sample, measured on the hoop-cylinder kernel (0.66 ns a lane for a stage, 0.58-0.8 with the
#: checks, 3.3 for a sample; with sines and square roots the stage dominates more):
#: ``integrator="auto"`` takes the scheme of least
#: ``n_steps * (stages + CHECK_COST) + n_samples * SAMPLE_COST`` (:func:`run_cost`).
CHECK_COST = 0.25
SAMPLE_COST = 4.0
#: Largest phase (rad) of the fastest linear mode between two samples of the summary metrics.
METRIC_PHASE = 0.03
#: The schemes ``integrator="auto"`` chooses from. Kahan-Li 8 is accepted by name but left out:
#: a batch samples its metrics at the steps (extremes, and period crossings interpolated
#: linearly), and Kahan-Li's long steps at the usual tolerances (omega h ~ 0.1-0.3) would make
#: those samples, not the motion, the error (single runs interpolate inside the steps instead).
AUTO_SCHEMES = ("verlet", "yoshida4", "yoshida6")
#: Most steps the step chosen from ``rtol`` may take: a run that alone would need more (a
#: frequency far above its neighbours', e.g. 1e-6 kg on 1e9 N/m) is ``unresolved`` and left
#: out of the step choice instead of making every run take that many.
MAX_STEPS = 10**8


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
class SpringPlan:
    ends: tuple[int, int]  # body index, -1 for an anchor
    kinds: tuple[str, str]  # 'centre', 'off' (off-centre attachment), 'anchor'
    geometry: str  # 'flat' (horizontal for ever), 'fixed' (ends at fixed heights), 'general'


@dataclass
class Plan:
    n: int
    rolls: tuple[bool, ...]
    springs: tuple[SpringPlan, ...]
    forces: tuple[tuple[int, bool], ...]  # (body, off-centre)
    normal_const: tuple[bool, ...]
    slip_check: tuple[bool, ...]
    fields: dict[str, FloatArray]  # name -> (n_runs,), read by the kernel
    scale: FloatArray  # (n_runs, n) s_i, for the linear frequencies
    inertia: FloatArray  # (n_runs, n) J_i
    simple: dict[int, list[int]]  # spring -> bodies whose slip test is on its tension


def _attachment_polar(at: Attachment, radius: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(r, alpha) of an attachment per run (a ``height`` attachment depends on the radius)."""
    if at.height is not None:
        dy = at.height - radius
        return np.abs(dy), np.where(dy >= 0, 0.0, math.pi)
    if at.radius is not None:
        return (
            np.full_like(radius, at.radius),
            np.full_like(radius, math.radians(at.angle or 0.0)),
        )
    return np.zeros_like(radius), np.zeros_like(radius)


def _placed(
    at: Attachment, radius: FloatArray, rolls: bool, where: str, body: str
) -> tuple[FloatArray, FloatArray, bool]:
    """:func:`_attachment_polar` of an attachment on ``body`` (radius per run), and whether it is
    off the centre in any run: a slider's may not be (:class:`ModelError` naming ``where``)."""
    r, alpha = _attachment_polar(at, radius)
    off = bool(np.any(r != 0.0))
    if off and not rolls:
        run = int(np.flatnonzero(r != 0.0)[0])
        raise ModelError(
            f"{where}: '{body}' is a slider (it does not rotate) and this height is off its "
            f"centre in run {run} (radius {float(radius[run])!r})"
        )
    return r, alpha, off


def _row_sums(values: FloatArray) -> FloatArray:
    """The sum of each row of a (runs, bodies) array, column by column (NumPy's reduction
    along a short last axis costs ten times as much)."""
    total = values[:, 0].copy()
    for column in values.T[1:]:
        total += column
    return total


def make_plan(system: System, runs: Runs, topology: Plan | None = None) -> Plan:
    """The fields of every run and the topology the kernel is generated for. The topology's
    choices (an end off its centre, a spring that stays horizontal, a body whose slip is checked)
    are ``topology``'s when given (see :func:`probe`), so that they do not depend on the values
    of the runs; the runs' values can only widen them (an end off its centre in some run)."""
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
    m_total, w_total = _row_sums(m), _row_sums(w)
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
        f[f"cq_{i}"] = m[:, i] / m_total
        f[f"xq_{i}"] = w[:, i] / w_total
    f["vhat"] = _row_sums(w * runs.v) / w_total

    springs = []
    for k, spring in enumerate(system.springs):
        kinds, ends, px, py = [], [], [], []
        for e, (end, at) in enumerate(zip(spring.ends, spring.attachments, strict=True)):
            if end in index:
                i = index[end]
                r, alpha, off = _placed(at, R[:, i], rolls[i], f"springs[{k}].at[{e}]", end)
                if topology is not None and topology.springs[k].kinds[e] == "off" and rolls[i]:
                    off = True
                kinds.append("off" if off else "centre")
                ends.append(i)
                if off:
                    f[f"r_{k}_{e}"] = r
                    f[f"al_{k}_{e}"] = alpha
                sin: FloatArray | float = alpha  # sin(+-0) = +-0 and cos(+-0) = 1 exactly
                cos: FloatArray | float = 1.0
                if np.any(alpha):
                    sin, cos = np.sin(alpha), np.cos(alpha)
                px.append(runs.x[:, i] + r * sin)
                py.append(cy[:, i] + r * cos)
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
            raise ModelError(
                f"springs[{k}]: its two ends coincide in the initial placement of "
                f"run {run} (length {length[run]:g})"
            )
        rest = runs.rest_length[:, k]
        f[f"L_{k}"] = np.where(np.isnan(rest), length, rest)
        f[f"k_{k}"] = runs.stiffness[:, k]
        if "off" in kinds:
            geometry = "general"
        else:
            dy = py[1] - py[0]
            flat = bool(np.all(dy == 0.0))
            if topology is not None and topology.springs[k].geometry != "flat":
                flat = False
            geometry = "flat" if flat else "fixed"
            f[f"dx_{k}"] = px[1] - px[0]
            if geometry == "fixed":
                f[f"dy_{k}"] = dy
        springs.append(SpringPlan((ends[0], ends[1]), (kinds[0], kinds[1]), geometry))

    forces = []
    efx = np.zeros((runs.n_runs, n))
    efy = np.zeros((runs.n_runs, n))
    for j, force in enumerate(system.forces):
        i = index[force.body]
        r, alpha, off = _placed(force.at, R[:, i], rolls[i], f"forces[{j}].at", force.body)
        if topology is not None and topology.forces[j][1] and rolls[i]:
            off = True
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
    slip_check = tuple(
        bool(
            rolls[i]
            and (
                np.any(np.isfinite(runs.mu_static[:, i]))
                or (topology is not None and topology.slip_check[i])
            )
        )
        for i in range(n)
    )
    # A body on one horizontal centre spring and nothing else needs the friction
    # f = (m s^2/J - 1) F_x = -(gamma/(1+gamma)) (+-T) (M10): its slip test is |T| >= mu N /
    # |m s^2/J - 1|, one threshold per spring for all such bodies (the cheapest per-step check).
    ends_on = [[k for k, sp in enumerate(springs) for e in sp.ends if e == i] for i in range(n)]
    simple: dict[int, list[int]] = {}
    for i in range(n):
        on = ends_on[i]
        if (
            slip_check[i]
            and len(on) == 1
            and springs[on[0]].geometry == "flat"
            and all(b != i for b, _ in forces)
        ):
            simple.setdefault(on[0], []).append(i)
    for k, members in simple.items():
        with np.errstate(divide="ignore", invalid="ignore"):
            limits = [f[f"mn_{i}"] / np.abs(f[f"m_{i}"] * f[f"xa_{i}"] - 1.0) for i in members]
        f[f"tth_{k}"] = np.minimum.reduce(limits)
    return Plan(
        n=n,
        rolls=rolls,
        springs=tuple(springs),
        forces=tuple(forces),
        normal_const=tuple(normal_const),
        slip_check=slip_check,
        fields=f,
        scale=s,
        inertia=J,
        simple=simple,
    )


def probe(
    system: System, targets: dict[str, tuple[str, int]]
) -> tuple[Plan | None, set[str] | None]:
    """The topology and the per-run ("varying") fields for a set of parameter keys, from probe
    runs of the system's own values with one given parameter changed at a time, up and down:
    the fields that change, and the topology that holds for all of them. Both depend on the
    system and the keys only, never on the runs' values, so a run makes the same kernel (and the
    same motion, bit for bit) in any batch; and a sweep compiles once per set of keys.
    ``(None, None)`` when the probes make a degenerate system (the values then decide)."""
    keys = list(targets)
    m = 1 + 2 * len(keys)
    for up, down in (((1.25, 0.125), (0.5, -0.25)), ((1.5, 0.3), (0.75, -0.15))):
        runs = system_runs(system, m)
        for r, key in enumerate(keys):
            quantity, i = targets[key]
            values = runs.gravity if quantity == "gravity" else getattr(runs, quantity)[:, i]
            old = values[0]
            if quantity in ("x", "v"):
                values[2 * r + 1], values[2 * r + 2] = old + up[1], old + down[1]
            elif not math.isfinite(old):
                values[2 * r + 1], values[2 * r + 2] = 1.0, 0.5
            else:
                values[2 * r + 1], values[2 * r + 2] = up[0] * old + up[1], down[0] * old
        fill_defaults(runs)
        try:
            with np.errstate(all="ignore"):
                plan = make_plan(system, runs)
        except ModelError:  # a changed value made a degenerate system: try other changes
            continue
        changed = set()
        with np.errstate(invalid="ignore"):
            for name, v in plan.fields.items():
                same = (v == v[0]) | (np.isnan(v) & np.isnan(v[0]))
                if not np.all(same):
                    changed.add(name)
        return plan, changed
    return None, None


# --------------------------------------------------------------------------------------------
# the highest linear frequency and the step


def run_omegas(plan: Plan, chunk: int = 1 << 15) -> FloatArray:
    r"""Highest linear frequency of each run (rad/s): the largest :math:`|\lambda|` of
    :math:`K v = \lambda M v` at the initial placement, for the full stiffness (M12) and for its
    elastic part :math:`\sum k b b^T` alone (the stiffness at a tension-free equilibrium);
    inf where the matrices are not finite (values beyond double precision).

    Computed once per distinct set of the numbers it reads (:func:`omega_inputs`, compared bit
    for bit): runs that differ only in what does not enter (velocities, friction
    coefficients, masses' share of the normal force, ...) share it, as a grid of initial speeds
    or friction coefficients does; the result is each run's own either way."""
    inputs = omega_inputs(plan)
    n_runs = plan.scale.shape[0]
    rows = distinct_rows([*inputs.values(), *plan.scale.T, *plan.inertia.T], n_runs)
    if rows is None:
        return _omegas(plan, inputs, plan.scale, plan.inertia, chunk)
    first, inverse = rows
    shared = {key: values[first] for key, values in inputs.items()}
    omegas = _omegas(plan, shared, plan.scale[first], plan.inertia[first], chunk)
    return np.asarray(omegas[inverse], dtype=np.float64)


def distinct_rows(columns: list[FloatArray], n_rows: int) -> tuple[np.ndarray, np.ndarray] | None:
    """(a row of each distinct row, the distinct row of each row) of the ``columns`` side by
    side, comparing bits (-0.0 is not 0.0, NaNs by payload); None when every row is distinct.
    Only the columns that vary are sorted, each once (mixed-radix codes of their values)."""
    varying = [c for c in columns if n_rows > 1 and np.any(c.view(np.int64) != c.view(np.int64)[0])]
    if not varying:
        return np.zeros(min(n_rows, 1), dtype=np.intp), np.zeros(n_rows, dtype=np.intp)
    key = varying[0].view(np.int64)
    if len(varying) > 1:
        key = np.zeros(n_rows, dtype=np.int64)
        for column in varying:  # fewer than 2**63 codes: at most n_rows values a column
            values, codes = np.unique(column.view(np.int64), return_inverse=True)
            if values.size > (2**62) // max(int(key.max(initial=0)) + 1, 1):
                return None  # too many combinations to code: computed run by run
            key = key * values.size + codes.reshape(-1)
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    if first.size == n_rows:
        return None
    return first, inverse.reshape(-1)


def omega_inputs(plan: Plan) -> dict[str, FloatArray]:
    """The fields :func:`run_omegas` reads besides the scale and inertia of each body: the
    anchors, attachments (radius and angle of those off the centre), centre positions and
    heights of the springs' ends, the stiffnesses and rest lengths, and the constant forces
    off a centre with their arms."""
    f = plan.fields
    keys: list[str] = []
    for k, sp in enumerate(plan.springs):
        for e, (i, kind) in enumerate(zip(sp.ends, sp.kinds, strict=True)):
            if kind == "anchor":
                keys += [f"ax_{k}_{e}", f"ay_{k}_{e}"]
                continue
            if kind == "off":
                keys += [f"r_{k}_{e}", f"al_{k}_{e}"]
            keys += [f"x0_{i}", f"cy_{i}"]
        keys += [f"k_{k}", f"L_{k}"]
    for j, (_, off) in enumerate(plan.forces):
        if off:
            keys += [f"Fx_{j}", f"frs_{j}", f"Fy_{j}", f"frc_{j}"]
    return {key: f[key] for key in dict.fromkeys(keys)}


def _omegas(
    plan: Plan, f: dict[str, FloatArray], scale: FloatArray, inertia: FloatArray, chunk: int
) -> FloatArray:
    """:func:`run_omegas` of the runs whose fields are ``f`` (:func:`omega_inputs`), scales
    and inertias."""
    n = plan.n
    n_runs = scale.shape[0]
    best = np.zeros(n_runs)
    for lo in range(0, n_runs, chunk):
        sl = slice(lo, min(lo + chunk, n_runs))
        c = sl.stop - sl.start
        s = scale[sl]
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
                k_full[:, i, i] += (
                    f[f"Fx_{j}"][sl] * f[f"frs_{j}"][sl] + f[f"Fy_{j}"][sl] * f[f"frc_{j}"][sl]
                )
        root = 1.0 / np.sqrt(inertia[sl])
        for matrix in (k_full, k_elastic):
            scaled = matrix * root[:, :, None] * root[:, None, :]
            scaled = 0.5 * (scaled + np.swapaxes(scaled, 1, 2))
            finite = np.all(np.isfinite(scaled), axis=(1, 2))
            part = np.full(c, np.inf)
            if np.any(finite):
                part[finite] = np.max(np.abs(np.linalg.eigvalsh(scaled[finite])), axis=-1)
            best[sl] = np.maximum(best[sl], part)
    return np.sqrt(best)


def choose_step(
    omega: float, duration: float, rtol: float, integrator: str, step: float | None
) -> tuple[str, int]:
    r"""Scheme and number of steps: the accumulated phase error :math:`C_p(\omega h)^p\,\omega T`
    at most ``rtol`` (``omega h <= 0.5``), the cheapest scheme for ``auto``."""
    if step is not None:
        name = "yoshida4" if integrator == "auto" else integrator
        return name, max(1, math.ceil(duration / step * (1 - 1e-12)))
    names = list(AUTO_SCHEMES) if integrator == "auto" else [integrator]
    best: tuple[str, int, float] | None = None
    for name in names:
        if omega > 0:
            radians = max(omega * duration, 2 * math.pi)
            omega_step = INTEGRATORS[name].omega_step(rtol, radians)
            n_steps = max(1, math.ceil(duration * omega / omega_step * (1 - 1e-12)))
        else:
            n_steps = 1
        cost = run_cost(name, n_steps, metric_every_for(omega, duration / n_steps, n_steps))
        if best is None or cost < best[2]:
            best = (name, n_steps, cost)
    assert best is not None
    return best[0], best[1]


def batch_schedule(
    omegas: FloatArray,
    duration: float,
    rtol: float,
    integrator: str,
    step: float | None,
    metric_every: int | None = None,
    *,
    multiple: int = 1,
) -> tuple[float, str, int, int]:
    r"""What a batch call whose integrated runs have the linear frequencies ``omegas`` runs
    with: ``(omega, scheme, n_steps, metric_every)``. ``omega`` is the highest frequency (0
    without runs); the scheme and step count are :func:`choose_step`'s, rounded up to a
    multiple of ``multiple`` (the trajectories' samples); the step is ``duration / n_steps``.
    Unless given, ``metric_every`` is :func:`metric_every_for` the fastest run the step can
    sample (a run beyond :math:`\omega h` = ``MAX_OMEGA_STEP`` cannot be sampled meaningfully
    and must not make its neighbours sample every step)."""
    omegas = np.asarray(omegas, dtype=np.float64)
    omega = float(np.max(omegas)) if omegas.size else 0.0
    name, n_steps = choose_step(omega, duration, rtol, integrator, step)
    n_steps = math.ceil(n_steps / multiple) * multiple
    if metric_every is None:
        h = duration / n_steps
        sampled = omegas[omegas * h <= MAX_OMEGA_STEP]
        metric_every = metric_every_for(
            float(np.max(sampled)) if sampled.size else omega, h, n_steps
        )
    return omega, name, n_steps, metric_every


def metric_every_for(omega: float, h: float, n_steps: int) -> int:
    """Steps between metric samples: the fastest mode turns by at most METRIC_PHASE; never
    more than ``n_steps + 1`` (sampled at the start alone, as any larger count: an integer the
    kernel takes however short ``h``, even 1e-300 s)."""
    if not omega > 0:
        return n_steps
    return max(1, min(n_steps + 1, int(min(METRIC_PHASE / (omega * h), 2.0**62))))


def run_cost(integrator: str, n_steps: int, metric_every: int) -> float:
    """The work of a run in stages: ``n_steps (stages + CHECK_COST)`` plus ``SAMPLE_COST`` per
    metric sample (one every ``metric_every`` steps, and the last step)."""
    samples = n_steps // metric_every + (n_steps % metric_every != 0)
    return n_steps * (INTEGRATORS[integrator].stages + CHECK_COST) + samples * SAMPLE_COST


def steps_needed(omega: FloatArray, duration: float, rtol: float, integrator: str) -> FloatArray:
    """Steps each run would need alone (the fewest over the schemes for ``auto``), as floats."""
    names = list(AUTO_SCHEMES) if integrator == "auto" else [integrator]
    radians = np.maximum(omega * duration, 2 * math.pi)
    need = np.full(omega.shape, np.inf)
    with np.errstate(all="ignore"):
        for name in names:
            scheme = INTEGRATORS[name]
            omega_step = np.minimum(
                (rtol / (scheme.error_constant * radians)) ** (1.0 / scheme.order), MAX_OMEGA_STEP
            )
            need = np.minimum(need, np.maximum(1.0, omega * duration / omega_step))
    return np.where(omega > 0, need, 1.0)


def omega_limit(duration: float, rtol: float, integrator: str) -> float:
    """The highest linear frequency (rad/s) a run may have for :data:`MAX_STEPS` steps."""
    lo, hi = 0.0, 1.0
    while steps_needed(np.array([hi]), duration, rtol, integrator)[0] <= MAX_STEPS:
        lo, hi = hi, 2.0 * hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if steps_needed(np.array([mid]), duration, rtol, integrator)[0] <= MAX_STEPS:
            lo = mid
        else:
            hi = mid
    return lo


#: Fields that may be infinite (a body that cannot slip: mu_s = inf).
_MAY_BE_INFINITE = ("mu_", "mn_", "tth_")

#: What the fields are, for messages.
_FIELD_NAMES = {
    "x0": "initial position",
    "cy": "centre height",
    "is": "1/R",
    "xa": "R^2/J (inverse inertia)",
    "m": "mass",
    "ku": "J/(2 R^2) (inertia)",
    "wt": "weight",
    "mu": "mu_s",
    "u0": "initial velocity",
    "cq": "centre-of-mass weight",
    "xq": "X-hat weight",
    "vhat": "X-hat velocity",
    "L": "rest length",
    "k": "stiffness",
    "dx": "spring x-offset",
    "dy": "spring height offset",
    "r": "attachment radius",
    "al": "attachment angle",
    "efx": "applied force",
    "efy": "applied force",
    "nn": "normal force",
    "mn": "mu_s N",
    "tth": "slip tension",
    "Fx": "force",
    "Fy": "force",
}


def check_runs(plan: Plan, omega: FloatArray) -> tuple[np.ndarray, list[str]]:
    """Runs whose values overflow double precision: a field the kernel reads or the linear
    frequency that is not finite. Returns the mask and, per run, a message ("" if fine)."""
    n_runs = omega.shape[0]
    bad = ~np.isfinite(omega)
    reasons = [""] * n_runs
    for r in np.flatnonzero(bad):
        reasons[r] = f"its linear frequency is not finite (omega^2 = {float(omega[r]) ** 2:.3g})"
    for name in sorted(plan.fields):
        values = plan.fields[name]
        with np.errstate(invalid="ignore"):
            wrong = np.isnan(values) if name.startswith(_MAY_BE_INFINITE) else ~np.isfinite(values)
        for r in np.flatnonzero(wrong & ~bad):
            stem = name.split("_")[0]
            reasons[r] = f"its {_FIELD_NAMES.get(stem, stem)} ('{name}') is {float(values[r])!r}"
        bad |= wrong
    return bad, reasons
