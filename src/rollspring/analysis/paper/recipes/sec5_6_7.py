"""Recipes for Sec. 5.6: Hamilton's equations in canonical coordinates.

From the engine's quadratic potential in q_i = sqrt(J_i/m_i) phi_i: the Hamiltonian, Hamilton's
equations, the ratio of the canonical coordinates in the mode and the potential of Fig. 3 (the
conclusion of Sec. 7 restates claims whose recipes live with their sections).
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from rollspring.analysis.paper.algebra import tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import p1, p2, pd1, q1, q2
from rollspring.analysis.paper.recipes.common import (
    CANONICAL_ORIENTATION,
    flip_first,
    flip_first_rate,
)
from rollspring.analysis.paper.symbols import k, m1
from rollspring.analysis.paper.types import Derived


def canonical(b: Bench) -> Derived:
    return Derived(
        tuple(b.canonical("fig2")),
        "q_i = sqrt(J_i/m_i) phi_i makes the engine's T = sum J_i phidot_i^2/2 equal to "
        "sum m_i qdot_i^2/2 (p_i = m_i qdot_i)",
    )


def hamiltonian(key: str = "fig2") -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        H, _ = b.hamiltonian(key, (q1, q2), (p1, p2))
        return Derived(
            H,
            "H = sum p_i^2/(2m_i) + V with the engine's V in q_i = sqrt(J_i/m_i) phi_i",
            condition=CANONICAL_ORIENTATION,
            paper_if=flip_first,
        )

    return derive


def hamilton_equations(b: Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        (sp.expand(sp.diff(H, q1)), sp.expand(sp.diff(H, q2))),
        "-pdot_i = dH/dq_i with the derived H",
        condition=CANONICAL_ORIENTATION,
        paper_if=flip_first_rate,
    )


def factor_2_sqrt3(b: Bench) -> Derived:
    # the paper's own (h) right-hand sides: the ratio of the second to the first
    common = k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3))
    first, second = common / sp.sqrt(2), common * sp.sqrt(2) / sp.sqrt(3)
    return Derived(
        tidy(second / first), "the ratio of the right-hand sides of the paper's (h) (SymPy)"
    )


def q_ratio(b: Bench) -> Derived:
    v = b.mode("fig2")
    canon = b.canonical("fig2")
    sym = b.sym("fig2")
    sub = {qq: v[i] for i, qq in enumerate(sym.q)}
    ratio = tidy(canon[1].xreplace(sub) / canon[0].xreplace(sub))
    # the pair (pdot_2/pdot_1, q_2 as a multiple of q_1) in the mode
    masses = [body.m for body in sym.bodies]
    value = (tidy(masses[1] * ratio / masses[0]) * pd1, ratio * q1)
    return Derived(
        value,
        "pdot_2/pdot_1 = m_2 q_2/(m_1 q_1) and q_2/q_1 in the oscillating mode "
        "(q_i = sqrt(J_i/m_i) phi_i)",
        assumed=value,
        condition=CANONICAL_ORIENTATION,
        paper_if=flip_first,
    )


def hamilton_final(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        sp.expand(m1 * w2) * q1,
        "-pdot_1 = m_1 Omega^2 q_1 in the mode (qddot_1 = -Omega^2 q_1) with the derived Omega^2",
    )


def hamilton_to_ep(b: Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.diff(H, p1), w2),
        "qdot_1 = dH/dp_1 from the derived H (so pdot_1 = m_1 qddot_1), and the engine's Omega^2",
    )


def qdot(b: Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived((sp.diff(H, p1), sp.diff(H, p2)), "qdot_i = dH/dp_i with the derived H")


def interchangeable(b: Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(tidy(sp.sqrt(body.J / body.m) * body.q) for body in sym.bodies),
        "the canonical coordinates sqrt(J_i/m_i) q_i of the two masses (J_i = m_i): the "
        "positions themselves",
    )
