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

The symbolic and picture parts (SymPy, Matplotlib) load on first use, so ``import rollspring``
stays light.
"""

from rollspring.analysis import LinearAnalysis, Mode, analyze, find_equilibrium, normal_modes
from rollspring.errors import AnalysisError, ModelError, RollspringError, SimulationError
from rollspring.model import (
    Anchor,
    Attachment,
    Body,
    ExternalForce,
    Spring,
    System,
    load_system,
    preset_names,
    system_from_dict,
    system_json_schema,
)
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

# rollspring.simulate is the subpackage, and callable: rollspring.simulate(system, duration)
from rollspring import simulate  # noqa: E402
from rollspring.simulate import BatchResult, Trajectory, simulate_batch  # noqa: E402
from rollspring import outputs  # noqa: E402  (registers Trajectory's views)


def _register_notebook_display() -> None:
    """In a running IPython (Jupyter), show System, analyses and trajectories as HTML."""
    import sys

    if "IPython" not in sys.modules:
        return
    from IPython import get_ipython

    if get_ipython() is not None:
        from rollspring.outputs.jupyter import register_formatters

        register_formatters()


_register_notebook_display()

#: Loaded on first use (SymPy, Matplotlib): name -> module that defines it.
_LAZY = {
    "derive": "rollspring.analysis.derivation",
    "Derivation": "rollspring.analysis.derivation",
    "symbolic_system": "rollspring.analysis.derivation",
    "check_paper": "rollspring.analysis.paper_check",
    "paper_claims": "rollspring.analysis.paper_check",
    "build_report": "rollspring.service.documents",
    "write_report": "rollspring.outputs.report",
    "worksheet": "rollspring.service.documents",
    "sweep": "rollspring.service.sweeps",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rollspring' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *_LAZY])

__version__ = "0.1.0"

__all__ = [
    "AnalysisError",
    "Derivation",
    "build_report",
    "check_paper",
    "derive",
    "paper_claims",
    "symbolic_system",
    "worksheet",
    "write_report",
    "BatchResult",
    "Anchor",
    "Attachment",
    "Body",
    "ExternalForce",
    "LinearAnalysis",
    "Mode",
    "ModelError",
    "RollspringError",
    "SimulationError",
    "Spring",
    "Trajectory",
    "System",
    "SystemArrays",
    "accelerations",
    "analyze",
    "centre_of_mass",
    "centre_positions",
    "contact_forces",
    "find_equilibrium",
    "generalized_forces",
    "kinetic_energy",
    "load_system",
    "mass_matrix",
    "normal_modes",
    "potential_energy",
    "preset_names",
    "simulate",
    "simulate_batch",
    "spring_state",
    "sweep",
    "stiffness_matrix",
    "system_arrays",
    "system_from_dict",
    "system_json_schema",
    "total_energy",
]
