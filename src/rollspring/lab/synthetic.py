r"""Synthetic recordings: a motion rendered as a camera would film it, for tests and examples.

A side view of the experiment: a wall (optionally textured) above a table whose front edge is
the floor line, each body drawn by its shape at its centre :math:`x_i(t)` with its rotation
:math:`\varphi_i(t)` (clockwise positive; :math:`x = x_0 + R\varphi` when rolling) — a hoop as
a ring, a cylinder, sphere or shell as a filled disc — with one contrasting marker on its rim
(a coloured stretch of a hoop's ring, a coloured dot near a disc's rim) that is straight up at
:math:`\varphi = 0`, and the springs behind the bodies. Edges are anti-aliased analytically
(each pixel's coverage of a circle from its distance to the centre), so the drawn geometry is
the truth to a small fraction of a pixel. Then, as a real camera adds them: a camera roll (the
whole scene turned counter-clockwise by a few degrees), a Gaussian blur, a brightness flicker
from frame to frame, pixel noise, and the lossy compression of an MP4 file (OpenCV's
``VideoWriter``, codec ``mp4v``). Every random choice comes from one seeded generator: the same
arguments give the same frames.

The motion comes from the caller (arrays ``t``, ``x``, ``phi``), or from :func:`exact_motion`,
which gives a system's exact motion at given times: for level springs joining body centres
(the paper's systems), damped or not and without rolling resistance, the closed form of the
linear equations :math:`J\ddot q + C\dot q + Kq = Q_0` (exact while the bodies roll);
otherwise :func:`rollspring.simulate` at ``rtol=1e-10``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rollspring.errors import TrackingError
from rollspring.model import System
from rollspring.physics.arrays import FloatArray

__all__ = ["Camera", "Motion", "exact_motion", "render_frames", "write_video"]


@dataclass(frozen=True)
class Motion:
    """A motion of a system's bodies at times ``t`` (s, shape (frames,)): centre positions
    ``x`` (m) and rotations ``phi`` (rad, clockwise positive), each (frames, bodies), the
    columns in the order of ``ids``."""

    ids: tuple[str, ...]
    t: FloatArray
    x: FloatArray
    phi: FloatArray


def exact_motion(system: System, t: FloatArray) -> Motion:
    r"""The exact motion of ``system`` from its initial state at the times ``t`` (s, from 0).

    When every spring joins body centres (or anchors) at one height, every body rolls
    (:func:`~rollspring.physics.springs_stay_level`) and none has rolling resistance, the
    equations of motion are exactly linear: :math:`J\ddot q = Q_0 - Kq - C\dot q` with
    constant :math:`J` (M4), :math:`K` (M12) and the dampers' :math:`C`, :math:`q = \varphi`
    for a rolling body. With
    :math:`z = (q, \dot q, 1)` this is :math:`\dot z = Az`, solved by the matrix exponential
    :math:`z(t) = e^{At}z(0)` (damped, undamped, with zero modes alike). Any other system is
    integrated by :func:`rollspring.simulate` at ``rtol=1e-10`` (``t`` then evenly spaced from
    0). Returns :class:`Motion` with :math:`x_i = x_{i0} + R_i\varphi_i`.
    """
    from rollspring.physics import (
        damping_matrix,
        generalized_forces,
        springs_stay_level,
        stiffness_matrix,
        system_arrays,
    )

    times = np.asarray(t, dtype=float)
    arrays = system_arrays(system)
    if not bool(np.all(arrays.rolls == 1.0)):
        raise TrackingError("system: exact_motion draws rolling bodies only (a slider found)")
    if springs_stay_level(arrays) and not arrays.resisted:
        from scipy.linalg import expm

        n = arrays.n_bodies
        q0 = np.zeros(n)
        inverse = 1.0 / arrays.inertia
        generator = np.zeros((2 * n + 1, 2 * n + 1))
        generator[:n, n : 2 * n] = np.eye(n)
        generator[n : 2 * n, :n] = -inverse[:, None] * stiffness_matrix(arrays, q0)
        generator[n : 2 * n, n : 2 * n] = -inverse[:, None] * damping_matrix(arrays, q0)
        generator[n : 2 * n, 2 * n] = inverse * generalized_forces(arrays, q0)
        start = np.concatenate([q0, arrays.v0 / arrays.scale, [1.0]])
        q = np.array([(expm(generator * time) @ start)[:n] for time in times])
    else:
        from rollspring.simulate import simulate

        if times.size < 2 or times[0] != 0.0 or not np.allclose(np.diff(times), times[1]):
            raise TrackingError("t: a system that is not linear needs evenly spaced t from 0")
        run = simulate(system, float(times[-1]), rtol=1e-10, n_output=times.size)
        if run.t.size != times.size:
            raise TrackingError(f"system: the simulation stopped early ({run.message})")
        q = run.phi
    x = arrays.x0 + arrays.scale * q
    return Motion(arrays.ids, times, x, q.copy())


@dataclass(frozen=True)
class Camera:
    """How the synthetic camera films the scene.

    ``width`` × ``height`` pixels at ``fps`` frames per second; ``scale`` px/m; ``x_left`` the
    world x (m) at the left edge of the frame (None: the bodies' initial extent centred);
    ``floor_row`` the floor line's row in the level scene (None: 80 % of the height);
    ``roll_deg`` the camera roll (the scene turned counter-clockwise in the image);
    ``noise`` the standard deviation of Gaussian pixel noise (grey levels); ``blur`` the
    standard deviation of a Gaussian blur (px); ``flicker`` the standard deviation of the
    frame-to-frame brightness factor; ``texture`` a textured wall and table; ``springs`` draw
    the springs (behind the bodies); ``codec`` the four characters of the codec; ``seed`` of
    every random choice; ``colours`` (BGR) of the wall, the table, a hoop, a disc, the markers
    and the springs.
    """

    width: int = 640
    height: int = 360
    fps: float = 30.0
    scale: float = 700.0
    x_left: float | None = None
    floor_row: float | None = None
    roll_deg: float = 0.0
    noise: float = 0.0
    blur: float = 0.0
    flicker: float = 0.0
    texture: bool = True
    springs: bool = True
    codec: str = "mp4v"
    seed: int = 0
    colours: dict[str, tuple[int, int, int]] = field(
        default_factory=lambda: {
            "wall": (200, 196, 188),
            "table": (96, 128, 160),
            "hoop": (60, 50, 45),
            "disc": (55, 55, 140),
            "marker": (40, 215, 245),
            "spring": (80, 80, 80),
        }
    )

    def frame_times(self, duration: float) -> FloatArray:
        """The frame times 0, 1/fps, ... up to ``duration`` (s)."""
        return np.arange(math.floor(duration * self.fps + 1e-9) + 1) / self.fps


#: A hoop's ring is this fraction of its radius thick; a disc's marker dot has this fraction
#: of its radius as radius and sits at 1 - 2 * it from the centre; a hoop's marker spans
#: this angle (rad) of the ring.
RING = 0.1
DOT = 0.14
HOOP_MARKER = 0.35


def _coverage(distance: FloatArray, radius: float) -> FloatArray:
    """A pixel's coverage by a disc of ``radius`` (px) at ``distance`` of its centre: a
    one-pixel linear ramp across the edge (exact for a straight edge through the pixel)."""
    return np.clip(radius - distance + 0.5, 0.0, 1.0)


def render_frames(
    system: System, motion: Motion, camera: Camera | None = None
) -> Iterator[np.ndarray]:
    """The frames (BGR, uint8, height × width × 3) of ``motion`` of ``system`` filmed by
    ``camera``, one per time of ``motion.t`` (the compression is :func:`write_video`'s)."""
    import cv2

    camera = Camera() if camera is None else camera
    rng = np.random.default_rng(camera.seed)
    height, width, scale = camera.height, camera.width, camera.scale
    bodies = system.bodies
    radii = np.array([body.radius for body in bodies])
    if motion.x.shape != (motion.t.size, len(bodies)) or motion.phi.shape != motion.x.shape:
        raise TrackingError("motion: x and phi must be (frames, bodies) arrays")
    floor_row = height * 0.8 if camera.floor_row is None else camera.floor_row
    if camera.x_left is None:
        low = float(np.min(motion.x[0] - radii))
        high = float(np.max(motion.x[0] + radii))
        x_left = (low + high) / 2 - width / 2 / scale
    else:
        x_left = camera.x_left
    roll = math.radians(camera.roll_deg)
    centre = np.array([(width - 1) / 2, (height - 1) / 2])
    # level scene -> image: turned counter-clockwise (as seen) by roll about the frame's centre
    rotation = np.array([[math.cos(roll), math.sin(roll)], [-math.sin(roll), math.cos(roll)]])

    def to_image(u: FloatArray, v: FloatArray) -> FloatArray:
        points = np.stack([np.asarray(u, float), np.asarray(v, float)], axis=-1) - centre
        result: FloatArray = points @ rotation.T + centre
        return result

    rows, cols = np.mgrid[0:height, 0:width].astype(np.float64)
    # the level scene's row of each image pixel: below the floor line is the table
    level = (np.stack([cols, rows], axis=-1) - centre) @ rotation + centre
    table = np.clip(level[..., 1] - floor_row + 0.5, 0.0, 1.0)[..., None]
    colours = {name: np.array(value, dtype=np.float64) for name, value in camera.colours.items()}
    if camera.texture:
        grain = cv2.GaussianBlur(rng.normal(0.0, 1.0, (height, width)), (0, 0), 3.0)
        grain = grain / grain.std()
        streaks = cv2.GaussianBlur(
            rng.normal(0.0, 1.0, (height, width)), (0, 0), sigmaX=25, sigmaY=1.5
        )
        streaks = streaks / streaks.std()
        wall = colours["wall"] + 14.0 * grain[..., None]
        tabletop = colours["table"] + 16.0 * streaks[..., None] + 6.0 * grain[..., None]
    else:
        wall = np.broadcast_to(colours["wall"], (height, width, 3))
        tabletop = np.broadcast_to(colours["table"], (height, width, 3))
    background = (wall * (1.0 - table) + tabletop * table).astype(np.float32)
    ids = [body.id for body in bodies]
    for k in range(motion.t.size):
        image = background.copy()
        u = (motion.x[k] - x_left) * scale
        v = floor_row - radii * scale
        centres = to_image(u, v)
        if camera.springs:
            _draw_springs(image, system, ids, centres, colours["spring"])
        for i, body in enumerate(bodies):
            _draw_body(
                image, body.shape, centres[i], radii[i] * scale, motion.phi[k, i] - roll, colours
            )
        if camera.blur > 0:
            image = cv2.GaussianBlur(image, (0, 0), camera.blur)
        if camera.flicker > 0:
            image *= np.float32(1.0 + camera.flicker * rng.standard_normal())
        if camera.noise > 0:
            image += camera.noise * rng.standard_normal(image.shape, dtype=np.float32)
        yield np.clip(np.rint(image), 0, 255).astype(np.uint8)


def _draw_springs(
    image: FloatArray, system: System, ids: list[str], centres: FloatArray, colour: FloatArray
) -> None:
    """Each spring between two bodies as a zigzag line between their centres (drawn first,
    so behind the bodies)."""
    import cv2

    canvas = np.zeros(image.shape[:2], dtype=np.uint8)
    for spring in system.springs:
        if spring.ends[0] not in ids or spring.ends[1] not in ids:
            continue
        a, b = centres[ids.index(spring.ends[0])], centres[ids.index(spring.ends[1])]
        along = b - a
        length = float(np.hypot(*along))
        if length < 1:
            continue
        normal = np.array([-along[1], along[0]]) / length
        turns = 16
        s = np.linspace(0.0, 1.0, 2 * turns + 1)
        wiggle = np.where(np.arange(s.size) % 2 == 0, 0.0, 1.0) * np.where(
            np.arange(s.size) % 4 == 1, 1.0, -1.0
        )
        wiggle[[0, -1]] = 0.0
        points = a + s[:, None] * along + 6.0 * wiggle[:, None] * normal
        cv2.polylines(
            canvas, [np.rint(points * 16).astype(np.int32)], False, 255, 2, cv2.LINE_AA, 4
        )
    rows, cols = np.nonzero(canvas)
    if rows.size == 0:
        return
    box = np.s_[rows.min() : rows.max() + 1, cols.min() : cols.max() + 1]
    alpha = canvas[box].astype(np.float32)[..., None] / np.float32(255.0)
    patch = image[box]
    patch *= 1.0 - alpha
    patch += alpha * colour


def _draw_body(
    image: FloatArray,
    shape: str,
    centre: FloatArray,
    radius: float,
    angle: float,
    colours: dict[str, FloatArray],
) -> None:
    """One body at ``centre`` (px) of ``radius`` (px), its marker at ``angle`` (rad, clockwise
    from straight up in the image), painted into ``image`` by coverage."""
    height, width = image.shape[:2]
    top, bottom = max(int(centre[1] - radius) - 2, 0), min(int(centre[1] + radius) + 3, height)
    left, right = max(int(centre[0] - radius) - 2, 0), min(int(centre[0] + radius) + 3, width)
    if top >= bottom or left >= right:
        return
    rows, cols = np.mgrid[top:bottom, left:right].astype(np.float64)
    du, dv = cols - centre[0], rows - centre[1]
    distance = np.hypot(du, dv)
    outer = _coverage(distance, radius)
    patch = image[top:bottom, left:right]
    marker_at = np.array([math.sin(angle), -math.cos(angle)])
    if shape == "hoop":
        body = outer - _coverage(distance, radius * (1 - RING))
        # the marker: a coloured stretch of the ring, HOOP_MARKER rad long, edges a pixel wide
        bearing = np.arctan2(
            du * marker_at[1] - dv * marker_at[0], du * marker_at[0] + dv * marker_at[1]
        )
        across = np.abs(bearing) * np.maximum(distance, 1.0)
        marker = body * np.clip(HOOP_MARKER / 2 * radius - across + 0.5, 0.0, 1.0)
        base = colours["hoop"]
    else:
        body = outer
        dot = centre + (1 - 2 * DOT) * radius * marker_at
        marker = _coverage(np.hypot(cols - dot[0], rows - dot[1]), DOT * radius)
        base = colours["disc"]
    body = body[..., None].astype(np.float32)
    marker = marker[..., None].astype(np.float32)
    patch *= 1.0 - body
    patch += body * base
    patch *= 1.0 - marker
    patch += marker * colours["marker"]


def write_video(
    path: str | os.PathLike[str],
    system: System,
    motion: Motion,
    camera: Camera | None = None,
) -> Path:
    """Render ``motion`` of ``system`` (:func:`render_frames`) and write it to ``path`` (an
    ``.mp4`` with codec ``camera.codec``, at ``camera.fps``); returns the path. Written under a
    temporary name and renamed into place when complete."""
    import cv2

    camera = Camera() if camera is None else camera
    target = Path(path)
    temporary = target.with_name(f".{target.stem}.{os.getpid()}.part{target.suffix}")
    writer = cv2.VideoWriter(
        str(temporary),
        cv2.VideoWriter.fourcc(*camera.codec),
        camera.fps,
        (camera.width, camera.height),
    )
    if not writer.isOpened():
        raise TrackingError(f"{target}: OpenCV cannot write a '{camera.codec}' video here")
    try:
        for frame in render_frames(system, motion, camera):
            writer.write(frame)
        writer.release()
        os.replace(temporary, target)
    except BaseException:
        writer.release()
        temporary.unlink(missing_ok=True)
        raise
    return target
