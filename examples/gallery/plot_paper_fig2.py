r"""
The paper's Fig. 2: modes, the stationary point and the centre of mass
======================================================================

A hoop and a cylinder joined at their centres (the default system). Two modes: a zero mode, the
free rolling of the pair that moves :math:`\hat X`, and the oscillation at
:math:`\Omega^2 = k/(2m_1) + 2k/(3m_2)`. Released from a compressed spring, :math:`\hat X` stays
put while the centre of mass swings by :math:`A/14`.
"""

import matplotlib.pyplot as plt

import rollspring
from rollspring.outputs.figures import plot_modes, plot_positions, plot_system

system = rollspring.load_system("hoop-cylinder")
result = rollspring.analyze(system)
for mode in result.modes:
    print(f"{mode.kind:12s} omega = {mode.omega:.6f} rad/s, centre displacements {mode.shape_x}")

# %%
# The system at its equilibrium, with the centre of mass and :math:`\hat X` on the floor.
fig, ax = plt.subplots(figsize=(7, 2.6), layout="constrained")
plot_system(result, ax, at="equilibrium")

# %%
# The two modes: arrows give each centre's displacement in the mode.
plot_modes(result, fig=plt.figure(figsize=(8, 3.2)))

# %%
# The motion: centre displacements, the CM (dashed) and :math:`\hat X` (dotted).
run = rollspring.simulate(system, 2.0)
fig, ax = plt.subplots(figsize=(7, 3.2), layout="constrained")
plot_positions(run, ax)
print(
    f"CM amplitude {result.cm_amplitude:.6g} m, X-hat amplitude {result.stationary_amplitude:.3g} m"
)
