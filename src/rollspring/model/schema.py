"""What a system is: bodies, anchors, springs and external forces (validated with pydantic).

Conventions (SI units everywhere): ``x`` to the right, ``y`` up, gravity downward. A body's
initial placement is its *reference configuration*: rotation angles are measured from it,
clockwise positive (a body rolling to the right has ``phi > 0``). Attachment points are fixed in
the body; they are given in the initial placement.
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any, Literal

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    SerializerFunctionWrapHandler,
    WithJsonSchema,
    field_validator,
    model_serializer,
    model_validator,
)

__all__ = [
    "INERTIA_FACTORS",
    "LIMITS",
    "RANGES",
    "Anchor",
    "Attachment",
    "Body",
    "ExternalForce",
    "Shape",
    "Spring",
    "System",
]

#: Central moment of inertia I = gamma m R^2 for each built-in shape (docs/physics.md section 1).
INERTIA_FACTORS: dict[str, float] = {
    "hoop": 1.0,
    "cylinder": 0.5,
    "sphere": 0.4,
    "shell": 2.0 / 3.0,
}

Shape = Literal["hoop", "cylinder", "sphere", "shell", "custom", "slider"]

Identifier = Annotated[
    str,
    Field(
        min_length=1,
        max_length=64,
        pattern=r"^[A-Za-z_][A-Za-z0-9_\-]*$",
        description="A name: a letter or '_' first, then letters, digits, '_' or '-'.",
    ),
]

#: The range of every quantity, ``name -> (low, high, unit)``, both ends included: the values
#: the engine is verified over (docs/system-files.md says how they were chosen). A value outside
#: is refused with a message naming the field and this range: beyond them the equilibrium
#: search, the eigensolvers or double precision itself stop giving right answers (a mass of
#: 1e-308 overflows 1/m, a position of 1e300 loses the bodies' size, an angle of 1e308 its
#: degrees), so a number outside is far more likely a typo than a system.
RANGES: dict[str, tuple[float, float, str]] = {
    "mass": (1e-6, 1e6, "kg"),
    "radius": (1e-3, 1e3, "m"),
    "position": (-1e4, 1e4, "m"),  # x, track_height, anchors' x and y
    "velocity": (-1e4, 1e4, "m/s"),
    "stiffness": (1e-6, 1e9, "N/m"),
    "rest_length": (0.0, 1e4, "m"),
    "damping": (0.0, 1e6, "N s/m"),
    "gravity": (0.0, 1e3, "m/s²"),
    "force": (-1e9, 1e9, "N"),
    "attachment": (0.0, 1e4, "m"),  # an attachment's height or radius (2 R and more)
    "angle": (-360.0, 360.0, "degrees"),
    "friction": (0.0, 1e6, ""),  # mu_static (which may also be inf) and mu_kinetic
    # C_rr: the normal force acts C_rr R ahead of the contact point (docs/physics.md section 5);
    # real wheels have 1e-4 (steel on steel) to 0.05 (a soft tyre), half a radius is no contact
    "rolling_resistance": (0.0, 0.5, ""),
}

#: How many of each a system may hold, and how long its texts may be (characters): a system file
#: is read whole and every command's cost grows with the number of bodies (the analysis' as n³).
LIMITS: dict[str, int] = {
    "bodies": 20000,
    "anchors": 20000,
    "springs": 60000,
    "forces": 20000,
    "name": 200,
    "description": 5000,
}


def _range_message(quantity: str) -> str:
    low, high, unit = RANGES[quantity]
    return f"must be between {low:g} and {high:g}{' ' + unit if unit else ''}, the verified range"


def _bounds(quantity: str) -> Any:
    """The finite-number check and the range in the JSON Schema."""
    low, high, _unit = RANGES[quantity]
    return Field(allow_inf_nan=False, json_schema_extra={"minimum": low, "maximum": high})


def _within(quantity: str) -> AfterValidator:
    """The range check, with a message naming the range."""
    low, high, _unit = RANGES[quantity]

    def check(value: float) -> float:
        if not low <= value <= high:
            raise ValueError(_range_message(quantity))
        return value

    return AfterValidator(check)


Finite = Annotated[float, Field(allow_inf_nan=False)]
Mass = Annotated[float, _bounds("mass"), _within("mass")]
Radius = Annotated[float, _bounds("radius"), _within("radius")]
Position = Annotated[float, _bounds("position"), _within("position")]
Velocity = Annotated[float, _bounds("velocity"), _within("velocity")]
Stiffness = Annotated[float, _bounds("stiffness"), _within("stiffness")]
RestLength = Annotated[float, _bounds("rest_length"), _within("rest_length")]
Damping = Annotated[float, _bounds("damping"), _within("damping")]
Gravity = Annotated[float, _bounds("gravity"), _within("gravity")]
ForceComponent = Annotated[float, _bounds("force"), _within("force")]
Distance = Annotated[float, _bounds("attachment"), _within("attachment")]
Angle = Annotated[float, _bounds("angle"), _within("angle")]
Friction = Annotated[float, _bounds("friction"), _within("friction")]
RollingResistance = Annotated[float, _bounds("rolling_resistance"), _within("rolling_resistance")]

#: Control characters (a terminal obeys them: ESC starts its escape sequences) and the
#: bidirectional overrides that reorder what is shown; a description may hold line breaks and
#: tabs, a name not even those.
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")
_CONTROL_OR_BREAK = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def _plain_text(pattern: re.Pattern[str]) -> AfterValidator:
    def check(value: str) -> str:
        found = pattern.search(value)
        if found is not None:
            raise ValueError(
                f"must not hold control characters (found {found.group()!r} at "
                f"character {found.start()})"
            )
        return value

    return AfterValidator(check)


Name = Annotated[str, Field(max_length=LIMITS["name"]), _plain_text(_CONTROL_OR_BREAK)]
Description = Annotated[str, Field(max_length=LIMITS["description"]), _plain_text(_CONTROL)]


class _Strict(BaseModel):
    """Base of every file section: unknown keys are errors, numbers must be numbers."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)


class Attachment(_Strict):
    """A point fixed in a body, given in the initial placement.

    Either ``{}`` (the centre), ``{height = h}`` (on the vertical through the centre, ``h``
    above the body's track) or ``{radius = r, angle = deg}`` (distance ``r`` from the centre,
    ``angle`` degrees clockwise from straight up: 0 top, 90 front/right, 180 bottom).
    """

    height: Distance | None = Field(
        default=None, description="Height above the body's track (m), on the centre vertical."
    )
    radius: Distance | None = Field(default=None, description="Distance from the centre (m).")
    angle: Angle | None = Field(
        default=None, description="Degrees clockwise from straight up (needs `radius`)."
    )

    @model_validator(mode="after")
    def _one_form(self) -> Attachment:
        if self.height is not None and (self.radius is not None or self.angle is not None):
            raise ValueError("give either `height` or `radius` and `angle`, not both")
        if self.angle is not None and self.radius is None:
            raise ValueError("`angle` needs `radius`")
        return self

    @property
    def is_centre_form(self) -> bool:
        """True for ``{}``."""
        return self.height is None and self.radius is None

    def polar(self, body: Body) -> tuple[float, float]:
        """Distance ``r`` (m) from the centre and angle ``alpha`` (rad, clockwise from up)."""
        if self.height is not None:
            dy = self.height - body.radius
            return abs(dy), (0.0 if dy >= 0 else math.pi)
        if self.radius is not None:
            return self.radius, math.radians(self.angle or 0.0)
        return 0.0, 0.0


CENTRE = Attachment()


class Body(_Strict):
    """A round body rolling without slipping on a horizontal track, or a frictionless slider."""

    id: Identifier
    shape: Shape = Field(
        description="hoop (I = mR^2), cylinder (mR^2/2), sphere (2mR^2/5), shell (2mR^2/3), "
        "custom (inertia_factor mR^2) or slider (a point mass sliding without friction)."
    )
    mass: Mass = Field(description="kg")
    radius: Radius = Field(
        description="m; for a slider, the height of its centre above the track (drawing size)."
    )
    inertia_factor: Annotated[float, Field(gt=0, le=1, allow_inf_nan=False)] | None = Field(
        default=None, description="gamma in I = gamma m R^2; only for shape = 'custom', in (0, 1]."
    )
    track_height: Position = Field(
        default=0.0, description="Height of the floor under the body (m)."
    )
    x: Position = Field(description="Initial horizontal position of the centre (m).")
    v: Velocity = Field(default=0.0, description="Initial velocity of the centre (m/s).")
    mu_static: Annotated[
        float,
        Field(ge=0, allow_inf_nan=True),
        WithJsonSchema(
            {
                "anyOf": [
                    {"type": "number", "minimum": 0, "maximum": RANGES["friction"][1]},
                    {"const": "inf"},
                ]
            }
        ),
    ] = Field(
        default=1.0,
        description="Static friction coefficient; inf enforces rolling (rack and pinion), "
        'written "inf" in JSON. Ignored for sliders.',
    )
    mu_kinetic: Friction | None = Field(
        default=None,
        description="Kinetic friction coefficient, at most mu_static; default mu_static "
        "(0 when mu_static is inf).",
    )
    rolling_resistance: RollingResistance = Field(
        default=0.0,
        description="Rolling resistance coefficient C_rr (a length ratio): the floor's normal "
        "force acts C_rr R ahead of the contact point, a torque C_rr N R opposing the rolling. "
        "Not for sliders.",
    )

    @field_validator("mu_static", mode="before")
    @classmethod
    def _not_nan(cls, value: object) -> object:
        if isinstance(value, float) and math.isnan(value):
            raise ValueError("must be a finite number or inf, not NaN")
        if value == "inf":  # JSON has no infinity: the JSON form writes it as "inf"
            return math.inf
        return value

    @field_validator("mu_static", mode="after")
    @classmethod
    def _in_range(cls, value: float) -> float:
        if math.isfinite(value) and value > RANGES["friction"][1]:
            raise ValueError(_range_message("friction") + ", or inf")
        return value

    @model_validator(mode="after")
    def _consistent(self) -> Body:
        if self.shape == "custom" and self.inertia_factor is None:
            raise ValueError("shape 'custom' needs `inertia_factor` in (0, 1]")
        if self.shape != "custom" and self.inertia_factor is not None:
            raise ValueError(
                f"`inertia_factor` is only for shape 'custom' (a {self.shape} has its own)"
            )
        if self.shape == "slider" and self.rolling_resistance > 0.0:
            raise ValueError(
                "`rolling_resistance` is for rolling bodies; a slider slides without friction"
            )
        if self.mu_kinetic is not None and self.mu_kinetic > self.mu_static:
            raise ValueError(
                f"mu_kinetic ({self.mu_kinetic:g}) must not exceed mu_static ({self.mu_static:g})"
            )
        return self

    @property
    def rolls(self) -> bool:
        """False for a slider (no rotation), True for every round body."""
        return self.shape != "slider"

    @property
    def gamma(self) -> float:
        """Inertia factor: I = gamma m R^2 (0 for a slider, which does not rotate)."""
        if self.shape == "slider":
            return 0.0
        if self.shape == "custom":
            assert self.inertia_factor is not None
            return self.inertia_factor
        return INERTIA_FACTORS[self.shape]

    @property
    def central_inertia(self) -> float:
        r"""Moment of inertia about the centre, :math:`I = \gamma m R^2` (kg m^2)."""
        return self.gamma * self.mass * self.radius**2

    @property
    def contact_inertia(self) -> float:
        r"""Inertia of the coordinate: :math:`J = I + m R^2` about the contact line (docs/physics.md
        (M4), the paper's :math:`I'` by Steiner's theorem); a slider's coordinate is x, J = m."""
        if not self.rolls:
            return self.mass
        return (1.0 + self.gamma) * self.mass * self.radius**2

    @property
    def percussion_height(self) -> float:
        """Height above the track where a force needs no friction: (1 + gamma) R (M10)."""
        return (1.0 + self.gamma) * self.radius

    @property
    def mu_kinetic_value(self) -> float:
        """The kinetic friction coefficient in force (default: mu_static, 0 if that is inf)."""
        if self.mu_kinetic is not None:
            return self.mu_kinetic
        return self.mu_static if math.isfinite(self.mu_static) else 0.0

    @model_serializer(mode="wrap")
    def _without_default_resistance(self, handler: SerializerFunctionWrapHandler) -> Any:
        """The written form leaves out a rolling resistance of 0 (the default): the files and
        JSON forms of systems without it stay as they were."""
        data = handler(self)
        if isinstance(data, dict) and data.get("rolling_resistance") == 0.0:
            del data["rolling_resistance"]
        return data

    def point_at_rest(self, at: Attachment) -> tuple[float, float]:
        """Position (x, y) of an attachment point in the initial placement, (M1) at phi = 0."""
        r, alpha = at.polar(self)
        return (
            self.x + r * math.sin(alpha),
            self.track_height + self.radius + r * math.cos(alpha),
        )


class Anchor(_Strict):
    """A fixed point (a wall hook)."""

    id: Identifier
    x: Position = Field(description="m")
    y: Position = Field(description="m")


class Spring(_Strict):
    """An ideal massless spring between two ends, each a body (at an attachment) or an anchor."""

    ends: list[Identifier] = Field(min_length=2, max_length=2, description="Ids of the two ends.")
    stiffness: Stiffness = Field(description="N/m")
    rest_length: RestLength | None = Field(
        default=None, description="m; default: the length in the initial placement."
    )
    damping: Damping = Field(default=0.0, description="N s/m, along the spring.")
    at: list[Attachment] | None = Field(
        default=None,
        min_length=2,
        max_length=2,
        description="Attachment per end ({} = a body's centre; an anchor end takes {}).",
    )

    @property
    def attachments(self) -> tuple[Attachment, Attachment]:
        """The two attachments, centres where none is given."""
        return (self.at[0], self.at[1]) if self.at is not None else (CENTRE, CENTRE)


class ExternalForce(_Strict):
    """A constant force applied at a point fixed in a body (the paper's Appendix A pull)."""

    body: Identifier
    at: Attachment = Field(default=CENTRE, description="Point of application.")
    fx: ForceComponent = Field(default=0.0, description="N")
    fy: ForceComponent = Field(default=0.0, description="N")


class System(_Strict):
    """A complete system: bodies on tracks, fixed anchors, springs, constant forces, gravity."""

    name: Name = ""
    description: Description = ""
    gravity: Gravity = Field(default=9.81, description="m/s^2, downward.")
    bodies: list[Body] = Field(min_length=1, max_length=LIMITS["bodies"])
    anchors: list[Anchor] = Field(default_factory=list, max_length=LIMITS["anchors"])
    springs: list[Spring] = Field(default_factory=list, max_length=LIMITS["springs"])
    forces: list[ExternalForce] = Field(default_factory=list, max_length=LIMITS["forces"])

    @model_validator(mode="before")
    @classmethod
    def _not_too_many(cls, data: Any) -> Any:
        """Counts first: 10 000 bodies are refused before any is validated."""
        if isinstance(data, dict):
            for key in ("bodies", "anchors", "springs", "forces"):
                items = data.get(key)
                if isinstance(items, list | tuple) and len(items) > LIMITS[key]:
                    raise ValueError(
                        f"{key}: at most {LIMITS[key]} {key} (got {len(items)}): rollspring's "
                        "cost grows with their number"
                    )
        return data

    @model_validator(mode="after")
    def _references(self) -> System:
        seen: dict[str, str] = {}
        ids = (("bodies", [b.id for b in self.bodies]), ("anchors", [a.id for a in self.anchors]))
        for kind, item_ids in ids:
            for i, item_id in enumerate(item_ids):
                if item_id in seen:
                    raise ValueError(
                        f"{kind}[{i}].id: duplicate id '{item_id}' "
                        f"(already used in {seen[item_id]})"
                    )
                seen[item_id] = f"{kind}[{i}]"
        bodies = self.body_map
        anchors = self.anchor_map
        for s, spring in enumerate(self.springs):
            where = f"springs[{s}]"
            a, b = spring.ends
            for end in (a, b):
                if end not in bodies and end not in anchors:
                    raise ValueError(f"{where}.ends: unknown id '{end}'")
            if a == b:
                raise ValueError(f"{where}.ends: a spring cannot join '{a}' to itself")
            if a in anchors and b in anchors:
                raise ValueError(f"{where}.ends: both ends are anchors ('{a}', '{b}')")
            for j, (end, at) in enumerate(zip(spring.ends, spring.attachments, strict=True)):
                if end in anchors and not at.is_centre_form:
                    raise ValueError(
                        f"{where}.at[{j}]: '{end}' is an anchor; its entry must be {{}}"
                    )
                if end in bodies:
                    _check_attachment(bodies[end], at, f"{where}.at[{j}]")
            length = _initial_length(spring, bodies, anchors)
            if not math.isfinite(length):
                raise ValueError(
                    f"{where}: its initial length is not finite (coordinates too large)"
                )
            if length == 0.0:
                raise ValueError(
                    f"{where}: its two ends coincide in the initial placement (length 0)"
                )
        for f, force in enumerate(self.forces):
            if force.body not in bodies:
                raise ValueError(f"forces[{f}].body: unknown body '{force.body}'")
            _check_attachment(bodies[force.body], force.at, f"forces[{f}].at")
        return self

    @property
    def body_map(self) -> dict[str, Body]:
        """Bodies by id."""
        return {b.id: b for b in self.bodies}

    @property
    def anchor_map(self) -> dict[str, Anchor]:
        """Anchors by id."""
        return {a.id: a for a in self.anchors}

    def end_point_at_rest(self, end: str, at: Attachment) -> tuple[float, float]:
        """Position of a spring end (body attachment or anchor) in the initial placement."""
        return _end_point(end, at, self.body_map, self.anchor_map)

    def spring_ends_at_rest(self) -> list[tuple[tuple[float, float], tuple[float, float]]]:
        """Both ends' positions of every spring in the initial placement (the bodies and anchors
        looked up once: O(S), where a call of :meth:`end_point_at_rest` per end is O(S n))."""
        bodies, anchors = self.body_map, self.anchor_map
        return [
            (
                _end_point(spring.ends[0], spring.attachments[0], bodies, anchors),
                _end_point(spring.ends[1], spring.attachments[1], bodies, anchors),
            )
            for spring in self.springs
        ]

    def _initial_length(self, spring: Spring) -> float:
        return _initial_length(spring, self.body_map, self.anchor_map)

    @property
    def rest_lengths(self) -> list[float]:
        """Rest length of every spring (m); the initial length where none is given."""
        bodies, anchors = self.body_map, self.anchor_map
        return [
            s.rest_length if s.rest_length is not None else _initial_length(s, bodies, anchors)
            for s in self.springs
        ]

    @property
    def overlaps(self) -> list[str]:
        """Warnings, one per pair of bodies that overlap in the initial placement (their discs
        intersect: bodies never touch each other in the model, they pass through one another,
        so an overlap is most often a wrong ``x`` or ``track_height``); at most
        :data:`MAX_OVERLAP_WARNINGS`, the last one counting the rest."""
        found: list[tuple[Body, Body, float]] = []
        reach = max(b.radius for b in self.bodies)
        ordered = sorted(self.bodies, key=lambda b: b.x)
        for i, first in enumerate(ordered):
            for second in ordered[i + 1 :]:
                if second.x - first.x >= first.radius + reach:
                    break
                apart = math.hypot(
                    second.x - first.x,
                    (second.track_height + second.radius) - (first.track_height + first.radius),
                )
                if apart < first.radius + second.radius:
                    found.append((first, second, apart))
        out = [
            f"bodies '{a.id}' and '{b.id}' overlap in the initial placement (centres "
            f"{apart:.3g} m apart, radii {a.radius:g} m and {b.radius:g} m); they pass "
            "through each other in the model"
            for a, b, apart in found[:MAX_OVERLAP_WARNINGS]
        ]
        if len(found) > MAX_OVERLAP_WARNINGS:
            out.append(f"{len(found) - MAX_OVERLAP_WARNINGS} more pairs of bodies overlap")
        return out


#: At most this many pairs of overlapping bodies are named (:attr:`System.overlaps`).
MAX_OVERLAP_WARNINGS = 3


def _end_point(
    end: str, at: Attachment, bodies: dict[str, Body], anchors: dict[str, Anchor]
) -> tuple[float, float]:
    if end in bodies:
        return bodies[end].point_at_rest(at)
    anchor = anchors[end]
    return anchor.x, anchor.y


def _initial_length(spring: Spring, bodies: dict[str, Body], anchors: dict[str, Anchor]) -> float:
    (xa, ya), (xb, yb) = (
        _end_point(end, at, bodies, anchors)
        for end, at in zip(spring.ends, spring.attachments, strict=True)
    )
    return math.hypot(xb - xa, yb - ya)


def _check_attachment(body: Body, at: Attachment, where: str) -> None:
    r, _ = at.polar(body)
    if not body.rolls and r > 0.0:
        raise ValueError(
            f"{where}: '{body.id}' is a slider (it does not rotate); attach at its centre, {{}}"
        )
