r"""The notation table of a derivation: every symbol its steps display, defined once.

:func:`notation_table` collects the symbols of every displayed equation (the free symbols of
each SymPy object, in their printed form) and gives each one line: what it stands for, with its
unit, and, for a parameter of the system, its value. A name has one meaning throughout a
derivation; the table is keyed by the printed name, so a name the steps used for two things
would show as two entries of one name (the acceptance test of the notation looks for that).

Besides the displayed symbols the table defines the names the words use for the geometry: the
spring's rest length :math:`L` (equal to its length :math:`\ell` at the reference when it is
relaxed there) and the contact line :math:`z'` (the paper's instantaneous axis).

Names follow the paper where it has one: :math:`I'` for the moment of inertia about the contact
line, :math:`\varphi` for the angles, :math:`\Omega` for frequencies, :math:`\hat X` for the
stationary point.
"""

from __future__ import annotations

import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp
from sympy.printing.conventions import split_super_sub

from rollspring.analysis.derivation.steps import Named, Section, latex_of, pretty_name
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = [
    "COMPOSITE",
    "UNDESCRIBED",
    "Entry",
    "displayed_symbols",
    "notation_table",
    "parameter_value",
    "printed",
    "width",
]

#: The meaning of a symbol the table cannot describe (a test makes sure no derivation has one).
UNDESCRIBED = "(not described)"


@dataclass(frozen=True)
class Entry:
    """One line of the notation table: the symbol as plain text (``text``) and LaTeX
    (``latex``), what it stands for (``meaning``, with its unit) and, for a parameter of the
    system, its ``value`` (with its unit; empty otherwise)."""

    text: str
    latex: str
    meaning: str
    value: str = ""


#: Display names that are not symbols but expressions written out (a partial derivative,
#: a determinant, a placeholder): their parts are defined instead.
COMPOSITE = ("dLag/", "det K", "not applicable")


def printed(symbol: sp.Basic) -> str:
    """A symbol's printed (plain-text) name, as the steps show it."""
    if isinstance(symbol, Named):
        return symbol.text
    return pretty_name(str(symbol.name))


def _symbols_of(obj: Any) -> set[sp.Basic]:
    if isinstance(obj, list | tuple):
        out: set[sp.Basic] = set()
        for item in obj:
            out |= _symbols_of(item)
        return out
    if isinstance(obj, sp.Basic | sp.MatrixBase):
        found = set(obj.atoms(sp.Symbol, sp.MatrixSymbol))
        return {s for s in found if not str(s.name).startswith(COMPOSITE)}
    return set()


def displayed_symbols(sections: Iterable[Section]) -> set[sp.Basic]:
    """Every symbol of every displayed equation of ``sections`` (composite display names such
    as :math:`\\partial\\mathcal L/\\partial\\varphi_1` left out: :data:`COMPOSITE`)."""
    out: set[sp.Basic] = set()
    for section in sections:
        for step in section.steps:
            out |= _symbols_of(step.equation)
    return out


# -- meanings ---------------------------------------------------------------------------------

_UNITS = {
    "m": "kg",
    "R": "m",
    "ell": "m",
    "L": "m",
    "y": "m",
    "r": "m",
    "h": "m",
    "k": "N/m",
    "g": "m/s²",
    "F": "N",
    "theta": "rad",
    "beta": "rad",
}


def _body(sym: SymbolicSystem, label: str) -> str:
    """'body 1 (hoop)' for a label naming a body, else 'body <label>'."""
    if label.isdigit() and 1 <= int(label) <= sym.n:
        body = sym.bodies[int(label) - 1]
        return f"body {label} ({body.shape})"
    return f"body {label}"


def _coordinate(sym: SymbolicSystem) -> str:
    return f"measured from the {sym.reference}"


def _meaning(base: str, sub: str, sup: str, sym: SymbolicSystem, *, parameter: bool) -> str | None:
    """What the symbol of name ``base_sub^sup`` stands for (None: unknown); ``parameter``: it
    is one of the system's parameters (a tilt beta, not an energy's coefficient beta)."""
    body = _body(sym, sub) if sub else "the body"
    spring = f"spring {sub}" if sub else "the spring"
    simple = {
        "g": "gravitational acceleration",
        "T": "kinetic energy of the system (J)",
        "V": "potential energy of the springs (and constant forces) (J)",
        "Lag": "Lagrangian, ℒ = T − V (J)",
        "Ham": "Hamiltonian, ℋ = T + V in the canonical coordinates (J)",
        "M": "mass matrix, diagonal with the bodies' I′: T = (1/2) q̇ᵀ M q̇",
        "K": "stiffness matrix, the second derivatives of V at the reference",
        "Xhat": "the stationary point: the weighted mean of the centres that stays at rest (m)",
        "A": "amplitude of the spring's deformation (m)",
        "a": "acceleration of the pulled body's centre (App. A) (m/s²)",
        "f": "static friction on the pulled body (App. A), counted against the pull (N)",
        "I": "moment of inertia about the centre, I = γ m R² (App. A) (kg m²)",
        "y": "height of the pull above the floor (App. A) (m)",
        "Omega": "angular frequency of the oscillation (1/s)",
    }
    if not sub and not sup and base in simple:
        return simple[base]
    if base == "Omega":
        if sup == "2" and not sub:
            return "squared angular frequency of the oscillating mode (1/s²)"
        if sup == "2" and sub.startswith("("):
            return f"squared angular frequency of normal mode {sub.strip('()')} (1/s²)"
        if sup == "2":
            return f"squared natural frequency of subsystem {sub}: {body} alone (1/s²)"
        if sub.startswith("("):
            return f"angular frequency of normal mode {sub.strip('()')} (1/s)"
    table = {
        "phi": f"angle turned by {body}, clockwise, {_coordinate(sym)} (rad)",
        "phidot": f"angular velocity of {body}, the rate of φ (rad/s)",
        "phiddot": f"angular acceleration of {body} (rad/s²)"
        if sub or sym.n == 1
        else "angular acceleration of the pulled body (App. A) (rad/s²)",
        "Phidot": f"largest angular velocity of {body} in the oscillation (rad/s)",
        "x": f"position of the centre of {body}, {_coordinate(sym)} (m)",
        "xdot": f"velocity of the centre of {body} (m/s)",
        "xddot": f"acceleration of the centre of {body} (m/s²)",
        "q": f"canonical coordinate of {body}, q = √(I′/m) φ (Sec. 5.6) (m)",
        "qdot": f"rate of the canonical coordinate of {body} (m/s)",
        "qddot": f"second derivative of the canonical coordinate of {body} (m/s²)",
        "p": f"momentum conjugate to the coordinate of {body} (of φ in Lagrange's method, of q "
        "in Hamilton's)",
        "pdot": f"rate of the momentum of {body}",
        "m": f"mass of {body}" if sub else "mass (of the body; in App. A, of the pulled body)",
        "R": f"radius of {body}"
        if sub
        else "radius (of every rolling body; in App. A, of the pulled body)",
        "gamma": f"inertia factor of {body}, I = γ m R² about the centre"
        if sub
        else "inertia factor, I = γ m R² about the centre",
        "Iprime": (
            f"mass of {body}, a slider: it takes the place of I′ in the equations (kg)"
            if sub.isdigit() and int(sub) <= sym.n and not sym.bodies[int(sub) - 1].rolls
            else f"moment of inertia of {body} about its contact line z′ (the paper's I′) (kg m²)"
        ),
        "k": (
            f"stiffness of {spring}"
            if parameter or not sub
            else f"stiffness of the spring's part between {body} and the stationary point "
            f"(the paper's k{pretty_name('k_' + sub)[1:]}) (N/m)"
        ),
        "ell": f"length of {spring} at the reference",
        "l": f"length of {spring} (it changes with the angles) (m)",
        "L": f"rest length of {spring}",
        "d": f"vector from the first end of {spring} to its second, at the reference (m)",
        "beta": f"tilt of {spring} from the horizontal at the reference",
        "E": f"energy of subsystem {sub}: {body} alone (J)"
        if sub
        else "mechanical energy, E = T + V (J)",
        "A": f"amplitude of the centre of {body} about the stationary point (m)",
        "v": f"largest speed of the centre of {body} (m/s)",
        "F": (
            f"force of spring {sub} (positive when stretched) (N)"
            if sub
            else "force of the spring (positive when stretched; in App. A, its pull) (N)"
        ),
        "f": f"static friction on {body}, along +x (N)",
        "N": f"normal force of the floor on {body} (N)",
        "Q": f"torque of the applied forces on {body} about its contact line (N m)",
        "sigma": f"share of the spring's part between {body} and the stationary point in the "
        "spring's deformation",
        "lambda": f"percussion ratio of {body}, η over the percussion height (1 + γ) R",
        "eta": f"height where the spring's line crosses the centre vertical of {body} (m)",
        "alpha": f"coefficient of the kinetic part of subsystem {sub}'s energy (kg m²)",
        "c": f"coefficient of q{pretty_name('q_' + sub)[1:]} in the Hamiltonian potential "
        "(k/2)(c₁ q₁ + c₂ q₂)²",
        "y": f"height of the attachment on {body} above its floor",
        "r": f"distance of the attachment from the centre of {body}",
        "theta": f"angle of the attachment on {body} at the reference",
        "h": f"height of the floor of {body} above the lowest floor",
    }
    if base == "beta" and sub and not parameter:
        return f"coefficient of the potential part of subsystem {sub}'s energy (N m)"
    if base == "K" and sub:
        return f"entry {sub[0]},{sub[1:]} of the stiffness matrix K" if len(sub) == 2 else None
    if base == "F" and len(sub) >= 2 and sub[-1] in "xy" and sub[:-1].isdigit():
        axis = "horizontal" if sub[-1] == "x" else "vertical"
        return f"{axis} part of the applied force on {_body(sym, sub[:-1])} (N)"
    if base == "F" and sub in ("x", "y"):
        axis = "horizontal" if sub == "x" else "vertical"
        return f"{axis} part of the spring's pull on body 1 (body 2 gets its opposite) (N)"
    if base == "F" and sub.startswith(("x,", "y,")):
        return f"{'horizontal' if sub[0] == 'x' else 'vertical'} part of force {sub[2:]} (N)"
    if base == "y" and sup == "*":
        if not sub:
            return "height of a pull that needs no friction (App. A) (m)"
        if sub.isdigit():
            return f"height where a pull on {body} needs no friction, (1 + γ) R (m)"
        return f"height where a pull on a {sub} needs no friction (m)"
    return table.get(base)


def _split(symbol: sp.Basic) -> tuple[str, str, str]:
    name = str(symbol.name)
    if isinstance(symbol, Named):
        if name.startswith("Iprime"):
            return "Iprime", name.partition("_")[2], ""
        if name.startswith("y^*_"):
            return "y", name[4:], "*"
        if name.startswith("Omega_("):
            return "Omega", name[len("Omega_") : name.index(")") + 1], "2" * name.endswith("^2")
        return name, "", ""
    base, sups, subs = split_super_sub(name)
    return base, "".join(subs), "".join(sups)


def width(text: str) -> int:
    """The columns ``text`` takes in a terminal (combining accents take none)."""
    return sum(1 for c in text if not unicodedata.combining(c))


def parameter_value(symbol: sp.Basic, sym: SymbolicSystem) -> str:
    """A parameter's value with its unit (``100 N/m``); empty for any other symbol."""
    if symbol not in sym.values:
        return ""
    value = sym.values[symbol]
    base = _split(symbol)[0]
    unit = _UNITS.get(base, "")
    number = f"{value:.6g}"
    return f"{number} {unit}".strip()


def notation_table(sections: Sequence[Section], sym: SymbolicSystem) -> list[Entry]:
    """One :class:`Entry` per printed name of the symbols ``sections`` display, in a
    textbook's order (parameters, coordinates and their rates, then the rest by name), and
    the geometry's words: the rest length L (a spring's) and the contact line z'."""
    entries: dict[tuple[str, str], tuple[tuple[int, str], Entry]] = {}
    for symbol in displayed_symbols(sections):
        base, sub, sup = _split(symbol)
        parameter = symbol in sym.values
        meaning = _meaning(base, sub, sup, sym, parameter=parameter) or UNDESCRIBED
        text = printed(symbol)
        entry = Entry(text, latex_of(symbol), meaning, parameter_value(symbol, sym))
        entries.setdefault((text, meaning), (_order(base, sup, text), entry))
    for extra in _word_names(sym):
        base = "L" if extra.text.startswith("L") else "z"
        entries.setdefault((extra.text, extra.meaning), (_order(base, "", extra.text), extra))
    return [entry for _, entry in sorted(entries.values(), key=lambda item: item[0])]


def _word_names(sym: SymbolicSystem) -> list[Entry]:
    """The names the words use that no equation displays: the rest length of each spring (with
    its value where it differs from the length at the reference), the contact line."""
    out = []
    for spring in sym.springs:
        label = "" if len(sym.springs) == 1 else str(spring.index + 1)
        name = "L" + (f"_{label}" if label else "")
        where = f"spring {label}" if label else "the spring"
        if spring.relaxed:
            length = pretty_name("ell" + (f"_{label}" if label else ""))
            meaning = (
                f"rest length of {where}: {where} is relaxed at the reference, so "
                f"{pretty_name(name)} = {length} (m)"
            )
            value = ""
        else:
            meaning = f"rest length of {where} (m)"
            value = parameter_value(spring.L, sym) if isinstance(spring.L, sp.Symbol) else ""
        out.append(Entry(pretty_name(name), latex_of(sp.Symbol(name)), meaning, value))
    if any(b.rolls for b in sym.bodies):
        out.append(
            Entry(
                "z\u2032",
                "z'",
                "contact line of a rolling body with its floor: the paper's instantaneous axis "
                "of rotation, through the body's lowest point",
            )
        )
    return out


#: The order of the table: the parameters, the coordinates and their rates, then the rest.
_ORDER = (
    "m",
    "R",
    "gamma",
    "Iprime",
    "k",
    "ell",
    "L",
    "d",
    "g",
    "phi",
    "phidot",
    "phiddot",
    "x",
    "xdot",
    "xddot",
    "z",
)


def _order(base: str, sup: str, text: str) -> tuple[int, str]:
    rank = _ORDER.index(base) if base in _ORDER and sup != "*" else len(_ORDER)
    return (rank, text)
