r"""
MuJoCo against exact rolling
============================

``rollspring export --format mjcf`` writes the same system as a MuJoCo model: planar bodies (slide
x, slide z, hinge), the right inertias, one plane per track, friction :math:`\mu_s`, springs as
tendons. MuJoCo's contact is soft, so its rolling is approximate: the bodies sink slightly into
the floor and the contact point creeps. Here both run the paper's system for 2 s.
"""

import matplotlib.pyplot as plt
import mujoco
import numpy as np

import rollspring
from rollspring.outputs.mjcf import system_to_mjcf

system = rollspring.load_system("hoop-cylinder")
exact = rollspring.simulate(system, 2.0, n_output=2001)

model = mujoco.MjModel.from_xml_string(system_to_mjcf(system))
data = mujoco.MjData(model)
mujoco.mj_resetDataKeyframe(model, data, 0)  # the keyframe "initial": the file's placement
steps = round(2.0 / model.opt.timestep)
time, x_hoop = np.empty(steps + 1), np.empty(steps + 1)
time[0], x_hoop[0] = data.time, data.joint("hoop:x").qpos[0]
for n in range(1, steps + 1):
    mujoco.mj_step(model, data)
    time[n], x_hoop[n] = data.time, data.joint("hoop:x").qpos[0]
print(f"MuJoCo {mujoco.__version__}: {steps} steps of {model.opt.timestep} s")

# %%
# The hoop's centre in both, and their difference.
reference = np.interp(time, exact.t, exact.x[:, 0])
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), sharex=True, layout="constrained")
top.plot(exact.t, 1e3 * exact.x[:, 0], label="rollspring (exact rolling)")
top.plot(time, 1e3 * x_hoop, "--", label="MuJoCo (soft contact)")
top.set_ylabel("hoop centre x (mm)")
top.legend()
bottom.plot(time, 1e6 * (x_hoop - reference))
bottom.set_xlabel("t (s)")
bottom.set_ylabel("MuJoCo − exact (µm)")
print(
    f"largest difference over 2 s: {1e6 * np.abs(x_hoop - reference).max():.1f} µm "
    f"against an amplitude of {1e3 * np.ptp(exact.x[:, 0]) / 2:.2f} mm"
)
