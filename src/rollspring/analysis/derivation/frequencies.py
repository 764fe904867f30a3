r"""Normal frequencies in closed form: :math:`\det(K - \Omega^2 M) = 0` (docs/physics.md section 7).

With the constant diagonal :math:`M` the characteristic polynomial is that of
:math:`A = M^{-1}K` (:math:`A_{ij} = K_{ij}/J_i`). One body: :math:`\Omega^2 = K/J`. Two bodies
with a zero mode (rank-1 K): :math:`\Omega^2 = \operatorname{tr}A = K_{11}/J_1 + K_{22}/J_2`
(the paper's sum rule (M15)); without one, the quadratic formula. More bodies: the polynomial
(a three-term recurrence for chains), its zero roots taken out, and the roots of every factor of
degree at most two, within a time budget.

With the parameters as exact numbers the polynomial is factored over the rationals whatever its
degree, and the roots of its factors of degree one or two are exact. With them as symbols,
beyond degree :data:`MAX_FACTORED` in :math:`\Omega^2` (zero roots taken out) no closed form is
offered (a polynomial of degree five or more has no general formula for its roots) and the
polynomial is not expanded either (a polynomial in every parameter: for a chain of ten bodies,
21 parameters, SymPy had not finished after five minutes); it is given at the parameters'
values instead (:attr:`Frequencies.at_values`, exact numbers), whose roots are the numbers the
derivation shows.
"""

from __future__ import annotations

import contextlib
import gc
import math
import signal
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import FrameType

import sympy as sp

from rollspring.analysis.derivation.parts import exact_number
from rollspring.analysis.derivation.symbolic import SymbolicSystem, is_tridiagonal
from rollspring.errors import BudgetExceeded

__all__ = [
    "OMEGA2",
    "BudgetExceeded",
    "Frequencies",
    "exact_values",
    "normal_frequencies",
    "time_budget",
]

#: The symbol of a squared normal frequency.
OMEGA2 = sp.Symbol("Omega^2")
#: Largest number of bodies whose characteristic polynomial is expanded.
MAX_POLYNOMIAL = 12
#: Largest degree (in Omega^2, zero roots taken out) of a polynomial in symbolic parameters
#: factored in search of quadratic factors: factoring one of higher degree costs seconds and
#: finds none in general (with exact numbers every degree is factored: that is cheap).
MAX_FACTORED = 4


#: When the budget's alarm comes inside a garbage collector's callback or a finaliser, it is
#: raised this much later (s): an exception leaving either is printed and dropped, never seen
#: by the block (Hypothesis times the collector with such a callback).
RETRY_SECONDS = 0.001


def _swallowed(frame: FrameType | None) -> bool:
    """Whether ``frame`` runs inside a garbage collector's callback or a ``__del__``, whose
    exceptions Python prints as "ignored" instead of raising them in the interrupted code."""
    callbacks = {getattr(callback, "__code__", None) for callback in gc.callbacks}
    while frame is not None:
        if frame.f_code in callbacks or frame.f_code.co_name == "__del__":
            return True
        frame = frame.f_back
    return False


@contextlib.contextmanager
def time_budget(seconds: float | None) -> Iterator[None]:
    """Raise :class:`BudgetExceeded` inside the block after ``seconds`` (main thread on POSIX;
    elsewhere the block runs without a limit). An alarm that comes while the garbage collector
    runs (its callbacks, the finalisers and weak-reference callbacks it calls) or inside a
    ``__del__``, where the exception would be dropped, is raised :data:`RETRY_SECONDS` later."""
    usable = (
        seconds is not None
        and seconds > 0
        and hasattr(signal, "setitimer")
        and threading.current_thread() is threading.main_thread()
    )
    if seconds is None or not usable:
        yield
        return

    collecting = [False]  # a garbage collection under way: its callbacks drop exceptions

    def track(phase: str, info: dict[str, int]) -> None:
        collecting[0] = phase == "start"

    def expire(signum: int, frame: FrameType | None) -> None:  # a signal handler
        if collecting[0] or _swallowed(frame):  # raised here it would be lost: a moment later
            signal.setitimer(signal.ITIMER_REAL, RETRY_SECONDS)
            return
        raise BudgetExceeded

    gc.callbacks.append(track)
    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        gc.callbacks.remove(track)


@dataclass
class Frequencies:
    r"""Squared normal frequencies of (M, K).

    ``characteristic``: :math:`\det(\Omega^2 I - M^{-1}K)` (monic in :data:`OMEGA2`), or None
    when not expanded; ``omega2``: closed forms of the non-zero roots, ascending by value
    (None entries where no closed form was found); ``numeric``: their numbers; ``n_zero`` zero
    modes; ``notes``: what was not done and why; ``at_values``: where ``characteristic`` is
    None, the same polynomial at the parameters' values (exact numbers; None if that was not
    computed either); ``factors``: the degrees of its irreducible factors (zero roots taken
    out, with multiplicity, ascending) where it was factored, else empty; ``degree``: its
    degree in :data:`OMEGA2` after the zero roots.
    """

    characteristic: sp.Expr | None
    omega2: list[sp.Expr | None]
    numeric: list[float]
    n_zero: int
    notes: list[str] = field(default_factory=list)
    at_values: sp.Expr | None = None
    factors: list[int] = field(default_factory=list)

    @property
    def degree(self) -> int:
        """The degree of the characteristic polynomial in Omega^2, zero roots taken out."""
        return len(self.numeric)

    @property
    def complete(self) -> bool:
        """Every non-zero root has a closed form."""
        return all(w is not None for w in self.omega2)


def dynamic_matrix(sym: SymbolicSystem) -> sp.Matrix:
    """:math:`A = M^{-1}K`, row i divided by :math:`J_i`."""
    K = sym.stiffness_matrix
    J = [b.J for b in sym.bodies]
    return sp.Matrix(sym.n, sym.n, lambda i, j: sp.cancel(K[i, j] / J[i]) if K[i, j] != 0 else 0)


def characteristic_polynomial(A: sp.Matrix, variable: sp.Symbol = OMEGA2) -> sp.Expr:
    r""":math:`\det(\lambda I - A)`: a three-term recurrence when A is tridiagonal, else
    Berkowitz."""
    n = A.shape[0]
    if is_tridiagonal(A):
        previous, current = sp.Integer(1), variable - A[0, 0]
        for k in range(1, n):
            previous, current = (
                current,
                sp.expand((variable - A[k, k]) * current - A[k, k - 1] * A[k - 1, k] * previous),
            )
        return sp.expand(current)
    return A.charpoly(variable).as_expr()


def exact_values(sym: SymbolicSystem) -> dict[sp.Symbol, sp.Expr]:
    """The parameters' values as the exact numbers ``symbols=False`` would use."""
    return {symbol: exact_number(value) for symbol, value in sym.values.items()}


def _at_values(sym: SymbolicSystem, A: sp.Matrix) -> sp.Expr:
    r""":math:`\det(\Omega^2 I - A)` with the parameters' exact values (rational arithmetic)."""
    return characteristic_polynomial(A.xreplace(exact_values(sym)))


def _polynomial_entries(sym: SymbolicSystem) -> bool:
    """Whether every entry of K and every J is a polynomial in the parameters (the
    recurrence of :func:`_tridiagonal_determinant` works in polynomials; a spring tilted
    between centres of different heights puts its length in a denominator)."""
    symbols = sorted(sym.stiffness_matrix.free_symbols | sym.mass_matrix.free_symbols, key=str)
    entries = [*sym.stiffness_matrix, *(body.J for body in sym.bodies)]
    return all(sp.sympify(entry).is_polynomial(*symbols) for entry in entries)


def _tridiagonal_determinant(sym: SymbolicSystem) -> sp.Poly:
    r""":math:`\det(K - \Omega^2 M)` of a tridiagonal K (a chain) by the three-term recurrence,
    as a polynomial in :math:`\Omega^2` and the parameters."""
    K = sym.stiffness_matrix
    gens = [OMEGA2, *sorted(K.free_symbols | sym.mass_matrix.free_symbols, key=str)]

    def poly(expr: sp.Expr) -> sp.Poly:
        return sp.Poly(expr, *gens)

    previous, current = poly(sp.Integer(1)), poly(K[0, 0] - OMEGA2 * sym.bodies[0].J)
    for k in range(1, sym.n):
        diagonal = poly(K[k, k] - OMEGA2 * sym.bodies[k].J)
        coupling = poly(K[k, k - 1] * K[k - 1, k])
        previous, current = current, diagonal * current - coupling * previous
    return current


def normal_frequencies(
    sym: SymbolicSystem, *, budget: float | None = 10.0, matrix: sp.Matrix | None = None
) -> Frequencies:
    """Closed forms of the squared normal frequencies where SymPy finds them (see module).

    ``matrix``: the dynamic matrix to use instead of :math:`M^{-1}K` (any matrix similar to
    it, e.g. the Hamiltonian coordinates' :math:`M_q^{-1}K_q`).
    """
    n, n_zero = sym.n, sym.zero_mode_count()
    from rollspring.analysis.derivation.symbolic import matrix_to_float
    from rollspring.analysis.linear import normal_modes

    mass = matrix_to_float(sym.mass_matrix, sym.values)
    stiff = matrix_to_float(sym.stiffness_matrix, sym.values)
    eigenvalues, _, kinds = normal_modes(mass, stiff)
    numeric = [float(v) for v, kind in zip(eigenvalues, kinds, strict=True) if kind != "zero"]
    A = dynamic_matrix(sym) if matrix is None else matrix
    notes: list[str] = []
    began = time.perf_counter()

    def left() -> float | None:
        return None if budget is None else max(budget - (time.perf_counter() - began), 1e-3)

    if n == 1:
        value = A[0, 0]
        return Frequencies(OMEGA2 - value, [value] if n_zero == 0 else [], numeric, n_zero)
    if n == 2:
        trace = sp.cancel(A[0, 0] + A[1, 1])
        det = sp.cancel(A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0])
        poly = sp.expand(OMEGA2**2 - trace * OMEGA2 + det)
        if n_zero == 2:
            return Frequencies(poly, [], numeric, n_zero)
        if n_zero == 1 and det == 0:
            return Frequencies(poly, [_tidy(trace)], numeric, n_zero)
        root = sp.sqrt(sp.factor(trace**2 - 4 * det))
        pair = [_tidy((trace - root) / 2), _tidy((trace + root) / 2)]
        pair.sort(key=lambda r: _value(sym, r))
        return Frequencies(poly, pair, numeric, n_zero)

    def at_values() -> sp.Expr | None:
        """The polynomial at the parameters' values, within what is left of the budget."""
        if not sym.symbolic:
            return None
        try:
            with time_budget(left()):
                return _at_values(sym, A)
        except BudgetExceeded:
            notes.append(
                f"the characteristic polynomial at the parameters' values took longer than the "
                f"{budget:g} s budget"
            )
            return None

    def numbers_only() -> Frequencies:
        return Frequencies(None, [None] * len(numeric), numeric, n_zero, notes, at_values())

    if any(entry.has(sp.sin, sp.cos, sp.atan2) for entry in A):
        notes.append(
            "the stiffness holds transcendental constants (sines and cosines of the "
            "equilibrium angles): the frequencies are given numerically"
        )
        try:
            with time_budget(left()):
                poly = characteristic_polynomial(A) if n <= 4 else None
        except BudgetExceeded:
            poly = None
        if poly is None:
            return numbers_only()
        return Frequencies(poly, [None] * len(numeric), numeric, n_zero, notes)
    if sym.symbolic and len(numeric) > MAX_FACTORED:
        notes.append(
            f"{_no_closed_form(len(numeric))}; with the parameters as symbols it is not "
            "expanded (a polynomial in every one of them), only at their values"
        )
        return numbers_only()
    if n > MAX_POLYNOMIAL and sym.symbolic:
        notes.append(
            f"{n} bodies: the characteristic polynomial (degree {n}) is left "
            "unexpanded; the frequencies are given numerically"
        )
        return numbers_only()
    try:
        with time_budget(left()):
            if matrix is None and is_tridiagonal(sym.stiffness_matrix) and _polynomial_entries(sym):
                # det(K - Omega^2 M) = (-1)^n prod(J) det(Omega^2 - M^-1 K): polynomial
                # arithmetic, no rational functions
                determinant = _tridiagonal_determinant(sym)
                scale = sp.Mul(*[-b.J for b in sym.bodies])
                poly = sp.Mul(determinant.as_expr(), sp.Pow(scale, -1))
                reduced = sp.Poly(determinant, OMEGA2)
            else:
                poly = characteristic_polynomial(A)
                reduced = sp.Poly(poly, OMEGA2)
    except BudgetExceeded:
        notes.append(f"the characteristic polynomial took longer than the {budget:g} s budget")
        return numbers_only()
    removed = 0
    while removed < n_zero and reduced.degree() > 0 and sp.cancel(reduced.nth(0)) == 0:
        reduced = sp.Poly(sp.cancel(reduced.as_expr() / OMEGA2), OMEGA2)
        removed += 1
    roots: list[sp.Expr | None] = []
    if reduced.degree() > MAX_FACTORED and sym.symbolic:
        notes.append(_no_closed_form(reduced.degree()))
        return Frequencies(poly, [None] * len(numeric), numeric, n_zero, notes)
    degrees: list[int] = []
    try:
        with time_budget(left()):
            # with exact numbers the polynomial has rational coefficients: factoring it is
            # cheap at any degree, and finds the exact roots it has (a uniform chain has some)
            factors = sp.factor_list(reduced.as_expr(), OMEGA2)[1] if reduced.degree() > 0 else []
            for factor, multiplicity in factors:
                fpoly = sp.Poly(factor, OMEGA2)
                if fpoly.degree() == 0:
                    continue
                degrees.extend([fpoly.degree()] * multiplicity)
                if fpoly.degree() <= 2:
                    found = [_tidy(r) for r in sp.roots(fpoly, OMEGA2, multiple=True)]
                else:
                    found = [None] * fpoly.degree()
                roots.extend(found * multiplicity)
            higher = sorted(d for d in degrees if d > 2)
            if higher:
                notes.append(
                    f"factors of degree {', '.join(map(str, higher))} of the characteristic "
                    "polynomial: no closed form offered for their roots (none exists in "
                    "general beyond degree four); they are given numerically"
                )
    except BudgetExceeded:
        notes.append(
            f"factoring the characteristic polynomial took longer than the {budget:g} s "
            "budget; the frequencies are given numerically"
        )
        roots = [None] * len(numeric)
    known = sorted((r for r in roots if r is not None), key=lambda r: _value(sym, r))
    ordered: list[sp.Expr | None] = []
    for value in numeric:  # match closed forms to the numbers
        match = next(
            (
                r
                for r in known
                if math.isclose(_value(sym, r), value, rel_tol=1e-8, abs_tol=1e-12 * max(numeric))
            ),
            None,
        )
        if match is not None:
            known.remove(match)
        ordered.append(match)
    return Frequencies(poly, ordered, numeric, n_zero, notes, factors=sorted(degrees))


def _no_closed_form(degree: int) -> str:
    """Why a characteristic polynomial of ``degree`` (in Omega^2) gets numbers, not formulas."""
    return (
        f"the characteristic polynomial has degree {degree} in Omega^2 (zero roots taken out): "
        "no closed form for its roots (a polynomial of degree five or more has no general "
        "formula); the frequencies are given numerically"
    )


def _value(sym: SymbolicSystem, expr: sp.Expr) -> float:
    value = complex(sp.sympify(expr).xreplace(sym.values).evalf(30))
    return value.real


def _tidy(expr: sp.Expr) -> sp.Expr:
    expr = sp.sympify(expr)
    if expr.count_ops() > 300:
        return expr
    if any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        return sp.together(expr)  # the quadratic formula: one fraction, no factoring (slow)
    candidates = [expr, sp.factor(sp.cancel(expr))]
    return min(candidates, key=sp.count_ops)
