r"""Chains: a repeating unit of bodies joined by springs, with walls and an initial condition.

:func:`chain` writes the system file of a chain of ``n`` bodies on one floor (track height 0):
body :math:`i` (0-based) is element :math:`i \bmod p` of the repeating unit ``pattern`` of
:math:`p` shapes, its centre at :math:`x_i = i\,a_0` (``spacing`` :math:`a_0`), and a spring of
stiffness :math:`k_{i \bmod p}` joins body :math:`i` to body :math:`i + 1`, attached on each
body's centre vertical at that body's ``height`` above the track (the centre by default), at
rest in the placement (its rest length, written explicitly, is its initial length). A wall
(``walls``) is an anchor where the missing neighbour's attachment point would be — element
:math:`-1 \bmod p` at :math:`x = -a_0` on the left, element :math:`n \bmod p` at
:math:`x = n a_0` on the right — so a wall acts as a clamped neighbour and the chain is a piece
of the periodic lattice (docs/physics.md section 7.2).

Initial conditions (at most one; the bodies start from rest unless a packet travels): the
chain is displaced by :func:`~rollspring.model.placement.rolled` (attachments turn with the
bodies, rest lengths kept), by centre displacements :math:`u_i` of at most ``amplitude``:

* ``pluck=i``: body :math:`i` (1-based) displaced by the amplitude;
* ``mode=n``: the :math:`n`-th lowest oscillating normal mode of the chain (zero modes not
  counted; :math:`n = 1` the lowest), largest displacement ``+amplitude`` (the leftmost of
  equally large ones);
* ``packet=(q, w)``: a Gaussian packet of wavenumber :math:`q` (rad/m, in the first Brillouin
  zone :math:`|q| \le \pi/a`, :math:`a = p a_0` the unit cell) and width :math:`w` (m) about the
  chain's middle :math:`x_c` on branch ``branch``:
  :math:`u_{c,r} = A\,g\,\mathrm{Re}(e_r e^{iqca})`,
  :math:`\dot u_{c,r} = A\,\omega\,g\,\mathrm{Im}(e_r e^{iqca})`,
  :math:`g = \exp(-(x - x_c)^2/2w^2)` (0 where it is below :math:`10^{-16}`: the bodies
  further than 8.6 widths stay exactly at rest), with the branch's Bloch vector :math:`e` (centre
  displacements of the cell's bodies, largest 1) and frequency :math:`\omega(q)`: the packet
  :math:`\mathrm{Re}\,[A g e_r e^{i(qca - \omega t)}]` travels with the group velocity
  :math:`d\omega/dq`.

The modes and the Bloch vectors come from the chain's linear model at rest length, which the
generator knows in closed form: with every spring at rest length the geometric stiffness
vanishes and (docs/physics.md (M12), section 7.2) :math:`K = \sum_s k_s b_s b_s^{\mathsf T}`,
:math:`b_s = e_{x}(-c_a, +c_b)` on its two bodies, :math:`c = h` (the attachment's height
above the contact, :math:`\partial P_x/\partial\varphi` on the centre vertical (M2)) for a
rolling body and :math:`c = 1` for a slider, :math:`e_x` the spring's horizontal direction
cosine; :math:`M = \mathrm{diag}(J_i)` (M4). ``rollspring.analysis.dispersion`` computes the
same branches from the exact stiffness matrix of any periodic system.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from rollspring.errors import ModelError
from rollspring.model.placement import rolled
from rollspring.model.schema import LIMITS, System

__all__ = ["CHAIN_SHAPES", "LONG_CHAIN", "WALLS", "chain"]

#: Shapes a chain's pattern may hold (``custom`` needs its own inertia factor: write a file).
CHAIN_SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")
#: Where ``walls`` may put walls.
WALLS = ("none", "left", "both")
#: More bodies than this are a long chain: the command line's tables, the report and the
#: animation summarise them (extremes over the bodies, space–time images) instead of showing
#: every body.
LONG_CHAIN = 20


def chain(
    pattern: str | Sequence[str] = ("hoop", "cylinder"),
    n: int = 10,
    *,
    mass: float | Sequence[float] = 1.0,
    radius: float | Sequence[float] = 0.1,
    height: float | Sequence[float] | None = None,
    stiffness: float | Sequence[float] = 100.0,
    spacing: float = 0.5,
    walls: str = "none",
    pluck: int | None = None,
    packet: tuple[float, float] | Sequence[float] | None = None,
    mode: int | None = None,
    branch: int = 1,
    amplitude: float = 0.01,
    mu_static: float = 1.0,
    name: str | None = None,
) -> System:
    r"""A chain of ``n`` bodies repeating ``pattern`` (module docstring): ``mass`` (kg),
    ``radius`` (m), ``height`` (m above the track, the springs' attachment; None: the centres)
    and ``stiffness`` (N/m, the spring after each element) are one value or one per element of
    the pattern; ``spacing`` (m) between neighbouring centres; ``walls`` none, left or both;
    at most one of ``pluck`` (a body, 1-based), ``mode`` (the n-th oscillating mode) and
    ``packet`` (q in rad/m, width in m; on branch ``branch``, 1 the lowest), of ``amplitude``
    metres. Raises :class:`~rollspring.errors.ModelError` with a one-line message naming the
    argument.

    Parameters
    ----------
    pattern
        The repeating unit: shapes, as a sequence or separated by commas.
    n
        The number of bodies.
    mass, radius, height, stiffness
        kg, m, m above the track, N/m: one value or one per element of ``pattern``.
    spacing, walls
        The distance between neighbouring centres (m); ``"none"``, ``"left"`` or ``"both"``.
    pluck, mode, packet, branch, amplitude
        At most one initial condition, and its largest displacement (m).
    mu_static, name
        The static friction coefficient of every contact; the system's name.

    Returns
    -------
    System
        The chain, ready for :func:`~rollspring.analyze` or :func:`~rollspring.simulate`.
    """
    shapes = _pattern(pattern)
    p = len(shapes)
    count = _count(n, walls)
    masses = _per_element("mass", mass, p)
    radii = _per_element("radius", radius, p)
    stiffnesses = _per_element("stiffness", stiffness, p)
    heights = None if height is None else _per_element("height", height, p)
    a0 = _positive("spacing", spacing)
    chosen = [
        label
        for label, value in (("pluck", pluck), ("mode", mode), ("packet", packet))
        if value is not None
    ]
    if len(chosen) > 1:
        raise ModelError(f"{chosen[1]}: give at most one initial condition (also {chosen[0]})")
    if chosen:
        _positive("amplitude", amplitude)
    for j, shape in enumerate(shapes):
        if shape == "slider" and heights is not None and heights[j] != radii[j]:
            raise ModelError(
                f"height: element {j + 1} is a slider (it does not rotate); its springs attach "
                f"at its centre, height {radii[j]:g}"
            )

    def element(i: int) -> int:
        return i % p

    def attach_height(i: int) -> float:
        j = element(i)
        return radii[j] if heights is None else heights[j]

    bodies: list[dict[str, Any]] = []
    for i in range(count):
        j = element(i)
        entry: dict[str, Any] = {
            "id": f"{shapes[j]}{i + 1}",
            "shape": shapes[j],
            "mass": masses[j],
            "radius": radii[j],
            "x": i * a0,
        }
        if shapes[j] != "slider":
            entry["mu_static"] = mu_static
        bodies.append(entry)
    ids = [b["id"] for b in bodies]

    def at(i: int) -> dict[str, float]:
        j = element(i)
        h = attach_height(i)
        return {} if h == radii[j] else {"height": h}

    def length(x_a: float, h_a: float, x_b: float, h_b: float) -> float:
        return math.hypot(x_b - x_a, h_b - h_a)

    springs: list[dict[str, Any]] = []
    anchors: list[dict[str, Any]] = []
    if walls in ("left", "both"):
        anchors.append({"id": "wall-left", "x": -a0, "y": attach_height(-1)})
        springs.append(
            {
                "ends": ["wall-left", ids[0]],
                "stiffness": stiffnesses[element(-1)],
                "rest_length": length(-a0, attach_height(-1), 0.0, attach_height(0)),
                "at": [{}, at(0)],
            }
        )
    for i in range(count - 1):
        springs.append(
            {
                "ends": [ids[i], ids[i + 1]],
                "stiffness": stiffnesses[element(i)],
                "rest_length": length(i * a0, attach_height(i), (i + 1) * a0, attach_height(i + 1)),
                "at": [at(i), at(i + 1)],
            }
        )
    if walls == "both":
        last = count - 1
        anchors.append({"id": "wall-right", "x": count * a0, "y": attach_height(count)})
        springs.append(
            {
                "ends": [ids[last], "wall-right"],
                "stiffness": stiffnesses[element(last)],
                "rest_length": length(
                    last * a0, attach_height(last), count * a0, attach_height(count)
                ),
                "at": [at(last), {}],
            }
        )
    for spring in springs:
        if all(not end for end in spring["at"]):
            del spring["at"]
    unit = ", ".join(shapes)
    start = ""
    if pluck is not None:
        start = f"; body {pluck} displaced by {amplitude:g} m"
    elif mode is not None:
        start = f"; displaced along oscillating mode {mode} ({amplitude:g} m)"
    elif packet is not None:
        start = f"; a Gaussian wave packet on branch {branch} ({amplitude:g} m)"
    data: dict[str, Any] = {
        "name": name if name is not None else f"Chain of {count} bodies ({unit})",
        "description": (
            f"A chain of {count} bodies repeating ({unit}), {a0:g} m apart, springs "
            f"{', '.join(f'{k:g}' for k in stiffnesses)} N/m at rest, walls: {walls}{start}. "
            "Written by rollspring chain."
        ),
        "bodies": bodies,
        "anchors": anchors,
        "springs": springs,
    }
    from rollspring.model.files import system_from_dict

    system = system_from_dict(data, source="chain")
    if not chosen:
        return system
    lever = np.array(
        [1.0 if shapes[element(i)] == "slider" else attach_height(i) for i in range(count)]
    )
    scale = np.array([1.0 if b.shape == "slider" else b.radius for b in system.bodies])
    inertia = np.array([b.contact_inertia for b in system.bodies])
    velocity = None
    if pluck is not None:
        index = _whole("pluck", pluck)
        if not 1 <= index <= count:
            raise ModelError(f"pluck: must be a body from 1 to {count} (got {index})")
        shift = np.zeros(count)
        shift[index - 1] = amplitude
    elif mode is not None:
        shift = amplitude * _mode_shape(system, _whole("mode", mode), lever, scale, inertia)
    else:
        assert packet is not None
        shift, velocity = _packet(
            packet,
            _whole("branch", branch),
            amplitude,
            a0,
            p,
            count,
            [stiffnesses[element(i)] for i in range(p)],
            [attach_height(i) for i in range(-1, p + 1)],
            lever[:p],
            scale[:p],
            inertia[:p],
        )
    try:
        return rolled(system, shift / scale, velocities=velocity)
    except ModelError as exc:
        raise ModelError(
            f"amplitude: {amplitude:g} m moves the chain out of what a system file may hold "
            f"({str(exc).removeprefix('rolled: ')})"
        ) from None


def _pattern(pattern: str | Sequence[str]) -> list[str]:
    if not isinstance(pattern, str | list | tuple):
        raise ModelError(
            f"pattern: give one or more shapes, e.g. hoop,cylinder (got {type(pattern).__name__})"
        )
    shapes = [s.strip() for s in pattern.split(",")] if isinstance(pattern, str) else list(pattern)
    if not shapes or any(not isinstance(s, str) or not s for s in shapes):
        raise ModelError("pattern: give one or more shapes, e.g. hoop,cylinder")
    for shape in shapes:
        if shape not in CHAIN_SHAPES:
            raise ModelError(
                f"pattern: unknown shape '{shape}' (shapes: {', '.join(CHAIN_SHAPES)})"
            )
    if len(shapes) > LIMITS["bodies"]:
        raise ModelError(f"pattern: at most {LIMITS['bodies']} shapes")
    return shapes


def _whole(label: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise ModelError(f"{label}: must be a whole number (got {value!r})")
    return int(value)


def _count(n: Any, walls: Any) -> int:
    count = _whole("n", n)
    if not 2 <= count <= LIMITS["bodies"]:
        raise ModelError(f"n: must be from 2 to {LIMITS['bodies']} bodies (got {count})")
    if walls not in WALLS:
        raise ModelError(f"walls: must be one of {', '.join(WALLS)} (got {walls!r})")
    return count


def _number(label: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise ModelError(f"{label}: must be a number (got {value!r})")
    try:
        number = float(value)
    except OverflowError:  # an integer beyond double precision
        number = math.inf
    if not math.isfinite(number):
        shown = "an integer beyond double precision" if isinstance(value, int) else repr(value)
        raise ModelError(f"{label}: must be a finite number (got {shown})")
    return number


def _positive(label: str, value: Any) -> float:
    number = _number(label, value)
    if not number > 0:
        raise ModelError(f"{label}: must be positive (got {number:g})")
    return number


def _per_element(label: str, value: Any, p: int) -> list[float]:
    """One value for every element of the pattern, or exactly one per element."""
    listed = isinstance(value, Sequence | np.ndarray) and not isinstance(value, str)
    values = list(np.ravel(value)) if listed else [value]
    if len(values) == 1:
        values = values * p
    if len(values) != p:
        raise ModelError(
            f"{label}: give one value or one per element of the pattern ({p}), not {len(values)}"
        )
    return [_positive(label, v) for v in values]


#: Up to this many bodies a chain's mode comes from the dense eigensolver (as it always did);
#: beyond, from the tridiagonal one (a 20 000-body chain: seconds, not hours).
_DENSE_MODES = 500


def _tridiagonal_modes(diagonal: np.ndarray, beside: np.ndarray) -> tuple[np.ndarray, Any]:
    """The eigenvalues (ascending; those above the zero-mode threshold stand as the largest) of
    the symmetric tridiagonal matrix of ``diagonal`` and ``beside``, and its eigenvectors on
    demand: ``vector((slice(None), k))`` computes the one
    of index k, never the n x n matrix (SciPy's ``eigvalsh_tridiagonal`` and
    ``eigh_tridiagonal``, LAPACK ``stebz``/``stein``)."""
    # on demand: only a long chain's mode needs SciPy
    from scipy.linalg import eigh_tridiagonal, eigvalsh_tridiagonal

    def vector(key: tuple[slice, int]) -> np.ndarray:
        k = key[1]
        _, found = eigh_tridiagonal(diagonal, beside, select="i", select_range=(k, k))
        return np.asarray(found[:, 0])

    # not all n eigenvalues (O(n^2)): the largest, and those below the zero-mode threshold; the
    # rest stand for "above it" (only which are oscillating, and their order, is used)
    count = diagonal.size
    (largest,) = eigvalsh_tridiagonal(
        diagonal, beside, select="i", select_range=(count - 1, count - 1)
    )
    threshold = 1e-10 * abs(float(largest))
    low = eigvalsh_tridiagonal(diagonal, beside, select="v", select_range=(-np.inf, threshold))
    values = np.full(count, float(largest))
    values[: low.size] = low
    return values, vector


def _mode_shape(
    system: System, n: int, lever: np.ndarray, scale: np.ndarray, inertia: np.ndarray
) -> np.ndarray:
    r"""Centre displacements of the n-th oscillating mode (largest +1) of
    :math:`K v = \omega^2 M v`, :math:`K = \sum_s k_s b_s b_s^{\mathsf T}` (module docstring)."""
    index = {b.id: i for i, b in enumerate(system.bodies)}
    count = len(system.bodies)
    # K's entries spring by spring: each spring's b has at most two entries, so each adds
    # k b_i b_j to at most four (the same products, in the same order, as k outer(b, b))
    diagonal, beside = np.zeros(count), np.zeros(max(count - 1, 0))
    entries: list[tuple[int, int, float]] = []
    for spring, ((xa, ya), (xb, yb)) in zip(
        system.springs, system.spring_ends_at_rest(), strict=True
    ):
        ex = (xb - xa) / math.hypot(xb - xa, yb - ya)
        ends = [
            (index[end], sign * ex * lever[index[end]])
            for sign, end in zip((-1.0, 1.0), spring.ends, strict=True)
            if end in index
        ]
        for i, bi in ends:
            for j, bj in ends:
                entries.append((i, j, spring.stiffness * (bi * bj)))
    root = np.sqrt(inertia)
    if all(abs(i - j) <= 1 for i, j, _ in entries) and count > _DENSE_MODES:
        # a chain's K is tridiagonal: its eigenpairs in O(n^2) (LAPACK's stemr), not O(n^3)
        for i, j, value in entries:
            if i == j:
                diagonal[i] += value
            elif j == i + 1:
                beside[i] += value
        eigenvalues, vector = _tridiagonal_modes(
            diagonal / inertia, beside / (root[:-1] * root[1:])
        )
    else:
        stiffness = np.zeros((count, count))
        for i, j, value in entries:
            stiffness[i, j] += value
        eigenvalues, vectors = np.linalg.eigh(stiffness / np.outer(root, root))
        vector = vectors.__getitem__  # vector((slice(None), k)): the dense path has them all
    oscillating = np.flatnonzero(eigenvalues > 1e-10 * float(np.abs(eigenvalues).max()))
    if not 1 <= n <= oscillating.size:
        raise ModelError(f"mode: must be from 1 to {oscillating.size}, the oscillating modes")
    shape = scale * vector((slice(None), int(oscillating[n - 1]))) / root
    size = np.abs(shape)
    biggest = int(np.argmax(size >= (1.0 - 1e-9) * size.max()))  # the leftmost of the largest
    result: np.ndarray = shape / shape[biggest]
    return result


#: The widest Gaussian packet (m): the span of positions a system file may hold.
_WIDEST_PACKET = 2e4


def _packet(
    packet: Sequence[float],
    branch: int,
    amplitude: float,
    a0: float,
    p: int,
    count: int,
    stiffnesses: list[float],
    heights: list[float],
    lever: np.ndarray,
    scale: np.ndarray,
    inertia: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    r"""Displacements and velocities of a Gaussian packet (module docstring), from the
    :math:`p \times p` Bloch matrix :math:`K(q) = \sum_c K_c e^{iqca}` of the unit cell:
    the spring after element :math:`r` has :math:`b = e_x(-c_r, +c_{r+1})` with
    :math:`e_x = a_0/\sqrt{a_0^2 + (h_{r+1} - h_r)^2}`, its second end in cell
    :math:`\lfloor (r+1)/p \rfloor`. ``heights``: the attachment heights of elements
    -1 … p."""
    if isinstance(packet, str) or not isinstance(packet, Sequence) or len(packet) != 2:
        raise ModelError("packet: give the wavenumber and the width, q,width")
    q = _number("packet", packet[0])
    width = _positive("packet width", packet[1])
    if not a0 * 1e-3 <= width <= _WIDEST_PACKET:
        raise ModelError(
            f"packet width: must be from {a0 * 1e-3:g} m (a thousandth of the spacing; "
            f"narrower is a pluck) to {_WIDEST_PACKET:g} m, got {width:g}"
        )
    cell = p * a0
    if abs(q) * cell > math.pi * (1 + 1e-12):
        raise ModelError(
            f"packet: the wavenumber must lie in the first Brillouin zone, |q| <= pi/a = "
            f"{math.pi / cell:.6g} rad/m (a = {cell:g} m, the unit cell)"
        )
    if not 1 <= branch <= p:
        raise ModelError(f"branch: must be from 1 to {p}, the branches of a {p}-body cell")
    bloch = np.zeros((p, p), dtype=complex)
    for r in range(p):
        h_a, h_b = heights[r + 1], heights[r + 2]
        ex = a0 / math.hypot(a0, h_b - h_a)
        c_a = lever[r]
        c_b = lever[(r + 1) % p]
        phase = np.exp(1j * q * cell) if r + 1 == p else 1.0
        b = np.zeros(p, dtype=complex)
        b[r] -= ex * c_a
        b[(r + 1) % p] += ex * c_b * phase
        bloch += stiffnesses[r] * np.outer(b.conj(), b)
    root = np.sqrt(inertia)
    eigenvalues, vectors = np.linalg.eigh(bloch / np.outer(root, root))
    omega = math.sqrt(max(float(eigenvalues[branch - 1]), 0.0))
    shape = scale * vectors[:, branch - 1] / root
    biggest = int(np.argmax(np.abs(shape)))
    shape = shape * (abs(shape[biggest]) / shape[biggest]) / abs(shape[biggest])
    index = np.arange(count)
    x = index * a0
    centre = 0.5 * x[-1]
    gauss = np.exp(-((x - centre) ** 2) / (2.0 * width**2))
    # beyond 8.6 widths g < 1e-16: below the rounding of the placement, so exactly at rest
    envelope = amplitude * np.where(gauss < 1e-16, 0.0, gauss)
    wave = shape[index % p] * np.exp(1j * q * cell * (index // p))
    return envelope * wave.real, omega * envelope * wave.imag
