"""The assumptions the paper itself states, each with its words (verbatim) and where it says them.

A claim that relies on one names it (``assumptions`` in its table of ``claims.toml``); the verdict
"holds under a stated assumption" quotes it.
"""

from __future__ import annotations

from rollspring.analysis.paper.types import Assumption

RELEASED_FIG1 = Assumption(
    "the masses start from rest (compressed, then released)",
    "The masses are compressed in the direction of the longitudinal axis of the spring and then "
    "released.",
    "Sec. 2",
)
RELEASED = Assumption(
    "the bodies start from rest (the spring compressed, then released)",
    r"As Fig.~\ref{fig2} shows the spring is initially compressed and suddenly released.",
    "Sec. 3",
)
EQUAL_RADII = Assumption(
    "the hoop and the cylinder have the same radius R",
    "The center of a thin ring of radius $R$ and mass $m_1$ and the center of the cylinder of "
    "radius $R$ and mass $m_2$ are connected by an ideal spring",
    "Sec. 3",
)
FORCE_AMOUNTS = Assumption(
    "F₁, F₂ are amounts (magnitudes)", "always exert the same amount of force", "Sec. 2"
)
SPRING_MAGNITUDES = Assumption(
    "the spring forces are compared in magnitude",
    "The spring forces are equal in magnitude",
    "Sec. 3",
)
FRICTION_AMOUNTS = Assumption(
    "f₁, f₂ are amounts (magnitudes)", "different amounts of static friction forces", "Sec. 3"
)
LEVEL = Assumption(
    "the centres of the two bodies are at the same height",
    "the centers of rigid bodies are at the same height",
    "Sec. 4",
)
SMALL_ANGLES = Assumption(
    "small angles (first order in the amplitude)",
    "the following equations describe the motion of the coupled system only in small angle "
    "approximation",
    "Sec. 4",
)
MAXIMAL = Assumption(
    "Φ̇₁, Φ̇₂ are the maximal angular speeds (magnitudes)",
    r"$\dot{\Phi_1}, \dot{\Phi_2}$ are the maximal angular velocities",
    "Sec. 5.2",
)
ORIGIN = Assumption(
    "the angles are measured about the stationary point X̂, the origin",
    r"Point $\hat{X}$ has been chosen as the origin of the coordinate system",
    "Sec. 5.3",
)
ORIGIN_APP_A = Assumption(
    "the angles are measured about the stationary point X̂, the origin",
    r"Point $\hat{X}$ has been selected as the origin of our coordinate system",
    "App. A",
)
