"""The bench: the paper's systems made symbolic, and the objects derived from them, built once.

A recipe (:mod:`rollspring.analysis.paper.recipes`) asks the bench for a system's symbolic form,
its closed-form frequencies, mode shapes, zero mode, lever arms, linear friction, the stationary
point's weights, ...; one bench serves every claim of a check, so each is derived once.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import sympy as sp

from rollspring.analysis.derivation import SymbolicSystem, symbolic_system
from rollspring.analysis.derivation.frequencies import normal_frequencies
from rollspring.analysis.paper.algebra import tidy
from rollspring.analysis.paper.notation import A
from rollspring.analysis.paper.systems import paper_system


class Bench:
    """The symbolic systems and the derived objects they share, built once each."""

    def __init__(self) -> None:
        self._cache: dict[tuple[Any, ...], Any] = {}

    def _cached(self, key: tuple[Any, ...], build: Callable[[], Any]) -> Any:
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    def sym(self, key: str) -> SymbolicSystem:
        result: SymbolicSystem = self._cached(
            ("sym", key), lambda: symbolic_system(paper_system(key), symbols=True)
        )
        return result

    def omega2(self, key: str) -> list[sp.Expr]:
        """Closed forms of the squared frequencies of the oscillating modes (the engine's
        det(K - Omega^2 M) = 0)."""

        def build() -> list[sp.Expr]:
            found = normal_frequencies(self.sym(key), budget=None)
            if not found.complete:
                raise RuntimeError(f"{key}: no closed-form frequencies")
            return list(found.omega2)

        result: list[Any] = self._cached(("omega2", key), build)
        return result

    def mode(self, key: str) -> sp.Matrix:
        """The one oscillating mode shape (in phi), the null vector of K - Omega^2 M."""

        def build() -> sp.Matrix:
            sym = self.sym(key)
            (w2,) = self.omega2(key)
            (v,) = (sym.stiffness_matrix - w2 * sym.mass_matrix).nullspace(simplify=True)
            return v.applyfunc(tidy)

        return self._cached(("mode", key), build)

    def zero_mode(self, key: str) -> sp.Matrix:
        def build() -> sp.Matrix:
            v0 = self.sym(key).zero_mode()
            if v0 is None:
                raise RuntimeError(f"{key}: no single zero mode")
            return v0

        return self._cached(("zero", key), build)

    def lever(self, key: str, spring: int = 0) -> list[sp.Expr]:
        """b_i = dl/dq_i at the reference: the spring's deformation is b . q (linear)."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            (length,) = sym.linearized([sym.springs[spring].length])
            return [tidy(sp.diff(length, q)) for q in sym.q]

        result: list[Any] = self._cached(("lever", key, spring), build)
        return result

    def friction_linear(self, key: str) -> list[sp.Expr]:
        """The required friction (M8) to first order in q, positive along +x."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            return [sp.expand(f) for f in sym.linearized(sym.friction_configuration)]

        result: list[Any] = self._cached(("friction", key), build)
        return result

    def weights(self, key: str) -> list[sp.Expr]:
        """Stationary-point weights w_i = J_i v0_i / s_i, normalised (docs/physics.md (M14))."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            v0 = self.zero_mode(key)
            raw = [b.J * v0[i] / b.s for i, b in enumerate(sym.bodies)]
            total = sp.Add(*raw)
            return [tidy(w / total) for w in raw]

        result: list[Any] = self._cached(("weights", key), build)
        return result

    def conserved(self, key: str) -> list[sp.Expr]:
        """Coefficients c = v0^T M of the conserved combination c . qdot (M14)."""
        sym = self.sym(key)
        v0 = self.zero_mode(key)
        return [tidy(v0[i] * sym.mass_matrix[i, i]) for i in range(sym.n)]

    def accelerations(self, key: str, *, linear: bool = False) -> list[sp.Expr]:
        """qdd_i = Q_i / J_i from the engine's equations of motion (M7)."""
        sym = self.sym(key)
        return [
            tidy(eq.rhs / b.J)
            for eq, b in zip(sym.equations_of_motion(linear=linear), sym.bodies, strict=True)
        ]

    def along_mode(self, exprs: Sequence[sp.Expr], key: str) -> list[sp.Expr]:
        """Linear forms of q evaluated on the oscillating mode shape."""
        sym = self.sym(key)
        v = self.mode(key)
        sub = {q: v[i] for i, q in enumerate(sym.q)}
        return [tidy(sp.sympify(e).xreplace(sub)) for e in exprs]

    def amplitudes(self, key: str) -> list[sp.Expr]:
        """Centre amplitudes A_i in the oscillating mode whose spring deformation is A."""
        sym = self.sym(key)
        v = self.mode(key)
        deformation = sp.Abs(tidy(sum(b * v[i] for i, b in enumerate(self.lever(key)))))
        return [tidy(A * sp.Abs(body.s * v[i]) / deformation) for i, body in enumerate(sym.bodies)]

    def canonical(self, key: str) -> list[sp.Expr]:
        r""":math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`: the point transformation that turns
        :math:`T = \sum J_i\dot\varphi_i^2/2` into :math:`\sum m_i\dot q_i^2/2`."""
        sym = self.sym(key)
        return [sp.sqrt(b.J / b.m) * b.q for b in sym.bodies]

    def hamiltonian(
        self, key: str, qs: Sequence[sp.Symbol], ps: Sequence[sp.Symbol]
    ) -> tuple[sp.Expr, sp.Expr]:
        """(H, V) in the canonical coordinates: H = sum p^2/(2m) + V, V the engine's quadratic
        potential with phi_i = sqrt(m_i/J_i) q_i."""
        sym = self.sym(key)
        to_q = {b.q: sp.sqrt(b.m / b.J) * qq for b, qq in zip(sym.bodies, qs, strict=True)}
        V = sp.expand(sym.quadratic_potential.xreplace(to_q))
        T = sp.Add(*[pp**2 / (2 * b.m) for b, pp in zip(sym.bodies, ps, strict=True)])
        return T + V, V
