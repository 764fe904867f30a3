"""Exceptions raised by rollspring.

Every error carries a one-line message meant for a person: it names the field or the
argument and the reason. The command-line interface prints it and exits with code 2.

::

    RollspringError
    ├── ModelError          an invalid system: a file, a value, a preset name
    ├── AnalysisError       the analysis cannot be carried out (e.g. no equilibrium)
    ├── SimulationError     invalid simulation arguments (duration, tolerance, integrator)
    ├── OutputError         an output file or directory cannot be written
    └── MissingExtraError   a feature needs an optional extra that is not installed
"""

from __future__ import annotations

__all__ = [
    "EXTRAS",
    "AnalysisError",
    "MissingExtraError",
    "ModelError",
    "OutputError",
    "RollspringError",
    "SimulationError",
    "require_extra",
]


class RollspringError(Exception):
    """Base class of every error rollspring raises on purpose."""


class ModelError(RollspringError, ValueError):
    """The description of a system is invalid (a file, a value, a preset name)."""


class AnalysisError(RollspringError):
    """An analysis cannot be carried out for this system."""


class SimulationError(RollspringError, ValueError):
    """A simulation was requested with invalid arguments (duration, tolerance, integrator)."""


class OutputError(RollspringError, ValueError):
    """An output file or directory cannot be written (checked before the work starts)."""


#: The optional extras (pyproject.toml) and the top-level modules each one brings: what
#: :func:`require_extra` checks. The core (model, physics, analysis, simulate, the CLI) needs none.
EXTRAS: dict[str, tuple[str, ...]] = {
    "plot": ("matplotlib", "PIL", "imageio", "imageio_ffmpeg"),
    "symbolic": ("sympy", "latex2mathml"),
    "sweep": ("dask", "distributed", "zarr", "xarray"),
}
EXTRAS["report"] = EXTRAS["plot"] + EXTRAS["symbolic"]
EXTRAS["web"] = ("fastapi", "uvicorn", "orjson") + EXTRAS["report"]


class MissingExtraError(RollspringError, ImportError):
    """A feature needs an optional extra that is not installed; the message says which, and the
    ``pip install`` line that adds it."""

    def __init__(self, what: str, extras: tuple[str, ...]) -> None:
        self.what, self.extras = what, extras
        names = " and ".join(f"'{extra}'" for extra in extras)
        super().__init__(
            f"{what} needs the {names} extra{'s' if len(extras) > 1 else ''}: "
            f"pip install 'rollspring[{','.join(extras)}]'"
        )


def _missing(extras: tuple[str, ...]) -> list[str]:
    from importlib.util import find_spec

    return [module for extra in extras for module in EXTRAS[extra] if find_spec(module) is None]


class require_extra:  # noqa: N801 - a check, and a context manager
    """Raise :class:`MissingExtraError` for ``what`` (``"rollspring report"``) unless every
    module of ``extras`` is installed. Checked at once, when called (no module is imported, so a
    command fails before it starts any work); used as a context manager it also turns a missing
    module of those extras met inside the block into the same error::

        require_extra("report", "rollspring report")          # a check
        with require_extra("report", "rollspring.build_report"):
            import rollspring.service.documents               # a check, and a guarded import
    """

    def __init__(self, extras: str | tuple[str, ...], what: str) -> None:
        self.extras = (extras,) if isinstance(extras, str) else tuple(extras)
        self.what = what
        if _missing(self.extras):
            raise MissingExtraError(what, self.extras)

    def __enter__(self) -> None:
        return None

    def __exit__(
        self, kind: type[BaseException] | None, exc: BaseException | None, traceback: object
    ) -> None:
        if isinstance(exc, ModuleNotFoundError):
            modules = {module for extra in self.extras for module in EXTRAS[extra]}
            if (exc.name or "").partition(".")[0] in modules:
                raise MissingExtraError(self.what, self.extras) from exc
