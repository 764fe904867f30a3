r"""What tracking a video and fitting a recording will cost, known before the work starts.

The lab's two long computations are estimated as every other command's are
(:mod:`rollspring.analysis.costs`): a :class:`~rollspring.analysis.costs.Cost` that
:func:`~rollspring.analysis.costs.check_cost` refuses above 5 minutes or 2 GiB unless confirmed
(``--yes``, ``confirm=True``), made in a fraction of a second from what is known up front.

* **Tracking** (:func:`tracking_cost`, :func:`rollspring.track`, ``rollspring track``): from the
  video's header (:func:`video_header`: frame count, frame rate, frame size), the frames
  before ``--from`` are decoded only (OpenCV reads a video from its start) and those from
  ``--from`` to ``--to`` are tracked,

  .. math:: t = N_{\rm skip}\,P\,c_{\rm decode}
            + N\,\bigl(t_{\rm frame} + P\,(c_{\rm track} + c_{\rm overlay})\bigr),

  :math:`P` the pixels of a frame, :math:`c_{\rm overlay}` only with ``--overlay``. Memory: the
  frame's working images, :math:`P\,b_{\rm pixel}`, and what is kept of each tracked frame
  (:math:`N\,(b_{\rm frame} + n\,b_{\rm body})`: the per-frame measurements, the tracks and
  their CSV text). A header without a frame count (a stream whose container says neither its
  length nor its duration, or a raw stream such as a ``.mjpeg`` file, for which OpenCV reports
  a meaningless negative count) is counted: the frames are grabbed (decoded, not converted) for at
  most :data:`COUNT_SECONDS`; a count cut short there is a lower bound, and the estimate says
  "at least", with the run's time counted as above the bound (it needs confirming).
* **Fitting** (:func:`fit_cost`, :func:`rollspring.fit`, ``rollspring fit``): on the exact
  linear motion (level centre springs, no rolling resistance:
  :func:`~rollspring.lab.fit.linear_route`) a product of matrices per frame and evaluation,

  .. math:: t = t_0 + t_{\rm scan} + c_{\rm linear}\,N_{\rm frames}\,(2n+1)^2\,E\,(p+2),

  on the simulated motion one :func:`rollspring.simulate` of the recording's span per
  evaluation of the residuals, every fitted parameter's forward difference included,

  .. math:: t = t_0 + t_{\rm scan} + \bigl(E\,(p + 2) + p\bigr)\,t_{\rm sim},

  :math:`t_{\rm scan} = c_{\rm scan} N_{\rm frames}` the scan of the start time when ``t0`` is
  fitted (``fix_initial``: some 80 starts, each a linear profile over the frames), 0 otherwise;

  :math:`p` the fitted parameters (the free PATHs and each body's initial state, or ``t0``
  and the offset), :math:`E` = :data:`~rollspring.lab.fit.EXPECTED_ITERATIONS` the solver's
  iterations (5 to 12 on the fits measured: rounded up) and :math:`t_{\rm sim}` the
  simulation's own estimate (:func:`rollspring.simulate.costs.simulation_cost` at
  ``rtol`` 1e-9 with four outputs per frame; DOP853's when a damping or a rolling resistance is
  free, as the solver soon makes it non-zero). Memory: the Jacobian
  (:math:`8\,N_{\rm points}\,(p+2)` bytes) and the motion's arrays.

The constants were measured by ``bench/bench_lab_costs.py`` on one core of the development
machine (2 cores shared with other work), CPU time, and rounded up: an estimate is meant to be
right within a factor of a few, enough to tell seconds from hours. The same script prints each
estimate against the time measured in its run.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass

from rollspring.analysis.costs import Cost, describe_bytes, describe_duration
from rollspring.errors import FitError, SimulationError
from rollspring.lab.data import BodyData
from rollspring.model import System

__all__ = [
    "COUNT_SECONDS",
    "FIT_SMALLER",
    "TRACK_SMALLER",
    "LabCost",
    "VideoHeader",
    "fit_cost",
    "tracked_frames",
    "tracking_cost",
    "video_header",
]

#: How long a video whose header gives no frame count is counted at most (s of grabbing).
COUNT_SECONDS = 2.0

#: how to make a tracking or a fit smaller, in the command line's words
TRACK_SMALLER = "a shorter stretch with --from/--to, or a smaller video"
FIT_SMALLER = "a shorter recording, fewer --free PATHs"

# -- tracking: seconds of one core (CPU time, bench/bench_lab_costs.py) --------------------------
#: seconds per pixel of a frame before --from: decoded, nothing else (OpenCV's grab)
_DECODE_PER_PIXEL = 3.0e-9
#: seconds per pixel of a tracked frame: decoding, colour conversion, smoothing, each body's
#: outline and marker (the bodies' size in pixels grows with the frame's)
_TRACK_PER_PIXEL = 1.0e-8
#: seconds per tracked frame apart from its pixels (the per-body Python work)
_TRACK_PER_FRAME = 3.0e-3
#: seconds per pixel of a frame drawn and encoded into the --overlay video (mp4v)
_OVERLAY_PER_PIXEL = 8.0e-9
#: bytes per pixel of the working images of one frame (BGR, grey, smoothed float32, remaps)
_BYTES_PER_PIXEL = 16.0
#: bytes kept per tracked frame (its time and index, the per-frame arrays' headers) and per
#: body in it (centre, radius, angle, residual, contrast; the tracks, the CSV's text)
_BYTES_PER_FRAME, _BYTES_PER_BODY_FRAME = 1200.0, 250.0

# -- fitting ------------------------------------------------------------------------------------
#: seconds before the solver (reading, the spectrum, the first guesses)
_FIT_SETUP = 0.2
#: seconds per frame, (2n+1)² matrix entry and evaluation on the linear route (4e-8 measured
#: on 120 s at 120 fps, where the solver took 26 iterations)
_LINEAR_PER_ENTRY = 1.0e-7
#: seconds per frame of the start time's scan when ``t0`` is fitted (``fix_initial``): 41 to 82
#: starts × each first guess, a linear profile over the frames each (measured: 0.2 ms with 41
#: starts, 1.0–1.6 ms with the release scanned too)
_T0_SCAN_PER_FRAME = 1.0e-3
#: bytes per frame and matrix entry held on the linear route at its peak (the transition
#: matrices, their products and copies): 150-190 measured (tracemalloc) for 20 000 and 60 000
#: frames of two bodies (24 before, five times too few: a fit of 2.2 GiB passed the bound)
_LINEAR_BYTES_PER_ENTRY = 170.0
#: free quantities that make the simulations dissipative (DOP853) once the solver moves them
_DISSIPATIVE = ("damping", "rolling_resistance")


@dataclass(frozen=True)
class LabCost(Cost):
    """A :class:`~rollspring.analysis.costs.Cost` whose time comes from ``work`` (said in the
    message: "432000 frames of 3840×2160 px × 2 bodies"); ``lower_bound`` when the work is
    only known to be at least that (a video counted only in part)."""

    work: str = ""
    lower_bound: bool = False

    def describe(self) -> str:
        """One line: the time, what it comes from, the memory."""
        line = f"{'at least' if self.lower_bound else 'about'} {describe_duration(self.seconds)}"
        line += f": {self.work}" if self.work else ""
        if self.memory:
            line += f", {describe_bytes(self.memory)} of {self.holds}"
        return line


# ------------------------------------------------------------------------------------ tracking


@dataclass(frozen=True)
class VideoHeader:
    """What a video's header says: ``frames`` (counted when the header gives none: then
    ``counted``, and ``complete`` False when the count was cut short, a lower bound), ``fps``
    (0 when unknown), ``width`` × ``height`` pixels."""

    frames: int
    fps: float
    width: int
    height: int
    counted: bool = False
    complete: bool = True


def video_header(
    video: str | os.PathLike[str], *, count_seconds: float = COUNT_SECONDS
) -> VideoHeader:
    """The header of ``video`` read with OpenCV (nothing decoded unless it gives no frame
    count: then frames are grabbed for at most ``count_seconds``). One-line
    :class:`~rollspring.errors.TrackingError` for a missing, irregular, empty or unreadable
    file, as tracking gives."""
    import cv2

    from rollspring.lab.tracking import open_video

    capture = open_video(video)
    try:
        fps = _finite(capture.get(cv2.CAP_PROP_FPS))
        width = int(_finite(capture.get(cv2.CAP_PROP_FRAME_WIDTH)))
        height = int(_finite(capture.get(cv2.CAP_PROP_FRAME_HEIGHT)))
        frames = int(_finite(capture.get(cv2.CAP_PROP_FRAME_COUNT)))
        if frames > 0:
            return VideoHeader(frames, fps, width, height)
        counted, complete = _count_frames(capture, count_seconds)
    finally:
        capture.release()
    return VideoHeader(counted, fps, width, height, counted=True, complete=complete)


def _finite(value: float) -> float:
    value = float(value)
    return value if math.isfinite(value) and value > 0 else 0.0


def _count_frames(capture: object, seconds: float) -> tuple[int, bool]:
    """Frames grabbed from ``capture`` until its end (complete) or ``seconds`` (cut short)."""
    grab = capture.grab  # type: ignore[attr-defined]
    ends = time.perf_counter() + seconds
    count = 0
    while grab():
        count += 1
        if count % 16 == 0 and time.perf_counter() > ends:
            return count, False
    return count, True


def tracked_frames(
    header: VideoHeader, start: float | None = None, stop: float | None = None
) -> tuple[int, int]:
    """``(skipped, tracked)``: the frames decoded before ``start`` and those tracked from
    ``start`` to ``stop`` (s), frame i at i/fps; without a frame rate every frame is counted as
    tracked."""
    frames = header.frames
    if header.fps <= 0:
        return 0, frames
    first = 0 if start is None else min(frames, math.ceil(start * header.fps - 1e-6))
    last = frames if stop is None else min(frames, math.floor(stop * header.fps + 1e-6) + 1)
    return first, max(0, last - first)


def tracking_cost(
    header: VideoHeader,
    bodies: int,
    *,
    start: float | None = None,
    stop: float | None = None,
    overlay: bool = False,
    what: str = "tracking",
    smaller: str = TRACK_SMALLER,
) -> LabCost:
    r"""The estimated cost of tracking ``bodies`` bodies in the video of ``header`` from
    ``start`` to ``stop`` (s), with the ``overlay`` video written too (the module's
    docstring):

    .. math:: t = N_{\rm skip}\,P\,c_{\rm decode}
              + N\,\bigl(t_{\rm frame} + P\,(c_{\rm track} + c_{\rm overlay})\bigr),
              \qquad m = P\,b_{\rm pixel} + N\,(b_{\rm frame} + n\,b_{\rm body}).

    A count cut short (:attr:`VideoHeader.complete` False) makes a lower bound, counted as
    above the bound so that it needs confirming."""
    from rollspring.analysis.costs import MAX_SECONDS

    skipped, tracked = tracked_frames(header, start, stop)
    pixels = float(header.width) * float(header.height)
    per_pixel = _TRACK_PER_PIXEL + (_OVERLAY_PER_PIXEL if overlay else 0.0)
    seconds = skipped * pixels * _DECODE_PER_PIXEL + tracked * (
        _TRACK_PER_FRAME + pixels * per_pixel
    )
    memory = pixels * _BYTES_PER_PIXEL + tracked * (
        _BYTES_PER_FRAME + bodies * _BYTES_PER_BODY_FRAME
    )
    work = (
        f"{'more than ' if not header.complete else ''}{tracked} frames of "
        f"{header.width}×{header.height} px × {bodies} bod{'y' if bodies == 1 else 'ies'}"
    )
    if skipped:
        work += f" (and {skipped} decoded before --from)"
    if header.counted:
        work += " (counted: the header gives no frame count)"
    if not header.complete:
        seconds = max(seconds, 2 * MAX_SECONDS)
    return LabCost(
        what,
        bodies,
        seconds,
        memory,
        smaller=smaller,
        holds="memory",
        work=work,
        lower_bound=not header.complete,
    )


# ------------------------------------------------------------------------------------- fitting


def fit_cost(
    data: BodyData,
    system: System,
    free: Sequence[str],
    *,
    fix_initial: bool = False,
    what: str = "the fit",
    smaller: str = FIT_SMALLER,
) -> LabCost:
    r"""The estimated cost of :func:`rollspring.fit` of ``system`` to ``data`` (matched to its
    bodies) freeing the PATHs ``free``, with ``fix_initial`` as there (the module's docstring):
    on the exact linear route
    :math:`t = t_0 + t_{\rm scan} + c_{\rm linear}\,N_{\rm frames}\,(2n+1)^2\,E\,(p+2)`, on
    the simulated route :math:`t = t_0 + t_{\rm scan} + (E\,(p+2) + p)\,t_{\rm sim}` with
    :math:`t_{\rm sim}` the estimate of one simulation of the recording's span (four outputs per
    frame, ``rtol`` 1e-9) and :math:`t_{\rm scan} = c_{\rm scan} N_{\rm frames}` with
    ``fix_initial``.
    The PATHs are not checked here (the fit checks them)."""
    from rollspring.lab.fit import EXPECTED_ITERATIONS, linear_route
    from rollspring.lab.motion import SIMULATION_RTOL

    n = len(system.bodies)
    frames = int(data.t.size)
    points = data.n_points
    anchored = bool(system.anchors)
    fitted = len(free) + (2 if fix_initial else 2 * n + (1 if anchored else 0))
    evaluations = EXPECTED_ITERATIONS * (fitted + 2)
    span = float(data.t[-1] - data.t[0]) if frames > 1 else 0.0
    jacobian = 8.0 * points * (fitted + 2)
    scan = _T0_SCAN_PER_FRAME * frames if fix_initial else 0.0
    if linear_route(system, free):
        entries = frames * (2 * n + 1) ** 2
        seconds = _FIT_SETUP + scan + _LINEAR_PER_ENTRY * entries * evaluations
        memory = jacobian + _LINEAR_BYTES_PER_ENTRY * entries
        work = (
            f"{points} points × {fitted} fitted parameters on the exact linear motion, "
            f"about {evaluations} evaluations"
        )
    else:
        from rollspring.simulate.costs import simulation_cost

        simulations = evaluations + fitted
        # a free damping or rolling resistance makes the runs dissipative as the solver moves
        # it from 0: DOP853's steps, whatever the system starts with
        dissipative = any(path.split(".")[-1] in _DISSIPATIVE for path in free)
        try:
            one = simulation_cost(
                system,
                max(span, 1e-3),
                rtol=SIMULATION_RTOL,
                integrator="dop853" if dissipative else "auto",
                outputs=max(2, 4 * frames),
            )
        except SimulationError as exc:
            raise FitError(
                f"{data.source}: a recording of {span:g} s cannot be simulated ({exc})"
            ) from None
        seconds = _FIT_SETUP + scan + simulations * one.seconds
        memory = jacobian + one.memory
        work = (
            f"about {simulations} simulations of {span:.3g} s ({points} points × {fitted} "
            f"fitted parameters; the motion is not linear)"
        )
    return LabCost(what, n, seconds, memory, smaller=smaller, holds="memory", work=work)
