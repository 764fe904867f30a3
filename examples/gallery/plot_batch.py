r"""
A batch: ten thousand runs in one call
======================================

``rollspring.simulate_batch`` runs many variants of one system in parallel, compiled once per
topology. Here the spring stiffness of the paper's system varies from 50 to 400 N/m over 10 000
runs and the hoop's :math:`\mu_s` is 0.1: each run reports its measured period, the friction it
needed, and its own status (``finished`` or ``slip``, with the instant).
"""

import matplotlib.pyplot as plt
import numpy as np

import rollspring
from rollspring.simulate.status import Status

system = rollspring.load_system("hoop-cylinder")
k = np.linspace(50.0, 400.0, 10_000)
batch = rollspring.simulate_batch(
    system, {"springs.0.stiffness": k, "bodies.hoop.mu_static": 0.1}, 2.0
)
theory = 2 * np.pi / np.sqrt(k / 2 + 2 * k / 3)  # Omega^2 = k/(2 m1) + 2k/(3 m2)

finished = batch.status == Status.FINISHED
print(f"{finished.sum()} runs rolled throughout, {(batch.status == Status.SLIP).sum()} slipped")
error = np.abs(batch.period_measured[finished] / theory[finished] - 1).max()
print(f"largest relative period error among them: {error:.2e}")

# %%
# The friction the hoop needs grows with k: it slips once :math:`kA/2 > \mu_s m g`.
fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.4), layout="constrained")
left.plot(k[finished], batch.period_measured[finished], ".", ms=2, label="measured")
left.plot(k, theory, "k--", lw=1, label=r"$2\pi/\Omega$")
left.set_xlabel("k (N/m)")
left.set_ylabel("period (s)")
left.legend()
right.plot(k, batch.max_friction_ratio[:, 0], lw=1)
right.axhline(0.1, color="k", ls=":", lw=1)
right.set_xlabel("k (N/m)")
right.set_ylabel("hoop's max |f|/N")
