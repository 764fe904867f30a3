"""The sign conventions every result states: in the JSON form of a linear analysis
(:meth:`rollspring.analysis.LinearAnalysis.to_dict`, ``rollspring analyze --json``), in the
report and in the CLI's tables.

Plain data, with no dependency on the rest of :mod:`rollspring.analysis`: the analysis modules
import it, never the other way round.
"""

from __future__ import annotations

__all__ = ["CONVENTIONS"]

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
