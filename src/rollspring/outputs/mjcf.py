r"""A system as a MuJoCo model (MJCF XML): the same bodies, springs and tracks, with soft contact.

rollspring enforces rolling exactly (a constraint); MuJoCo reproduces it with contact friction
between a body and a plane, solved as a soft constraint. The export lets you compare the two.

Mapping (SI units on both sides)
--------------------------------
* **Frame.** MuJoCo is z-up. Our planar frame (``x`` right, ``y`` up) is MuJoCo's ``x``-``z``
  plane: our ``(x, y)`` is MuJoCo ``(x, 0, y)``. Seen from ``-y`` (the ``side`` camera, looking
  along ``+y``), ``x`` points right and ``z`` up, as in our drawings.
* **Rotation sign.** A positive rotation about MuJoCo's ``+y`` axis moves the top of a body
  towards ``+x``: it is *clockwise* as seen by the ``side`` camera, which is our ``phi > 0``.
  So the hinge angle equals our ``phi`` with no sign change, and rolling to ``+x`` has
  ``x = R phi``. An attachment at angle ``alpha`` (clockwise from straight up) and distance
  ``r`` sits at ``(r sin alpha, 0, r cos alpha)`` in the body frame, (M1) at ``phi = 0``.
* **Coordinates.** Every body is placed at its initial placement, so **qpos = 0 is the initial
  placement** (MuJoCo's ``qpos0``; ``mj_resetData`` gives it, as does the keyframe
  ``initial``). A rolling body ``ID`` has three joints, in this order: ``ID:x`` (slide along
  ``x``: centre displacement, m), ``ID:z`` (slide along ``z``: lift-off, m) and ``ID:phi``
  (hinge about ``+y``: our rotation angle, rad). Without slip ``ID:x = R * ID:phi``. A slider
  has one joint, ``ID:x``.
* **Initial velocities.** The keyframe ``initial`` has ``qpos = 0`` and the rolling
  velocities: ``(v, 0, v/R)`` per rolling body, ``v`` per slider.
* **Inertia.** Each body has an explicit ``<inertial>``: mass ``m`` and the moment
  ``I = gamma m R^2`` about ``y`` (hoop 1, cylinder 1/2, sphere 2/5, shell 2/3, custom: its
  ``inertia_factor``). The geometry (a solid cylinder for hoops, cylinders and custom shapes,
  a sphere for spheres and shells) only makes contact: a hoop is inertially exact although
  its geom is solid. The moments about ``x`` and ``z`` have no effect (no such rotation) and
  are set equal to ``I``.
* **Tracks and contact.** One infinite plane per distinct track height, each with its own
  contact bit: a track plane has ``contype = bit, conaffinity = 0`` and the geoms of the bodies
  on it ``contype = 0, conaffinity = bit``, so a body touches its own track only and bodies
  never touch each other (docs/physics.md section 1 models no collisions). At most 31 distinct
  track heights can be exported. Body geoms have ``priority = 1``, so a contact uses the
  body's friction and ``condim = 3`` (sliding friction only: a body's ``rolling_resistance`` is
  not exported, and :func:`mjcf_warnings` says so). **Friction coefficient = mu_static**:
  MuJoCo has one friction coefficient (no separate kinetic one). ``mu_static = 0`` gives a
  frictionless contact (``condim = 1``);
  ``mu_static = inf`` (rolling enforced, a rack) is exported as a frictionless contact plus a
  joint equality ``ID:x = R * ID:phi``. Like every MuJoCo constraint it is soft; its
  ``solref`` time constant is set to twice the time step (the stiffest MuJoCo recommends),
  because the default 0.02 s lets the contact point drift by millimetres under spring forces.
  (Friction does not need this: MuJoCo's friction constraints act on the slip *velocity*.)
* **Sliders** (frictionless point masses) have only the slide joint ``ID:x`` at their height;
  they cannot lift off (neither can they in rollspring) and have no contact at all.
* **Springs.** Each spring is a spatial tendon between two sites (``stiffness = k``,
  ``springlength = L0``, ``damping = c``, the same law ``T = k (l - L0) + c dl/dt``). An end on
  a body is a body-fixed site named ``SPRING@BODY`` (``SPRING`` as in
  :attr:`~rollspring.physics.SystemArrays.spring_names`); an anchor is a world site named by
  the anchor's id.
* **Constant forces** (``[[forces]]``) are exported faithfully as ``general`` actuators with a
  site transmission: the point of application is a body-fixed site, the reference site
  ``world:frame`` is fixed and world-aligned, so the gear ``(fx, 0, fy, 0, 0, 0)`` is the force
  in world axes; the force does not depend on ``ctrl`` (``gain = 0``, affine ``bias = 1``).
* **Gravity** ``(0, 0, -g)``; **time step** 1e-4 s unless given; integrator ``RK4``. Contact
  parameters keep MuJoCo's defaults.

What cannot be exported (and why)
---------------------------------
* Exact rolling: MuJoCo contact is soft (a body sinks slightly into its track, and the
  friction constraint allows a small creep), so the periods and friction forces agree only
  approximately; see the tunable settings in the file's comments (``solref``, ``solimp``,
  ``cone="elliptic"``, ``impratio``, ``noslip_iterations``).
* ``mu_kinetic`` when it differs from ``mu_static`` (one coefficient in MuJoCo), and the
  re-sticking rule of docs/physics.md section 9: MuJoCo's friction cone decides slip by itself.
  Such cases are listed by :func:`mjcf_warnings`.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from importlib import metadata
from typing import Any

from rollspring.errors import ExportError
from rollspring.model import Body, System, as_system
from rollspring.outputs.atomic import atomic_write_text, writable_file
from rollspring.physics import system_arrays

__all__ = [
    "DEFAULT_TIMESTEP",
    "MAX_TRACKS",
    "ExportError",
    "body_joint_names",
    "export_mjcf",
    "mjcf_warnings",
    "spring_site_name",
    "system_to_mjcf",
    "track_heights",
    "write_mjcf",
]

#: Default MuJoCo time step (s): small against every period of the presets and the contact
#: time constant (MuJoCo's default ``solref`` time constant is 0.02 s).
DEFAULT_TIMESTEP = 1e-4

#: Distinct track heights that fit in MuJoCo's ``contype``/``conaffinity`` bit masks.
MAX_TRACKS = 31

#: Name of the fixed, world-aligned site that constant forces are expressed in.
WORLD_FRAME_SITE = "world:frame"

_TUNING_NOTE = (
    "Contact keeps MuJoCo's defaults. Settings to tune for closer agreement with exact "
    'rolling: <option cone="elliptic" impratio="10" noslip_iterations="5"/> (less '
    "tangential creep), and geom solref (contact stiffness/damping time constant, default "
    '0.02 1) and solimp (impedance), e.g. solref="0.002 1" with a smaller timestep.'
)


def body_joint_names(body: Body) -> tuple[str, ...]:
    """Names of a body's MuJoCo joints in qpos order: ``(ID:x, ID:z, ID:phi)`` for a rolling
    body, ``(ID:x,)`` for a slider (ids never contain ``:``, so names cannot clash)."""
    if not body.rolls:
        return (f"{body.id}:x",)
    return (f"{body.id}:x", f"{body.id}:z", f"{body.id}:phi")


def spring_site_name(spring_name: str, body_id: str) -> str:
    """Name of the site where a spring (named as in ``SystemArrays.spring_names``) is attached
    to a body. A spring's two ends are on different bodies, so the name is unique."""
    return f"{spring_name}@{body_id}"


def track_heights(system: System) -> list[float]:
    """Distinct track heights (m) of the rolling bodies, ascending. Track ``k`` gets the
    contact bit ``1 << k``."""
    return sorted({b.track_height for b in system.bodies if b.rolls})


def mjcf_warnings(system: System) -> list[str]:
    """One line per property of ``system`` that the MJCF model does not reproduce exactly
    (beyond soft contact itself, which affects every model)."""
    warnings = []
    for b in system.bodies:
        if not b.rolls:
            continue
        if math.isinf(b.mu_static):
            warnings.append(
                f"body '{b.id}': mu_static = inf (rolling enforced) is exported as a soft joint "
                f"equality {b.id}:x = R {b.id}:phi on a frictionless contact"
            )
        elif b.mu_kinetic_value != b.mu_static:
            warnings.append(
                f"body '{b.id}': MuJoCo has one friction coefficient; mu_static = "
                f"{b.mu_static:g} is used, mu_kinetic = {b.mu_kinetic_value:g} is not exported"
            )
        if b.rolling_resistance > 0:
            warnings.append(
                f"body '{b.id}': rolling_resistance = {b.rolling_resistance:g} is not exported "
                "(the contacts have condim = 3: sliding friction only)"
            )
    return warnings


def system_to_mjcf(
    system: System | dict[str, Any] | str | os.PathLike[str], *, timestep: float | None = None
) -> str:
    """The MJCF XML text of ``system`` (a pure function; see the module docstring for the
    mapping). ``timestep`` (s) defaults to :data:`DEFAULT_TIMESTEP`.

    Raises :class:`ExportError` for a non-positive or non-finite ``timestep`` or more than
    :data:`MAX_TRACKS` distinct track heights. ``system`` may also be its JSON form, a file path
    or a preset name (:func:`rollspring.model.as_system`).
    """
    system = as_system(system)
    step = DEFAULT_TIMESTEP if timestep is None else timestep
    if not (isinstance(step, int | float) and math.isfinite(step) and step > 0):
        raise ExportError(f"timestep: must be a positive number of seconds, not {step!r}")
    heights = track_heights(system)
    if len(heights) > MAX_TRACKS:
        raise ExportError(
            f"{len(heights)} distinct track heights; MJCF contact bits allow at most {MAX_TRACKS}"
        )
    arrays = system_arrays(system)
    bit_of_height = {h: 1 << k for k, h in enumerate(heights)}

    root = ET.Element("mujoco", model=_xml_safe(system.name) or "rollspring system")
    root.append(ET.Comment(_comment(_header(system))))
    ET.SubElement(root, "compiler", angle="radian")
    root.append(ET.Comment(_comment(_TUNING_NOTE)))
    ET.SubElement(
        root,
        "option",
        timestep=_num(step),
        integrator="RK4",
        gravity=_vec(0.0, 0.0, -arrays.gravity),
    )
    world = ET.SubElement(root, "worldbody")
    _add_view(world, system)
    for k, h in enumerate(heights):
        world.append(
            ET.Comment(
                _comment(
                    f"track {k}: floor at height {_num(h)} m, contact bit "
                    f"{1 << k}; friction comes from the bodies"
                )
            )
        )
        ET.SubElement(
            world,
            "geom",
            name=f"track:{k}",
            type="plane",
            pos=_vec(0.0, 0.0, h),
            size="0 0 1",
            contype=str(1 << k),
            conaffinity="0",
            rgba="0.8 0.8 0.8 1",
        )
    for anchor in system.anchors:
        ET.SubElement(
            world,
            "site",
            name=anchor.id,
            pos=_vec(anchor.x, 0.0, anchor.y),
            size="0.01",
            rgba="0.2 0.2 0.2 1",
        )
    if system.forces:
        ET.SubElement(
            world, "site", name=WORLD_FRAME_SITE, pos="0 0 0", size="0.001", rgba="0 0 0 0"
        )

    for i, body in enumerate(system.bodies):
        element = ET.SubElement(
            world,
            "body",
            name=body.id,
            pos=_vec(arrays.x0[i], 0.0, arrays.track[i] + arrays.radius[i]),
        )
        _add_joints_and_geom(element, body, bit_of_height)
        for s, name in enumerate(arrays.spring_names):
            for j in range(2):
                if arrays.end_body[s, j] == i:
                    r, alpha = arrays.end_r[s, j], arrays.end_alpha[s, j]
                    ET.SubElement(
                        element,
                        "site",
                        name=spring_site_name(name, body.id),
                        pos=_body_offset(r, alpha),
                        size="0.005",
                    )
        for f in range(len(system.forces)):
            if arrays.force_body[f] == i:
                ET.SubElement(
                    element,
                    "site",
                    name=f"{body.id}:force{f}",
                    pos=_body_offset(arrays.force_r[f], arrays.force_alpha[f]),
                    size="0.005",
                    rgba="1 0 0 1",
                )

    equalities = [b for b in system.bodies if b.rolls and math.isinf(b.mu_static)]
    if equalities:
        equality = ET.SubElement(root, "equality")
        equality.append(
            ET.Comment(
                _comment(
                    "mu_static = inf: rolling enforced by x = R phi; "
                    "solref time constant = 2 timesteps "
                    "(MuJoCo's default 0.02 s would let x - R phi drift by millimetres)"
                )
            )
        )
        for b in equalities:
            x_joint, _, phi_joint = body_joint_names(b)
            ET.SubElement(
                equality,
                "joint",
                name=f"{b.id}:rolling",
                joint1=x_joint,
                joint2=phi_joint,
                polycoef=f"0 {_num(b.radius)} 0 0 0",
                solref=f"{_num(2.0 * step)} 1",
            )

    if system.springs:
        tendon = ET.SubElement(root, "tendon")
        for s, (spring, name) in enumerate(zip(system.springs, arrays.spring_names, strict=True)):
            spatial = ET.SubElement(
                tendon,
                "spatial",
                name=name,
                stiffness=_num(arrays.stiffness[s]),
                springlength=_num(arrays.rest_length[s]),
                damping=_num(arrays.damping[s]),
                width="0.003",
            )
            for j, end in enumerate(spring.ends):
                site = end if arrays.end_body[s, j] < 0 else spring_site_name(name, end)
                ET.SubElement(spatial, "site", site=site)

    if system.forces:
        actuator = ET.SubElement(root, "actuator")
        actuator.append(
            ET.Comment(
                _comment(
                    "constant forces: gear = (fx, 0, fy) N in the world frame (refsite), "
                    "applied at a body-fixed site; "
                    "force = gain*ctrl + bias = 0*ctrl + 1, independent of ctrl"
                )
            )
        )
        for f, force in enumerate(system.forces):
            fx, fy = arrays.force[f]
            ET.SubElement(
                actuator,
                "general",
                name=f"{force.body}:force{f}",
                site=f"{force.body}:force{f}",
                refsite=WORLD_FRAME_SITE,
                gear=_vec(fx, 0.0, fy, 0.0, 0.0, 0.0),
                gainprm="0",
                biastype="affine",
                biasprm="1 0 0",
            )

    keyframe = ET.SubElement(root, "keyframe")
    keyframe.append(
        ET.Comment(
            _comment(
                "qpos = 0 is the initial placement; velocities roll without slipping (omega = v/R)"
            )
        )
    )
    qvel: list[float] = []
    for i, body in enumerate(system.bodies):
        v = float(arrays.v0[i])
        qvel.extend((v, 0.0, v / body.radius) if body.rolls else (v,))
    ET.SubElement(
        keyframe, "key", name="initial", qpos=_vec(*([0.0] * len(qvel))), qvel=_vec(*qvel)
    )

    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def write_mjcf(
    system: System | dict[str, Any] | str | os.PathLike[str],
    path: str | os.PathLike[str],
    *,
    timestep: float | None = None,
) -> None:
    """Write :func:`system_to_mjcf` to ``path`` atomically (the previous file or the complete
    new one, never a partial file)."""
    export_mjcf(system, path, timestep=timestep)


def export_mjcf(
    system: System | dict[str, Any] | str | os.PathLike[str],
    path: str | os.PathLike[str] | None = None,
    *,
    timestep: float | None = None,
) -> str:
    """The system as a MuJoCo model (MJCF; module docstring), written atomically to ``path``
    when one is given (``rollspring export SYSTEM --format mjcf -o PATH``). A ``path`` that
    cannot be written (a directory, a device, a FIFO, a socket, a missing or read-only folder)
    is a one-line :class:`~rollspring.errors.OutputError`, raised before any work.

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    path
        Where to write the model (None: only return it).
    timestep
        MuJoCo's time step (s; None: :data:`DEFAULT_TIMESTEP`).

    Returns
    -------
    str
        The MJCF document.
    """
    target = None if path is None else writable_file(path, "path")
    text = system_to_mjcf(system, timestep=timestep)
    if target is not None:
        atomic_write_text(target, text)
    return text


def _add_joints_and_geom(element: ET.Element, body: Body, bit_of_height: dict[float, int]) -> None:
    """Joints, inertial and geom of one body (in the body frame, centre at the origin)."""
    names = body_joint_names(body)
    if not body.rolls:
        element.append(ET.Comment(_comment("slider: slides along x without friction, no contact")))
        ET.SubElement(element, "joint", name=names[0], type="slide", axis="1 0 0")
        moment = 0.4 * body.mass * body.radius**2  # no rotation: any positive value
        ET.SubElement(
            element,
            "inertial",
            pos="0 0 0",
            mass=_num(body.mass),
            diaginertia=_vec(moment, moment, moment),
        )
        ET.SubElement(
            element,
            "geom",
            name=body.id,
            type="sphere",
            size=_num(body.radius),
            contype="0",
            conaffinity="0",
            rgba="0.3 0.5 0.8 1",
        )
        return
    element.append(
        ET.Comment(
            _comment(
                f"{body.shape}: I = {_num(body.gamma)} m R^2 about y; hinge angle = our phi "
                "(clockwise positive as seen from -y)"
            )
        )
    )
    ET.SubElement(element, "joint", name=names[0], type="slide", axis="1 0 0")
    ET.SubElement(element, "joint", name=names[1], type="slide", axis="0 0 1")
    ET.SubElement(element, "joint", name=names[2], type="hinge", axis="0 1 0")
    moment = body.central_inertia
    ET.SubElement(
        element,
        "inertial",
        pos="0 0 0",
        mass=_num(body.mass),
        diaginertia=_vec(moment, moment, moment),
    )
    if body.shape in ("sphere", "shell"):
        geom = {"name": body.id, "type": "sphere", "size": _num(body.radius)}
    else:  # a cylinder lying along y; its half-width (R/4) does not enter the dynamics
        geom = {
            "name": body.id,
            "type": "cylinder",
            "size": _vec(body.radius, 0.25 * body.radius),
            "zaxis": "0 1 0",
        }
    frictionless = math.isinf(body.mu_static) or body.mu_static == 0.0
    geom |= {
        "contype": "0",
        "conaffinity": str(bit_of_height[body.track_height]),
        "priority": "1",
        "condim": "1" if frictionless else "3",
    }
    if not frictionless:  # sliding, torsional, rolling; the last two act only for condim 4, 6
        geom["friction"] = f"{_num(body.mu_static)} 0.005 0.0001"
    geom["rgba"] = "0.8 0.5 0.2 1"
    ET.SubElement(element, "geom", geom)


def _add_view(world: ET.Element, system: System) -> None:
    """A light and a fixed ``side`` camera looking along +y (x right, z up, as our drawings)."""
    xs = [b.x for b in system.bodies] + [a.x for a in system.anchors]
    zs = (
        [b.track_height + 2 * b.radius for b in system.bodies]
        + [b.track_height for b in system.bodies]
        + [a.y for a in system.anchors]
    )
    centre_x, centre_z = (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2
    extent = max(max(xs) - min(xs), max(zs) - min(zs), 0.1)
    ET.SubElement(
        world,
        "light",
        pos=_vec(centre_x, -2.0 * extent, centre_z + 2.0 * extent),
        dir="0 1 -1",
        directional="true",
    )
    ET.SubElement(
        world,
        "camera",
        name="side",
        pos=_vec(centre_x, -1.5 * extent, centre_z),
        xyaxes="1 0 0 0 0 1",
    )


def _body_offset(r: float, alpha: float) -> str:
    """Body-frame position of a point at distance ``r``, angle ``alpha`` clockwise from up."""
    return _vec(r * math.sin(alpha), 0.0, r * math.cos(alpha))


def _header(system: System) -> str:
    try:
        version = metadata.version("rollspring")
    except metadata.PackageNotFoundError:  # running from a source tree without installing
        version = "(unknown version)"
    title = system.name or "(unnamed system)"
    return (
        f"{title} - generated by rollspring {version}. Planar model: our (x, y) is MuJoCo "
        "(x, z); rotations about +y, clockwise positive seen from -y (our phi); qpos = 0 is "
        "the initial placement; keyframe 'initial' holds the initial velocities. "
        "Friction = mu_static (MuJoCo has one coefficient). Contact is soft, rolling only "
        "approximately exact."
    )


def _num(value: float) -> str:
    """Shortest text that reads back as the same float."""
    value = float(value)
    return "0" if value == 0.0 else repr(value)


def _vec(*values: float) -> str:
    return " ".join(_num(v) for v in values)


def _xml_safe(text: str) -> str:
    """``text`` without the characters XML 1.0 cannot hold (control characters, surrogates)."""
    return "".join(
        c
        for c in text
        if c in "\t\n\r"
        or 0x20 <= ord(c) <= 0xD7FF
        or 0xE000 <= ord(c) <= 0xFFFD
        or 0x10000 <= ord(c) <= 0x10FFFF
    )


def _comment(text: str) -> str:
    """Text that is valid inside ``<!-- -->`` (no ``--``, not ending in ``-``), padded."""
    text = " ".join(_xml_safe(text).split())
    while "--" in text:
        text = text.replace("--", "- -")
    return f" {text} "
