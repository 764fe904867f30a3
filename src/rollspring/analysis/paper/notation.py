"""The paper's own symbols, which the engine does not use: its notation for what it derives.

An amplitude ``A`` and the mode's frequency ``Omega``, maximal angular velocities, canonical
coordinates and momenta ``q_i, p_i``, the spring forces and static frictions as the paper names
them, the constants of the motion ``P_0, D_0``, and the isotonic oscillator's variables (Sec. 5.2).
A recipe maps those that stand for an engine quantity onto it (``Derived.paper_subs``).
"""

from __future__ import annotations

import sympy as sp

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
