"""The JSON form of a linear analysis (``rollspring analyze --json``)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from rollspring.analysis.linear import LinearAnalysis

__all__ = ["CONVENTIONS", "analysis_to_dict"]

#: Sign conventions, stated in every JSON result.
CONVENTIONS = {
    "axes": "x to the right, y up; SI units throughout",
    "phi": "rotation in rad, clockwise positive (rolling to the right), from the initial placement",
    "coordinates": "a rolling body's coordinate is phi (rad); a slider's is its displacement x (m)",
    "friction": "static friction on a body at its contact, N, positive along +x; the paper's "
    "f1/f2 = 3/2 is a ratio of magnitudes: the two frictions point opposite ways",
    "normal_force": "N, upward on the body",
    "tension": "N, positive when the spring is stretched",
    "tilt_deg": "angle of the spring line from its first end to its second, above the "
    "horizontal, in (-90, 90]",
    "mode_normalisation": "largest centre displacement = +1 m; friction, normal_force and "
    "spring_extension are the first-order changes along that shape",
    "response": "exact linear motion from the initial placement, about the equilibrium (which "
    "moves at drift_velocity when a zero mode is set moving); with several frequencies an "
    "amplitude is the supremum over all phases: reached when the frequencies are "
    "incommensurate, an upper bound otherwise",
}


def _num(value: float) -> float | None:
    value = float(value)
    if not math.isfinite(value):
        return None
    return 0.0 if value == 0 else value


def _by_id(ids: tuple[str, ...], values: Any) -> dict[str, float | None]:
    return {i: _num(v) for i, v in zip(ids, np.asarray(values, dtype=float), strict=True)}


def analysis_to_dict(analysis: LinearAnalysis) -> dict[str, Any]:
    """A JSON-ready dictionary: every number finite or null, every per-body value keyed by id."""
    arrays = analysis.arrays
    ids = arrays.ids
    q = analysis.equilibrium.q
    rotation = arrays.rolls * q
    modes = []
    for mode in analysis.modes:
        modes.append(
            {
                "kind": mode.kind,
                "omega": _num(mode.omega) if mode.kind != "unstable" else 0.0,
                "growth_rate": _num(mode.omega) if mode.kind == "unstable" else None,
                "frequency_hz": _num(mode.frequency),
                "period": _num(mode.period),
                "damping_ratio": _num(mode.damping_ratio),
                "shape": _by_id(ids, mode.shape_x),
                "shape_phi": _by_id(ids, arrays.rolls * mode.shape_q),
                "spring_extension": [_num(v) for v in mode.spring_extension],
                "friction": _by_id(ids, mode.friction),
                "normal_force": _by_id(ids, mode.normal_force),
            }
        )
    stationary = None
    if analysis.stationary_weights is not None:
        weights = analysis.stationary_weights
        cm_weights = arrays.mass / arrays.mass.sum()
        stationary = {
            "weights": _by_id(ids, weights),
            "position": _num(analysis.stationary_position or 0.0),
            "velocity": _num(analysis.stationary_velocity or 0.0),
            "is_centre_of_mass": bool(np.allclose(weights, cm_weights, rtol=1e-9, atol=1e-12)),
        }
    response = None
    if analysis.amplitude is not None:
        assert analysis.friction_amplitude is not None
        assert analysis.normal_force_range is not None and analysis.required_mu is not None
        response = {
            "amplitude": _by_id(ids, analysis.amplitude),
            "velocity_amplitude": _by_id(ids, analysis.velocity_amplitude),
            "drift_velocity": _by_id(ids, analysis.drift_velocity),
            "cm_amplitude": _num(analysis.cm_amplitude or 0.0),
            "stationary_point_amplitude": (
                None
                if analysis.stationary_amplitude is None
                else _num(analysis.stationary_amplitude)
            ),
            "friction_amplitude": _by_id(ids, analysis.friction_amplitude),
            "normal_force_range": {
                i: [_num(lo), _num(hi)]
                for i, (lo, hi) in zip(ids, analysis.normal_force_range, strict=True)
            },
            "required_mu": _by_id(ids, analysis.required_mu),
        }
    springs = []
    for s, name in enumerate(arrays.spring_names):
        spring = analysis.system.springs[s]
        springs.append(
            {
                "name": name,
                "ends": list(spring.ends),
                "tilt_deg": _num(analysis.spring_tilt_deg[s]),
                "tension": _num(analysis.spring_tension[s]),
                "length": _num(analysis.spring_length[s]),
                "rest_length": _num(arrays.rest_length[s]),
            }
        )
    split = None
    if analysis.spring_split is not None:
        split = {
            "k": _by_id(ids, analysis.spring_split["k"]),
            "share": _by_id(ids, analysis.spring_split["share"]),
            "clamped_omega": _by_id(ids, analysis.spring_split["clamped_omega"]),
            "omega": _num(analysis.spring_split["omega"]),
        }
    return {
        "system": analysis.system.name,
        "coordinates": list(ids),
        "coordinate_units": {
            i: ("rad" if r else "m") for i, r in zip(ids, arrays.rolls, strict=True)
        },
        "conventions": CONVENTIONS,
        "matrices": {
            "M": [[_num(v) for v in row] for row in analysis.mass],
            "K": [[_num(v) for v in row] for row in analysis.stiffness],
        },
        "equilibrium": {
            "found": analysis.equilibrium.found,
            "phi": _by_id(ids, rotation),
            "x": _by_id(ids, arrays.x0 + arrays.scale * q),
            "friction": _by_id(ids, analysis.equilibrium_friction),
            "normal_force": _by_id(ids, analysis.equilibrium_normal),
        },
        "modes": modes,
        "stationary_point": stationary,
        "response": response,
        "springs": springs,
        "spring_split": split,
        "warnings": list(analysis.warnings),
    }
