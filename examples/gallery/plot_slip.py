r"""
Slip and stick–slip
===================

The hoop and cylinder of Fig. 2 need :math:`\mu = 0.051` (hoop) to roll. Give the hoop
:math:`\mu_s = 0.04`: the spring's push is largest at release, so the hoop slips at once, and a
run with ``on_slip="stop"`` (the default) ends there with status ``slip`` and the instant. With
``on_slip="continue"`` the hoop slides with kinetic friction :math:`\mu_k N` (M19) and sticks
again when its contact point stops and the friction then needed is within :math:`\mu_s N`.
"""

import matplotlib.pyplot as plt

import rollspring
from rollspring.outputs.figures import plot_contact_forces, plot_energy, plot_friction_ratio

data = rollspring.load_system("hoop-cylinder").model_dump()
data["bodies"][0].update(mu_static=0.04, mu_kinetic=0.03)
system = rollspring.system_from_dict(data)

stopped = rollspring.simulate(system, 2.0)
print(stopped.status, "-", stopped.message)
print("first slip:", stopped.summary["first_slip"])

# %%
# Stick–slip: the run goes on through the slipping phases.
run = rollspring.simulate(system, 2.0, on_slip="continue")
print(run.status, "-", len(run.events), "events:")
for event in run.events[:6]:
    print("  ", event)

fig, ax = plt.subplots(figsize=(7, 3), layout="constrained")
plot_friction_ratio(run, ax)
plot_contact_forces(run, fig=plt.figure(figsize=(7, 4.5)))

# %%
# Energy is dissipated only while the hoop slides, at the rate :math:`\mu_k N |v_s|`.
fig, ax = plt.subplots(figsize=(7, 3), layout="constrained")
plot_energy(run, ax)
