r"""The engine's symbols, in which the paper check writes the paper's expressions.

:math:`m_i, R_i, k, \gamma, y, F, \varphi_i, \dot\varphi_i, \ddot\varphi_i, x_i, \dot x_i`:
the same names and assumptions as :mod:`rollspring.analysis.derivation` uses, so that an
expression of the paper and one of the engine share their symbols. The paper's own symbols (not
the engine's) are in :mod:`~rollspring.analysis.paper.notation`.
"""

from __future__ import annotations

import sympy as sp

# -- the symbols (the same names and assumptions as the derivation engine's) ---------------------
m, m1, m2 = sp.symbols("m m_1 m_2", positive=True)
R, R1, R2 = sp.symbols("R R_1 R_2", positive=True)
k, k1, k2 = sp.symbols("k k_1 k_2", positive=True)
gamma, y = sp.symbols("gamma y", positive=True)
F = sp.Symbol("F", real=True)
phi, phi1, phi2 = sp.symbols("phi phi_1 phi_2", real=True)
phid1, phid2 = sp.symbols("phidot_1 phidot_2", real=True)
phidd, phidd1, phidd2 = sp.symbols("phiddot phiddot_1 phiddot_2", real=True)
x1, x2 = sp.symbols("x_1 x_2", real=True)
xd1, xd2 = sp.symbols("xdot_1 xdot_2", real=True)
