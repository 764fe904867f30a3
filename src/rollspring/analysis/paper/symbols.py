"""The symbols the paper check writes the paper's expressions in.

The engine's own (:math:`m_i, R_i, k, \\varphi_i, \\dot\\varphi_i, \\ddot\\varphi_i, x_i`: the same
names and assumptions as :mod:`rollspring.analysis.derivation` uses, so that an expression of the
paper and one of the engine share their symbols) and the paper's own (an amplitude ``A``, the
frequency ``Omega``, canonical coordinates ``q_i, p_i``, the friction forces ``f_i``, ...).
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
# the paper's own symbols (not the engine's)
A = sp.Symbol("A", positive=True)  # amplitude of the spring's deformation (Sec. 5.2)
Omega = sp.Symbol("Omega", positive=True)  # the paper's angular frequency of the mode
Phid1, Phid2 = sp.symbols("Phidot_1 Phidot_2", positive=True)  # maximal angular velocities
q1, q2, q3, q4 = sp.symbols("q_1 q_2 q_3 q_4", real=True)  # canonical coordinates
p1, p2, p3, p4 = sp.symbols("p_1 p_2 p_3 p_4", real=True)  # canonical momenta
pd1 = sp.Symbol("pdot_1", real=True)  # the rate of p_1 (Sec. 5.6)
Fx1, Fx2 = sp.symbols("F_1x F_2x", real=True)  # horizontal spring force on body 1, 2
f1, f2 = sp.symbols("f_1 f_2", real=True)  # the paper's static friction forces (App. A)
fpull = sp.Symbol("f", real=True)  # the friction of the pulled body (App. A), against F
I_ = sp.Symbol("I", positive=True)  # the pulled body's moment of inertia (App. A)
ell_total = sp.Symbol("l", positive=True)  # the spring's length (Sec. 5.3)
# constants of the motion (fixed by the start): the conserved combination and its integral
P0 = sp.Symbol("P_0", real=True)
D0 = sp.Symbol("D_0", real=True)
t = sp.Symbol("t", real=True)
a = sp.Symbol("a", real=True)  # amplitude along a mode shape
# the isotonic oscillator (Sec. 5.2, "unique to harmonic oscillation")
xi, xid, omega0, beta0, energy = sp.symbols("x xdot omega beta E", positive=True)
half = sp.Rational(1, 2)
