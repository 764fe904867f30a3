r"""Tracking a video of rolling bodies: each body's centre x (m) and rotation φ (rad) per frame.

:func:`track_video` reads a video with OpenCV and, in every frame, finds the bodies of a system
— a hoop seen as a ring, a cylinder, sphere or shell as a disc, each with one contrasting
marker on its rim — as a camera filming the experiment from the side sees them:

1. **The floor line and the bodies** (first frame): circle candidates of
   ``cv2.HoughCircles``, each refined (as in step 2) and kept when its outline stands well
   above the background's texture; candidate lines, the strongest near-horizontal lines of
   ``cv2.HoughLines`` on Canny edges (within 15° of horizontal), each refined to a fraction of
   a pixel by a straight-line fit to the edge's position in every other column (outliers
   dropped). The floor line is the candidate the most circles stand on (the centre's height
   above it equal to the radius), refined once more without the columns where they stand;
   its angle is the **camera roll**, corrected: positions are
   measured along the floor line and heights above it, angles from its normal. The circles
   standing on it are matched to the system's bodies in the order of their x, by the ratios
   of their radii and by their spacing. The marker's colour, its distance from the centre and
   the body's colour are read from a polar sampling of each body.
2. **Every frame**, per body, in a search window around the centre predicted from the two
   frames before (constant velocity): the outer edge is located on 96 rays from the centre
   (``cv2.remap`` of the smoothed grey image along each ray, the strongest step of the
   body's contrast, to a fraction of a pixel by a parabola), and a circle fitted to those edge
   points by least squares (Kåsa's algebraic fit, outliers beyond three robust standard
   deviations dropped and the fit repeated; rays near the floor contact and towards another
   body left out). A blurred circle's steepest edge lies :math:`\sigma^2/2r` inside it: the
   blur's width σ is read from the curvature of the edge's peak and the radius corrected.
   The centre is then refined on the pixels themselves: every pixel within 3.5 px of that
   circle, in the sectors of the rays kept, weighted by the square of its outward gradient,
   and a weighted circle fit (an edge located along a ray carries an error of a few hundredths
   of a pixel that depends on where the edge falls between pixels; moments over the pixels do
   not). Then the marker: the ring of pixels at its distance from the centre, scored by the
   projection of each pixel's colour on the (marker − body) colour difference, its angle the
   midpoint of the two half-height crossings of the score's peak. A body whose outline or
   marker is not found is looked for farther in the next frame, where it was last seen.

Units and conventions (the columns of ``tracks.csv``):

* ``t``: the frame's time in the video (s; the container's time stamps, or index / fps).
* ``x_<id>``: the centre's position along the floor line (m, +x to the right of the image).
  Origin: the first body's centre in the first tracked frame is at its ``x`` in the system
  file, unless ``origin`` says where (m).
* ``phi_<id>``: the marker's angle from the floor's normal (straight up), clockwise positive,
  unwrapped from frame to frame (rad). A marker put at the top of the body at the system's
  initial placement makes it the model's φ.

* ``xlocked1_<id>``, ``xlocked2_<id>``, ``xlocked3_<id>``: the error of ``x_<id>`` that the
  background locks to the body's position (m, the same in every row; :func:`locked_error`),
  which the fit adds to its uncertainties.

The scale (px/m) is the bodies' measured radii over their known radii (the median over the
frames; the discs' alone when there are any, as a blurred thin ring looks a little larger than
it is), unless given. The quality per body: the RMS of the circle fit's edge residuals, the
RMS of the centre's height above the floor minus its radius (a body that rolls on the floor
keeps it zero), the median contrast of the marker, and the error locked to the position: in
front of a textured wall the grain shifts each located edge by a few hundredths of a pixel, by
the same amount whenever the body stands at the same place, so that the error follows the
position, not the frame, and widens or narrows a swing instead of adding noise; it is measured
from how each sector's residual about the fitted circle changes with the body's position
(:func:`locked_error`), and written to the CSV for the fit.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from rollspring.errors import TrackingError
from rollspring.model import System
from rollspring.physics.arrays import FloatArray

__all__ = [
    "FloorLine",
    "FrameTrack",
    "TrackResult",
    "check_options",
    "draw_overlay",
    "locked_error",
    "open_video",
    "track_video",
]

#: Rays per body for the outline, samples per turn for the marker.
RAYS = 96
MARKER_SAMPLES = 360
#: Rays within this angle (rad) of straight down (the floor contact) are not used.
CONTACT_HALF_ANGLE = math.radians(40.0)
#: A body is lost in a frame when fewer than this fraction of its usable rays find its edge,
#: when its radius is off by more than this fraction, or its marker's contrast is below this.
MIN_RAY_FRACTION = 0.35
MAX_RADIUS_CHANGE = 0.12
MIN_MARKER_SCORE = 0.45
#: Radial sampling step along a ray (px).
STEP = 0.5
#: Half-width (px) of the ring of pixels about the outline that refines a centre.
REFINE_HALF_WIDTH = 3.5
#: Sectors this many rays apart at most count as sharing a background's texture, and the
#: degree of the polynomial in the position an error locked to it is measured to
#: (:func:`locked_error`).
MAX_SECTOR_LAG = 3
LOCKED_DEGREE = 3


@dataclass(frozen=True)
class FloorLine:
    """The floor line in the image: a ``point`` on it (px), its unit ``direction`` (towards
    the image's right) and unit ``normal`` (towards the image's top), all (u, v) with v down.
    ``roll`` is the camera roll (rad): the scene is seen turned counter-clockwise by it."""

    point: FloatArray
    direction: FloatArray
    normal: FloatArray

    @property
    def roll(self) -> float:
        """The angle of the floor line in the image, counter-clockwise positive (rad)."""
        return math.atan2(-float(self.direction[1]), float(self.direction[0]))

    def along(self, points: FloatArray) -> FloatArray:
        """Positions of image ``points`` (..., 2) along the floor line (px)."""
        result: FloatArray = (np.asarray(points) - self.point) @ self.direction
        return result

    def height(self, points: FloatArray) -> FloatArray:
        """Heights of image ``points`` (..., 2) above the floor line (px)."""
        result: FloatArray = (np.asarray(points) - self.point) @ self.normal
        return result


@dataclass(frozen=True)
class FrameTrack:
    """What one frame's tracking found, in pixels (the overlay draws it): per body the centre
    (n, 2), the radius (n,), the marker's point (n, 2) and whether the body was found (n,)."""

    index: int
    time: float
    centre: FloatArray
    radius: FloatArray
    marker: FloatArray
    found: np.ndarray
    floor: FloorLine


@dataclass
class _Body:
    """A body as the tracker knows it after the first frame."""

    id: str
    shape: str
    radius_m: float
    radius_px: float
    polarity: float  # +1: the body is darker than what surrounds it
    colour: FloatArray  # BGR
    marker_direction: FloatArray  # marker colour - body colour, BGR
    marker_radii: FloatArray  # the rows (px from the centre) the marker is sampled at
    marker_half_width: float  # rad


@dataclass
class TrackResult:
    """The tracks of a video (see :mod:`rollspring.lab.tracking` for the conventions).

    ``t`` (frames,) s; ``x`` and ``phi`` (frames, bodies) in m and rad, the columns in the
    order of ``ids`` (the system's); ``frames`` the video's frame indices; ``fps`` the video's
    frame rate; ``scale`` px/m (``scale_source``: ``"radii"`` or ``"given"``); ``roll`` the
    camera roll (rad); ``residuals`` per body: ``circle_rms`` (m), ``height_rms`` (m),
    ``marker_contrast``, ``locked_rms`` (m: the RMS over the body's range of the error locked
    to its position, :func:`locked_error`); the image measurements per frame and body:
    ``centre_px`` (frames, bodies, 2), ``radius_px``, ``circle_rms_px`` (the outline fit's RMS
    residual) and ``marker_contrast`` (about 1 for a clear marker); ``locked_error`` (bodies, 3)
    the standard deviations (m) of that error's coefficients on :math:`P_1, P_2, P_3` (the
    CSV's ``xlocked<m>_<id>``)."""

    video: str
    ids: tuple[str, ...]
    t: FloatArray
    x: FloatArray
    phi: FloatArray
    frames: np.ndarray
    fps: float
    scale: float
    scale_source: str
    roll: float
    residuals: dict[str, dict[str, float]]
    centre_px: FloatArray
    radius_px: FloatArray
    circle_rms_px: FloatArray
    marker_contrast: FloatArray
    locked_error: FloatArray = field(default_factory=lambda: np.zeros((0, LOCKED_DEGREE)))
    seconds: float = 0.0

    def columns(self) -> dict[str, FloatArray]:
        """The CSV's columns in order: ``t``, then ``x_<id>``, ``phi_<id>`` per body (the
        contract's pairs, in the system's order), then ``xlocked<m>_<id>`` (m = 1, 2, 3) per
        body: the error of ``x_<id>`` that the background locks to the body's position, as the
        standard deviations (m) of its coefficients on the Legendre polynomials :math:`P_m` of
        the position over the body's range (:func:`locked_error`), the same in every row; the
        fit adds it to its uncertainties. Without ``locked_error`` (a result made by hand),
        only ``t``, ``x_<id>``, ``phi_<id>``."""
        columns = {"t": self.t}
        for i, name in enumerate(self.ids):
            columns[f"x_{name}"] = self.x[:, i]
            columns[f"phi_{name}"] = self.phi[:, i]
        if self.locked_error.shape[0] == len(self.ids):
            for i, name in enumerate(self.ids):
                for m, value in enumerate(self.locked_error[i], start=1):
                    columns[f"xlocked{m}_{name}"] = np.full(self.t.size, value)
        return columns

    def to_csv(self, path: str | os.PathLike[str] | None = None) -> str:
        """The tracks as CSV text (header ``t,x_<id>,phi_<id>,...``, one row per frame, SI
        units, 17 significant digits); written to ``path`` too when given (atomically: the
        command line writes through :mod:`rollspring.outputs.atomic`)."""
        columns = self.columns()
        table = np.column_stack(list(columns.values()))
        lines = [",".join(columns)]
        lines += [",".join(f"{value:.17g}" for value in row) for row in table.tolist()]
        text = "\n".join(lines) + "\n"
        if path is not None:
            target = Path(path)
            temporary = target.with_name(f".{target.name}.{os.getpid()}.part")
            try:
                temporary.write_text(text, encoding="utf-8")
                os.replace(temporary, target)
            finally:
                temporary.unlink(missing_ok=True)
        return text

    def summary(self) -> dict[str, Any]:
        """The JSON summary (``rollspring track --json``): ``video``, ``frames``, ``fps``,
        ``t_start``, ``t_end``, ``scale`` (px/m), ``scale_source``, ``roll_deg``, ``bodies``
        (the ids in order) and ``residuals`` per body (``circle_rms``, ``height_rms`` in m,
        ``marker_contrast``, ``locked_rms`` in m), ``frames_per_second`` (the tracking's
        speed)."""
        return {
            "video": self.video,
            "frames": int(self.t.size),
            "fps": self.fps,
            "t_start": float(self.t[0]),
            "t_end": float(self.t[-1]),
            "scale": self.scale,
            "scale_source": self.scale_source,
            "roll_deg": math.degrees(self.roll),
            "bodies": list(self.ids),
            "residuals": self.residuals,
            "frames_per_second": (self.t.size / self.seconds) if self.seconds > 0 else None,
        }

    def _repr_html_(self) -> str:
        from html import escape

        rows = "".join(
            f"<tr><td>{escape(name)}</td><td>{values['circle_rms'] * 1e3:.3g}</td>"
            f"<td>{values['height_rms'] * 1e3:.3g}</td>"
            f"<td>{values['marker_contrast']:.2f}</td></tr>"
            for name, values in self.residuals.items()
        )
        return (
            f"<div><b>Tracks of {escape(Path(self.video).name)}</b>: {self.t.size} frames, "
            f"t = {self.t[0]:.4g} … {self.t[-1]:.4g} s at {self.fps:.4g} fps; scale "
            f"{self.scale:.5g} px/m ({self.scale_source}); camera roll "
            f"{math.degrees(self.roll):.3g}°"
            "<table><tr><th>body</th><th>circle fit RMS (mm)</th><th>height RMS (mm)</th>"
            f"<th>marker contrast</th></tr>{rows}</table></div>"
        )


# ------------------------------------------------------------------------------ reading


def open_video(video: str | os.PathLike[str]) -> Any:
    """The video opened with OpenCV, or a one-line :class:`TrackingError` naming the file."""
    import cv2

    path = Path(video)
    if not path.exists():
        raise TrackingError(f"{video}: no such file")
    if not path.is_file():
        raise TrackingError(f"{video}: not a regular file")
    if path.stat().st_size == 0:
        raise TrackingError(f"{video}: empty file")
    capture = cv2.VideoCapture(str(path))
    if not capture.isOpened():
        capture.release()
        raise TrackingError(f"{video}: cannot be read as a video")
    return capture


def check_options(
    *,
    scale: float | None = None,
    start: float | None = None,
    stop: float | None = None,
    origin: float | None = None,
) -> None:
    """The options of :func:`track_video` checked before any work: one-line
    :class:`TrackingError` naming the option (``--scale``, ``--from``, ``--to``,
    ``--origin``) and the reason."""
    for name, value in (
        ("--scale", scale),
        ("--from", start),
        ("--to", stop),
        ("--origin", origin),
    ):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int | float)):
            raise TrackingError(f"{name}: must be a number, got {value!r}")
    if scale is not None and not (math.isfinite(scale) and scale > 0):
        raise TrackingError(f"--scale: must be a positive number of px/m, got {scale:g}")
    if origin is not None and not math.isfinite(origin):
        raise TrackingError(f"--origin: must be a finite position in m, got {origin:g}")
    for name, value in (("--from", start), ("--to", stop)):
        if value is not None and not (math.isfinite(value) and value >= 0):
            raise TrackingError(f"{name}: must be a time >= 0 s, got {value:g}")
    if start is not None and stop is not None and stop <= start:
        raise TrackingError(f"--to: must be after --from ({start:g} s), got {stop:g}")


# ------------------------------------------------------------------------------ geometry


def _floor_lines(gray: np.ndarray, count: int = 12) -> list[FloorLine]:
    """Candidate floor lines of a grey frame, strongest first: the ``count`` strongest distinct
    near-horizontal lines of the Hough transform of its edges (within 15° of horizontal), each
    refined to a least-squares line through the edge's sub-pixel row in each column near it
    (outliers — the bodies — dropped)."""
    import cv2

    smooth = cv2.GaussianBlur(gray, (0, 0), 1.5)
    edges = cv2.Canny(smooth, 8, 24)  # low: a floor edge can be faint beside a textured wall
    lines = cv2.HoughLines(
        edges,
        1,
        math.pi / 720,
        gray.shape[1] // 4,
        min_theta=math.pi / 2 - 0.26,
        max_theta=math.pi / 2 + 0.26,
    )
    found: list[FloorLine] = []
    for rho, theta in [] if lines is None else lines[:60, 0].tolist():
        line = _refined_line(smooth.astype(np.float32), rho, theta)
        if line is None:
            continue
        if any(
            abs(float(line.height(other.point))) < 4.0
            and abs(float(line.direction @ other.normal)) < 0.01
            for other in found
        ):
            continue
        found.append(line)
        if len(found) == count:
            break
    return found


def _refined_line(
    smooth: np.ndarray,
    rho: float,
    theta: float,
    halves: tuple[float, ...] = (6.0, 2.5),
    hidden: tuple[tuple[float, float], ...] = (),
) -> FloorLine | None:
    """The line ``u cos(theta) + v sin(theta) = rho`` refined in passes: in every other column
    (but those within ``hidden``'s (u, half-width) spans, where bodies stand) the strongest
    step within 6 px of it, located to a fraction of a pixel (a parabola through the peak), and
    a straight line fitted to those points with outliers dropped; then again within 2.5 px of
    that line, counting only steps of the line's own sign (the texture beside an edge has
    both). None when too few columns show an edge."""
    width = smooth.shape[1]
    columns = np.arange(4, width - 4, 2, dtype=np.float64)
    for centre, half_width in hidden:
        columns = columns[np.abs(columns - centre) > half_width]
    if columns.size < 10:
        return None
    rows = (rho - columns * math.cos(theta)) / math.sin(theta)
    sign = 0.0
    line = None
    for half in halves:
        edge, strength, found = _column_edges(smooth, columns, rows, half, sign)
        if found.sum() < 10:
            return None
        if sign == 0.0:
            sign = 1.0 if np.median(strength[found]) > 0 else -1.0
            found &= np.sign(strength) == sign
            if found.sum() < 10:
                return None
        u, v = columns[found], edge[found]
        keep = np.ones(u.size, dtype=bool)
        for _ in range(4):
            slope, intercept = np.polyfit(u[keep], v[keep], 1)
            residual = v - (slope * u + intercept)
            spread = 1.4826 * _median(np.abs(residual[keep])) + 0.02
            keep = np.abs(residual) < 3 * spread
        rows = slope * columns + intercept
        direction = np.array([1.0, slope]) / math.hypot(1.0, slope)
        normal = np.array([direction[1], -direction[0]])
        line = FloorLine(np.array([0.0, intercept]), direction, normal)
    return line


def _column_edges(
    smooth: np.ndarray, columns: FloatArray, rows: FloatArray, half: float, sign: float
) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """In each column, the strongest vertical step within ``half`` px of ``rows`` (of ``sign``,
    or either with 0): its sub-pixel row, its signed strength (grey levels per px) and whether
    it is a clear one (a peak inside the window, at least half the median strength)."""
    import cv2

    offsets = np.arange(-half, half + 1e-9, 0.5)
    map_u = np.repeat(columns[:, None], offsets.size, axis=1).astype(np.float32)
    map_v = (rows[:, None] + offsets[None, :]).astype(np.float32)
    profile = cv2.remap(smooth, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    signed = profile[:, 2:] - profile[:, :-2]  # per px (two samples of 0.5 px apart)
    step = np.abs(signed) if sign == 0.0 else sign * signed
    peak = np.argmax(step, axis=1)
    k = np.clip(peak, 1, step.shape[1] - 2)
    index = np.arange(k.size)
    left, mid, right = step[index, k - 1], step[index, k], step[index, k + 1]
    curvature = left - 2 * mid + right
    safe = np.where(curvature < 0, curvature, -1.0)
    shift = np.where(curvature < 0, np.clip(0.5 * (left - right) / safe, -0.5, 0.5), 0.0)
    edge = rows + offsets[1:-1][k] + shift * 0.5
    found = (peak > 0) & (peak < step.shape[1] - 1) & (mid > 0.5 * _median(np.abs(mid)))
    return edge, signed[index, k], found


def _ray_grid(radius: float, band: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Ray directions (RAYS, 2) and radial samples (J,) from ``radius - band`` to
    ``radius + band``, and the angles."""
    angles = 2 * math.pi * np.arange(RAYS) / RAYS
    directions = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    radii = np.arange(max(radius - band, 1.0), radius + band + 1e-9, STEP)
    return directions, radii, angles


def _fit_outline(
    image: np.ndarray,
    centre: FloatArray,
    radius: float,
    band: float,
    polarity: float,
    usable: np.ndarray,
) -> tuple[FloatArray, float, float, int, float, np.ndarray]:
    """The circle through a body's outer edge near (``centre``, ``radius``): the strongest step
    of ``polarity`` (+1: dark inside) within ``band`` px of ``radius`` on each ``usable`` ray,
    located to a fraction of a pixel, then Kåsa's algebraic fit with outliers dropped.
    Returns the centre, the radius, the RMS residual (px), the number of rays used, their
    median edge strength (grey levels per px) and which rays were used (RAYS,)."""
    import cv2

    directions, radii, _ = _ray_grid(radius, band)
    points = centre + radii[None, :, None] * directions[:, None, :]
    map_u = points[..., 0].astype(np.float32)
    map_v = points[..., 1].astype(np.float32)
    profile = cv2.remap(image, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    step = polarity * (profile[:, 2:] - profile[:, :-2]) / (2 * STEP)
    peak = np.argmax(step, axis=1)
    rows = np.arange(RAYS)
    k = np.clip(peak, 1, step.shape[1] - 2)
    left, mid, right = step[rows, k - 1], step[rows, k], step[rows, k + 1]
    curvature = left - 2 * mid + right
    safe = np.where(curvature < 0, curvature, -1.0)
    shift = np.where(curvature < 0, np.clip(0.5 * (left - right) / safe, -0.5, 0.5), 0.0)
    edge = radii[1:-1][k] + shift * STEP
    strength = mid
    good = usable & (peak > 0) & (peak < step.shape[1] - 1) & (strength > 0)
    if good.sum() >= 6:
        good &= strength > 0.35 * _median(strength[good])
    if good.sum() < 6:
        return centre, radius, math.inf, 0, 0.0, good
    xy = centre + edge[:, None] * directions
    keep = good.copy()
    fitted_centre, fitted_radius, rms = centre, radius, math.inf
    for _ in range(3):
        # Kasa: u^2 + v^2 = a u + b v + c, linear least squares (about the points' mean, by
        # the normal equations), centre (a/2, b/2), radius^2 = c + |centre|^2
        mean = xy[keep].mean(axis=0)
        u, v = xy[keep, 0] - mean[0], xy[keep, 1] - mean[1]
        design = np.column_stack([u, v, np.ones(u.size)])
        a, b, c = np.linalg.solve(design.T @ design, design.T @ (u * u + v * v))
        offset = np.array([a / 2, b / 2])
        fitted_centre = mean + offset
        squared = c + offset @ offset
        if squared <= 0:
            return centre, radius, math.inf, 0, 0.0, good
        fitted_radius = math.sqrt(squared)
        residual = (
            np.hypot(xy[:, 0] - fitted_centre[0], xy[:, 1] - fitted_centre[1]) - fitted_radius
        )
        spread = 1.4826 * _median(np.abs(residual[keep]))
        rms = float(np.sqrt(np.mean(residual[keep] ** 2)))
        new_keep = good & (np.abs(residual) < max(3 * spread, 0.3))
        if new_keep.sum() < 6 or np.array_equal(new_keep, keep):
            break
        keep = new_keep
    # A blurred circle's steepest edge lies sigma^2 / (2 r) inside it (sigma: the blur's
    # width, the camera's and the smoothing's together, read from the peak's curvature: a
    # Gaussian peak g has g'' / g = -1 / sigma^2; the central difference adds a 1-px box)
    width = -mid[keep] * STEP**2 / np.minimum(curvature[keep], -1e-9)
    blur = max(_median(width) - 1.0 / 12.0, 0.0)
    fitted_radius += blur / (2.0 * fitted_radius)
    return fitted_centre, fitted_radius, rms, int(keep.sum()), _median(strength[keep]), keep


def _refine_centre(
    image: np.ndarray, centre: FloatArray, radius: float, polarity: float, rays: np.ndarray
) -> tuple[FloatArray, FloatArray]:
    r"""The centre of the outline fitted (:func:`_fit_outline`) at (``centre``, ``radius``),
    refined on the image's pixels rather than along rays: every pixel within
    :data:`REFINE_HALF_WIDTH` px of the circle, in the sector of a ray the fit used (``rays``),
    weighted by the square of its gradient's outward component of the body's ``polarity``
    (``cv2.Sobel``; zero where the step has the other sign), and a circle fitted to those
    pixels' centres by weighted least squares (Kåsa's, as the rays' fit).

    Why: an edge located along a ray by interpolating the image and a parabola through the peak
    of its derivative is off by a few hundredths of a pixel in a way that depends on where the
    edge falls between pixels, and the rays near the horizontal, which carry the centre's
    position along the floor, all see about the same fraction: the centre kept a periodic error
    of about 0.025 px (period 1 px) as a body moved, enough to change a swing of a few pixels
    by up to 1 %. A weighted mean over the pixels themselves does not depend on that fraction:
    the gradient's profile across the edge is smooth (a few pixels wide) and sampled on the
    pixel grid, its moments are the continuous ones to about 1e-3 px. The radius (and so the
    scale) stays the rays' (blur-corrected); only the centre is replaced.

    Also returned: each ray's sector's residual about the refined circle (RAYS,) px, the
    weighted mean of :math:`|p - c| - r` over its pixels (NaN for a sector not used), which
    :func:`scale_errors` reads the wall's texture from."""
    import cv2

    unused = np.full(RAYS, np.nan)

    height, width = image.shape
    reach = radius + REFINE_HALF_WIDTH + 2.0
    top, bottom = max(int(centre[1] - reach), 1), min(int(centre[1] + reach) + 2, height - 1)
    left, right = max(int(centre[0] - reach), 1), min(int(centre[0] + reach) + 2, width - 1)
    if bottom - top < 8 or right - left < 8:
        return centre, unused
    # one pixel of margin: the Sobel of the patch is then exact inside it
    patch = image[top - 1 : bottom + 1, left - 1 : right + 1]
    slope_u = cv2.Sobel(patch, cv2.CV_32F, 1, 0, ksize=3)[1:-1, 1:-1]
    slope_v = cv2.Sobel(patch, cv2.CV_32F, 0, 1, ksize=3)[1:-1, 1:-1]
    du = np.arange(left, right, dtype=np.float64) - centre[0]
    dv = np.arange(top, bottom, dtype=np.float64)[:, None] - centre[1]
    distance = np.sqrt(du * du + dv * dv)
    ring = np.abs(distance - radius) < REFINE_HALF_WIDTH
    du_ring = np.broadcast_to(du, ring.shape)[ring]
    dv_ring = np.broadcast_to(dv, ring.shape)[ring]
    outward = polarity * (slope_u[ring] * du_ring + slope_v[ring] * dv_ring) / distance[ring]
    sector = np.rint(np.arctan2(dv_ring, du_ring) * (RAYS / (2 * math.pi))).astype(np.intp)
    weight = np.where(rays[sector % RAYS] & (outward > 0), outward, 0.0) ** 2
    total = float(weight.sum())
    if not total > 0:
        return centre, unused
    mean_u = float(weight @ du_ring) / total
    mean_v = float(weight @ dv_ring) / total
    u, v = du_ring - mean_u, dv_ring - mean_v
    design = np.column_stack([u, v, np.ones(u.size)])
    weighted = design * weight[:, None]
    try:
        a, b, c = np.linalg.solve(weighted.T @ design, weighted.T @ (u * u + v * v))
    except np.linalg.LinAlgError:
        return centre, unused
    refined = centre + np.array([mean_u + a / 2, mean_v + b / 2])
    # a refinement moves the centre by hundredths of a pixel: a larger move is not one
    if not np.all(np.isfinite(refined)) or float(np.hypot(*(refined - centre))) > 1.0:
        return centre, unused
    # each sector's mean distance from the refined circle, weighted as the fit weighted it
    fitted_radius = math.sqrt(max(c + (a / 2) ** 2 + (b / 2) ** 2, 0.0))
    apart = np.hypot(u - a / 2, v - b / 2) - fitted_radius
    sector %= RAYS
    mass = np.bincount(sector, weights=weight, minlength=RAYS)
    moment = np.bincount(sector, weights=weight * apart, minlength=RAYS)
    with np.errstate(invalid="ignore", divide="ignore"):
        sectors = np.where(mass > 0.05 * total / RAYS, moment / mass, np.nan)
    return refined, sectors


def _median(values: FloatArray) -> float:
    """The median of a short 1-D array (``np.median`` costs ten times more on 100 values)."""
    ordered = np.sort(values)
    n = ordered.size
    return 0.5 * float(ordered[(n - 1) // 2] + ordered[n // 2])


def _usable_rays(
    floor: FloorLine, centres: FloatArray, radii: FloatArray, index: int, band: float
) -> np.ndarray:
    """The rays of body ``index`` that can see its outline: not within
    :data:`CONTACT_HALF_ANGLE` of the floor contact, not ending inside another body."""
    directions, _, _ = _ray_grid(1.0, 0.0)
    down = -floor.normal
    usable = directions @ down < math.cos(CONTACT_HALF_ANGLE)
    ends = centres[index] + (radii[index] + band) * directions
    for other in range(len(radii)):
        if other != index:
            distance = np.hypot(*(ends - centres[other]).T)
            usable &= distance > radii[other] + band
    return usable


def _polar(
    frame: np.ndarray, centre: FloatArray, radii: FloatArray, samples: int
) -> tuple[np.ndarray, FloatArray]:
    """A polar sampling of a colour ``frame`` about ``centre``: (len(radii), samples, 3), and
    the angles (image angles: (cos θ, sin θ) with v down)."""
    import cv2

    angles = 2 * math.pi * np.arange(samples) / samples
    map_u = (centre[0] + radii[:, None] * np.cos(angles)[None, :]).astype(np.float32)
    map_v = (centre[1] + radii[:, None] * np.sin(angles)[None, :]).astype(np.float32)
    values = cv2.remap(frame, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    values = values.astype(np.float32)
    return values, angles


def _marker_angle(frame: np.ndarray, centre: FloatArray, body: _Body) -> tuple[float, float]:
    """The image angle of the body's marker (rad, (cos θ, sin θ) with v down) and its score
    (about 1 on the marker, 0 on the body). On the ring of the marker's radii each sample is
    scored by the projection of its colour, less the ring's median colour, on the marker's
    colour difference; the marker's angle is the midpoint of the two half-height crossings of
    the score's peak (interpolated linearly), which a marker's uneven inside does not move."""
    values, angles = _polar(frame, centre, body.marker_radii, MARKER_SAMPLES)
    colour = np.median(values.reshape(-1, 3), axis=0)
    direction = body.marker_direction
    score = ((values - colour) @ direction / float(direction @ direction)).mean(axis=0)
    width = int(body.marker_half_width / (2 * math.pi) * MARKER_SAMPLES) + 6
    smooth = np.convolve(np.concatenate([score[-2:], score, score[:2]]), np.ones(5) / 5, "valid")
    top = int(np.argmax(smooth))
    offsets = np.arange(-width, width + 1)
    window = score[(top + offsets) % MARKER_SAMPLES]
    high = window > 0.5 * float(smooth[top])
    plateau = _median(window[high]) if high.any() else float(smooth[top])
    level = 0.5 * plateau
    centre_index = width
    edges = []
    for step in (-1, 1):
        k = centre_index
        while 0 < k < window.size - 1 and window[k + step] >= level:
            k += step
        inner, outer = window[k], window[k + step] if 0 <= k + step < window.size else level
        fraction = (inner - level) / (inner - outer) if inner != outer else 0.5
        edges.append(k + step * min(max(fraction, 0.0), 1.0))
    shift = 0.5 * (edges[0] + edges[1]) - centre_index
    return float(angles[top] + shift * 2 * math.pi / MARKER_SAMPLES), plateau


def _learn_body(
    frame: np.ndarray,
    centre: FloatArray,
    radius: float,
    polarity: float,
    spec: Any,
) -> _Body:
    """A body's looks from its first frame: its colour, the marker's colour, radii and angular
    width. On a polar sampling of the body (a disc's every row, a hoop's ring: the rows whose
    colour is nearer the outermost row's than the hoop's inside), the body's colour is the
    median, the marker the samples farthest from it (beyond half the 99th percentile of the
    distances), where most of them are."""
    radii = np.arange(0.3 * radius, radius - 1.0 + 1e-9, 1.0)
    values, _ = _polar(frame, centre, radii, MARKER_SAMPLES)
    typical = np.median(values, axis=1)  # each row's colour
    if spec.shape == "hoop":
        outside = np.linalg.norm(typical - typical[-1], axis=-1)
        rows = outside < 0.5 * float(np.linalg.norm(typical[0] - typical[-1]))
        rows[-1] = True
    else:
        rows = np.ones(radii.size, dtype=bool)
    colour = np.median(values[rows].reshape(-1, 3), axis=0)
    distance = np.linalg.norm(values - colour, axis=-1)
    threshold = max(0.5 * float(np.percentile(distance[rows], 99.0)), 20.0)
    far = (distance > threshold) & rows[:, None]
    if far.sum() < 4:
        raise TrackingError(f"body '{spec.id}': no marker found on it in the first frame")
    counts = far.sum(axis=0).astype(np.float64)
    kernel = np.ones(9)
    smooth = np.convolve(np.concatenate([counts[-4:], counts, counts[:4]]), kernel, "valid")
    top = int(np.argmax(smooth))
    near = (np.abs(((np.arange(MARKER_SAMPLES) - top + 180) % MARKER_SAMPLES) - 180)) <= 30
    marked = far & near[None, :]
    marker_colour = np.median(values[marked], axis=0)
    marker_rows = radii[marked.any(axis=1)]
    span = marked.any(axis=0)
    half_width = span.sum() * math.pi / MARKER_SAMPLES
    lo, hi = float(marker_rows.min()), float(marker_rows.max())
    inset = 0.25 * (hi - lo)
    ring = np.linspace(lo + inset, hi - inset, max(2, min(5, int(hi - lo) + 1)))
    return _Body(
        id=spec.id,
        shape=spec.shape,
        radius_m=float(spec.radius),
        radius_px=radius,
        polarity=polarity,
        colour=colour,
        marker_direction=marker_colour - colour,
        marker_radii=ring,
        marker_half_width=float(half_width),
    )


def _find_bodies(
    gray: np.ndarray, smooth: np.ndarray, system: System
) -> tuple[FloorLine, list[tuple[FloatArray, float, float]]]:
    """The floor line and the bodies in the first frame: (centre, radius, polarity) each, in
    the system's order. Circle candidates (``cv2.HoughCircles``) are refined on rays
    (:func:`_fit_outline`, both contrasts tried) and kept when their outline stands well above
    the background's texture; the floor line is the candidate line (:func:`_floor_lines`) on
    which most of them stand (the centre's height equal to the radius), the strongest among
    equals; then the system's bodies are matched to those standing on it."""
    import cv2

    height = gray.shape[0]
    floors = _floor_lines(gray)
    if not floors:
        raise TrackingError("no floor line found (a straight horizontal edge under the bodies)")
    circles = cv2.HoughCircles(
        cv2.GaussianBlur(gray, (0, 0), 2.0),
        cv2.HOUGH_GRADIENT,
        dp=1,
        minDist=8,
        param1=100,
        param2=25,
        minRadius=max(6, height // 40),
        maxRadius=height // 2,
    )
    if circles is None:
        raise TrackingError("no round body found in the first frame")
    # the typical edge of the background: a body's outline must be well above it
    slope_u = cv2.Sobel(smooth, cv2.CV_32F, 1, 0) / 8
    slope_v = cv2.Sobel(smooth, cv2.CV_32F, 0, 1) / 8
    texture = float(np.median(np.hypot(slope_u, slope_v)))
    directions, _, _ = _ray_grid(1.0, 0.0)
    usable = directions @ np.array([0.0, 1.0]) < math.cos(CONTACT_HALF_ANGLE)  # not the bottom
    candidates: list[tuple[FloatArray, float, float, float]] = []
    for u, v, r in circles[0][:40]:
        if any(  # a circle refined already (the transform finds each a few times)
            math.hypot(u - other[0][0], v - other[0][1]) < 0.2 * other[1]
            and abs(r - other[1]) < 0.2 * other[1]
            for other in candidates
        ):
            continue
        for polarity in (1.0, -1.0):
            centre, radius = np.array([u, v], dtype=np.float64), float(r)
            for band in (0.3 * radius, 0.12 * radius, 3.0):
                centre, radius, rms, used, strength, _ = _fit_outline(
                    smooth, centre, radius, max(band, 3.0), polarity, usable
                )
                if used == 0:
                    break
            if (
                used >= MIN_RAY_FRACTION * usable.sum()
                and strength >= 3 * texture
                and rms <= 0.6 + 0.01 * radius
            ):
                candidates.append((centre, radius, polarity, strength * used / (1.0 + rms)))
    n = len(system.bodies)
    best: tuple[int, FloorLine, list[tuple[FloatArray, float, float, float]]] | None = None
    for floor in floors:
        standing: list[tuple[FloatArray, float, float, float]] = []
        for candidate in sorted(candidates, key=lambda item: -item[3]):
            centre, radius = candidate[0], candidate[1]
            if abs(float(floor.height(centre)) - radius) > 0.04 * radius + 1.5:
                continue
            if not any(
                np.hypot(*(centre - other[0])) < 0.5 * min(radius, other[1]) for other in standing
            ):
                standing.append(candidate)
        if best is None or min(len(standing), n) > best[0]:
            best = (min(len(standing), n), floor, standing)
    assert best is not None
    _, floor, standing = best
    # the floor line again, without the columns where the bodies stand (their outlines meet it)
    theta = math.atan2(-float(floor.normal[1]), -float(floor.normal[0]))
    rho = float(floor.point @ np.array([math.cos(theta), math.sin(theta)]))
    hidden = tuple((float(c[0]), 0.7 * r) for c, r, _, _ in standing)
    floor = _refined_line(smooth, rho, theta, (2.5,), hidden) or floor
    if len(standing) < n:
        raise TrackingError(
            f"{n} bodies standing on the floor line expected in the first frame, "
            f"found {len(standing)}"
        )
    # the bodies left to right are the system's in the order of x: the n candidates (in their
    # order along the floor) whose radii have the system's ratios and whose spacing is the
    # system's, the clearest outlines breaking ties
    order = np.argsort([body.x for body in system.bodies], kind="stable")
    standing = sorted(standing[: n + 6], key=lambda item: float(floor.along(item[0])))
    wanted = np.array([system.bodies[i].radius for i in order])
    placed = np.array([system.bodies[i].x for i in order])
    from itertools import combinations

    best_choice, best_cost = None, math.inf
    for choice in combinations(range(len(standing)), n):
        measured = np.array([standing[j][1] for j in choice])
        ratio = np.log(measured / wanted)
        along = np.array([float(floor.along(standing[j][0])) for j in choice])
        scale = float(np.exp(np.median(ratio)))
        spacing = np.abs(np.diff(along) / scale - np.diff(placed)).sum() / wanted.sum()
        clarity = sum(math.log(standing[j][3]) for j in choice) / n
        cost = float(np.ptp(ratio)) + 0.1 * float(spacing) - 0.02 * clarity
        if cost < best_cost:
            best_choice, best_cost = choice, cost
    assert best_choice is not None
    found: list[tuple[FloatArray, float, float]] = [(np.zeros(2), 0.0, 1.0)] * n
    for slot, j in zip(order, best_choice, strict=True):
        found[int(slot)] = standing[j][:3]
    return floor, found


# ------------------------------------------------------------------------------ tracking


def track_video(
    video: str | os.PathLike[str],
    system: System,
    *,
    scale: float | None = None,
    start: float | None = None,
    stop: float | None = None,
    origin: float | None = None,
    progress: Callable[[float], None] | None = None,
    on_frame: Callable[[np.ndarray, FrameTrack], None] | None = None,
) -> TrackResult:
    r"""Track every body of ``system`` in ``video`` from ``start`` to ``stop`` (s of the video,
    default all of it): :class:`TrackResult` with t, x (m) and φ (rad) per frame.

    The method and the conventions are the module's (:mod:`rollspring.lab.tracking`). ``scale``
    (px/m) replaces the scale measured from the radii; ``origin`` (m) is the first body's
    position in the first tracked frame (default its ``x`` in the system). ``progress`` is
    called with the fraction of the frames done; ``on_frame(frame, found)`` with each frame
    (BGR) and :class:`FrameTrack` (the overlay). One-line :class:`TrackingError` for an
    unreadable or empty video, a bad time range or scale, and a body or marker not found (naming
    the body and the first range of frames and times where it is lost).
    """
    import time as clock

    import cv2

    check_options(scale=scale, start=start, stop=stop, origin=origin)
    for body in system.bodies:
        if not body.rolls:
            raise TrackingError(f"bodies.{body.id}: a slider cannot be tracked (round bodies only)")
    began = clock.perf_counter()
    capture = open_video(video)
    try:
        fps = float(capture.get(cv2.CAP_PROP_FPS))
        if not (math.isfinite(fps) and fps > 0):
            fps = 0.0
        count = int(capture.get(cv2.CAP_PROP_FRAME_COUNT) or 0)
        result = _track(
            capture, video, system, fps, count, scale, start, stop, origin, progress, on_frame
        )
    finally:
        capture.release()
    result.seconds = clock.perf_counter() - began
    return result


def _frame_time(capture: Any, index: int, fps: float, last: float | None) -> float:
    import cv2

    stamp = float(capture.get(cv2.CAP_PROP_POS_MSEC)) / 1000.0
    if math.isfinite(stamp) and (last is None or stamp > last) and (stamp > 0 or index == 0):
        return stamp
    if fps > 0:
        return index / fps
    raise TrackingError("the video has neither time stamps nor a frame rate")


@dataclass
class _Sightings:
    """What the frames showed, frame by frame (lists of per-frame rows)."""

    times: list[float] = field(default_factory=list)
    indices: list[int] = field(default_factory=list)
    centre: list[FloatArray] = field(default_factory=list)
    radius: list[FloatArray] = field(default_factory=list)
    angle: list[FloatArray] = field(default_factory=list)
    found: list[np.ndarray] = field(default_factory=list)
    edge_rms: list[FloatArray] = field(default_factory=list)
    contrast: list[FloatArray] = field(default_factory=list)
    sectors: list[FloatArray] = field(default_factory=list)


def _locate(
    smooth: np.ndarray,
    frame: np.ndarray,
    floor: FloorLine,
    bodies: list[_Body],
    predicted: FloatArray,
    was_lost: np.ndarray,
) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray, FloatArray, FloatArray, FloatArray]:
    """Every body in one frame, each looked for about its ``predicted`` centre (farther for a
    body ``was_lost`` in the frame before): centres (n, 2) and radii (n,) in px, the markers'
    image angles (n,), whether each was found (its outline on enough rays, its radius as
    expected, its marker clear), the fits' RMS residuals (px), the markers' contrasts and the
    outline's residual per sector (n, RAYS; :func:`_refine_centre`)."""
    n = len(bodies)
    sectors = np.full((n, RAYS), np.nan)
    expected = np.array([body.radius_px for body in bodies])
    centres, radii, angles = np.empty((n, 2)), np.empty(n), np.empty(n)
    found, edge_rms, contrast = np.zeros(n, dtype=bool), np.full(n, np.nan), np.zeros(n)
    for i, body in enumerate(bodies):
        usable = _usable_rays(floor, predicted, expected, i, 0.25 * body.radius_px)
        centre, radius, rms, used = predicted[i], body.radius_px, math.inf, 0
        bands = (0.5, 0.25, 0.12) if was_lost[i] else (0.25,)
        for band in (*(max(b * body.radius_px, 4.0) for b in bands), 3.0):
            centre, radius, rms, used, _, rays = _fit_outline(
                smooth, centre, radius, band, body.polarity, usable
            )
            if used == 0:
                break
        outline = (
            used >= MIN_RAY_FRACTION * usable.sum()
            and abs(radius - body.radius_px) < MAX_RADIUS_CHANGE * body.radius_px + 1.0
        )
        if outline:
            centre, sectors[i] = _refine_centre(smooth, centre, radius, body.polarity, rays)
        else:
            centre, radius = predicted[i], body.radius_px
        angles[i], contrast[i] = _marker_angle(frame, centre, body)
        centres[i], radii[i], edge_rms[i] = centre, radius, rms
        found[i] = outline and contrast[i] >= MIN_MARKER_SCORE
    return centres, radii, angles, found, edge_rms, contrast, sectors


def _track(
    capture: Any,
    video: str | os.PathLike[str],
    system: System,
    fps: float,
    count: int,
    scale: float | None,
    start: float | None,
    stop: float | None,
    origin: float | None,
    progress: Callable[[float], None] | None,
    on_frame: Callable[[np.ndarray, FrameTrack], None] | None,
) -> TrackResult:
    """The frames of ``capture`` from ``start`` to ``stop`` tracked (:func:`track_video`)."""
    import cv2

    n = len(system.bodies)
    seen = _Sightings()
    bodies: list[_Body] = []
    floor: FloorLine | None = None
    index, last = -1, None
    reached = False  # the loop ended at ``stop``, not where the decoding ended
    while capture.grab():
        index += 1
        moment = last = _frame_time(capture, index, fps, last)
        if start is not None and moment < start - 1e-9:
            continue
        if stop is not None and moment > stop + 1e-9:
            reached = True
            break
        ok, frame = capture.retrieve()
        if not ok or frame is None:
            index -= 1  # this frame was not read
            break
        if frame.ndim == 2:
            frame = cv2.cvtColor(frame, cv2.COLOR_GRAY2BGR)
        gray = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
        smooth = cv2.GaussianBlur(gray, (5, 5), 1.0).astype(np.float32)
        if floor is None:
            floor, bodies, previous = _first_frame(video, system, frame, gray, smooth, moment)
            before, was_lost = previous.copy(), np.zeros(n, dtype=bool)
        # constant velocity from the last two sightings; a lost body is looked for where it
        # was last seen
        predicted = 2 * previous - before
        centres, radii, angles, found, edge_rms, contrast, sectors = _locate(
            smooth, frame, floor, bodies, predicted, was_lost
        )
        sighted = np.where(found[:, None], centres, previous)
        before = np.where((found & ~was_lost)[:, None], previous, sighted)
        previous, was_lost = sighted, ~found
        seen.times.append(moment)
        seen.indices.append(index)
        seen.centre.append(centres)
        seen.radius.append(radii)
        seen.angle.append(angles)
        seen.found.append(found)
        seen.edge_rms.append(edge_rms)
        seen.contrast.append(contrast)
        seen.sectors.append(sectors)
        if on_frame is not None:
            reach = np.array([body.marker_radii.mean() for body in bodies])[:, None]
            marker = centres + reach * np.stack([np.cos(angles), np.sin(angles)], axis=1)
            on_frame(frame, FrameTrack(index, moment, centres, radii, marker, found, floor))
        if progress is not None and count > 0 and index % 8 == 0:
            progress(min(index / count, 1.0))
    if index < 0:
        raise TrackingError(f"{video}: holds no frames")
    if stop is not None and last is not None and fps > 0 and last + 1.0 / fps > stop + 1e-9:
        reached = True  # the frames asked for were all read (the next one may be damaged)
    if not reached and count > 0 and index + 1 < count - max(2, count // 100):
        # the header's frame count is exact for most containers, off by a frame or two for
        # some: many frames fewer means a file damaged or cut after the last one read
        raise TrackingError(
            f"{video}: decoding stopped after {index + 1} of the {count} frames its header "
            f"gives (t = {last:.6g} s): the file is damaged or cut there; --to {last:.6g} "
            "tracks the part before"
        )
    if floor is None:
        first = 0 if start is None else start
        until = math.inf if stop is None else stop
        raise TrackingError(
            f"--from/--to: no frame of {video} between {first:g} and {until:g} s "
            f"(it ends at {last:g} s)"
        )
    _check_found(video, bodies, seen)
    if progress is not None:
        progress(1.0)
    return _result(video, system, bodies, floor, seen, fps, scale, origin)


def _first_frame(
    video: str | os.PathLike[str],
    system: System,
    frame: np.ndarray,
    gray: np.ndarray,
    smooth: np.ndarray,
    moment: float,
) -> tuple[FloorLine, list[_Body], FloatArray]:
    """The floor line, the bodies' looks and their centres (n, 2) from the first frame tracked;
    a failure names the video and the frame's time."""
    try:
        floor, first = _find_bodies(gray, smooth, system)
        bodies = [
            _learn_body(frame, c, r, p, spec)
            for (c, r, p), spec in zip(first, system.bodies, strict=True)
        ]
    except TrackingError as exc:
        raise TrackingError(f"{video}: {exc} (t = {moment:.3f} s)") from None
    return floor, bodies, np.array([c for c, _, _ in first])


def _check_found(video: str | os.PathLike[str], bodies: list[_Body], seen: _Sightings) -> None:
    """A body not found in some frames: :class:`TrackingError` naming it, the first range of
    frames (and times) where it was lost and how many frames in all."""
    found = np.array(seen.found)
    for i, body in enumerate(bodies):
        lost = np.flatnonzero(~found[:, i])
        if lost.size:
            first = end = int(lost[0])
            while end + 1 < found.shape[0] and not found[end + 1, i]:
                end += 1
            raise TrackingError(
                f"{video}: body '{body.id}' not found in frames {seen.indices[first]}–"
                f"{seen.indices[end]} (t = {seen.times[first]:.3f}–{seen.times[end]:.3f} s; "
                f"{lost.size} frames in all)"
            )


def _result(
    video: str | os.PathLike[str],
    system: System,
    bodies: list[_Body],
    floor: FloorLine,
    seen: _Sightings,
    fps: float,
    scale: float | None,
    origin: float | None,
) -> TrackResult:
    r"""The sightings in SI units. Scale :math:`s = \sum_i \tilde r_i / \sum_i R_i` (px/m,
    :math:`\tilde r_i` the median radius over the frames; discs only when there are any),
    :math:`x_i = x_0 + (a_i - a_{1,\text{first}})/s` (:math:`a` along the floor line),
    :math:`\varphi_i = \operatorname{atan2}(m\cdot d, m\cdot n)` (:math:`m` towards the
    marker, :math:`d`, :math:`n` the floor's direction and normal), unwrapped."""
    t = np.array(seen.times)
    centre_px = np.array(seen.centre)
    radius_px = np.array(seen.radius)
    radius_m = np.array([body.radius_m for body in bodies])
    if scale is None:
        # a disc's outline is a step, measured where it is; a hoop's thin ring, once blurred,
        # looks a little larger (its two edges push each other apart): discs set the scale
        # when there are any
        discs = np.array([body.shape != "hoop" for body in bodies])
        chosen = discs if discs.any() else ~discs
        measured = float(np.sum(np.median(radius_px[:, chosen], axis=0)) / np.sum(radius_m[chosen]))
        source = "radii"
    else:
        measured, source = float(scale), "given"
    along = floor.along(centre_px)
    heights = floor.height(centre_px)
    zero = float(system.bodies[0].x) if origin is None else float(origin)
    x = zero + (along - along[0, 0]) / measured
    angle = np.array(seen.angle)
    towards = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
    phi = np.unwrap(np.arctan2(towards @ floor.direction, towards @ floor.normal), axis=0)
    edge_rms = np.array(seen.edge_rms)
    contrast = np.array(seen.contrast)
    sectors = np.array(seen.sectors)
    locked = (
        np.array(
            [locked_error(along[:, i], sectors[:, i], floor.direction) for i in range(len(bodies))]
        )
        / measured
    )
    residuals = {
        body.id: {
            "circle_rms": float(np.sqrt(np.mean(edge_rms[:, i] ** 2)) / measured),
            "height_rms": float(
                np.sqrt(np.mean((heights[:, i] - body.radius_m * measured) ** 2)) / measured
            ),
            "marker_contrast": float(np.median(contrast[:, i])),
            "locked_rms": float(
                np.sqrt(np.sum(locked[i] ** 2 / (2 * np.arange(1, LOCKED_DEGREE + 1) + 1)))
            ),
        }
        for i, body in enumerate(bodies)
    }
    if fps <= 0:
        fps = float(1 / np.median(np.diff(t))) if t.size > 1 else 0.0
    return TrackResult(
        video=str(video),
        ids=tuple(body.id for body in system.bodies),
        t=t,
        x=x,
        phi=phi,
        frames=np.array(seen.indices),
        fps=fps,
        scale=measured,
        scale_source=source,
        roll=floor.roll,
        residuals=residuals,
        centre_px=centre_px,
        radius_px=radius_px,
        circle_rms_px=edge_rms,
        marker_contrast=contrast,
        locked_error=locked,
    )


def locked_error(along: FloatArray, sectors: FloatArray, direction: FloatArray) -> FloatArray:
    r"""The error of a body's tracked centre that a textured background locks to the position,
    as the standard deviations (px) of its coefficients on :math:`P_1, P_2, P_3`: a body's
    outline, located in front of a textured wall, is shifted ray by ray by the slope of the
    texture behind the edge (a few hundredths of a pixel), by the same amount whenever the body
    stands at the same place; the centre inherits the error
    :math:`e(a)`, a smooth function of the position :math:`a` along the floor that the fit
    cannot tell from the motion (a swing scaled by :math:`1 + \epsilon` is another initial
    state).

    Each ray's sector of the outline has its residual :math:`r_j` about the fitted circle in
    every frame (``sectors`` (frames, RAYS), px). Regressed on the Legendre polynomials
    :math:`P_1, P_2, P_3` of the position ``along`` the floor (px; scaled to [-1, 1] over the
    frames' range), it has coefficients :math:`eta_{jm} \pm s_{jm}` (zero but for noise
    before a plain wall). A centre fitted to the outline moves along the floor by
    :math:`\sum_j c_j r_j`, :math:`c_j` the least-squares weights of a circle fit (centre and
    radius) to the sectors used, projected on the floor's ``direction``; with the sectors'
    coefficients alike (their covariance depending on the sectors' distance alone, counted to
    :data:`MAX_SECTOR_LAG` sectors: neighbours share the texture's grain),

    .. math:: \sigma_m^2 = \sum_{L} (2 - \delta_{L0}) \Big(\overline{eta_{jm}eta_{j+L,m}}
              - \delta_{L0}\,\overline{s_{jm}^2}\Big) \sum_j c_jc_{j+L}, \qquad
              \sigma^2 = \sum_{m=1}^{3} rac{\sigma_m^2}{2m+1}

    (:math:`\sigma_m` the standard deviation of the centre's coefficient of :math:`P_m`, each
    clipped at zero; :math:`1/(2m+1)` the mean square of :math:`P_m` over [-1, 1]). Sectors
    with a residual in fewer than 80 % of the frames (the floor contact, another body, a marker)
    are left out. Returns :math:`\sigma` (px); 0 for fewer than 16 frames or a body that moves
    less than half a pixel."""
    from numpy.polynomial import legendre

    frames = along.size
    if frames < 16 or float(np.ptp(along)) < 0.5:
        return np.zeros(LOCKED_DEGREE)
    scaled = 2.0 * (along - along.min()) / float(np.ptp(along)) - 1.0
    basis = legendre.legvander(scaled, LOCKED_DEGREE)  # (frames, 1 + degree)
    present = np.isfinite(sectors)
    used = present.mean(axis=0) >= 0.8
    if used.sum() < 8:
        return np.zeros(LOCKED_DEGREE)
    angles = 2 * math.pi * np.arange(RAYS) / RAYS
    design = np.column_stack([np.cos(angles), np.sin(angles), np.ones(RAYS)])[used]
    weights = np.linalg.pinv(design)  # (3, sectors): centre (u, v) and radius from r
    along_weights = np.zeros(RAYS)
    along_weights[used] = direction[0] * weights[0] + direction[1] * weights[1]
    coefficients = np.zeros((RAYS, LOCKED_DEGREE))
    noise = np.zeros((RAYS, LOCKED_DEGREE))
    for j in np.flatnonzero(used):
        ok = present[:, j]
        matrix = basis[ok]
        solution, *_ = np.linalg.lstsq(matrix, sectors[ok, j], rcond=None)
        scatter = sectors[ok, j] - matrix @ solution
        dof = max(int(ok.sum()) - matrix.shape[1], 1)
        inverse = np.linalg.pinv(matrix.T @ matrix)
        coefficients[j] = solution[1:]
        noise[j] = np.sqrt(float(scatter @ scatter) / dof * np.diag(inverse)[1:])
    spread = np.zeros(LOCKED_DEGREE)
    for m in range(LOCKED_DEGREE):
        variance = 0.0
        for lag in range(MAX_SECTOR_LAG + 1):
            pairs = used & np.roll(used, -lag)
            covariance = float(
                np.mean((coefficients[:, m] * np.roll(coefficients[:, m], -lag))[pairs])
            )
            if lag == 0:
                covariance -= float(np.mean(noise[used, m] ** 2))
            product = float(np.sum((along_weights * np.roll(along_weights, -lag))[pairs]))
            variance += (1.0 if lag == 0 else 2.0) * covariance * product
        spread[m] = math.sqrt(max(variance, 0.0))
    return spread


def draw_overlay(frame: np.ndarray, found: FrameTrack) -> np.ndarray:
    """``frame`` (BGR) with what the tracker found drawn on it: the floor line, each body's
    fitted outline and centre, the radius to its marker (green found, red lost)."""
    import cv2

    image = frame.copy()
    floor = found.floor
    width = image.shape[1]
    a = floor.point - floor.direction * 2 * width
    b = floor.point + floor.direction * 2 * width
    cv2.line(image, _px(a), _px(b), (255, 0, 255), 1, cv2.LINE_AA, 4)
    for centre, radius, marker, ok in zip(
        found.centre, found.radius, found.marker, found.found, strict=True
    ):
        colour = (0, 200, 0) if ok else (0, 0, 255)
        cv2.circle(image, _px(centre), int(round(radius * 16)), colour, 1, cv2.LINE_AA, 4)
        cv2.drawMarker(
            image, (int(round(centre[0])), int(round(centre[1]))), colour, cv2.MARKER_CROSS, 10, 1
        )
        cv2.line(image, _px(centre), _px(marker), colour, 1, cv2.LINE_AA, 4)
        cv2.circle(image, _px(marker), 3 * 16, colour, 1, cv2.LINE_AA, 4)
    return image


def _px(point: FloatArray) -> tuple[int, int]:
    """A point for OpenCV's drawing with 4 fractional bits."""
    return int(round(float(point[0]) * 16)), int(round(float(point[1]) * 16))
