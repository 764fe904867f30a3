r"""
The frictionless geometry, and where it stops being frictionless
================================================================

The spring joins the hoop's top (:math:`2R_1`) and the cylinder at :math:`1.5R_2`, both at
0.15 m: each end sits at its body's percussion point, :math:`\lambda_1 = \lambda_2 = 1` (M10), so
the linear motion needs no static friction at all and the centre of mass stays at rest (M17),
(M18). At finite amplitude the ends leave the percussion points (each drops by about
:math:`r\varphi^2/2`) and the spring tilts: friction comes back at third order in the amplitude
(docs/physics.md §8).
"""

import matplotlib.pyplot as plt
import numpy as np

import rollspring
from rollspring.outputs.figures import plot_contact_forces, plot_system

system = rollspring.load_system("frictionless")
result = rollspring.analyze(system)
print(f"Omega^2 = {result.oscillating[0].omega ** 2:.4f} 1/s^2 (2k/m1 + 3k/(2m2) = 350)")
print("linear friction amplitudes (N):", result.friction_amplitude)

fig, ax = plt.subplots(figsize=(7, 2.6), layout="constrained")
plot_system(result, ax)

# %%
# The exact motion: the friction needed is not zero, only small.
run = rollspring.simulate(system, 1.0)
plot_contact_forces(run, fig=plt.figure(figsize=(7, 4.5)))
print("max |f|/N over the run:", run.summary["max_friction_ratio"])

# %%
# Scaling with the amplitude: the launch speeds (hence the amplitude) are multiplied by a factor
# s; the largest friction grows as :math:`s^3`.
scales = np.array([0.5, 1.0, 2.0, 4.0])
peak = []
for s in scales:
    data = system.model_dump()
    for body in data["bodies"]:
        body["v"] *= s
    scaled = rollspring.simulate(rollspring.system_from_dict(data), 1.0)
    peak.append(np.abs(scaled.friction).max())
peak = np.array(peak)
slope = np.polyfit(np.log(scales), np.log(peak), 1)[0]
print(f"max |f| grows as amplitude^{slope:.2f}")

fig, ax = plt.subplots(figsize=(5, 3.2), layout="constrained")
ax.loglog(scales, peak, "o-", label="exact motion")
ax.loglog(scales, peak[1] * scales**3, "--", label=r"$\propto s^3$")
ax.set_xlabel("amplitude scale s")
ax.set_ylabel("max |f| (N)")
ax.legend()
