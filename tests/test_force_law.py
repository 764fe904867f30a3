"""One force law, every copy that must remain checked against it (docs/force-law.md).

The force terms are written once, in :mod:`rollspring.simulate.kernels.law`; the single-run
kernels, the compiled level setup and the generated batch kernels call them. The forms that must
stay separate -- the NumPy physics (vectorised over states, the reference of the other layers,
below ``simulate`` so it cannot import Numba), the SymPy derivation (exact, symbolic), the
generated batch source (strings that call the law), the level pulls of ``analysis.batch_linear``
(Numba below ``simulate``) -- are the rows of :data:`ROWS`, each checked
on random states (Hypothesis). A new force term adds its function to ``law.py`` and its row here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rollspring.model import system_from_dict
from rollspring.physics import SystemArrays, system_arrays
from rollspring.physics import mechanics as numpy_law
from rollspring.simulate import kernels
from rollspring.simulate.kernels import law
from rollspring.simulate.kernels.model import (
    AAX,
    AAY,
    ABX,
    ABY,
    ALPHA_A,
    ALPHA_B,
    CY,
    FALPHA,
    FR,
    FX,
    FY,
    RA,
    RB,
    REST,
    ROLLS,
    SCALE,
    STIFF,
    X0,
)

finite = {"allow_nan": False, "allow_infinity": False}

#: a system with every kind of term: polar and height attachments, an anchor, a slider, a
#: constant force off the centre, level and tilted springs
EVERY_TERM = {
    "bodies": [
        {"id": "a", "shape": "hoop", "mass": 1.0, "radius": 0.1, "x": 0.0},
        {"id": "b", "shape": "cylinder", "mass": 2.0, "radius": 0.15, "x": 0.6},
        {"id": "c", "shape": "slider", "mass": 0.5, "radius": 0.05, "x": 1.2},
    ],
    "anchors": [{"id": "w", "x": -0.5, "y": 0.2}],
    "springs": [
        {"ends": ["a", "b"], "stiffness": 100.0, "rest_length": 0.5},
        {
            "ends": ["w", "a"],
            "stiffness": 40.0,
            "at": [{}, {"radius": 0.07, "angle": 30.0}],
        },
        {
            "ends": ["b", "c"],
            "stiffness": 70.0,
            "rest_length": 0.55,
            "at": [{"height": 0.2}, {}],
        },
    ],
    "forces": [{"body": "b", "fx": 0.3, "fy": -0.7, "at": {"radius": 0.1, "angle": -60.0}}],
}
PRESETS = ("hoop-cylinder", "frictionless", "three-bodies", "wall-hoop-cylinder")


@cache
def _arrays(name: str) -> SystemArrays:
    return system_arrays(system_from_dict(EVERY_TERM) if name == "every-term" else name)


SYSTEMS = st.sampled_from(("every-term", *PRESETS))
ANGLES = st.lists(st.floats(-3.0, 3.0, **finite), min_size=3, max_size=3)


def _q(arrays: SystemArrays, values: list[float]) -> np.ndarray:
    return np.array(values[: arrays.n_bodies], dtype=float)


def law_generalized_forces(model: tuple, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The generalised forces Q (M7) and resultant forces of an all-rolling state, composed from
    the law's terms in Python (their ``py_func``: the uncompiled source), in the kernels' order."""
    bodies, springs, ends, forces, force_body = model[:5]
    n = q.shape[0]
    fx, fy, tau = np.zeros(n), np.zeros(n), np.zeros(n)

    def point(i: int, r: float, alpha: float) -> tuple[float, float, float, float]:
        x = bodies[i, X0] + bodies[i, SCALE] * q[i]
        return law.attachment.py_func(x, bodies[i, CY], bodies[i, ROLLS], r, alpha, q[i])

    for s in range(springs.shape[0]):
        ia, ib = ends[s]
        oa = ob = (0.0, 0.0)
        if ia >= 0:
            pax, pay, *oa = point(ia, springs[s, RA], springs[s, ALPHA_A])
        else:
            pax, pay = springs[s, AAX], springs[s, AAY]
        if ib >= 0:
            pbx, pby, *ob = point(ib, springs[s, RB], springs[s, ALPHA_B])
        else:
            pbx, pby = springs[s, ABX], springs[s, ABY]
        dx, dy = pbx - pax, pby - pay
        k, rest = springs[s, STIFF], springs[s, REST]
        if law.is_level.py_func(dx, dy):
            tx, ty = law.level_pull.py_func(k, rest, dx), 0.0
        else:
            length = law.distance.py_func(dx, dy)
            t = law.elastic_tension.py_func(k, rest, length)
            tx, ty = law.pull.py_func(t, dx, dy, length)
        for i, sign, (ox, oy) in ((ia, 1.0, oa), (ib, -1.0, ob)):
            if i >= 0:
                fx[i] += sign * tx
                fy[i] += sign * ty
                tau[i] += sign * law.torque.py_func(ox, oy, tx, ty)
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, ox, oy = point(i, forces[j, FR], forces[j, FALPHA])
        fx[i] += forces[j, FX]
        fy[i] += forces[j, FY]
        tau[i] += law.torque.py_func(ox, oy, forces[j, FX], forces[j, FY])
    gen = np.array(
        [law.generalized_force.py_func(bodies[i, SCALE], fx[i], tau[i]) for i in range(n)]
    )
    return gen, np.stack([fx, fy], axis=-1)


def _scale(arrays: SystemArrays) -> float:
    """A typical generalised force, for the tolerances of rows that round differently."""
    return float(np.sum(arrays.stiffness) * np.max(arrays.scale) + np.sum(np.abs(arrays.force)))


# -- the rows ------------------------------------------------------------------------------------


@settings(max_examples=60)
@given(SYSTEMS, ANGLES)
def check_compiled_kernels(name: str, values: list[float]) -> None:
    """simulate.kernels (rolling_forces through generalized_forces; level_setup's Q): the law's
    terms inlined, the same bits as the law composed in Python."""
    arrays = _arrays(name)
    q = _q(arrays, values)
    model = kernels.kernel_model(arrays)
    expected, _ = law_generalized_forces(model, q)
    assert kernels.generalized_forces(model, q).tobytes() == expected.tobytes()


@settings(max_examples=60)
@given(SYSTEMS, ANGLES, ANGLES)
def check_numpy_physics(name: str, values: list[float], rates: list[float]) -> None:
    """physics.mechanics (vectorised NumPy, the other layers' reference): the elastic tension and
    the normal force are the law's expressions (the same bits); the generalised and resultant
    forces and the needed friction sum in another order (to rounding)."""
    arrays = _arrays(name)
    q, qdot = _q(arrays, values), _q(arrays, rates)
    springs = numpy_law.spring_state(arrays, q)
    tension = law.elastic_tension.py_func(arrays.stiffness, arrays.rest_length, springs.length)
    assert np.array_equal(springs.tension, tension)
    expected, loads = law_generalized_forces(kernels.kernel_model(arrays), q)
    tolerance = 1e-12 * _scale(arrays)
    gen = numpy_law.generalized_forces(arrays, q)
    np.testing.assert_allclose(gen, expected, rtol=0, atol=tolerance)
    force = numpy_law.body_forces(arrays, q)
    np.testing.assert_allclose(force, loads, rtol=0, atol=tolerance)
    friction, normal = numpy_law.contact_forces(arrays, q, qdot if name == "every-term" else None)
    weight = arrays.mass * arrays.gravity
    undamped_force = numpy_law.body_forces(arrays, q, qdot if name == "every-term" else None)
    assert np.array_equal(normal, law.normal_force.py_func(weight, undamped_force[:, 1]))
    needed = law.needed_friction.py_func(
        arrays.mass,
        arrays.scale,
        arrays.inertia,
        numpy_law.generalized_forces(arrays, q),
        force[:, 0],
    )
    rolling = arrays.rolls > 0
    np.testing.assert_allclose(friction[rolling], needed[rolling], rtol=0, atol=tolerance)


@cache
def _symbolic_forces(name: str) -> tuple[Callable[..., list[float]], np.ndarray]:
    """-dV/dq of the SymPy derivation, as a function of the coordinates from its reference."""
    import sympy as sp

    from rollspring.analysis.derivation import symbolic_system

    sym = symbolic_system(name)
    forces = [-sp.diff(sym.potential, qi) for qi in sym.q]
    return sp.lambdify(sym.q, forces, "math"), sym.q_reference


@settings(max_examples=10)
@given(st.sampled_from(PRESETS), st.lists(st.floats(-0.5, 0.5, **finite), min_size=3, max_size=3))
def check_sympy(name: str, values: list[float]) -> None:
    """analysis.derivation (exact SymPy, the derivations' and LaTeX's form): Q = -dV/dq of its
    potential (springs' :math:`\\tfrac12 k(l - L_0)^2`, forces' work) equals the law's."""
    arrays = _arrays(name)
    forces, reference = _symbolic_forces(name)
    dq = _q(arrays, values)
    expected, _ = law_generalized_forces(kernels.kernel_model(arrays), reference + dq)
    np.testing.assert_allclose(forces(*dq), expected, rtol=0, atol=1e-11 * _scale(arrays))


def check_batch_source() -> None:
    """simulate.batch.codegen (strings of generated code): every force term is a call of the
    law (inlined by Numba with the kernel's fastmath flags), none is written out; the source
    carries the law's hash (the cache follows it). The generated code's numbers are checked
    against physics on random layouts in tests/test_batch_layouts.py."""
    from rollspring.simulate.batch.api import kernel_fields
    from rollspring.simulate.batch.codegen import BLOCK, Source
    from rollspring.simulate.batch.parameters import parse_parameters
    from rollspring.simulate.batch.plan import make_plan, probe

    system = system_from_dict(EVERY_TERM)
    runs = parse_parameters(system, {"bodies.a.mass": [1.0, 1.5]})
    topology, fields = probe(system, runs.targets)
    plan = make_plan(system, runs, topology)
    varying, constant, _, _ = kernel_fields(plan, fields, np.arange(runs.n_runs), BLOCK)
    source = Source(plan, varying, constant, True).module()
    assert "from rollspring.simulate.kernels.law import" in source
    for term in ("elastic_tension(", "pull(", "arm_torque(", "normal_force(", "reduced_force("):
        assert term in source, term
    for written_out in ("math.sqrt", "math.copysign(k", "* acc0 - fx", " - fy", "* tx0 - "):
        assert written_out not in source, written_out


@settings(max_examples=60)
@given(
    st.integers(1, 3),
    st.integers(1, 3),
    st.randoms(use_true_random=False),
)
def check_batch_linear(n_springs: int, n_bodies: int, rng) -> None:
    """analysis.batch_linear (Numba in ``analysis``, below ``simulate``; its equilibrium check
    over many runs): ``_pulls``'s level pull and generalised force of centre attachments are the
    law's ``level_pull`` and ``generalized_force`` (the same bits; a level spring's ends never
    meet there, d != 0, which the model refuses at the start and the check at equilibrium)."""
    import importlib

    batch_linear = importlib.import_module("rollspring.analysis.batch_linear")  # the module
    pulls = getattr(batch_linear._pulls, "py_func", batch_linear._pulls)

    def value(low: float, high: float, shape: tuple[int, ...]) -> np.ndarray:
        return np.array([rng.uniform(low, high) for _ in range(math.prod(shape))]).reshape(shape)

    d = value(0.05, 1.0, (n_springs,)) * np.array(
        [rng.choice((-1.0, 1.0)) for _ in range(n_springs)]
    )
    rest = value(0.0, 1.0, (n_springs,))
    k = value(1.0, 500.0, (2, n_springs))
    sigma = np.array(
        [[rng.choice((-1.0, 0.0, 1.0)) for _ in range(n_bodies)] for _ in range(n_springs)]
    )
    external = value(-2.0, 2.0, (1, n_bodies))
    s = value(0.05, 0.3, (2, n_bodies))
    force_x, force_q = np.empty(n_bodies), np.empty(n_bodies)
    pulls(d, rest, k, sigma, external, s, 1, force_x, force_q)
    expected_x = np.zeros(n_bodies)
    for spring in range(n_springs):
        pull = law.level_pull.py_func(k[1, spring], rest[spring], d[spring])
        expected_x -= pull * sigma[spring]
    expected_x += external[0]
    expected_q = law.generalized_force.py_func(s[1], expected_x, 0.0)
    assert force_x.tobytes() == expected_x.tobytes()
    assert force_q.tobytes() == expected_q.tobytes()


@dataclass(frozen=True)
class Copy:
    """A form of the force law that must remain, where it lives and its check."""

    where: str
    why: str
    check: Callable[[], None]


ROWS = (
    Copy(
        "rollspring.simulate.kernels (forces, observation, linear_setup)",
        "call the law",
        check_compiled_kernels,
    ),
    Copy("rollspring.physics.mechanics", "NumPy, vectorised; below simulate", check_numpy_physics),
    Copy("rollspring.analysis.derivation", "SymPy, exact", check_sympy),
    Copy("rollspring.simulate.batch.codegen", "generated source calls the law", check_batch_source),
    Copy(
        "rollspring.analysis.batch_linear",
        "Numba below simulate; the equilibrium check's level pulls",
        check_batch_linear,
    ),
)


@pytest.mark.parametrize("row", ROWS, ids=[row.where for row in ROWS])
def test_every_copy_agrees_with_the_law(row: Copy) -> None:
    row.check()


def test_the_law_is_every_kernel_force_expression() -> None:
    """The kernels' force modules import the law's terms rather than writing them: no spring
    tension, pull or contact expression is left in their source."""
    import inspect

    from rollspring.simulate.kernels import forces, observation

    for module in (forces, observation):
        text = inspect.getsource(module)
        assert "from rollspring.simulate.kernels.law import" in text
        for written_out in (
            "* (dist - springs[s, REST])",
            "MASS] * g - fy",
            "MU_K] * normal",
            # the columns as the kernels name them (``col``, the model module)
            "* (dist - springs[s, col.REST])",
            "col.MASS] * g - fy",
            "col.MU_K] * normal",
            "/ (length * length * length)",
        ):
            assert written_out not in text, (module.__name__, written_out)
    assert math.isclose(law.level_pull.py_func(2.0, 0.5, -1.5), -2.0)


def test_an_edit_to_any_kernel_source_drops_the_cached_kernels(tmp_path: Path) -> None:
    """Numba checks a cached kernel against its own file only: an edit to law.py alone must
    still recompile the kernels that inline it (kernels/_cache.py)."""
    from rollspring.simulate.kernels import _cache

    package = tmp_path / "kernels"
    package.mkdir()
    (package / "law.py").write_text("A = 1\n")
    (package / "forces.py").write_text("B = 2\n")
    cache = package / "__pycache__"
    assert _cache.sync_cache(package)  # no digest yet: the cache is (re)started
    kernels = [cache / "forces.f-1.py311.nbi", cache / "forces.f-1.py311.1.nbc"]
    for compiled in kernels:
        compiled.write_bytes(b"machine code")
    (cache / "forces.cpython-311.pyc").write_bytes(b"bytecode")
    assert not _cache.sync_cache(package)  # the same sources keep every cached kernel
    assert all(compiled.exists() for compiled in kernels)
    (package / "law.py").write_text("A = 2\n")  # the law edited alone
    assert _cache.sync_cache(package)
    assert not any(compiled.exists() for compiled in kernels)
    assert (cache / "forces.cpython-311.pyc").exists()  # Python's own cache is not Numba's
    assert (cache / _cache.STAMP).read_text() == _cache.source_digest(package)


def test_the_package_cache_was_built_from_its_current_sources() -> None:
    import rollspring.simulate.kernels as kernels
    from rollspring.simulate.kernels import _cache

    package = Path(kernels.__file__).resolve().parent
    assert (package / "__pycache__" / _cache.STAMP).read_text() == _cache.source_digest(package)
