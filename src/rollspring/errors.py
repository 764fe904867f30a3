"""Exceptions raised by rollspring: the whole tree lives here, and nowhere else.

Every error carries a one-line message meant for a person: it names the field or the
argument and the reason. The command-line interface prints it and exits with code 2; the web
API answers HTTP 422 with it (the web branch below has its own codes). The modules of each layer
raise these classes and re-export the ones they raise to their users
(``rollspring.outputs.mjcf.ExportError`` is :class:`ExportError`). This module imports nothing
from rollspring and nothing heavy: it is the lowest layer.

The tree, grouped by the layer that raises each class (bottom layer first)::

    RollspringError             the base: every error rollspring raises on purpose
    │ model
    ├── ModelError              an invalid system: a file, a value, a preset name
    │ analysis
    ├── AnalysisError           the analysis cannot be carried out (e.g. no equilibrium)
    │   ├── NotFiniteError      a stiffness or mass matrix that is not finite (a ValueError too)
    │   └── DerivationError     invalid arguments to derive() (an unknown method)
    ├── BudgetExceeded          a symbolic step ran past its time budget (caught inside)
    ├── CostTooHigh             a run's estimated time or memory is above the bound (--yes)
    │ simulate
    ├── SimulationError         invalid simulation arguments (duration, tolerance, integrator)
    │ lab
    ├── TrackingError           a video cannot be tracked as asked (unreadable, a body not found)
    ├── DataError               a measured table cannot be read or matched to the system's bodies
    ├── FitError                a fit cannot be set up as asked (a PATH, too few points)
    │ outputs
    ├── OutputError             an output file or directory cannot be written
    ├── ReportError             the report cannot be made or written as asked
    │   └── MathConversionError a LaTeX formula latex2mathml cannot turn into MathML
    ├── AnimationError          invalid animation arguments (format, duration, speed, fps, dpi)
    ├── MapError                a sweep map cannot be drawn (a PATH, metric, body, value, store)
    ├── ExportError             the system cannot be exported in the requested form (MJCF)
    ├── WorksheetError          invalid worksheet options (level, seed, format)
    │ service
    ├── SweepError              a sweep cannot be run as asked (a PATH, value, metric, store)
    │   └── StoreMismatchError  the store at --out holds another sweep (another fingerprint)
    │ web
    ├── WebError                the web server could not compute a request
    │   ├── Overloaded          no worker was free within the time budget (HTTP 503)
    │   ├── OverBudget          the job ran past its budget; its worker was replaced (HTTP 503)
    │   └── JobFailed           the job raised: "invalid" (HTTP 422) or "crash" (HTTP 500)
    │ cli
    ├── SweepPlotError          a bad option of rollspring sweep-plot
    ├── PaperCheckError         a bad option of rollspring paper-check
    ├── WorksheetOptionError    a bad option of rollspring worksheet
    ├── ServeError              the server cannot start as asked (address, port, port in use)
    │ any layer
    └── MissingExtraError       a feature needs an optional extra that is not installed

Most classes also derive from :class:`ValueError` (see each one), so that code catching
``ValueError`` for bad arguments keeps working; :class:`MissingExtraError` is an
:class:`ImportError`. Neither :class:`BudgetExceeded` nor the web branch is a ``ValueError``: a
budget signal must not be swallowed by a library's ``except ValueError``.
"""

from __future__ import annotations

__all__ = [
    "EXTRAS",
    "AnalysisError",
    "AnimationError",
    "BudgetExceeded",
    "CostTooHigh",
    "DataError",
    "DerivationError",
    "ExportError",
    "FitError",
    "JobFailed",
    "MapError",
    "MathConversionError",
    "MissingExtraError",
    "ModelError",
    "NotFiniteError",
    "OutputError",
    "OverBudget",
    "Overloaded",
    "PaperCheckError",
    "ReportError",
    "RollspringError",
    "ServeError",
    "SimulationError",
    "StoreMismatchError",
    "SweepError",
    "SweepPlotError",
    "TrackingError",
    "WebError",
    "WorksheetError",
    "WorksheetOptionError",
    "require_extra",
]


class RollspringError(Exception):
    """Base class of every error rollspring raises on purpose."""


# ---------------------------------------------------------------------------------- model


class ModelError(RollspringError, ValueError):
    """The description of a system is invalid (a file, a value, a preset name)."""


# ------------------------------------------------------------------------------- analysis


class AnalysisError(RollspringError):
    """An analysis cannot be carried out for this system."""


class NotFiniteError(AnalysisError, ValueError):
    """A stiffness or mass matrix that is not finite (a value beyond double precision, or a
    spring of non-zero rest length squeezed to zero length, whose force has no direction); a
    ``ValueError`` too, as SciPy's check of the same matrices raises."""


class DerivationError(AnalysisError, ValueError):
    """Invalid arguments to :func:`rollspring.analysis.derivation.derive` (an unknown method)."""


class BudgetExceeded(RollspringError):
    """A symbolic computation ran out of its time budget (raised by
    :func:`rollspring.analysis.derivation.frequencies.time_budget`, caught by its callers,
    which fall back to numbers or say so: it never reaches a user)."""


class CostTooHigh(RollspringError, ValueError):
    """A run's estimated cost (steps × bodies, hence time, or the memory of its outputs) is above
    the bound (:mod:`rollspring.analysis.costs`); the message gives the estimate, and how to
    confirm the run (``--yes`` on the command line, ``confirm=True`` in Python) or make it
    smaller. Raised by :func:`rollspring.analyze`, :func:`rollspring.derive`,
    :func:`rollspring.simulate`, :func:`rollspring.build_report` and the command line."""


# ------------------------------------------------------------------------------- simulate


class SimulationError(RollspringError, ValueError):
    """A simulation was requested with invalid arguments (duration, tolerance, integrator)."""


# ------------------------------------------------------------------------------------ lab


class TrackingError(RollspringError, ValueError):
    """A video cannot be tracked as asked: an unreadable or empty video, a body or its marker
    not found in a range of frames, a bad time range or scale (one line naming the file or the
    option and the reason)."""


class DataError(RollspringError, ValueError):
    """A measured table (a ``track`` CSV, a plain CSV, a Tracker export) cannot be read or
    matched to the system's bodies: the one-line message names the file, the row or column and
    the reason (no time column, unsorted or repeated times, an unknown track)."""


class FitError(RollspringError, ValueError):
    """A fit cannot be set up as asked: a ``--free`` PATH that is not a number of the system,
    fewer measured points than fitted parameters (the message names the PATH or the file)."""


# -------------------------------------------------------------------------------- outputs


class OutputError(RollspringError, ValueError):
    """An output file or directory cannot be written (checked before the work starts)."""


class ReportError(RollspringError, ValueError):
    """The report cannot be made or written as asked (a one-line reason)."""


class MathConversionError(ReportError):
    """A LaTeX formula that latex2mathml cannot turn into MathML (a one-line reason)."""


class AnimationError(RollspringError, ValueError):
    """An animation was requested with invalid arguments (format, duration, speed, fps, dpi)."""


class MapError(RollspringError, ValueError):
    """A map cannot be drawn from these arguments (an unknown PATH, metric, body or value, a
    store that is not a sweep store); the message is one line naming the argument."""


class ExportError(RollspringError, ValueError):
    """The system cannot be exported in the requested form (a one-line reason)."""


class WorksheetError(RollspringError, ValueError):
    """Invalid worksheet options (level, seed, format)."""


# -------------------------------------------------------------------------------- service


class SweepError(RollspringError, ValueError):
    """A sweep cannot be run as asked (a bad PATH or value, a metric, a store); one line."""


class StoreMismatchError(SweepError):
    """The store at ``--out`` holds another sweep (its grid fingerprint differs)."""


# ------------------------------------------------------------------------------------ web


class WebError(RollspringError):
    """The web server could not compute a request (raised by its pool of worker processes,
    turned into an HTTP answer by the app; never a bad system by itself)."""


class Overloaded(WebError):
    """No worker became free within the budget: the server is at capacity (HTTP 503)."""


class OverBudget(WebError):
    """The job ran past its time budget; its worker was killed and replaced (HTTP 503)."""


class JobFailed(WebError):
    """The job raised: ``kind`` ``"invalid"`` (a RollspringError: a bad request, HTTP 422,
    ``loc`` the field it names), ``"over_budget"`` (estimated beyond the time budget before it
    started, HTTP 503) or ``"crash"`` (a bug or a dead worker, HTTP 500)."""

    def __init__(self, kind: str, message: str, loc: tuple[object, ...] = ()) -> None:
        super().__init__(kind, message, loc)
        self.kind, self.message, self.loc = kind, message, loc

    def __str__(self) -> str:
        return self.message

    def __repr__(self) -> str:
        return f"JobFailed(kind={self.kind!r}, message={self.message!r}, loc={self.loc!r})"


# ------------------------------------------------------------------------------------ cli


class SweepPlotError(RollspringError, ValueError):
    """A bad option of ``rollspring sweep-plot`` (the message names it)."""


class PaperCheckError(RollspringError, ValueError):
    """Invalid options of ``rollspring paper-check``."""


class WorksheetOptionError(RollspringError, ValueError):
    """Invalid options of ``rollspring worksheet``."""


class ServeError(RollspringError, ValueError):
    """The server cannot start as asked (a bad address or port, the port in use)."""


# ------------------------------------------------------------------------------ any layer


#: The optional extras (pyproject.toml) and the top-level modules each one brings: what
#: :func:`require_extra` checks. The core (model, physics, analysis, simulate, the CLI) needs none.
EXTRAS: dict[str, tuple[str, ...]] = {
    "plot": ("matplotlib", "PIL", "imageio", "imageio_ffmpeg"),
    "symbolic": ("sympy", "latex2mathml"),
    "sweep": ("dask", "distributed", "zarr", "xarray"),
    "lab": ("cv2", "emcee"),
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

    def __reduce__(self) -> tuple[type[MissingExtraError], tuple[str, tuple[str, ...]]]:
        # rebuilt from its arguments, not from its message (it crosses process boundaries)
        return type(self), (self.what, self.extras)


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
