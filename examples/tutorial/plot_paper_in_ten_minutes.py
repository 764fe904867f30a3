r"""
The paper in ten minutes
========================

G. Nyitray's *On the edge of complexity: the simplest not simple coupled mechanical system*
(arXiv 2508.01379) asks a simple question: a hoop and a solid cylinder, joined at their centres
by a spring, roll without slipping on a floor. Does their centre of mass stay at rest, as it would
for two blocks on ice? It does not. This page goes through the paper's argument with rollspring,
every number computed as the page is built. The equations are in :doc:`the model <../physics>`.
"""

# %%
# Two blocks on ice (the paper's Fig. 1)
# --------------------------------------
# Two point masses on a frictionless floor joined by a spring: the only horizontal forces are
# the spring's, internal to the pair, so the centre of mass stays at rest.
import numpy as np

import rollspring

blocks = rollspring.analyze(rollspring.load_system("two-masses"))
print(
    f"omega = {blocks.oscillating[0].omega:.4f} rad/s, CM amplitude = {blocks.cm_amplitude:.3g} m"
)

# %%
# A hoop and a cylinder (Fig. 2)
# ------------------------------
# The default system: a hoop and a cylinder of 1 kg and R = 0.1 m, joined at their centres by a
# spring of k = 100 N/m, released with the spring compressed by A = 0.01 m.
system = rollspring.load_system("hoop-cylinder")
result = rollspring.analyze(system)
mode = result.oscillating[0]
k, m1, m2, A = 100.0, 1.0, 1.0, 0.01

# %%
# Rolling makes each body one coordinate with the inertia about its contact line,
# :math:`J = I + mR^2` (M4): :math:`2mR^2` for the hoop, :math:`\tfrac32 mR^2` for the cylinder.
# The paper's eq. (QQQ1), :math:`\Omega^2 = k/(2m_1) + 2k/(3m_2)`:
print("M =", np.diag(result.mass), "kg m^2")
print(f"Omega^2 = {mode.omega**2:.6f} 1/s^2, formula {k / (2 * m1) + 2 * k / (3 * m2):.6f}")
print(f"period = {mode.period:.6f} s")

# %%
# The stationary point
# --------------------
# Static friction is an external force, so the centre of mass is free to move. What stays put
# is :math:`\hat X`, the centres weighted by :math:`(1+\gamma)m` — the paper's eq. (c), (M11):
print("weights of X-hat:", result.stationary_weights)  # 4/7, 3/7
print(f"X-hat amplitude = {result.stationary_amplitude:.3g} m")
print(f"CM amplitude    = {result.cm_amplitude:.6g} m  (A/14 = {A / 14:.6g} m)")

# %%
# Friction, in size and in sign
# -----------------------------
# Appendix A: a pull F at the centre needs static friction F/2 on the hoop and F/3 on the
# cylinder (M10). The paper's "f1/f2 = 3/2" is a ratio of magnitudes: in the mode the two
# frictions point opposite ways.
print("friction amplitudes (N):", result.friction_amplitude)  # kA/2, kA/3
print("friction coefficient the motion needs:", result.required_mu)
shape = mode.friction
print(f"f1/f2 in the mode = {shape[0] / shape[1]:.3f}")

# %%
# The exact motion
# ----------------
# With the centres level and joined at the centres the equations are exactly linear, so the
# nonlinear simulation's measured period equals the linear one to rounding, and the figure shows
# the CM swinging while :math:`\hat X` stays still.
import matplotlib.pyplot as plt

from rollspring.outputs.figures import plot_positions, plot_system

run = rollspring.simulate(system, 2.0, rtol=1e-10)
print(
    f"measured period {run.summary['period_measured']:.10f} s, "
    f"linear {run.summary['period_linear']:.10f} s"
)

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), layout="constrained")
plot_system(result, top)
plot_positions(run, bottom)

# %%
# Where the paper needs a correction
# ----------------------------------
# The paper's Fig. 3 joins the hoop's top to the cylinder at :math:`1.5R_2`, the percussion
# points, so that no friction is needed to first order. With the paper's :math:`R_1 = R_2/2` on
# one floor the two ends are 0.1 m and 0.15 m high: the spring is tilted, and the frequency is
# the paper's :math:`\Omega^2 = 2k/m_1 + 3k/(2m_2)` times :math:`\cos^2` of the tilt (M15).
import math

paper_fig3 = rollspring.system_from_dict(
    {
        "name": "Fig. 3 on one floor, R1 = R2/2",
        "bodies": [
            {"id": "hoop", "shape": "hoop", "mass": 1.0, "radius": 0.05, "x": 0.0, "v": -0.05},
            {
                "id": "cylinder",
                "shape": "cylinder",
                "mass": 1.0,
                "radius": 0.1,
                "x": 0.5,
                "v": 0.05,
            },
        ],
        "springs": [
            {
                "ends": ["hoop", "cylinder"],
                "stiffness": 100.0,
                "at": [{"height": 0.1}, {"height": 0.15}],
            }
        ],  # rest length: as placed
    }
)
fig3 = rollspring.analyze(paper_fig3)
tilt = float(fig3.spring_tilt_deg[0])
print(f"spring tilt {tilt:.2f} deg")
print(
    f"Omega^2 = {fig3.oscillating[0].omega ** 2:.3f} 1/s^2; "
    f"paper 350 x cos^2(tilt) = {350 * math.cos(math.radians(tilt)) ** 2:.3f}"
)

# %%
# Every claim, checked
# --------------------
# ``rollspring.check_paper()`` compares each quantitative claim of the paper with what the
# derivation engine derives (the full table is :doc:`on its own page <../_generated/paper_check>`).
from collections import Counter

checks = rollspring.check_paper()
print(Counter(check.verdict for check in checks))
for check in checks:
    if check.verdict == "wrong":
        print(f"- {check.claim.location}: {check.reason}")
