"""Simulation: the exact nonlinear motion (symplectic, compiled), slip and lift-off to the
instant, stick-slip with kinetic friction, and batches of runs.

The package itself is callable: ``rollspring.simulate(system, duration, ...)`` is
:func:`rollspring.simulate.run.simulate` (its result a
:class:`~rollspring.simulate.trajectory.Trajectory`), while ``rollspring.simulate.kernels`` and
friends stay importable as usual. :mod:`.batch` (``simulate_batch``, ``BatchResult``) loads on
first use: a single run does not need its planner and code generator.
"""

import sys
import types
from typing import TYPE_CHECKING, Any


def _load_blas_check_module() -> None:
    """Load ``scipy.linalg.cython_blas`` alone, without the rest of ``scipy.linalg``.

    When Numba's CPU target is refreshed (before a compilation, and before a kernel loads from
    the cache, except those of :func:`_load_cached_kernels_lightly`: the batch kernels) it checks
    that a BLAS is there with ``import scipy.linalg.cython_blas``
    (``numba.np.arraymath._check_blas``), which runs ``scipy.linalg``'s ``__init__``: about
    0.1-0.2 s of imports (every decomposition, ``numpy.f2py``, ``numpy.testing``,
    ``unittest``...) that a run never uses. Loaded here first under its own name (the extension
    module alone takes about 2 ms; Numba imports ``scipy`` itself anyway), that import finds it
    in ``sys.modules`` and Numba sees the same module, with the same BLAS, as it would
    otherwise. ``scipy.linalg`` still imports normally when something asks for it. Nothing is
    done when ``scipy.linalg`` is loaded already or SciPy is missing (Numba then runs without
    BLAS, as it would).
    """
    name = "scipy.linalg.cython_blas"
    if name in sys.modules or "scipy.linalg" in sys.modules:
        return
    try:
        import importlib.machinery

        import scipy

        from rollspring.simulate.modules import exec_spec

        spec = importlib.machinery.PathFinder.find_spec(
            name, [f"{path}/linalg" for path in scipy.__path__]
        )
        if spec is None or not isinstance(spec.loader, importlib.machinery.ExtensionFileLoader):
            return
        exec_spec(spec)
    except Exception:  # noqa: BLE001 - an optimisation only: Numba imports it itself
        return


_load_blas_check_module()

from rollspring.simulate.integrators import Integrator, choose_scheme  # noqa: E402 - after BLAS
from rollspring.simulate.request import INTEGRATORS  # noqa: E402
from rollspring.simulate.run import simulate  # noqa: E402
from rollspring.simulate.status import RunStatus, Status  # noqa: E402
from rollspring.simulate.trajectory import Trajectory  # noqa: E402


def _load_cached_kernels_lightly() -> None:
    """Let the kernels of :mod:`.kernels` load from Numba's on-disk cache without starting all
    of Numba's compiler.

    Numba's cache, before it loads a compiled kernel, refreshes its CPU target: it imports and
    installs every implementation a *compilation* could use (about 40 modules: typed
    containers, NumPy's random generators and linear algebra, datetime, unicode...; 0.1-0.15 s)
    although a cached kernel is machine code that needs none of them, only Numba's runtime
    (NRT), which the refresh also starts. The kernels' caches here start that runtime alone,
    then load as Numba does. Only these kernels' loads change: a kernel that is not in the
    cache (or any other compilation) still refreshes the target first
    (``numba.core.compiler.compile_extra``), and the machine code, the arguments' types and
    the results are the same. Kept as Numba's when its internals are not what this expects.
    """
    try:
        from numba.core.caching import FunctionCache
        from numba.core.runtime import rtsys
    except ImportError:  # pragma: no cover - another Numba
        return
    if not all(
        hasattr(FunctionCache, name)
        for name in ("load_overload", "_load_overload", "_guard_against_spurious_io_errors")
    ):  # pragma: no cover - another Numba
        return

    class _CachedKernelCache(FunctionCache):
        def load_overload(self, sig: Any, target_context: Any) -> Any:
            rtsys.initialize(target_context)
            with self._guard_against_spurious_io_errors():
                return self._load_overload(sig, target_context)  # type: ignore[no-untyped-call]
            return None  # the guard swallowed an I/O error: compile, as Numba does

    from rollspring.simulate import kernels

    for value in vars(kernels).values():
        if type(getattr(value, "_cache", None)) is FunctionCache:
            value._cache.__class__ = _CachedKernelCache


_load_cached_kernels_lightly()

if TYPE_CHECKING:
    from rollspring.simulate.batch import BatchResult, simulate_batch

# ``INTEGRATORS`` here is the tuple of names ``simulate`` accepts; the integrator objects are
# ``rollspring.simulate.integrators.INTEGRATORS``.
__all__ = [
    "INTEGRATORS",
    "BatchResult",
    "Integrator",
    "RunStatus",
    "Status",
    "Trajectory",
    "choose_scheme",
    "simulate",
    "simulate_batch",
]

#: Names of :mod:`.batch`, loaded on first use.
_BATCH = frozenset({"BatchResult", "simulate_batch"})


def __getattr__(name: str) -> Any:
    if name in _BATCH or name == "batch":  # ``rollspring.simulate.batch`` as an attribute too
        # the submodule itself (``from rollspring.simulate import batch`` would ask this
        # function for it again before importing it)
        import rollspring.simulate.batch as batch

        return batch if name == "batch" else getattr(batch, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_BATCH, "batch"})


class _CallableModule(types.ModuleType):
    """This package, callable as :func:`simulate`."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return simulate(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
