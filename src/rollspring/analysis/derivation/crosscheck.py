r"""Cross-check: every method that applies must give the same equations of motion and Omega^2.

The reference is the structure-exploiting route of :class:`~.symbolic.SymbolicSystem`: the
exact :math:`Q = -\partial V/\partial\varphi`, the linearised :math:`\ddot\varphi = -M^{-1}K
\varphi` and the closed-form roots of :math:`\det(K - \Omega^2 M)`. For each method the
residuals (its result minus the reference) are simplified and must be exactly zero; methods that
do not apply are listed with the reason. The Euler-Lagrange equations that
``sympy.physics.mechanics`` forms from the Lagrangian are compared with the structure route as
one more check (named "lagrange, second route" in the output: no class names are shown).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import BudgetExceeded, Frequencies, time_budget
from rollspring.analysis.derivation.method import MethodResult
from rollspring.analysis.derivation.steps import How, Section, latex_of, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = ["Check", "CrossCheck", "cross_check", "equations_matrix"]


@dataclass(frozen=True)
class Check:
    """One comparison: ``what`` was compared for ``method``; ``residual`` (SymPy, zero when they
    agree) and ``agrees`` (None when the simplification ran out of time)."""

    method: str
    what: str
    residual: Any
    agrees: bool | None


@dataclass
class CrossCheck:
    """Which methods applied, every check made, and why the others did not apply."""

    applied: list[str]
    not_applicable: dict[str, str]
    checks: list[Check] = field(default_factory=list)

    @property
    def agree(self) -> bool:
        """True when every check's residual simplified to zero."""
        return all(c.agrees is True for c in self.checks)

    @property
    def failures(self) -> list[Check]:
        """Checks whose residual did not simplify to zero (or ran out of time)."""
        return [c for c in self.checks if c.agrees is not True]

    def section(self) -> Section:
        """The report as a section of steps."""
        section = Section("Cross-check of the methods")
        for check in self.checks:
            verdict = {True: "agrees", False: "DIFFERS", None: "undecided (time budget)"}
            # (an Eq of a symbol and a Matrix would evaluate to False: the LaTeX is built here)
            section.add(
                check.residual,
                f"{check.method}: {check.what} {verdict[check.agrees]}.",
                how=How("check"),
                latex=r"\mathrm{residual} = " + latex_of(check.residual),
            )
        for name, reason in self.not_applicable.items():
            section.add(
                named("not applicable", r"\text{not applicable}"),
                f"{name} does not apply: {reason}.",
                how=How("check"),
                latex=r"\text{not applicable}",
            )
        overall = "all methods agree" if self.agree else "the methods DO NOT all agree"
        section.note = (
            f"{len(self.applied)} method(s) applied ({', '.join(self.applied)}); {overall}."
        )
        return section


def equations_matrix(equations: list[sp.Eq], sym: SymbolicSystem) -> tuple[sp.Matrix, sp.Matrix]:
    r"""Linear equations :math:`c_i\ddot q_i = a_i + \sum_j b_{ij} q_j` as
    :math:`\ddot q = A q + c` (A, c returned)."""
    n = sym.n
    A = sp.zeros(n, n)
    c = sp.zeros(n, 1)
    for i, eq in enumerate(equations):
        expr = sp.expand(eq.lhs - eq.rhs)
        lead = expr.coeff(sym.qdd[i])
        rest = sp.expand(expr - lead * sym.qdd[i])
        for j in range(n):
            A[i, j] = sp.cancel(-rest.coeff(sym.q[j]) / lead)
        c[i] = sp.cancel(-rest.subs(dict.fromkeys(sym.q, 0)) / lead)
    return A, c


def _zero(expr: Any, budget: float | None) -> tuple[Any, bool | None]:
    """Simplify a residual (matrix or expression); (simplified, is it zero)."""
    is_matrix = isinstance(expr, sp.MatrixBase)
    items = list(expr) if is_matrix else [expr]
    out = []
    try:
        with time_budget(budget):
            for item in items:
                item = sp.expand(item)
                if item != 0:
                    item = sp.cancel(item)
                if item != 0:
                    item = sp.simplify(item)
                out.append(item)
    except BudgetExceeded:
        return expr, None
    result = sp.Matrix(expr.shape[0], expr.shape[1], out) if is_matrix else out[0]
    return result, all(item == 0 for item in out)


def cross_check(
    sym: SymbolicSystem,
    results: dict[str, MethodResult],
    frequencies: Frequencies,
    *,
    budget: float | None = 20.0,
) -> CrossCheck:
    """Compare every applicable method with the reference (see the module docstring)."""
    applied = [name for name, r in results.items() if r.applies]
    skipped = {name: r.reason for name, r in results.items() if not r.applies}
    report = CrossCheck(applied, skipped)
    J = [b.J for b in sym.bodies]
    reference_A = sp.Matrix(
        sym.n, sym.n, lambda i, j: sp.cancel(-sym.stiffness_matrix[i, j] / J[i])
    )
    reference_c = sp.Matrix([sp.cancel(sym.reference_forces[i] / J[i]) for i in range(sym.n)])
    reference_Q = sym.generalized_forces
    for name in applied:
        result = results[name]
        if result.nonlinear is not None:
            residual = sp.Matrix([result.nonlinear[i].rhs - reference_Q[i] for i in range(sym.n)])
            lhs_ok = all(
                sp.expand(result.nonlinear[i].lhs - J[i] * sym.qdd[i]) == 0 for i in range(sym.n)
            )
            simplified, zero = _zero(residual, budget)
            report.checks.append(
                Check(
                    name,
                    "exact equations of motion vs -dV/dphi (residual: each body's right side "
                    "minus -dV/dphi_i)",
                    simplified,
                    zero if lhs_ok else False,
                )
            )
        if result.equations is not None:
            A, c = equations_matrix(result.equations, sym)
            simplified, zero = _zero((A - reference_A).row_join(c - reference_c), budget)
            report.checks.append(
                Check(
                    name,
                    "linearised equations vs -M^-1 K (residual: the "
                    "coefficients of q in q'' = A q + b minus -M^-1 K, then b minus the "
                    "reference's constant terms)",
                    simplified,
                    zero,
                )
            )
        if result.omega2 or frequencies.omega2:
            report.checks.append(_compare_omega2(name, result.omega2, frequencies, budget))
        mechanics = result.extras.get("mechanics")
        if mechanics is not None:
            report.checks.append(
                Check(
                    "lagrange, second route",
                    "the Euler-Lagrange equations that SymPy's mechanics module forms from the "
                    "Lagrangian vs the structure route I' phi'' = -dV/dphi",
                    mechanics["residual"],
                    mechanics["agrees"],
                )
            )
    return report


def _compare_omega2(
    name: str,
    omega2: list[Any],
    frequencies: Frequencies,
    budget: float | None,
) -> Check:
    reference = frequencies.omega2
    if len(omega2) != len(reference):
        return Check(
            name, f"Omega^2 ({len(omega2)} values vs {len(reference)})", sp.Symbol("count"), False
        )
    residuals = []
    decided: list[bool | None] = []
    for mine, ref in zip(omega2, reference, strict=True):
        if mine is None and ref is None:  # both numeric: the same eigenvalue problem
            residuals.append(sp.Integer(0))
            decided.append(True)
            continue
        if mine is None or ref is None:
            residuals.append(sp.nan)
            decided.append(None)
            continue
        simplified, zero = _zero(sp.sympify(mine) - ref, budget)
        residuals.append(simplified)
        decided.append(zero)
    agrees: bool | None = True
    if any(d is False for d in decided):
        agrees = False
    elif any(d is None for d in decided):
        agrees = None
    return Check(
        name,
        "Omega^2 vs the roots of det(K - Omega^2 M) (residual: each squared frequency "
        "minus the root)",
        sp.Matrix(residuals) if len(residuals) != 1 else residuals[0],
        agrees,
    )
