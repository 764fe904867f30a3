"""The paper's own expressions that several sections' claims are written in.

I'_1, I'_2 (Fig. 2), the stiffness k_1 of the hoop's part of the spring (Sec. 5.3), the
Hamiltonian of the hoop and the cylinder in canonical coordinates, Omega^2 as the four methods give
it, and the truth value of a claim "X differs from Y".
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.notation import half
from rollspring.analysis.paper.symbols import R, k, m1, m2


def hoop_cylinder_hamiltonian(
    qa: sp.Symbol, qb: sp.Symbol, pa: sp.Symbol, pb: sp.Symbol, ca: sp.Expr, cb: sp.Expr
) -> sp.Expr:
    """H = p_a^2/(2m_1) + p_b^2/(2m_2) + (k/2)(c_a q_a + c_b q_b)^2: the hoop and the cylinder in
    canonical coordinates (Sec. 5.6, App. C), c_a, c_b the coefficients the paper gives."""
    return pa**2 / (2 * m1) + pb**2 / (2 * m2) + k / 2 * (ca * qa + cb * qb) ** 2


J1, J2 = 2 * m1 * R**2, sp.Rational(3, 2) * m2 * R**2  # the paper's I'_1, I'_2 (Fig. 2)
k1_paper = k * (3 * m2 + 4 * m1) / (3 * m2)
TRUE = sp.true

# Omega^2 as the paper's four methods give it: (QQ1), the speeds' display of Sec. 5.2, (ep),
# Sec. 5.6's -pdot_1 = k(q_1/2 + 2m_1 q_1/(3m_2)) with pdot_1 = m_1 qddot_1
METHODS = (
    k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
    (k / (2 * m1) + 2 * k / (3 * m2)),
    k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
    k / m1 * (half + 2 * m1 / (3 * m2)),
)
