r"""``simulate_batch``: one topology, arrays of parameter values, many runs at once.

Every run is the exact rolling motion :math:`J_i\ddot\varphi_i = Q_i(\varphi)`
(docs/physics.md (M7)) of the same system with some scalar parameters changed (masses, radii,
friction coefficients, initial positions and velocities, stiffnesses, rest lengths, gravity).
The runs are integrated by an explicit symplectic kick-drift-kick composition (valid because the
mass matrix :math:`\mathrm{diag}(J_i)` is constant, (M6)) with one fixed step for all runs,
compiled with Numba and spread over all cores. Each run keeps a handful of summary metrics, not its
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

Each step checks every run (docs/physics.md section 5): slip (:math:`|f_i| \ge \mu_s N_i`, compared
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

Runs are independent: which code is generated (the topology, and which fields are per run)
depends on the system and the parameter keys, never on the values; a run whose values overflow
or whose frequency no reasonable common step resolves gets its own status and is left out of the
step choice. With the same step and ``metric_every`` a run's result is the same, bit for bit, in
any batch (see :func:`simulate_batch`).

The package, by responsibility: :mod:`.parameters` (paths, checks, per-run values),
:mod:`.plan` (per-run fields, topology, frequencies, the step), :mod:`.codegen` (the kernel
source), :mod:`.cache` (the on-disk kernel cache: ``ROLLSPRING_CACHE_DIR``, one directory per
rollspring and Numba version, stale ones pruned) and :mod:`.api` (:func:`simulate_batch`,
:class:`BatchResult`).
"""

from rollspring.simulate.batch.api import INTEGRATORS, BatchResult, simulate_batch
from rollspring.simulate.batch.cache import kernel_dir
from rollspring.simulate.batch.codegen import BLOCK, SINCOS
from rollspring.simulate.batch.parameters import PARAMETER_QUANTITIES
from rollspring.simulate.batch.plan import (
    AUTO_SCHEMES,
    CHECK_COST,
    MAX_STEPS,
    METRIC_PHASE,
    SAMPLE_COST,
    run_cost,
)
from rollspring.simulate.integrators import INTEGRATORS as _REGISTRY
from rollspring.simulate.kernels.stepping import (
    STATUS_FINISHED,
    STATUS_LIFTOFF,
    STATUS_NONFINITE,
    STATUS_SLIP,
)
from rollspring.simulate.status import Status

__all__ = [
    "BLOCK",
    "CHECK_COST",
    "INTEGRATORS",
    "MAX_STEPS",
    "METRIC_PHASE",
    "PARAMETER_QUANTITIES",
    "SAMPLE_COST",
    "SCHEMES",
    "STATUS_FINISHED",
    "STATUS_INVALID",
    "STATUS_LIFTOFF",
    "STATUS_NAMES",
    "STATUS_NONFINITE",
    "STATUS_SLIP",
    "STATUS_UNRESOLVED",
    "BatchResult",
    "Status",
    "kernel_dir",
    "run_cost",
    "simulate_batch",
]

# the batch's own codes; the others are the single-run kernels' (kernels.stepping)
STATUS_UNRESOLVED, STATUS_INVALID = int(Status.UNRESOLVED), int(Status.INVALID)
#: Status code -> name (every :class:`~rollspring.simulate.status.Status` a batch reports).
STATUS_NAMES = {int(s): s.label for s in Status}

#: The schemes ``integrator="auto"`` chooses from (:data:`.plan.AUTO_SCHEMES`; ``"kahanli8"`` is
#: accepted by name too), name -> (order p, stage weights w_k, C_p): the relative frequency
#: error of the composition is C_p (omega h)^p
#: (:data:`rollspring.simulate.integrators.INTEGRATORS`).
SCHEMES: dict[str, tuple[int, tuple[float, ...], float]] = {
    name: (_REGISTRY[name].order, _REGISTRY[name].coefficients, _REGISTRY[name].error_constant)
    for name in AUTO_SCHEMES
}

#: The vectorisable sine and cosine of the generated kernels (:data:`.codegen.SINCOS`).
_SINCOS = SINCOS
