r"""Animations of a trajectory: GIF (Pillow), MP4 (imageio-ffmpeg), HTML (Matplotlib's JS player).

The bodies roll (every rolling body carries a radius mark, so its rotation shows), the springs
stretch, arrows show the spring, friction, normal (and applied) forces at fixed scales given in
a legend, the CM and :math:`\hat X` move (or stay) on the floor, and a clock shows the simulated
time with the latest event (slip, stick, lift-off). Frames are drawn from the
:class:`~rollspring.simulate.Trajectory` at the frame times (positions and rotations by cubic
Hermite interpolation with their own velocities, forces linearly); nothing is recomputed.

Public API
----------
* :func:`write_animation` ``(trajectory, path, *, duration=None, speed=1.0, fps=25, dpi=80,
  forces=True, progress=None) -> Path``: the format from the suffix (``.gif``, ``.mp4``,
  ``.html``/``.htm``), written atomically (a temporary file renamed into place).
* :func:`animation_html` ``(trajectory, *, duration=None, speed=1.0, fps=25, dpi=80,
  forces=True, progress=None) -> str``: the JS animation markup to embed in a page or a
  notebook: self-contained (frames as base64 PNG, no network, no external icon font).
* :func:`frame_times` ``(trajectory, *, duration=None, speed=1.0, fps=25) -> ndarray``.
* :class:`MotionAnimation`: the frames one by one (``times``, ``render(i) -> RGBA array``,
  ``pixel(x, y)`` to find a point of the scene in a frame).
* :data:`FORMATS`, :class:`AnimationError` (a :class:`~rollspring.errors.RollspringError`).

A long chain (more than :data:`~rollspring.model.chains.LONG_CHAIN` bodies) is drawn as a
:class:`ChainAnimation` instead: every body a point at its rest position, raised by its
displacement (or, without the waves analysis, its velocity) and coloured by the friction it
needs against :math:`\mu_s N` (signed), with a strip of the same colours below (the friction
pattern travelling with the wave) and, given a :class:`~rollspring.analysis.waves.Waves`
(``waves=``), the energy centroid and the group-velocity prediction as vertical lines.

``duration`` is the stretch of simulated time shown (default: the whole trajectory), ``speed``
the playback speed (0.5 = slow motion: one simulated second lasts two seconds), ``fps`` frames
per second of playback. ``progress`` is called with the fraction of frames rendered (0 to 1).
"""

from __future__ import annotations

import hashlib
import html
import math
import os
import re
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from rollspring.analysis.waves import Waves
from rollspring.errors import AnimationError
from rollspring.model.chains import LONG_CHAIN
from rollspring.outputs.atomic import atomic_path, atomic_write, atomic_write_text
from rollspring.outputs.figures import (
    SystemScene,
    new_figure,
    scene_for_trajectory,
    signed_friction_ratio,
    states_at,
    theme,
)
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import Trajectory

__all__ = [
    "FORMATS",
    "AnimationError",
    "ChainAnimation",
    "MotionAnimation",
    "animation_html",
    "frame_times",
    "write_animation",
]

#: File suffix -> format.
FORMATS = {".gif": "gif", ".mp4": "mp4", ".html": "html", ".htm": "html"}
#: At most this many frames per animation (a guard against hours of rendering).
MAX_FRAMES = 10_000

Progress = Callable[[float], None]


def _check_positive(
    name: str, value: Any, *, integer: bool = False, upper: float = math.inf
) -> None:
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    if ok and integer:
        ok = float(value).is_integer()
    if not ok or not math.isfinite(float(value)) or not 0 < float(value) <= upper:
        kind = "a whole number" if integer else "a number"
        limit = f" up to {upper:g}" if math.isfinite(upper) else ""
        raise AnimationError(f"{name}: must be {kind} > 0{limit}, got {value!r}")


def frame_times(
    trajectory: Trajectory, *, duration: float | None = None, speed: float = 1.0, fps: int = 25
) -> FloatArray:
    """Simulated times of the frames: from the start, one every ``speed/fps`` seconds, up to
    ``duration`` (default, and at most, the end of the trajectory)."""
    _check_positive("speed", speed)
    _check_positive("fps", fps, integer=True, upper=120)
    if duration is not None:
        _check_positive("duration", duration)
    t0, t_end = float(trajectory.t[0]), float(trajectory.t[-1])
    end = t_end if duration is None else min(t0 + float(duration), t_end)
    step = float(speed) / int(fps)
    count = int(math.floor((end - t0) / step * (1 + 1e-12) + 1e-9)) + 1
    if count > MAX_FRAMES:
        raise AnimationError(
            f"duration: {end - t0:g} s at speed {speed:g} and {int(fps)} fps is {count} frames "
            f"(at most {MAX_FRAMES}); shorten it, or raise the speed or lower the fps"
        )
    return np.asarray(t0 + step * np.arange(count), dtype=np.float64)


class _Frames:
    """What every animation shares: ``times`` (the frames' simulated times) and ``figure``,
    set by the subclass with its :meth:`update`; the frames drawn on Agg."""

    times: np.ndarray
    figure: Figure

    def __len__(self) -> int:
        return int(self.times.size)

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) of a frame in pixels."""
        width, height = self.figure.canvas.get_width_height()
        return int(width), int(height)

    def update(self, i: int) -> None:
        """Move the figure's artists to frame ``i`` (without drawing)."""
        raise NotImplementedError

    def render(self, i: int) -> np.ndarray:
        """Frame ``i`` as a (height, width, 4) uint8 array."""
        self.update(i)
        canvas = self.figure.canvas
        assert isinstance(canvas, FigureCanvasAgg)  # new_figure gives every figure an Agg canvas
        with theme():
            canvas.draw()
        return np.array(canvas.buffer_rgba())

    def frames(self, progress: Progress | None = None) -> Iterator[np.ndarray]:
        """Every frame in order, reporting the fraction done to ``progress``."""
        total = len(self)
        for i in range(total):
            frame = self.render(i)
            if progress is not None:
                progress((i + 1) / total)
            yield frame


class MotionAnimation(_Frames):
    """The frames of a trajectory's animation, drawn on one figure whose artists are moved from
    frame to frame (Agg, no display).

    ``times`` are the simulated times of the frames; :meth:`render` gives frame ``i`` as an RGBA
    array (row 0 at the top); :meth:`pixel` maps a scene point (m) to (column, row) in it.
    """

    def __init__(
        self,
        trajectory: Trajectory,
        *,
        duration: float | None = None,
        speed: float = 1.0,
        fps: int = 25,
        dpi: float = 80,
        forces: bool = True,
        width: float = 8.0,
    ) -> None:
        _check_positive("dpi", dpi, upper=1200)
        self.trajectory = trajectory
        self.fps = int(fps)
        self.speed = float(speed)
        self.dpi = float(dpi)
        self.times = frame_times(trajectory, duration=duration, speed=speed, fps=fps)
        self.scene: SystemScene = scene_for_trajectory(
            trajectory, forces=forces, clock=True, width=width, dpi=dpi
        )
        figure = self.scene.ax.figure
        assert isinstance(figure, Figure)  # the scene's own figure (new_figure)
        self.figure = figure
        self._forces = forces

    def update(self, i: int) -> None:
        """Move the scene to frame ``i`` (without drawing)."""
        state = states_at(self.trajectory, self.times[i : i + 1], forces=self._forces)[0]
        self.scene.update(state)

    def pixel(self, x: float, y: float) -> tuple[float, float]:
        """(column, row) of the scene point (x, y) in metres, in a rendered frame."""
        ax = self.scene.ax
        with theme():
            self.figure.canvas.draw()  # the axes box (equal aspect) is placed at draw time
        column, up = ax.transData.transform((x, y))
        return float(column), float(self.size[1] - up)


class ChainAnimation(_Frames):
    """The frames of a long chain's animation (module docstring), with the interface of
    :class:`MotionAnimation` (``times``, ``render(i)``, ``frames()``, ``update(i)``, ``size``,
    ``figure``). Values between output rows are interpolated linearly."""

    def __init__(
        self,
        trajectory: Trajectory,
        *,
        duration: float | None = None,
        speed: float = 1.0,
        fps: int = 25,
        dpi: float = 80,
        waves: Waves | None = None,
        width: float = 8.0,
    ) -> None:
        _check_positive("dpi", dpi, upper=1200)
        self.trajectory = trajectory
        self.fps = int(fps)
        self.speed = float(speed)
        self.dpi = float(dpi)
        self.waves = waves
        self.times = frame_times(trajectory, duration=duration, speed=speed, fps=fps)
        x = np.asarray(trajectory.x, dtype=float)
        if waves is not None:
            self._rest = np.asarray(waves.reference, dtype=float)
            self._height = x - self._rest
            label = "displacement from rest (m)"
        else:
            self._rest = x[0]
            self._height = np.asarray(trajectory.v, dtype=float)
            label = "centre velocity (m/s)"
        self._ratio = signed_friction_ratio(trajectory)
        top = float(np.max(np.abs(self._height), initial=0.0)) or 1.0
        ratio_top = float(np.max(np.abs(self._ratio), initial=0.0)) or 1.0
        left, right = float(self._rest.min()), float(self._rest.max())
        pad = 0.01 * (right - left) or 1.0
        with theme():
            figure = new_figure(width, 0.45 * width, dpi=dpi)
            ax, strip = figure.subplots(
                2, 1, sharex=True, gridspec_kw={"height_ratios": [4, 1], "hspace": 0.08}
            )
            figure.subplots_adjust(left=0.1, right=0.88, bottom=0.14, top=0.88)
            self._points = ax.scatter(
                self._rest,
                self._height[0],
                c=self._ratio[0],
                s=max(2.0, min(20.0, 3000.0 / len(self._rest))),
                cmap="PuOr_r",
                vmin=-ratio_top,
                vmax=ratio_top,
                linewidths=0,
            )
            ax.set_xlim(left - pad, right + pad)
            ax.set_ylim(-1.15 * top, 1.15 * top)
            ax.set_ylabel(label, fontsize=7.5)
            ax.axhline(0.0, color="#bbbbbb", lw=0.6, zorder=0)
            order = np.argsort(self._rest, kind="stable")
            self._order = order
            self._strip = strip.imshow(
                self._ratio[:1, order],
                aspect="auto",
                extent=(left, right, 0.0, 1.0),
                cmap="PuOr_r",
                vmin=-ratio_top,
                vmax=ratio_top,
                interpolation="nearest",
            )
            strip.set_yticks([])
            strip.set_xlabel("rest position x (m)")
            bar = figure.colorbar(self._points, ax=[ax, strip], fraction=0.03, pad=0.02)
            bar.set_label("f / (μs N), signed", fontsize=7.5)
            self._centroid = self._predicted = None
            if waves is not None:
                self._centroid = ax.axvline(left, color="#1b9e77", lw=1.4, label="energy centroid")
                if waves.kind == "packet" and math.isfinite(waves.group_velocity):
                    self._predicted = ax.axvline(
                        left, color="#e7298a", lw=1.2, ls="--", label="X_E(0) + v_g t"
                    )
                ax.legend(loc="upper right", fontsize=7, framealpha=0.8)
            self._clock = ax.set_title("", loc="left", fontsize=8.5)
            ax.set_title(trajectory.system.name or "", loc="right", fontsize=7.5)
        self.figure = figure

    def _at(self, values: np.ndarray, time: float) -> np.ndarray:
        t = self.trajectory.t
        if t.size == 1:
            return np.asarray(values[0])
        k = int(np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 2))
        w = float(np.clip((time - t[k]) / (t[k + 1] - t[k]), 0.0, 1.0))
        result: np.ndarray = (1.0 - w) * values[k] + w * values[k + 1]
        return result

    def update(self, i: int) -> None:
        """Move the drawing to frame ``i`` (without drawing)."""
        time = float(self.times[i])
        ratio = self._at(self._ratio, time)
        self._points.set_offsets(np.column_stack([self._rest, self._at(self._height, time)]))
        self._points.set_array(ratio)
        self._strip.set_data(ratio[self._order][None, :])
        waves = self.waves
        if waves is not None and self._centroid is not None:
            where = float(np.interp(time, waves.t, waves.centroid))
            self._centroid.set_xdata([where, where])
            if self._predicted is not None:
                ahead = waves.centroid[0] + waves.group_velocity * (time - float(waves.t[0]))
                self._predicted.set_xdata([ahead, ahead])
        self._clock.set_text(f"t = {time:.2f} s")


def write_animation(
    trajectory: Trajectory,
    path: str | os.PathLike[str],
    *,
    duration: float | None = None,
    speed: float = 1.0,
    fps: int = 25,
    dpi: float = 80,
    forces: bool = True,
    progress: Progress | None = None,
    waves: Waves | None = None,
) -> Path:
    """Render the animation and write it to ``path`` (``.gif``, ``.mp4``, ``.html``), atomically:
    a temporary file in the same directory renamed into place. Returns the path. A long chain
    is a :class:`ChainAnimation` (with ``waves``, its energy centroid)."""
    target = Path(path)
    kind = FORMATS.get(target.suffix.lower())
    if kind is None:
        raise AnimationError(
            f"{target}: unknown animation format '{target.suffix or '(no suffix)'}' "
            f"(use .gif, .mp4 or .html)"
        )
    animation = _animation(trajectory, duration, speed, fps, dpi, forces, waves)
    if kind == "gif":
        _write_gif(animation, target, progress)
    elif kind == "mp4":
        _write_mp4(animation, target, progress)
    else:
        title = html.escape(trajectory.system.name or "rollspring animation")
        page = (
            '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
            f"<title>{title}</title>\n</head>\n<body>\n{_html_markup(animation, progress)}"
            "\n</body>\n</html>\n"
        )
        atomic_write_text(target, page)
    return target


def animation_html(
    trajectory: Trajectory,
    *,
    duration: float | None = None,
    speed: float = 1.0,
    fps: int = 25,
    dpi: float = 80,
    forces: bool = True,
    progress: Progress | None = None,
    waves: Waves | None = None,
) -> str:
    """The animation as HTML markup (Matplotlib's JS player: play, pause, step, speed, loop),
    self-contained: frames embedded as base64 PNG, no network access, no icon font. The element
    ids derive from the frames' hash, so equal inputs give equal markup. A long chain is a
    :class:`ChainAnimation` (with ``waves``, its energy centroid)."""
    animation = _animation(trajectory, duration, speed, fps, dpi, forces, waves)
    return _html_markup(animation, progress)


def _animation(
    trajectory: Trajectory,
    duration: float | None,
    speed: float,
    fps: int,
    dpi: float,
    forces: bool,
    waves: Waves | None,
) -> MotionAnimation | ChainAnimation:
    if len(trajectory.ids) > LONG_CHAIN:
        return ChainAnimation(
            trajectory, duration=duration, speed=speed, fps=fps, dpi=dpi, waves=waves
        )
    return MotionAnimation(
        trajectory, duration=duration, speed=speed, fps=fps, dpi=dpi, forces=forces
    )


# -- writers ---------------------------------------------------------------------------------


def _write_gif(
    animation: MotionAnimation | ChainAnimation, target: Path, progress: Progress | None
) -> None:
    from PIL import Image

    images = []
    for frame in animation.frames(progress):
        rgb = Image.fromarray(frame[..., :3])
        images.append(
            rgb.quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        )
    milliseconds = round(1000 / animation.fps)
    with atomic_write(target, "wb") as handle:
        images[0].save(
            handle,
            format="GIF",
            save_all=True,
            append_images=images[1:],
            duration=milliseconds,
            loop=0,
        )


def _padded(frame: np.ndarray, block: int) -> np.ndarray:
    """The RGB part of ``frame`` padded with white to multiples of ``block`` pixels (video
    encoders work on 16-pixel macro blocks)."""
    height, width = frame.shape[:2]
    rows, columns = -height % block, -width % block
    rgb = frame[..., :3]
    if rows or columns:
        rgb = np.pad(rgb, ((0, rows), (0, columns), (0, 0)), constant_values=255)
    return np.ascontiguousarray(rgb)


def _write_mp4(
    animation: MotionAnimation | ChainAnimation, target: Path, progress: Progress | None
) -> None:
    import imageio_ffmpeg

    with atomic_path(target, suffix=".part.mp4") as temporary:
        writer = None
        for frame in animation.frames(progress):
            rgb = _padded(frame, 16)
            if writer is None:
                writer = imageio_ffmpeg.write_frames(
                    str(temporary),
                    (rgb.shape[1], rgb.shape[0]),
                    fps=animation.fps,
                    codec="libx264",
                    pix_fmt_out="yuv420p",
                    quality=8,
                    macro_block_size=16,
                    ffmpeg_log_level="error",
                    output_params=["-movflags", "+faststart"],
                )
                writer.send(None)
            writer.send(rgb.tobytes())
        if writer is not None:
            writer.close()


_ICONS = {
    "minus": "\u2212",
    "plus": "+",
    "fast-backward": "\u23ee",
    "step-backward": "\u2039",
    "play fa-flip-horizontal": "\u25c0",
    "pause": "\u23f8",
    "play": "\u25b6",
    "step-forward": "\u203a",
    "fast-forward": "\u23ed",
}


def _html_markup(animation: MotionAnimation | ChainAnimation, progress: Progress | None) -> str:
    """Matplotlib's HTMLWriter output for the frames, made offline: the Font Awesome link is
    dropped and its icons become Unicode symbols; the random element id becomes a hash."""
    from matplotlib.animation import HTMLWriter

    with tempfile.TemporaryDirectory(prefix="rollspring-html-") as folder:
        out = Path(folder) / "animation.html"
        writer = HTMLWriter(
            fps=animation.fps, embed_frames=True, default_mode="loop", embed_limit=1e6
        )
        total = len(animation)
        with theme(), writer.saving(animation.figure, out, dpi=animation.dpi):
            for i in range(total):
                animation.update(i)
                writer.grab_frame()
                if progress is not None:
                    progress((i + 1) / total)
        markup = out.read_text(encoding="utf-8")
    markup = re.sub(r"<link[^>]*font-awesome[^>]*>\s*", "", markup)

    def icon(match: re.Match[str]) -> str:
        return _ICONS.get(match.group(1), "")

    markup = re.sub(r'<i class="fa fa-([a-z\- ]+?)"></i>', icon, markup)
    for old in set(re.findall(r"_anim_img([0-9a-f]{32})", markup)):
        markup = markup.replace(old, "{id}")
    digest = hashlib.sha256(markup.encode("utf-8")).hexdigest()[:32]
    return markup.replace("{id}", digest)
