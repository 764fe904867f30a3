"""The systems the paper's claims are checked on: its Fig. 1, 2, 3 systems and their variants.

Each is a rollspring system file (a dictionary, :data:`SYSTEMS`) that the derivation engine turns
symbolic; :func:`paper_figure` tells which of them a user's system is (by structure, for the
report's paper section).
"""

from __future__ import annotations

import math
from typing import Any

from rollspring.model import System, system_from_dict


def _body(
    id_: str, shape: str, mass: float, radius: float, x: float, **extra: Any
) -> dict[str, Any]:
    return {"id": id_, "shape": shape, "mass": mass, "radius": radius, "x": x, **extra}


def _pair(
    shape1: str,
    shape2: str,
    *,
    r1: float = 0.1,
    r2: float = 0.1,
    track1: float = 0.0,
    at: list[dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """Two bodies joined by one spring (k = 100 N/m); distinct masses 1.3 kg and 0.7 kg so that
    no equality of masses is assumed by accident."""
    spring: dict[str, Any] = {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}
    if at is not None:
        spring["at"] = at
        spring.pop("rest_length")  # at rest length in the initial placement
        return {
            "bodies": [
                _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
                _body("b2", shape2, 0.7, r2, 0.5),
            ],
            "springs": [spring],
        }
    return {
        "bodies": [
            _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
            _body("b2", shape2, 0.7, r2, 0.49),
        ],
        "springs": [spring],
    }


def _pulled(shape: str, **extra: Any) -> dict[str, Any]:
    """One body pulled horizontally by a constant force at height 0.137 m (paper App. A, Fig. 5);
    0.137/R is no simple ratio, so the engine names the height y."""
    return {
        "bodies": [_body("b", shape, 1.3, 0.1, 0.0, **extra)],
        "forces": [{"body": "b", "at": {"height": 0.137}, "fx": 2.0}],
    }


#: The systems the claims are checked on, as system files (dictionaries).
SYSTEMS: dict[str, dict[str, Any]] = {
    # Fig. 1: two point masses, compressed and released
    "fig1": {
        "bodies": [_body("b1", "slider", 1.3, 0.05, 0.0), _body("b2", "slider", 0.7, 0.05, 0.49)],
        "springs": [{"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}],
    },
    # Fig. 2: hoop (m1) and cylinder (m2) of equal radius R, centres joined
    "fig2": _pair("hoop", "cylinder"),
    "two-hoops": _pair("hoop", "hoop"),
    "two-cylinders": _pair("cylinder", "cylinder"),
    # Fig. 3 as the paper sizes it: R1 = R2/2, centres level (the hoop's track raised by R1),
    # the spring from the hoop's top (2R1) to the cylinder at 1.5 R2: horizontal
    "fig3": _pair(
        "hoop", "cylinder", r1=0.05, r2=0.1, track1=0.05, at=[{"height": 0.1}, {"height": 0.15}]
    ),
    # a wall spring on the hoop, the hoop-cylinder spring: a system whose normal modes do not
    # obey the sum rule (the counter-example to Sec. 5.4's "consequently")
    "fig4a": {
        "anchors": [{"id": "wall", "x": -0.5, "y": 0.1}],
        "bodies": [_body("b1", "hoop", 1.3, 0.1, 0.0), _body("b2", "cylinder", 0.7, 0.1, 0.49)],
        "springs": [
            {"ends": ["wall", "b1"], "stiffness": 80.0, "rest_length": 0.5},
            {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5},
        ],
    },
    # Sec. 4's "We need to ensure that there is no static friction force": a hoop of radius
    # 3R2/4 beside the cylinder on one floor, the spring level with the hoop's centre (at
    # 3R2/4 on the cylinder): the frictions cancel, neither vanishes
    "zero-sum": _pair(
        "hoop", "cylinder", r1=0.075, r2=0.1, at=[{"height": 0.075}, {"height": 0.075}]
    ),
    # Sec. 3 with unequal radii: the hoop (R1 = 0.1 m) on a track raised by R2 - R1 so that the
    # centres stay level, the cylinder R2 = 0.137 m: X-hat's weights are I'_i/R_i^2, not I'_i
    "fig2-radii": _pair("hoop", "cylinder", r1=0.1, r2=0.137, track1=0.037),
    # the Abstract's "same moment of inertia": a hoop (m) and a cylinder (2m) of one radius have
    # I_1 = I_2 = m R^2, yet their frictions do not cancel
    "same-inertia": {
        "bodies": [
            _body("b1", "hoop", 0.7, 0.1, 0.0),
            _body("b2", "cylinder", 1.4, 0.1, 0.49),
        ],
        "springs": [{"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}],
    },
    # ... and read as the inertias about the contact lines, I'_1 = I'_2: m_1 = 3m_2/4 (where
    # Sec. 5.3 has k_1 = k_2): X-hat is the midpoint, the centre of mass still moves
    "same-contact-inertia": {
        "bodies": [
            _body("b1", "hoop", 0.75, 0.1, 0.0),
            _body("b2", "cylinder", 1.0, 0.1, 0.49),
        ],
        "springs": [{"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}],
    },
    # Fig. 3 on one floor: R1 = R2/2, the spring from the hoop's top (2R1) to the cylinder's
    # point 3R2/2 high, tilted by atan(0.05/0.5) = 5.7 degrees: no first-order friction either
    "fig3-tilted": _pair(
        "hoop", "cylinder", r1=0.05, r2=0.1, at=[{"height": 0.1}, {"height": 0.15}]
    ),
    # fig4a at its equilibrium (both springs at their rest lengths): a start in one normal mode
    "fig4a-rest": {
        "anchors": [{"id": "wall", "x": -0.5, "y": 0.1}],
        "bodies": [_body("b1", "hoop", 1.3, 0.1, 0.0), _body("b2", "cylinder", 0.7, 0.1, 0.5)],
        "springs": [
            {"ends": ["wall", "b1"], "stiffness": 80.0, "rest_length": 0.5},
            {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5},
        ],
    },
    # App. A: a body with I = gamma m R^2 pulled at height y; and a hoop, a cylinder
    "pulled": _pulled("custom", inertia_factor=0.3),
    "pulled-hoop": _pulled("hoop"),
    "pulled-cylinder": _pulled("cylinder"),
}


def paper_system(key: str) -> System:
    """One of :data:`SYSTEMS` as a validated rollspring system."""
    return system_from_dict(SYSTEMS[key])


def paper_figure(system: System) -> tuple[str, set[str]] | None:
    """Which of the paper's systems ``system`` is, as ``(label, keys of`` :data:`SYSTEMS` ``)``,
    or None.

    By structure, not by numbers (the paper's claims are symbolic): two sliders joined at their
    centres (Fig. 1); a hoop and a solid cylinder, or two hoops, or two cylinders, joined at
    their centres, centres level (Fig. 2); a hoop and a cylinder joined at their percussion
    heights (1 + γ)R (Fig. 3); a wall spring on a hoop that is joined to a cylinder at the centres
    (Fig. 4 (a)). No constant forces in any of them.
    """
    if system.forces:
        return None
    bodies = {b.id: b for b in system.bodies}
    shapes = sorted(b.shape for b in system.bodies)
    springs = system.springs

    def centres(spring: Any) -> bool:
        return all(at.is_centre_form for at in spring.attachments)

    level = len({round(b.track_height + b.radius, 12) for b in system.bodies}) == 1
    if len(bodies) == 2 and len(springs) == 1 and not system.anchors:
        (spring,) = springs
        if shapes == ["slider", "slider"] and centres(spring):
            return "Fig. 1 (two point masses)", {"fig1"}
        if centres(spring) and level:
            if shapes == ["cylinder", "hoop"]:
                return "Fig. 2 (hoop and cylinder joined at their centres)", {"fig2"}
            if shapes == ["hoop", "hoop"]:
                return "Sec. 3 variant with two hoops", {"two-hoops"}
            if shapes == ["cylinder", "cylinder"]:
                return "Sec. 3 variant with two cylinders", {"two-cylinders"}
        if shapes == ["cylinder", "hoop"] and all(
            at.height is not None
            and math.isclose(at.height, bodies[end].percussion_height, rel_tol=1e-9)
            for end, at in zip(spring.ends, spring.attachments, strict=True)
        ):
            return "Fig. 3 (springs at the percussion points, no friction)", {"fig3"}
    if (
        len(bodies) == 2
        and len(system.anchors) == 1
        and len(springs) == 2
        and shapes == ["cylinder", "hoop"]
        and all(centres(s) for s in springs)
    ):
        anchor = system.anchors[0].id
        wall = [s for s in springs if anchor in s.ends]
        if len(wall) == 1 and any(bodies[e].shape == "hoop" for e in wall[0].ends if e in bodies):
            return (
                "a wall spring on the hoop (as Fig. 4 (a) builds up; the Sec. 5.4 counter-example)",
                {"fig4a"},
            )
    return None
