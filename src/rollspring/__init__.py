"""rollspring: coupled rolling oscillators with exact rolling physics.

Hoops, cylinders, spheres and shells rolling without slipping on horizontal tracks, linked by
springs to each other and to walls. Quick start::

    import rollspring
    system = rollspring.load_system("hoop-cylinder")      # a preset, or a .toml/.json file
    result = rollspring.analyze(system)                   # equilibrium, modes, X-hat, friction
    result.modes[1].omega, result.stationary_weights, result.required_mu
    run = rollspring.simulate(system, 10.0)               # the exact nonlinear motion
    rollspring.derive(system).to_markdown()               # five derivations, cross-checked
    rollspring.check_paper()                              # the paper's claims with verdicts
    rollspring.build_report(system)                       # the self-contained HTML report
    rollspring.sweep(system, {"springs.0.stiffness": k}, 10.0)   # a grid of runs -> xarray
    rollspring.track("film.mp4", system).x                # a video of the bodies tracked
    rollspring.fit("tracks.csv", system, free=["springs.0.stiffness"])  # a measured table fitted

Every name loads its part on first use (SciPy for the analysis, the compiled kernels for the
simulation, SymPy and Matplotlib for derivations and reports), so ``import rollspring`` stays
light. The core needs NumPy, SciPy, Numba and pydantic; derivations, reports, the web page and
sweeps need the extras ``symbolic``, ``report``, ``web`` and ``sweep`` (``pip install
'rollspring[report]'``).

This package is also the composition root, above every layer: it registers the views of a
trajectory that a higher layer draws (``Trajectory.to_pandas``, ``to_xarray``, ``animate``,
:mod:`rollspring.outputs.jupyter`) in :data:`rollspring.presenters.PRESENTERS`, and the notebook
displays, each as a callable that loads its module only when it is called.
"""

from rollspring.errors import AnalysisError, ModelError, RollspringError, SimulationError

TYPE_CHECKING = False  # as typing.TYPE_CHECKING, without importing typing (10 ms)
if TYPE_CHECKING:  # what the names below load on first use, for type checkers and editors
    from rollspring import analysis as analysis
    from rollspring import cli as cli
    from rollspring import lab as lab
    from rollspring import model as model
    from rollspring import outputs as outputs
    from rollspring import physics as physics
    from rollspring import service as service
    from rollspring import simulate as simulate
    from rollspring import web as web
    from rollspring.analysis import LinearAnalysis, Mode, analyze, find_equilibrium, normal_modes
    from rollspring.analysis.derivation import Derivation, derive, symbolic_system
    from rollspring.analysis.dispersion import dispersion
    from rollspring.analysis.paper import check_paper, paper_claims
    from rollspring.lab.api import fit, track
    from rollspring.lab.tracking import TrackResult
    from rollspring.model import (
        Anchor,
        Attachment,
        Body,
        ExternalForce,
        Spring,
        System,
        chain,
        load_system,
        preset_names,
        system_from_dict,
        system_json_schema,
    )
    from rollspring.outputs.mjcf import export_mjcf
    from rollspring.outputs.report import write_report
    from rollspring.physics import (
        SystemArrays,
        accelerations,
        centre_of_mass,
        centre_positions,
        contact_forces,
        generalized_forces,
        kinetic_energy,
        mass_matrix,
        potential_energy,
        spring_state,
        stiffness_matrix,
        system_arrays,
        total_energy,
    )
    from rollspring.service.documents import build_report, worksheet
    from rollspring.service.sweeps import sweep
    from rollspring.simulate import BatchResult, Trajectory, simulate_batch
    from rollspring.web.app import create_app

    __version__: str
del TYPE_CHECKING


#: How a running IPython shows rollspring's objects: (MIME type, the module and class of the
#: object, the function of rollspring.outputs.jupyter that renders it).
_DISPLAYS = (
    ("text/html", "rollspring.model.schema", "System", "system_html"),
    ("text/html", "rollspring.analysis.linear", "LinearAnalysis", "analysis_html"),
    ("text/html", "rollspring.analysis.linear", "Mode", "mode_html"),
    ("text/html", "rollspring.simulate.trajectory", "Trajectory", "trajectory_html"),
    ("text/latex", "rollspring.analysis.linear", "LinearAnalysis", "analysis_latex"),
)


def _shown_by(function: str, module: str = "jupyter"):
    """A call of ``rollspring.outputs.<module>.<function>`` that imports it only when called."""

    def show(*args, **kwargs):
        from importlib import import_module

        return getattr(import_module(f"rollspring.outputs.{module}"), function)(*args, **kwargs)

    return show


def _register_presenters() -> None:
    """``Trajectory.to_pandas``/``to_xarray``/``animate``: the Jupyter views of
    :mod:`rollspring.outputs.jupyter`, and ``FitResult._repr_html_``
    (:mod:`rollspring.outputs.lab`), registered here (this package is the composition root, above
    every layer: the simulation never imports the outputs layer) and imported on first
    use (Matplotlib and pandas stay out of ``import rollspring``)."""
    from rollspring.presenters import PRESENTERS

    PRESENTERS.update(
        to_pandas=_shown_by("trajectory_to_pandas"),
        to_xarray=_shown_by("trajectory_to_xarray"),
        animate=_shown_by("animate_inline"),
        fit_html=_shown_by("fit_html", "lab"),
    )


_register_presenters()


def _register_notebook_display() -> None:
    """In a running IPython (Jupyter), show System, analyses and trajectories as HTML. Registered
    by the classes' names, so nothing (the analysis, the kernels, Matplotlib) loads before such
    an object is shown."""
    import sys

    if "IPython" not in sys.modules:
        return
    from IPython import get_ipython

    shell = get_ipython()
    if shell is None:
        return
    formatters = shell.display_formatter.formatters
    for mime, module, name, function in _DISPLAYS:
        formatters[mime].for_type_by_name(module, name, _shown_by(function))


_register_notebook_display()

#: Everything but the errors loads on first use (``rollspring.analyze`` imports SciPy,
#: ``rollspring.simulate`` the compiled kernels, ``rollspring.derive`` SymPy, ...), so
#: ``import rollspring`` and the command line start fast: name -> module that defines it.
_LAZY = {
    **dict.fromkeys(
        ("LinearAnalysis", "Mode", "analyze", "find_equilibrium", "normal_modes"),
        "rollspring.analysis",
    ),
    **dict.fromkeys(
        (
            "Anchor",
            "Attachment",
            "Body",
            "ExternalForce",
            "Spring",
            "System",
            "chain",
            "load_system",
            "preset_names",
            "system_from_dict",
            "system_json_schema",
        ),
        "rollspring.model",
    ),
    **dict.fromkeys(
        (
            "SystemArrays",
            "accelerations",
            "centre_of_mass",
            "centre_positions",
            "contact_forces",
            "generalized_forces",
            "kinetic_energy",
            "mass_matrix",
            "potential_energy",
            "spring_state",
            "stiffness_matrix",
            "system_arrays",
            "total_energy",
        ),
        "rollspring.physics",
    ),
    # rollspring.simulate is the subpackage, and callable: rollspring.simulate(system, duration)
    **dict.fromkeys(("BatchResult", "Trajectory", "simulate_batch"), "rollspring.simulate"),
    "derive": "rollspring.analysis.derivation",
    "Derivation": "rollspring.analysis.derivation",
    "symbolic_system": "rollspring.analysis.derivation",
    "check_paper": "rollspring.analysis.paper",
    "paper_claims": "rollspring.analysis.paper",
    "build_report": "rollspring.service.documents",
    "write_report": "rollspring.outputs.report",
    "worksheet": "rollspring.service.documents",
    "sweep": "rollspring.service.sweeps",
    "dispersion": "rollspring.analysis.dispersion",
    "export_mjcf": "rollspring.outputs.mjcf",
    "fit": "rollspring.lab.api",
    "create_app": "rollspring.web.app",
    "track": "rollspring.lab.api",
    "TrackResult": "rollspring.lab.tracking",
}

#: The subpackages, also loaded on first use (``rollspring.simulate`` is one of them).
_SUBPACKAGES = frozenset(
    {"analysis", "cli", "lab", "model", "outputs", "physics", "service", "simulate", "web"}
)

#: Names that need an optional extra (``pip install 'rollspring[extra]'``).
_EXTRAS = {
    "derive": "symbolic",
    "Derivation": "symbolic",
    "symbolic_system": "symbolic",
    "check_paper": "symbolic",
    "paper_claims": "symbolic",
    "build_report": "report",
    "write_report": "report",
    "worksheet": "report",
    "sweep": "sweep",
    "web": "web",
    "create_app": "web",
    "track": "lab",
    "TrackResult": "lab",
}


def __getattr__(name: str):
    import importlib

    if name == "__version__":  # read on first use (importlib.metadata is not free either)
        from rollspring._version import version

        globals()[name] = text = version()
        return text
    if name in _SUBPACKAGES:
        module_name, attribute = f"rollspring.{name}", None
    elif name in _LAZY:
        module_name, attribute = _LAZY[name], name
    else:
        raise AttributeError(f"module 'rollspring' has no attribute {name!r}")
    if name in _EXTRAS:
        from rollspring.errors import require_extra

        with require_extra(_EXTRAS[name], f"rollspring.{name}"):
            module = importlib.import_module(module_name)
    else:
        module = importlib.import_module(module_name)
    value = module if attribute is None else getattr(module, attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY, *_SUBPACKAGES, "__version__"})


__all__ = [
    "AnalysisError",
    "Anchor",
    "Attachment",
    "BatchResult",
    "Body",
    "Derivation",
    "ExternalForce",
    "LinearAnalysis",
    "Mode",
    "ModelError",
    "RollspringError",
    "SimulationError",
    "Spring",
    "System",
    "SystemArrays",
    "TrackResult",
    "Trajectory",
    "accelerations",
    "analyze",
    "build_report",
    "centre_of_mass",
    "centre_positions",
    "chain",
    "check_paper",
    "contact_forces",
    "create_app",
    "derive",
    "dispersion",
    "export_mjcf",
    "find_equilibrium",
    "fit",
    "generalized_forces",
    "kinetic_energy",
    "load_system",
    "mass_matrix",
    "normal_modes",
    "paper_claims",
    "potential_energy",
    "preset_names",
    "simulate",
    "simulate_batch",
    "spring_state",
    "stiffness_matrix",
    "sweep",
    "symbolic_system",
    "system_arrays",
    "system_from_dict",
    "system_json_schema",
    "total_energy",
    "track",
    "worksheet",
    "write_report",
]
