r"""
A wall chain
============

A wall, a hoop and a cylinder in a chain (the style of the paper's Fig. 4). The wall removes the
zero mode: both modes oscillate, and no point stays put. The trace identity
:math:`\sum_n\omega_n^2 = \sum_i K_{ii}/J_i` still holds (docs/physics.md §7.2).
"""

import matplotlib.pyplot as plt
import numpy as np

import rollspring
from rollspring.outputs.figures import plot_modes, plot_positions, plot_system

system = rollspring.load_system("wall-hoop-cylinder")
result = rollspring.analyze(system)
omegas = np.array([mode.omega for mode in result.modes])
print("omega (rad/s):", omegas)
print(
    "sum omega^2 =",
    np.sum(omegas**2),
    " sum K_ii/J_i =",
    np.sum(np.diag(result.stiffness) / np.diag(result.mass)),
)
print("stationary point:", result.stationary_weights)

fig, ax = plt.subplots(figsize=(7, 2.6), layout="constrained")
plot_system(result, ax)
plot_modes(result, fig=plt.figure(figsize=(8, 3.2)))

# %%
# Two incommensurate frequencies: the motion never repeats.
run = rollspring.simulate(system, 4.0)
fig, ax = plt.subplots(figsize=(7, 3.2), layout="constrained")
plot_positions(run, ax)
