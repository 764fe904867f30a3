"""What drawing a system needs, as arrays: spring end points, the scene's extent, zigzags, and
the fixed force-arrow scales.

A body point is drawn from the centre position ``x`` and the rotation ``phi``
(docs/physics.md (M1)): this is geometry, not physics; nothing here computes a force.
:func:`_zigzag` is the one zigzag spring of the Matplotlib drawings (the report's player and the
page draw theirs with ``outputs/js/geometry.js``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rollspring.model import System
from rollspring.physics import SystemArrays, system_arrays
from rollspring.physics.arrays import FloatArray


@dataclass(frozen=True)
class _Geometry:
    """What drawing needs from a system, as arrays."""

    arrays: SystemArrays
    shapes: tuple[str, ...]

    @classmethod
    def of(cls, system: System) -> _Geometry:
        return cls(system_arrays(system), tuple(b.shape for b in system.bodies))

    @property
    def n(self) -> int:
        return self.arrays.n_bodies

    @property
    def centre_height(self) -> FloatArray:
        return self.arrays.track + self.arrays.radius

    def end_points(self, x: FloatArray, phi: FloatArray) -> FloatArray:
        r"""Spring end positions (..., S, 2 ends, 2) for centre positions ``x`` and rotations
        ``phi`` (..., n): :math:`P = (x + r\sin\theta, h + R + r\cos\theta)`,
        :math:`\theta = \alpha + \varphi` (M1), with the actual ``x`` (also while a body
        slips); anchors are fixed."""
        a = self.arrays
        body = np.where(a.end_body >= 0, a.end_body, 0)
        theta = a.end_alpha + a.rolls[body] * phi[..., body]
        px = x[..., body] + a.end_r * np.sin(theta)
        py = self.centre_height[body] + a.end_r * np.cos(theta)
        points = np.stack([px, py], axis=-1)
        return np.where((a.end_body < 0)[..., None], a.end_anchor, points)

    def force_points(self, x: FloatArray, phi: FloatArray) -> FloatArray:
        """Points of application of the constant external forces, (F, 2)."""
        a = self.arrays
        body = a.force_body
        theta = a.force_alpha + a.rolls[body] * phi[body]
        return np.stack(
            [
                x[body] + a.force_r * np.sin(theta),
                self.centre_height[body] + a.force_r * np.cos(theta),
            ],
            axis=-1,
        )


@dataclass(frozen=True)
class _Extent:
    """Data limits of a scene and the levels it is drawn against (m)."""

    xmin: float
    xmax: float
    ymin: float
    ymax: float
    floor: float
    size: float  # the largest body radius: the unit of every drawing length
    track_spans: tuple[tuple[float, float, float], ...]  # (height, x from, x to) raised tracks
    walls: tuple[tuple[float, float, float, float], ...]  # rectangles (x, y, width, height)


def _extent(
    geometry: _Geometry,
    xs: FloatArray,
    phis: FloatArray,
    *,
    top_extra: float = 0.0,
    side_extra: float = 0.0,
) -> _Extent:
    """Limits covering the states ``xs``, ``phis`` (k, n), the anchors, walls and labels."""
    a = geometry.arrays
    radius, track = a.radius, a.track
    size = float(np.max(radius))
    floor = float(min(np.min(track), 0.0)) if np.any(track <= 0.0) else float(np.min(track))
    lefts = np.min(xs - radius, axis=0)
    rights = np.max(xs + radius, axis=0)
    xmin, xmax = float(np.min(lefts)), float(np.max(rights))
    top = float(np.max(track + 2 * radius))
    if a.n_springs:
        ends = geometry.end_points(xs, phis)
        xmin = min(xmin, float(np.min(ends[..., 0])))
        xmax = max(xmax, float(np.max(ends[..., 0])))
        top = max(top, float(np.max(ends[..., 1])))
    spans = []
    for i in range(geometry.n):
        if track[i] > floor:
            spans.append(
                (
                    float(track[i]),
                    float(lefts[i] - 0.5 * radius[i]),
                    float(rights[i] + 0.5 * radius[i]),
                )
            )
    walls = []
    thickness = 0.25 * size
    left_end, right_end = float(np.min(lefts)), float(np.max(rights))
    anchor_points = {
        (float(p[0]), float(p[1]))
        for p in a.end_anchor.reshape(-1, 2)[(a.end_body < 0).reshape(-1)]
    }
    for ax_, ay in sorted(anchor_points):
        height = max(ay + 0.6 * size, floor + size) - floor
        if ax_ <= left_end:  # a wall on the left, from the floor up past the hook
            walls.append((ax_ - thickness, floor, thickness, height))
            xmin = min(xmin, ax_ - thickness)
            top = max(top, floor + height)
        elif ax_ >= right_end:  # on the right
            walls.append((ax_, floor, thickness, height))
            xmax = max(xmax, ax_ + thickness)
            top = max(top, floor + height)
        else:  # above the bodies' range: a ceiling block
            walls.append((ax_ - 0.75 * size, ay, 1.5 * size, thickness))
            xmin, xmax = min(xmin, ax_ - 0.75 * size), max(xmax, ax_ + 0.75 * size)
            top = max(top, ay + thickness)
    for _height, left, right in spans:
        xmin, xmax = min(xmin, left), max(xmax, right)
    pad = 0.3 * size + side_extra
    return _Extent(
        xmin=xmin - pad,
        xmax=xmax + pad,
        ymin=floor - 1.05 * size,  # the floor band with the CM and X-hat markers and labels
        ymax=top + 0.45 * size + top_extra,  # body labels
        floor=floor,
        size=size,
        track_spans=tuple(spans),
        walls=tuple(walls),
    )


def _zigzag(start: FloatArray, end: FloatArray, half_width: float, teeth: int) -> FloatArray:
    """Points of a zigzag spring from ``start`` to ``end``: straight leads (15% each), then
    ``teeth`` zigzags of constant width, stretched with the spring."""
    d = end - start
    length = math.hypot(float(d[0]), float(d[1]))
    if length <= 0.0:
        return np.array([start, end])
    e = d / length
    normal = np.array([-e[1], e[0]])
    s = np.concatenate([[0.0], 0.15 + 0.7 * (np.arange(2 * teeth + 1) / (2 * teeth)), [1.0]])
    offset = np.zeros_like(s)
    offset[2:-2:2] = half_width
    offset[3:-2:2] = -half_width
    return start + s[:, None] * d + offset[:, None] * normal


def _nice(value: float) -> float:
    """The largest of 1, 2, 5 times a power of ten that is at most ``value`` (> 0)."""
    power = 10.0 ** math.floor(math.log10(value))
    for factor in (5.0, 2.0, 1.0):
        if factor * power <= value * (1 + 1e-12):
            return factor * power
    return power


@dataclass(frozen=True)
class ForceScale:
    """Fixed arrow scales (m of drawing per N): one for springs, friction and applied forces,
    one for normal forces (usually ten times larger); ``*_reference`` are the round forces
    shown in the legend (0 when there is nothing to show)."""

    horizontal: float
    normal: float
    horizontal_reference: float
    normal_reference: float

    @classmethod
    def fit(
        cls, size: float, horizontal_max: float, normal_max: float, legend_length: float = math.inf
    ) -> ForceScale:
        """The largest spring/friction/applied force drawn as long as the largest radius, the
        largest normal force 0.9 of it; the legend's round forces are drawn at most
        ``legend_length`` long."""

        def one(largest: float, length: float) -> tuple[float, float]:
            if not (math.isfinite(largest) and largest > 0.0):
                return 1.0, 0.0
            scale = length / largest
            return scale, _nice(min(largest, legend_length / scale))

        h, h_ref = one(horizontal_max, size)
        n, n_ref = one(normal_max, 0.9 * size)
        return cls(h, n, h_ref, n_ref)


def _finite_max(values: FloatArray) -> float:
    values = np.abs(np.asarray(values, dtype=float))
    values = values[np.isfinite(values)]
    return float(np.max(values)) if values.size else 0.0
