r"""Symbolic derivations (SymPy): the equations of motion of a system, derived step by step.

Public API::

    from rollspring.analysis.derivation import symbolic_system, derive

    sym = symbolic_system(system, symbols=True)    # the system in SymPy form (see .symbolic)
    sym.mass_matrix, sym.stiffness_matrix, sym.potential, sym.friction, sym.normal, ...

    result = derive(system, method="all", symbols=True)   # a Derivation
    result.methods["lagrange"].steps       # [Step(equation, words, ref, tag, how), ...]
    step.tag, step.how                     # "L5"; How("substitute", uses=("L3", "L4"), ...)
    result.methods["newton"].omega2        # Omega^2 of the oscillating modes (closed forms)
    result.cross_check                     # CrossCheck: which methods agree, residuals, reasons
    result.to_text(), result.to_markdown(), result.to_latex()   # renderers (latex: a document)
    result                                 # in Jupyter: rendered as math (_repr_markdown_)

    appendix_a_friction()                  # the paper's f(y) = F(1 - mRy/(I + mR^2)) derived
    zero_friction_heights()                # y* = R + I/(mR) for every shape

Every displayed step is numbered (``S5``, ``N3``, ...) and says how it follows from the steps it
names: one operation a student can name (:data:`OPERATIONS`: substitute, solve, add,
differentiate, integrate, linearise, ...). The setup (``S``) derives the constraints, the
inertias about the contact lines, T, V, M and K once; every method refers to it.

Methods (the paper's order of ideas): ``newton`` (torques about the contact points, Sec. 2, 3
and 5.1), ``conservation`` (energy and the zero mode's momentum, Sec. 5.2),
``lagrange`` (Euler-Lagrange, Sec. 5.3; also via ``sympy.physics.mechanics.LagrangesMethod``),
``natural-frequencies`` (subsystem frequencies, Sec. 5.4 and App. B, C) and ``hamilton``
(canonical equations, Sec. 5.6).
"""

from rollspring.analysis.derivation.build import symbolic_system
from rollspring.analysis.derivation.crosscheck import Check, CrossCheck, cross_check
from rollspring.analysis.derivation.derive import (
    ALL,
    Derivation,
    DerivationError,
    derive,
    parse_methods,
    run_method,
    setup_section,
)
from rollspring.analysis.derivation.forces import (
    appendix_a_friction,
    contact_force_section,
    zero_friction_heights,
)
from rollspring.analysis.derivation.frequencies import OMEGA2, Frequencies, normal_frequencies
from rollspring.analysis.derivation.lagrange import mechanics_lagrange_check
from rollspring.analysis.derivation.method import METHODS, MethodResult
from rollspring.analysis.derivation.parts import (
    EXACT_INERTIA_FACTORS,
    SymbolicBody,
    SymbolicForce,
    SymbolicSpring,
    exact_number,
)
from rollspring.analysis.derivation.render import FORMATS
from rollspring.analysis.derivation.steps import OPERATIONS, How, Section, Step
from rollspring.analysis.derivation.symbolic import SymbolicSystem, matrix_to_float

__all__ = [
    "ALL",
    "EXACT_INERTIA_FACTORS",
    "FORMATS",
    "METHODS",
    "OMEGA2",
    "OPERATIONS",
    "Check",
    "CrossCheck",
    "Derivation",
    "DerivationError",
    "Frequencies",
    "How",
    "MethodResult",
    "Section",
    "Step",
    "SymbolicBody",
    "SymbolicForce",
    "SymbolicSpring",
    "SymbolicSystem",
    "appendix_a_friction",
    "contact_force_section",
    "cross_check",
    "derive",
    "exact_number",
    "matrix_to_float",
    "mechanics_lagrange_check",
    "normal_frequencies",
    "parse_methods",
    "run_method",
    "setup_section",
    "symbolic_system",
    "zero_friction_heights",
]
