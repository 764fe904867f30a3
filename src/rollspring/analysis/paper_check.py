r"""Every quantitative statement of the paper, checked by the derivation engine.

Paper: G. Nyitray, *On the edge of complexity: the simplest not simple coupled mechanical system*
(arXiv 2508.01379). Sections are numbered as the paper prints them (1 Introduction, 2 two point
masses, 3 the hoop and the cylinder, 4 the frictionless system, 5 the methods with 5.1-5.6, 6
teaching, 7 conclusion, appendices A-C); equation labels are the paper's LaTeX labels, and an
unlabelled display is located by the label or sentence next to it. Each :class:`Claim` holds

* ``location``: the sentence or equation where the paper asserts it;
* ``quote``: the paper's own words for it, verbatim from its LaTeX source (``&``, ``\label``,
  ``\\`` and white space aside: :func:`quote_key`), never broader than what the paper says;
* ``latex``: the claim as a formula (transcribed from the paper);
* ``paper``: the same claim as a SymPy expression (or a tuple of them, or a truth value for a
  claim "X differs from Y"): the value the paper gives for one **quantity** (``quantity``,
  LaTeX), in the symbols the derivation engine uses (:math:`m_1, m_2, R, R_1, R_2, k,
  \varphi_i, \dot\varphi_i, \ddot\varphi_i, \dots`);
* ``system``: which system(s) it is checked on (keys of :data:`SYSTEMS`, comma-separated: the
  paper's Fig. 1, 2, 3 systems built as rollspring systems and turned symbolic by
  :func:`rollspring.analysis.derivation.symbolic_system` with ``symbols=True``);
* ``assumptions``: the assumptions the paper itself states that the claim relies on
  (:class:`Assumption`: our words, the paper's words verbatim, where it says them);
* ``derive``: the recipe: computes, from the engine's SymPy objects (M, K, V, the Lagrangian,
  the friction and force expressions, the zero mode, the closed-form frequencies), the same
  quantity in general, under the paper's stated assumptions, and under a condition the paper
  does not state where the claim needs one.

The verdict is computed (:func:`check_claim`): ``simplify(paper - derived) == 0`` gives
``"verified"``; otherwise, if the claim agrees with the value derived under the assumptions the
paper states (released from rest, magnitudes, small angles, the centres level, X-hat as origin),
``"holds-under-stated-assumption"``; otherwise, if the recipe names a condition the paper does
not state (an angle counted the other way, a coordinate measured from its equilibrium, ...) and
the two agree under it, ``"holds-only-if"``; otherwise ``"wrong"``, with the derived expression,
in the paper's own terms (under its stated assumptions), as the correction. Nothing in a verdict
is typed in: the words (``reason``) explain, the engine decides.

Sign conventions (docs/physics.md): :math:`\varphi_i` clockwise positive (rolling to the right), in
one common orientation for all bodies, measured from the equilibrium; friction :math:`f_i` is
the force of the floor on body i, positive along +x.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from sympy.logic.boolalg import BooleanAtom

from rollspring.analysis.derivation import SymbolicSystem, symbolic_system
from rollspring.analysis.derivation.frequencies import normal_frequencies
from rollspring.model import System, system_from_dict

__all__ = [
    "HOLDS_ONLY_IF",
    "HOLDS_STATED",
    "SYSTEMS",
    "VERDICTS",
    "VERIFIED",
    "WRONG",
    "Assumption",
    "Claim",
    "ClaimCheck",
    "Derived",
    "check_claim",
    "check_claims",
    "check_paper",
    "paper_claims",
    "paper_figure",
    "paper_system",
    "quote_key",
]

VERIFIED = "verified"
HOLDS_STATED = "holds-under-stated-assumption"
HOLDS_ONLY_IF = "holds-only-if"
WRONG = "wrong"
#: The four verdicts, in the order they are counted.
VERDICTS = (VERIFIED, HOLDS_STATED, HOLDS_ONLY_IF, WRONG)

# -- the symbols (the same names and assumptions as the derivation engine's) ---------------------
m, m1, m2 = sp.symbols("m m_1 m_2", positive=True)
R, R1, R2 = sp.symbols("R R_1 R_2", positive=True)
k, k1, k2 = sp.symbols("k k_1 k_2", positive=True)
gamma, y = sp.symbols("gamma y", positive=True)
F = sp.Symbol("F", real=True)
phi, phi1, phi2 = sp.symbols("phi phi_1 phi_2", real=True)
phid1, phid2 = sp.symbols("phidot_1 phidot_2", real=True)
phidd, phidd1, phidd2 = sp.symbols("phiddot phiddot_1 phiddot_2", real=True)
x1, x2 = sp.symbols("x_1 x_2", real=True)
xd1, xd2 = sp.symbols("xdot_1 xdot_2", real=True)
# the paper's own symbols (not the engine's)
A = sp.Symbol("A", positive=True)  # amplitude of the spring's deformation (Sec. 5.2)
Omega = sp.Symbol("Omega", positive=True)  # the paper's angular frequency of the mode
Phid1, Phid2 = sp.symbols("Phidot_1 Phidot_2", positive=True)  # maximal angular velocities
q1, q2, q3, q4 = sp.symbols("q_1 q_2 q_3 q_4", real=True)  # canonical coordinates
p1, p2, p3, p4 = sp.symbols("p_1 p_2 p_3 p_4", real=True)  # canonical momenta
pd1 = sp.Symbol("pdot_1", real=True)  # the rate of p_1 (Sec. 5.6)
Fx1, Fx2 = sp.symbols("F_1x F_2x", real=True)  # horizontal spring force on body 1, 2
f1, f2 = sp.symbols("f_1 f_2", real=True)  # the paper's static friction forces (App. A)
fpull = sp.Symbol("f", real=True)  # the friction of the pulled body (App. A), against F
I_ = sp.Symbol("I", positive=True)  # the pulled body's moment of inertia (App. A)
ell_total = sp.Symbol("l", positive=True)  # the spring's length (Sec. 5.3)
# constants of the motion (fixed by the start): the conserved combination and its integral
P0 = sp.Symbol("P_0", real=True)
D0 = sp.Symbol("D_0", real=True)
t = sp.Symbol("t", real=True)
a = sp.Symbol("a", real=True)  # amplitude along a mode shape
# the isotonic oscillator (Sec. 5.2, "unique to harmonic oscillation")
xi, xid, omega0, beta0, energy = sp.symbols("x xdot omega beta E", positive=True)

half = sp.Rational(1, 2)


def quote_key(text: str) -> str:
    r"""The form in which a quote is looked up in the paper's LaTeX source: ``\label{...}``,
    ``\nonumber``, ``&`` and ``\\`` removed, no white space."""
    text = re.sub(r"\\label\{[^}]*\}", "", text)
    text = text.replace("\\nonumber", "").replace("\\\\", " ").replace("&", "")
    return re.sub(r"\s+", "", text)


# -- the systems -------------------------------------------------------------------------------


def _body(
    id_: str, shape: str, mass: float, radius: float, x: float, **extra: Any
) -> dict[str, Any]:
    return {"id": id_, "shape": shape, "mass": mass, "radius": radius, "x": x, **extra}


def _pair(
    shape1: str,
    shape2: str,
    *,
    r1: float = 0.1,
    r2: float = 0.1,
    track1: float = 0.0,
    at: list[dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """Two bodies joined by one spring (k = 100 N/m); distinct masses 1.3 kg and 0.7 kg so that
    no equality of masses is assumed by accident."""
    spring: dict[str, Any] = {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}
    if at is not None:
        spring["at"] = at
        spring.pop("rest_length")  # at rest length in the initial placement
        return {
            "bodies": [
                _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
                _body("b2", shape2, 0.7, r2, 0.5),
            ],
            "springs": [spring],
        }
    return {
        "bodies": [
            _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
            _body("b2", shape2, 0.7, r2, 0.49),
        ],
        "springs": [spring],
    }


def _pulled(shape: str, **extra: Any) -> dict[str, Any]:
    """One body pulled horizontally by a constant force at height 0.137 m (paper App. A, Fig. 5);
    0.137/R is no simple ratio, so the engine names the height y."""
    return {
        "bodies": [_body("b", shape, 1.3, 0.1, 0.0, **extra)],
        "forces": [{"body": "b", "at": {"height": 0.137}, "fx": 2.0}],
    }


#: The systems the claims are checked on, as system files (dictionaries).
SYSTEMS: dict[str, dict[str, Any]] = {
    # Fig. 1: two point masses, compressed and released
    "fig1": {
        "bodies": [_body("b1", "slider", 1.3, 0.05, 0.0), _body("b2", "slider", 0.7, 0.05, 0.49)],
        "springs": [{"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}],
    },
    # Fig. 2: hoop (m1) and cylinder (m2) of equal radius R, centres joined
    "fig2": _pair("hoop", "cylinder"),
    "two-hoops": _pair("hoop", "hoop"),
    "two-cylinders": _pair("cylinder", "cylinder"),
    # Fig. 3 as the paper sizes it: R1 = R2/2, centres level (the hoop's track raised by R1),
    # the spring from the hoop's top (2R1) to the cylinder at 1.5 R2: horizontal
    "fig3": _pair(
        "hoop", "cylinder", r1=0.05, r2=0.1, track1=0.05, at=[{"height": 0.1}, {"height": 0.15}]
    ),
    # a wall spring on the hoop, the hoop-cylinder spring: a system whose normal modes do not
    # obey the sum rule (the counter-example to Sec. 5.4's "consequently")
    "fig4a": {
        "anchors": [{"id": "wall", "x": -0.5, "y": 0.1}],
        "bodies": [_body("b1", "hoop", 1.3, 0.1, 0.0), _body("b2", "cylinder", 0.7, 0.1, 0.49)],
        "springs": [
            {"ends": ["wall", "b1"], "stiffness": 80.0, "rest_length": 0.5},
            {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5},
        ],
    },
    # Sec. 4's "We need to ensure that there is no static friction force": a hoop of radius
    # 3R2/4 beside the cylinder on one floor, the spring level with the hoop's centre (at
    # 3R2/4 on the cylinder): the frictions cancel, neither vanishes
    "zero-sum": _pair(
        "hoop", "cylinder", r1=0.075, r2=0.1, at=[{"height": 0.075}, {"height": 0.075}]
    ),
    # App. A: a body with I = gamma m R^2 pulled at height y; and a hoop, a cylinder
    "pulled": _pulled("custom", inertia_factor=0.3),
    "pulled-hoop": _pulled("hoop"),
    "pulled-cylinder": _pulled("cylinder"),
}


def paper_system(key: str) -> System:
    """One of :data:`SYSTEMS` as a validated rollspring system."""
    return system_from_dict(SYSTEMS[key])


# -- claims, derivations, verdicts ---------------------------------------------------------------


@dataclass(frozen=True)
class Assumption:
    """An assumption the paper itself states: ``words`` (ours), ``quote`` (the paper's words,
    verbatim from its source) and ``location`` (where it says them)."""

    words: str
    quote: str
    location: str

    def text(self) -> str:
        """``words (location: "quote")``, with the quote's LaTeX markup as it stands."""
        return f'{self.words} ({self.location}: "{self.quote}")'


@dataclass(frozen=True)
class Derived:
    """What a recipe derives: ``value`` (the quantity in general, SymPy or a tuple); ``how`` (one
    line: from which engine objects). Under the assumptions the paper states (the claim's
    ``assumptions``): ``assumed`` (the derived quantity under them) and ``paper_assumed`` (a map
    applied to the paper's expression under them, e.g. magnitudes; identity when None). Where the
    claim needs a condition the paper does not state: ``condition`` (words), ``value_if`` (the
    derived quantity under it and the stated assumptions) and ``paper_if`` (a map applied to the
    paper's expression under it, e.g. an angle counted the other way). ``paper_subs`` substitutes
    the paper's auxiliary symbols (a force, a moment of inertia) by the engine's expressions
    before comparing; ``why`` explains a difference; ``correction`` (LaTeX) replaces the plain
    derived value where that is not the best display."""

    value: Any
    how: str
    why: str = ""
    assumed: Any = None
    paper_assumed: Callable[[Any], Any] | None = None
    condition: str | None = None
    value_if: Any = None
    paper_if: Callable[[Any], Any] | None = None
    paper_subs: dict[Any, Any] = field(default_factory=dict)
    correction: str | None = None


@dataclass(frozen=True)
class Claim:
    """One quantitative statement of the paper (see the module docstring)."""

    key: str
    location: str
    statement: str
    latex: str
    quantity: str
    paper: Any
    system: str
    derive: Callable[[_Bench], Derived] = field(repr=False, compare=False)
    quote: str = ""
    assumptions: tuple[Assumption, ...] = ()


@dataclass(frozen=True)
class ClaimCheck:
    """A claim with its computed verdict; ``assumption`` names the paper's stated assumptions
    the verdict relies on (None for a claim verified without them)."""

    claim: Claim
    verdict: str
    correction: str | None
    reason: str
    paper: Any
    derived: Any
    assumption: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: ``location``, ``claim`` (LaTeX), ``quote`` (the paper's words),
        ``verdict``, ``assumption`` (the paper's stated assumptions the verdict relies on, or
        None), ``correction`` (LaTeX or None), ``reason``."""
        return {
            "location": self.claim.location,
            "claim": self.claim.latex,
            "quote": self.claim.quote,
            "verdict": self.verdict,
            "assumption": self.assumption,
            "correction": self.correction,
            "reason": self.reason,
        }


class _Bench:
    """The symbolic systems and the derived objects they share, built once each."""

    def __init__(self) -> None:
        self._cache: dict[tuple[Any, ...], Any] = {}

    def _cached(self, key: tuple[Any, ...], build: Callable[[], Any]) -> Any:
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    def sym(self, key: str) -> SymbolicSystem:
        result: SymbolicSystem = self._cached(
            ("sym", key), lambda: symbolic_system(paper_system(key), symbols=True)
        )
        return result

    def omega2(self, key: str) -> list[sp.Expr]:
        """Closed forms of the squared frequencies of the oscillating modes (the engine's
        det(K - Omega^2 M) = 0)."""

        def build() -> list[sp.Expr]:
            found = normal_frequencies(self.sym(key), budget=None)
            if not found.complete:
                raise RuntimeError(f"{key}: no closed-form frequencies")
            return list(found.omega2)

        result: list[Any] = self._cached(("omega2", key), build)
        return result

    def mode(self, key: str) -> sp.Matrix:
        """The one oscillating mode shape (in phi), the null vector of K - Omega^2 M."""

        def build() -> sp.Matrix:
            sym = self.sym(key)
            (w2,) = self.omega2(key)
            (v,) = (sym.stiffness_matrix - w2 * sym.mass_matrix).nullspace(simplify=True)
            return v.applyfunc(_tidy)

        return self._cached(("mode", key), build)

    def zero_mode(self, key: str) -> sp.Matrix:
        def build() -> sp.Matrix:
            v0 = self.sym(key).zero_mode()
            if v0 is None:
                raise RuntimeError(f"{key}: no single zero mode")
            return v0

        return self._cached(("zero", key), build)

    def lever(self, key: str, spring: int = 0) -> list[sp.Expr]:
        """b_i = dl/dq_i at the reference: the spring's deformation is b . q (linear)."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            (length,) = sym.linearized([sym.springs[spring].length])
            return [_tidy(sp.diff(length, q)) for q in sym.q]

        result: list[Any] = self._cached(("lever", key, spring), build)
        return result

    def friction_linear(self, key: str) -> list[sp.Expr]:
        """The required friction (M8) to first order in q, positive along +x."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            return [sp.expand(f) for f in sym.linearized(sym.friction_configuration)]

        result: list[Any] = self._cached(("friction", key), build)
        return result

    def weights(self, key: str) -> list[sp.Expr]:
        """Stationary-point weights w_i = J_i v0_i / s_i, normalised (docs/physics.md (M14))."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            v0 = self.zero_mode(key)
            raw = [b.J * v0[i] / b.s for i, b in enumerate(sym.bodies)]
            total = sp.Add(*raw)
            return [_tidy(w / total) for w in raw]

        result: list[Any] = self._cached(("weights", key), build)
        return result

    def conserved(self, key: str) -> list[sp.Expr]:
        """Coefficients c = v0^T M of the conserved combination c . qdot (M14)."""
        sym = self.sym(key)
        v0 = self.zero_mode(key)
        return [_tidy(v0[i] * sym.mass_matrix[i, i]) for i in range(sym.n)]

    def accelerations(self, key: str, *, linear: bool = False) -> list[sp.Expr]:
        """qdd_i = Q_i / J_i from the engine's equations of motion (M7)."""
        sym = self.sym(key)
        return [
            _tidy(eq.rhs / b.J)
            for eq, b in zip(sym.equations_of_motion(linear=linear), sym.bodies, strict=True)
        ]

    def along_mode(self, exprs: Sequence[sp.Expr], key: str) -> list[sp.Expr]:
        """Linear forms of q evaluated on the oscillating mode shape."""
        sym = self.sym(key)
        v = self.mode(key)
        sub = {q: v[i] for i, q in enumerate(sym.q)}
        return [_tidy(sp.sympify(e).xreplace(sub)) for e in exprs]

    def amplitudes(self, key: str) -> list[sp.Expr]:
        """Centre amplitudes A_i in the oscillating mode whose spring deformation is A."""
        sym = self.sym(key)
        v = self.mode(key)
        deformation = sp.Abs(_tidy(sum(b * v[i] for i, b in enumerate(self.lever(key)))))
        return [_tidy(A * sp.Abs(body.s * v[i]) / deformation) for i, body in enumerate(sym.bodies)]

    def canonical(self, key: str) -> list[sp.Expr]:
        r""":math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`: the point transformation that turns
        :math:`T = \sum J_i\dot\varphi_i^2/2` into :math:`\sum m_i\dot q_i^2/2`."""
        sym = self.sym(key)
        return [sp.sqrt(b.J / b.m) * b.q for b in sym.bodies]

    def hamiltonian(
        self, key: str, qs: Sequence[sp.Symbol], ps: Sequence[sp.Symbol]
    ) -> tuple[sp.Expr, sp.Expr]:
        """(H, V) in the canonical coordinates: H = sum p^2/(2m) + V, V the engine's quadratic
        potential with phi_i = sqrt(m_i/J_i) q_i."""
        sym = self.sym(key)
        to_q = {b.q: sp.sqrt(b.m / b.J) * qq for b, qq in zip(sym.bodies, qs, strict=True)}
        V = sp.expand(sym.quadratic_potential.xreplace(to_q))
        T = sp.Add(*[pp**2 / (2 * b.m) for b, pp in zip(sym.bodies, ps, strict=True)])
        return T + V, V


def _same(left: Any, right: Any) -> bool:
    """True when the two (expressions, or sequences of them of equal length) are identical:
    ``simplify(left - right) == 0``; truth values compare as such. A difference that is not
    zero at a random rational point (exact arithmetic) is not identically zero, which spares the
    simplification."""
    truth = (bool, BooleanAtom)
    if isinstance(left, truth) or isinstance(right, truth):  # a claim "X differs from Y"
        return isinstance(left, truth) and isinstance(right, truth) and bool(left) == bool(right)
    if isinstance(left, Sequence | sp.MatrixBase) or isinstance(right, Sequence | sp.MatrixBase):
        left_items, right_items = list(left), list(right)
        return len(left_items) == len(right_items) and all(
            _same(a_, b_) for a_, b_ in zip(left_items, right_items, strict=True)
        )
    difference = sp.sympify(left) - sp.sympify(right)
    if difference == 0:
        return True
    if _nonzero_somewhere(difference):
        return False
    if sp.cancel(sp.expand(difference)) == 0:
        return True
    result: bool = sp.simplify(difference) == 0 or sp.simplify(sp.expand(difference)) == 0
    return result


def _tidy(expr: Any) -> Any:
    """A cheap normal form: cancel for rational expressions, simplify where radicals, absolute
    values or signs appear."""
    expr = sp.sympify(expr)
    if expr.has(sp.Abs, sp.sign) or any(
        p_.exp.is_Rational and not p_.exp.is_Integer for p_ in expr.atoms(sp.Pow)
    ):
        return sp.simplify(expr)
    return sp.factor(sp.cancel(expr)) if expr.free_symbols else expr


def _nonzero_somewhere(expr: sp.Expr) -> bool:
    """True when ``expr`` is clearly non-zero at a rational point (positive symbols get values
    in (1/2, 3), real ones in (-2, 2) but not 0)."""
    point = {}
    for n, symbol in enumerate(sorted(expr.free_symbols, key=lambda s_: s_.name)):
        value = sp.Rational(53 + 37 * n % 101, 47 + 13 * n % 29)  # deterministic, generic
        if not symbol.is_positive:
            value = value - 2 if n % 2 else 2 - value
            if value == 0:
                value = sp.Rational(1, 3)
        point[symbol] = value
    number = sp.N(expr.xreplace(point), 30)
    if not number.is_number or number.is_finite is not True:
        return False  # undecided: leave it to simplify
    return bool(abs(number) > sp.Float("1e-20"))


def _latex(value: Any) -> str:
    if isinstance(value, Sequence) and not isinstance(value, str):
        return r"\left(" + r",\ ".join(_latex(v) for v in value) + r"\right)"
    result: str = sp.latex(value)
    return result


def _subs(value: Any, mapping: dict[Any, Any]) -> Any:
    if not mapping:
        return value
    if isinstance(value, Sequence) and not isinstance(value, str):
        return tuple(_subs(v, mapping) for v in value)
    return sp.sympify(value).subs(mapping)


def _words_of(assumptions: Sequence[Assumption]) -> str:
    return "; ".join(a.words for a in assumptions)


def check_claim(claim: Claim, bench: _Bench | None = None) -> ClaimCheck:
    """Derive the claim's quantity with the engine and compare (see the module docstring)."""
    bench = bench or _Bench()
    derived = claim.derive(bench)
    paper = _subs(claim.paper, derived.paper_subs)
    if _same(paper, derived.value):
        return ClaimCheck(claim, VERIFIED, None, derived.how, paper, derived.value)
    stated = claim.assumptions
    if bool(stated) != (derived.assumed is not None):
        raise RuntimeError(
            f"{claim.key}: the claim's stated assumptions and the recipe's value under them "
            "go together"
        )
    assumption = "; ".join(a.text() for a in stated) or None
    if stated:
        paper_assumed = derived.paper_assumed(paper) if derived.paper_assumed else paper
        if _same(paper_assumed, derived.assumed):
            reason = f"holds under the paper's stated assumption: {_words_of(stated)}"
            if derived.why:
                reason += f"; {derived.why}"
            return ClaimCheck(
                claim, HOLDS_STATED, None, reason, paper, derived.value, assumption=assumption
            )
    # the correction in the paper's own terms: under the assumptions it states
    own = derived.assumed if stated else derived.value
    correction = derived.correction or f"{claim.quantity} = {_latex(own)}"
    if derived.condition is not None:
        paper_if = derived.paper_if(paper) if derived.paper_if is not None else paper
        value_if = derived.value_if if derived.value_if is not None else own
        if _same(paper_if, value_if):
            reason = f"holds only if {derived.condition}"
            if stated:
                reason += f" (besides the paper's stated assumption: {_words_of(stated)})"
            if derived.why:
                reason += f"; {derived.why}"
            return ClaimCheck(
                claim, HOLDS_ONLY_IF, correction, reason, paper, derived.value, assumption
            )
    reason = derived.why or derived.how
    return ClaimCheck(claim, WRONG, correction, reason, paper, derived.value, assumption)


def check_claims(claims: Iterable[Claim]) -> tuple[ClaimCheck, ...]:
    """Each of ``claims`` with its verdict; the claims share the symbolic systems they are
    derived on (each built once)."""
    bench = _Bench()
    return tuple(check_claim(claim, bench) for claim in claims)


@functools.cache
def check_paper() -> tuple[ClaimCheck, ...]:
    """Every claim of :func:`paper_claims` with its verdict (computed once per process)."""
    return check_claims(paper_claims())


def paper_figure(system: System) -> tuple[str, set[str]] | None:
    """Which of the paper's systems ``system`` is, as ``(label, keys of`` :data:`SYSTEMS` ``)``,
    or None.

    By structure, not by numbers (the paper's claims are symbolic): two sliders joined at their
    centres (Fig. 1); a hoop and a solid cylinder, or two hoops, or two cylinders, joined at
    their centres, centres level (Fig. 2); a hoop and a cylinder joined at their percussion
    heights (1 + γ)R (Fig. 3); a wall spring on a hoop that is joined to a cylinder at the centres
    (Fig. 4 (a)). No constant forces in any of them.
    """
    if system.forces:
        return None
    bodies = {b.id: b for b in system.bodies}
    shapes = sorted(b.shape for b in system.bodies)
    springs = system.springs

    def centres(spring: Any) -> bool:
        return all(at.is_centre_form for at in spring.attachments)

    level = len({round(b.track_height + b.radius, 12) for b in system.bodies}) == 1
    if len(bodies) == 2 and len(springs) == 1 and not system.anchors:
        (spring,) = springs
        if shapes == ["slider", "slider"] and centres(spring):
            return "Fig. 1 (two point masses)", {"fig1"}
        if centres(spring) and level:
            if shapes == ["cylinder", "hoop"]:
                return "Fig. 2 (hoop and cylinder joined at their centres)", {"fig2"}
            if shapes == ["hoop", "hoop"]:
                return "Sec. 3 variant with two hoops", {"two-hoops"}
            if shapes == ["cylinder", "cylinder"]:
                return "Sec. 3 variant with two cylinders", {"two-cylinders"}
        if shapes == ["cylinder", "hoop"] and all(
            at.height is not None
            and math.isclose(at.height, bodies[end].percussion_height, rel_tol=1e-9)
            for end, at in zip(spring.ends, spring.attachments, strict=True)
        ):
            return "Fig. 3 (springs at the percussion points, no friction)", {"fig3"}
    if (
        len(bodies) == 2
        and len(system.anchors) == 1
        and len(springs) == 2
        and shapes == ["cylinder", "hoop"]
        and all(centres(s) for s in springs)
    ):
        anchor = system.anchors[0].id
        wall = [s for s in springs if anchor in s.ends]
        if len(wall) == 1 and any(bodies[e].shape == "hoop" for e in wall[0].ends if e in bodies):
            return (
                "a wall spring on the hoop (as Fig. 4 (a) builds up; the Sec. 5.4 counter-example)",
                {"fig4a"},
            )
    return None


# -- the assumptions the paper states --------------------------------------------------------------

_RELEASED_FIG1 = Assumption(
    "the masses start from rest (compressed, then released)",
    "The masses are compressed in the direction of the longitudinal axis of the spring and then "
    "released.",
    "Sec. 2",
)
_RELEASED = Assumption(
    "the bodies start from rest (the spring compressed, then released)",
    r"As Fig.~\ref{fig2} shows the spring is initially compressed and suddenly released.",
    "Sec. 3",
)
_FORCE_AMOUNTS = Assumption(
    "F₁, F₂ are amounts (magnitudes)", "always exert the same amount of force", "Sec. 2"
)
_SPRING_MAGNITUDES = Assumption(
    "the spring forces are compared in magnitude",
    "The spring forces are equal in magnitude",
    "Sec. 3",
)
_FRICTION_AMOUNTS = Assumption(
    "f₁, f₂ are amounts (magnitudes)", "different amounts of static friction forces", "Sec. 3"
)
_LEVEL = Assumption(
    "the centres of the two bodies are at the same height",
    "the centers of rigid bodies are at the same height",
    "Sec. 4",
)
_SMALL_ANGLES = Assumption(
    "small angles (first order in the amplitude)",
    "the following equations describe the motion of the coupled system only in small angle "
    "approximation",
    "Sec. 4",
)
_MAXIMAL = Assumption(
    "Φ̇₁, Φ̇₂ are the maximal angular speeds (magnitudes)",
    r"$\dot{\Phi_1}, \dot{\Phi_2}$ are the maximal angular velocities",
    "Sec. 5.2",
)
_ORIGIN = Assumption(
    "the angles are measured about the stationary point X̂, the origin",
    r"Point $\hat{X}$ has been chosen as the origin of the coordinate system",
    "Sec. 5.3",
)
_ORIGIN_APP_A = Assumption(
    "the angles are measured about the stationary point X̂, the origin",
    r"Point $\hat{X}$ has been selected as the origin of our coordinate system",
    "App. A",
)


# -- the recipes -------------------------------------------------------------------------------


def _flip_first(expr: Any) -> Any:
    """The paper's expression read in the orientation of its Sec. 5.3, where body 1's angle is
    counted the other way (epsilon_1 = X-hat - x_1): phi_1 -> -phi_1 (and its rates)."""
    flip = {phi1: -phi1, phid1: -phid1, phidd1: -phidd1, q1: -q1, p1: -p1, pd1: -pd1, q3: -q3}
    if isinstance(expr, Sequence) and not isinstance(expr, str):
        return tuple(sp.sympify(e).xreplace(flip) for e in expr)
    return sp.sympify(expr).xreplace(flip)


def _flip_first_rate(expr: Any) -> Any:
    """As :func:`_flip_first` for a pair whose first entry is itself odd in phi_1 (an
    acceleration, a momentum rate of body 1)."""
    first, second = _flip_first(expr)
    return (-first, second)


def _magnitudes(expr: Any) -> Any:
    if isinstance(expr, Sequence) and not isinstance(expr, str):
        return tuple(sp.Abs(e) for e in expr)
    return sp.Abs(expr)


_ORIENTATION = (
    "body 1's angle is counted the other way (ε₁ = X̂ − x₁, leftward): the paper defines "
    "ε₁ = x₁ − X̂ (Sec. 5.2, App. A), with which the spring's deformation is ε₂ − ε₁; it refers "
    "the orientation to Fig. 2, whose drawing is not in the source, and its Sec. 5.1 counts both "
    "angles one way (φ₂ = −(4m₁/3m₂)φ₁)"
)

_CANONICAL_ORIENTATION = (
    "the first canonical coordinate is counted the other way (q₁ with body 1 anticlockwise, as "
    "the Lagrangian (l) does); with both angles counted one way, as Sec. 5.1 counts them, the "
    "coefficients are (−Ω₁/√(k/m₁), +Ω₂/√(k/m₂)) = (−1/√2, +√(2/3))"
)


def _fig3_geometry(b: _Bench) -> dict[Any, Any]:
    """The paper's Fig. 3: the centres level (the hoop's track at h_1 = R_2 - R_1) and
    R_1 = R_2/2, so that the spring is horizontal at rest (the engine's symbols)."""
    names = {p_.name: p_ for p_ in b.sym("fig3").parameters}
    return {names["h_1"]: names["R_2"] / 2, names["R_1"]: names["R_2"] / 2}


def _exact_accelerations(b: _Bench, key: str, subs: dict[Any, Any] | None = None) -> list[Any]:
    """phiddot_i = Q_i/J_i from the engine's exact equations of motion (not simplified)."""
    sym = b.sym(key)
    out = [eq.rhs / body.J for eq, body in zip(sym.equations_of_motion(), sym.bodies, strict=True)]
    return [e.xreplace(subs) for e in out] if subs else out


def _split(b: _Bench, key: str = "fig2") -> list[sp.Expr]:
    """The stiffnesses of the two parts of the spring cut at the stationary point X-hat: the part
    between body i and X-hat has the length w_j l (j the other body, w the engine's X-hat
    weights), so k_i = k l / (w_j l) = k / w_j (a spring's stiffness is inversely proportional to
    its length)."""
    w = b.weights(key)
    spring_k = b.sym(key).springs[0].k
    return [_tidy(spring_k / w[1]), _tidy(spring_k / w[0])]


def _mode_ratio(b: _Bench, key: str = "fig2") -> sp.Expr:
    """phi_2/phi_1 in the oscillating mode (the engine's null vector of K - Omega^2 M)."""
    v = b.mode(key)
    result: sp.Expr = _tidy(v[1] / v[0])
    return result


def _fig1_eom(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(eq.rhs for eq in sym.equations_of_motion()),
        "m_i xddot_i = Q_i = -dV/dx_i from the engine's potential (M7)",
    )


def _fig1_potential(b: _Bench) -> Derived:
    return Derived(
        b.sym("fig1").potential,
        "the engine's exact spring potential (M5), displacements from the equilibrium",
    )


def _fig1_no_external(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    friction = sp.Add(*sym.friction_configuration)
    vertical = _tidy(
        sp.Add(*[n - body.m * sym.g for n, body in zip(sym.normal, sym.bodies, strict=True)])
    )
    return Derived(
        (friction, vertical),
        "the engine's floor forces on the two masses: friction (frictionless floor) and "
        "N_i - m_i g (M9) summed",
    )


def _fig1_vertical(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(_tidy(n - body.m * sym.g) for n, body in zip(sym.normal, sym.bodies, strict=True)),
        "N_i - m_i g from the engine's normal forces (M9): the spring stays horizontal",
    )


def _fig1_end_forces(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    (first, _), (second, _) = sym.body_forces
    ratio = _tidy(second / first)
    return Derived(
        ratio,
        "F_2x/F_1x of the engine's spring forces on the two masses",
        assumed=sp.Abs(ratio),
        why="signed along +x the two forces are opposite, F₂ = −F₁, as (f1), (f2) write them",
    )


def _fig1_forces_from_u(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(sp.expand(q) for q in sym.generalized_forces),
        "the engine's generalised forces Q_i (M7), its own -dV/dx_i",
    )


def _fig1_momentum_sum(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    total = _tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()]))
    return Derived((total, total), "sum of the engine's m_i xddot_i = Q_i (M7)")


def _cm_theorem(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    masses = sp.Add(*[body.m for body in sym.bodies])
    return Derived(
        _tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()]) / masses),
        "Xddot = sum Q_i / sum m_i for the two masses of Fig. 1, with the engine's Q_i (M7)",
    )


def _cm_velocity(key: str, how: str, *, small: bool = False) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym(key)
        w = b.weights(key)
        masses = [body.m for body in sym.bodies]
        total = sp.Add(*masses)
        if not _same(w, [mm / total for mm in masses]):
            raise RuntimeError(f"{key}: the stationary point is expected at the centre of mass")
        value = P0 / total
        why = (
            "the conserved combination (zero mode of K, M14) is the total momentum "
            "Σ mᵢẋᵢ = P₀, fixed by the start"
        )
        if small:
            why += (
                "; beyond first order the frictions are O(a³) (the attachment points leave the "
                "percussion heights as the bodies turn) and the centre of mass drifts"
            )
        return Derived(value, how, why=why, assumed=_subs(value, {P0: 0}))

    return derive


def _fig2_horizontal(b: _Bench) -> Derived:
    return Derived(
        tuple(_tidy(force[1]) for force in b.sym("fig2").body_forces),
        "the vertical components of the engine's spring forces on the two bodies (M7) at every "
        "configuration: the centres, both at height R, stay level",
    )


def _fig2_dof(b: _Bench) -> Derived:
    return Derived(
        sp.Integer(b.sym("fig2").n), "the engine's generalised coordinates of the rolling pair"
    )


def _fig2_constraints(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(body.s * body.q for body in sym.bodies),
        "centre displacement s_i phi_i of the engine's rolling bodies (M2), s_i the radius",
    )


def _fig2_spring_force(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (first, _), (second, _) = sym.body_forces
    return Derived(
        (_tidy(first), sp.Abs(_tidy(second))),
        "the engine's spring force on body 1 and the size of the one on body 2",
    )


def _steiner(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    J = [sym.mass_matrix[i, i] for i in range(2)]
    return Derived(
        (J[0], J[0], J[1], J[1]),
        "diagonal of the engine's mass matrix M = diag(J_i), J = I + mR^2 (M4)",
    )


def _fig2_eom(b: _Bench) -> Derived:
    return Derived(
        tuple(b.accelerations("fig2")),
        "phiddot_i = Q_i/J_i from the engine's exact equations of motion (M7)",
    )


def _fig2_sum(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        _tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()])),
        "sum of the engine's J_i phiddot_i = Q_i (M7)",
    )


def _momentum(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    c = b.conserved("fig2")
    J = [body.J for body in sym.bodies]
    scaled = [_tidy(ci * J[0] / c[0]) for ci in c]
    value = P0 if _same(scaled, J) else J[0] * phid1 + J[1] * phid2
    return Derived(
        value,
        "the zero mode v0 of K gives the conserved v0^T M phidot (M14)",
        assumed=_subs(value, {P0: 0}),
        why="I'₁φ̇₁ + I'₂φ̇₂ = P₀ is conserved (zero mode v₀ = (1, 1) of K, M14), its value fixed "
        "by the initial velocities",
    )


def _w_relation(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    c = b.conserved("fig2")
    J = [body.J for body in sym.bodies]
    if not _same([_tidy(ci * J[0] / c[0]) for ci in c], J):
        raise RuntimeError("fig2: the conserved combination is expected to be sum J_i phidot_i")
    radius = sym.bodies[0].s
    value = (P0 / radius, P0 / radius)
    return Derived(
        value,
        "the conserved sum J_i phidot_i = P_0 (zero mode of K, M14) divided by R, with "
        "xdot_i = R phidot_i",
        assumed=(sp.Integer(0), sp.Integer(0)),
        why="the combination is conserved; its value P₀/R is fixed by the start",
    )


def _phase_opposition(b: _Bench) -> Derived:
    return Derived(
        sp.sign(_mode_ratio(b)),
        "sign of phi_2/phi_1 in the oscillating mode (null vector of K - Omega^2 M)",
    )


def _cm_moves(key: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym(key)
        v = b.mode(key)
        masses = [body.m for body in sym.bodies]
        cm = _tidy(
            sp.Add(
                *[
                    mm * body.s * v[i]
                    for i, (mm, body) in enumerate(zip(masses, sym.bodies, strict=True))
                ]
            )
            / (sp.Add(*masses) * sym.bodies[0].s * v[0])
        )
        return Derived(
            sp.true if cm != 0 else sp.false,
            f"in the oscillating mode Xdot = ({sp.sstr(cm)}) xdot_1 (engine's mode shape)",
        )

    return derive


def _stationary_point(b: _Bench) -> Derived:
    """X-hat of eq. (c) with the paper's weights I'_i: its velocity, from the engine's conserved
    combination."""
    sym = b.sym("fig2")
    paper_weights = [2 * m1 * R**2, sp.Rational(3, 2) * m2 * R**2]
    c = b.conserved("fig2")
    rate_terms = [w_ * body.s for w_, body in zip(paper_weights, sym.bodies, strict=True)]
    ratios = {_tidy(term / ci) for term, ci in zip(rate_terms, c, strict=True)}
    total = sp.Add(*paper_weights)
    if len(ratios) == 1:  # the paper's weights are the conserved combination's
        (scale,) = ratios
        value = _tidy(scale * P0 / total)
    else:
        value = (
            sp.Add(*[t_ * body.qd for t_, body in zip(rate_terms, sym.bodies, strict=True)]) / total
        )
    return Derived(
        value,
        "d/dt of (I'_1 x_1 + I'_2 x_2)/(I'_1 + I'_2), with the engine's conserved "
        "combination v0^T M phidot = P_0 (M14)",
        assumed=_subs(value, {P0: 0}),
        why="the weights I'ᵢ are those of the conserved combination, so X̂ moves uniformly, "
        "at rest only for a start from rest",
    )


def _stationary(key: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        return Derived(
            tuple(b.weights(key)),
            "X-hat weights w_i = J_i v0_i / R_i from the zero mode of K (M14)",
        )

    return derive


def _same_spring_forces(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (first, _), (second, _) = sym.body_forces
    Q = sym.generalized_forces
    value = (_tidy(second / first), _tidy(Q[1] / Q[0]))
    return Derived(
        value,
        "F_2x/F_1x and the ratio of the torques Q_i about the contact lines (engine, M7)",
        assumed=_magnitudes(value),
        why="signed, the forces and their torques are opposite",
    )


def _friction_ratio(b: _Bench) -> Derived:
    first, second = b.along_mode(b.friction_linear("fig2"), "fig2")
    ratio = _tidy(first / second)
    return Derived(
        ratio,
        "ratio of the engine's friction (M8), linearised, in the mode",
        assumed=sp.Abs(ratio),
        paper_assumed=sp.Abs,
        why=f"signed along +x the frictions point opposite ways, f₁/f₂ = {sp.sstr(ratio)}, so "
        "f₁ + f₂ ≠ 0: the resultant external force that moves the centre of mass",
    )


def _friction_cause(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    acc = b.accelerations("fig2", linear=True)
    friction = b.friction_linear("fig2")
    newton = _tidy(
        sp.Add(*[body.m * body.s * acc[i] for i, body in enumerate(sym.bodies)]) - sp.Add(*friction)
    )
    in_mode = _tidy(sp.Add(*b.along_mode(friction, "fig2")))
    return Derived(
        (newton, sp.true if in_mode != 0 else sp.false),
        "(m_1 + m_2) Xddot minus the sum of the engine's frictions (M8), and that sum in the "
        f"mode (= {sp.sstr(in_mode)} per unit of the mode shape)",
    )


def _same_inertia(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    total = sp.factor(sp.Add(*b.friction_linear("fig2")))
    # equal moments of inertia, I_1 = I_2: m_1 R^2 = m_2 R^2 / 2
    b1, b2 = sym.bodies
    (solution,) = sp.solve(sp.Eq(b1.I, b2.I), m2)
    with_equal_inertia = sp.factor(total.subs(m2, solution))
    hoops = _tidy(sp.Add(*b.friction_linear("two-hoops")))
    cylinders = _tidy(sp.Add(*b.friction_linear("two-cylinders")))
    note = (
        "it vanishes for two hoops and for two cylinders, the same inertia factor I/(mR²), "
        "whatever their moments of inertia"
        if hoops == 0 and cylinders == 0
        else ""
    )
    return Derived(
        with_equal_inertia,
        "sum of the engine's linearised frictions (M8) with I_1 = I_2 imposed",
        why="with I₁ = I₂ (m₂ = 2m₁) a hoop and a cylinder still need "
        f"f₁ + f₂ = {sp.sstr(with_equal_inertia)} ≠ 0; {note}".rstrip("; "),
        correction=r"f_1+f_2="
        + sp.latex(total)
        + r"\neq 0\ \text{unless}\ \frac{I_1}{m_1R_1^2}=\frac{I_2}{m_2R_2^2}",
    )


def _pulled_friction(b: _Bench, key: str) -> sp.Expr:
    """The paper's f (counted against F) of the pulled body ``key`` at phi = 0."""
    sym = b.sym(key)
    (f,) = sym.friction_configuration
    result: sp.Expr = _tidy(-f.subs(sym.bodies[0].q, 0))
    return result


def _fric(b: _Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    f = _pulled_friction(b, "pulled")
    slope = sp.diff(f, y)
    return Derived(
        (f, _tidy(sp.diff(f, y, 2)), sp.sign(_tidy(-slope / F))),
        "minus the engine's friction (M8) of the pulled body at phi = 0 (the paper counts f "
        "opposite to F), its curvature in y and the sign of its slope against F",
        paper_subs={I_: body.I},
    )


def _fric_app_a(b: _Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        _pulled_friction(b, "pulled"),
        "minus the engine's friction (M8) of the pulled body at phi = 0",
        paper_subs={I_: body.I},
    )


def _fric_coupled(b: _Bench) -> Derived:
    """Sec. 4: (fric) with the spring's varying force, on the coupled systems it is meant for:
    Fig. 2 (the spring at the centres, y = R: exact) and Fig. 3 (at 2R_1 and 3R_2/2, where (fric)
    gives zero: to first order in the angles)."""
    sym = b.sym("fig2")
    forces = [F_[0] for F_ in sym.body_forces]
    exact = tuple(_tidy(f) for f in sym.friction_configuration)
    fig3 = b.sym("fig3")
    geometry = _fig3_geometry(b)
    exact3 = tuple(f.xreplace(geometry) for f in fig3.friction_configuration)
    linear3 = tuple(
        _tidy(f.xreplace(geometry)) for f in fig3.linearized(fig3.friction_configuration)
    )
    return Derived(
        exact + exact3,
        "the engine's exact friction (M8) of the coupled bodies at every configuration: Fig. 2 "
        "and Fig. 3",
        assumed=exact + linear3,
        paper_subs={Fx1: forces[0], Fx2: forces[1]},
        why="exact for the spring at the centres (Fig. 2, y = R); in Fig. 3 the attachment points "
        "leave 2R₁ and 3R₂/2 as the bodies turn and the spring tilts: there the frictions are "
        "O(φ³), zero only to first order",
    )


def _zero_friction_height(b: _Bench, key: str) -> sp.Expr:
    """y with f(y) = 0 for the pulled body ``key``: the engine's friction at phi = 0, solved."""
    (height,) = sp.solve(sp.Eq(_pulled_friction(b, key), 0), y)
    result: sp.Expr = height
    return result


def _heights(b: _Bench) -> Derived:
    return Derived(
        (_zero_friction_height(b, "pulled-hoop"), _zero_friction_height(b, "pulled-cylinder")),
        "solving the engine's friction f(y) = 0 (M8) for a pulled hoop and cylinder",
    )


def _geometry(b: _Bench) -> Derived:
    hoop = _zero_friction_height(b, "pulled-hoop")
    cylinder = _zero_friction_height(b, "pulled-cylinder")
    track = sp.Symbol("h", real=True)  # height of the hoop's track above the cylinder's
    hoop_end = track + hoop.subs(R, R1)
    cylinder_end = cylinder.subs(R, R2)
    (one_floor,) = sp.solve(sp.Eq(hoop_end.subs(track, 0), cylinder_end), R1)
    level = sp.solve([sp.Eq(hoop_end, cylinder_end), sp.Eq(track + R1, R2)], [R1, track], dict=True)
    (level_solution,) = level
    return Derived(
        one_floor,
        "the spring joins the zero-friction heights (solved from the engine's f(y) = 0): "
        "horizontal iff h + 2R_1 = 3R_2/2",
        assumed=level_solution[R1],
        why="the level centres need the hoop's track raised by R₂ − R₁ = R₁; on one floor a "
        "horizontal spring would need R₁ = 3R₂/4",
    )


def _fig3_eom(b: _Bench) -> Derived:
    return Derived(
        tuple(_exact_accelerations(b, "fig3", _fig3_geometry(b))),
        "phiddot_i = Q_i/J_i from the engine's exact equations of motion (M7) of the paper's "
        "Fig. 3; linearised (small angles) they are (Q(0) - K phi)_i / J_i",
        assumed=tuple(b.accelerations("fig3", linear=True)),
        why="the exact equations differ at third order in the angles: the spring turns with the "
        "bodies",
    )


def _fig3_combination(
    weights: Callable[[SymbolicSystem], Sequence[sp.Expr]], how: str
) -> Callable[[_Bench], Derived]:
    """sum w_i phiddot_i for the weights ``weights(sym)`` (tuples of them), exact and
    linearised."""

    def derive(b: _Bench) -> Derived:
        sym = b.sym("fig3")
        exact = _exact_accelerations(b, "fig3", _fig3_geometry(b))
        linear = b.accelerations("fig3", linear=True)
        rows = weights(sym)
        value = tuple(
            sp.Add(*[w_ * acc for w_, acc in zip(row, exact, strict=True)]) for row in rows
        )
        assumed = tuple(
            _tidy(sp.Add(*[w_ * acc for w_, acc in zip(row, linear, strict=True)])) for row in rows
        )
        return Derived(
            value if len(rows) > 1 else value[0],
            how,
            assumed=assumed if len(rows) > 1 else assumed[0],
            why="with the exact equations of motion the sum is O(φ³), not zero: the spring turns "
            "with the bodies",
        )

    return derive


def _fig3_x(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    exact = _exact_accelerations(b, "fig3", _fig3_geometry(b))
    linear = b.accelerations("fig3", linear=True)
    centres = tuple(body.s * body.q for body in sym.bodies)
    return Derived(
        (
            *centres,
            sp.Add(*[body.m * body.s * acc for body, acc in zip(sym.bodies, exact, strict=True)]),
        ),
        "the engine's centre displacements s_i phi_i and sum m_i s_i phiddot_i, exact",
        assumed=(
            *centres,
            _tidy(
                sp.Add(
                    *[body.m * body.s * acc for body, acc in zip(sym.bodies, linear, strict=True)]
                )
            ),
        ),
        why="with the exact equations of motion m₁ẍ₁ + m₂ẍ₂ is O(φ³), not zero",
    )


def _fig3_friction(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    geometry = _fig3_geometry(b)
    v = b.mode("fig3").xreplace(geometry)
    v = v / v[1]  # amplitude a of phi_2
    along = {q: a * v[i] for i, q in enumerate(sym.q)}
    orders = []
    for f in sym.friction_configuration:
        d = f.xreplace(_fig3_geometry(b)).xreplace(along)
        terms = []
        for n in (1, 2, 3):
            d = sp.diff(d, a)
            terms.append(sp.factor(sp.cancel(d.subs(a, 0))) / sp.factorial(n))
        orders.append(terms)
    linear = tuple(terms[0] * a for terms in orders)
    leading = tuple(terms[0] * a + terms[1] * a**2 + terms[2] * a**3 for terms in orders)
    shown = ", ".join(
        f"f{i + 1} = {sp.sstr(sp.factor(v_))} + O(a^4)" for i, v_ in enumerate(leading)
    )
    return Derived(
        leading,
        "the engine's exact friction (M8) of the paper's Fig. 3 expanded along the mode "
        "phi = a v to third order in a",
        assumed=linear,
        why="the attachment points leave the percussion heights as the bodies turn: beyond first "
        f"order {shown} (φ₂ = a)",
    )


def _fig3_torques_differ(b: _Bench) -> Derived:
    levers = [_tidy(sp.Abs(lever)) for lever in b.lever("fig3")]
    ratio = _tidy((levers[0] / levers[1]).xreplace(_fig3_geometry(b)))
    return Derived(
        sp.true if ratio != 1 else sp.false,
        f"the lever arms of the spring about the contact lines (engine's dl/dphi_i): |b_1|/|b_2| "
        f"= {sp.sstr(ratio)} with the paper's R_1 = R_2/2",
    )


def _fig3_angular_momentum(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    acc = b.accelerations("fig3", linear=True)
    # centre heights above the lower floor: the paper's Fig. 3 has the centres level, at R_2
    centre = [R2, R2]
    model = paper_system("fig3").bodies
    if abs(model[0].track_height + model[0].radius - model[1].radius) > 1e-12:
        raise RuntimeError("fig3: the centres are expected level")
    rate = sum((body.I + body.m * centre[i] * body.s) * acc[i] for i, body in enumerate(sym.bodies))
    value = _tidy(rate.subs(R1, R2 / 2))
    return Derived(
        value,
        "dL_O/dt for L_O = sum (I_i phidot_i + m_i y_ci xdot_i) about a fixed point on the "
        "floor, with the engine's linearised equations of motion",
        paper_subs={R1: R2 / 2},
        why="ΣI'ᵢφ̇ᵢ does change (the torques differ), but it is not the angular momentum here: "
        "the contact lines are at different heights; the angular momentum about any fixed axis "
        "is conserved (no external torque: friction vanishes to first order, Nᵢ = mᵢg)",
        correction=r"\dot L_O=0",
    )


def _qq2(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    v0 = b.zero_mode("fig2")
    c = b.conserved("fig2")
    norm = sp.Add(*[ci * v0[i] for i, ci in enumerate(c)])
    drift = (P0 * t + D0) / norm  # the zero-mode coordinate: c . phi = P_0 t + D_0
    value = _tidy(w2 * drift * v0[0])
    return Derived(
        value,
        "phiddot_1 + Omega^2 phi_1 for the general motion: zero mode (P_0 t + D_0) v0 plus "
        "the oscillating mode",
        assumed=_subs(value, {P0: 0}),
        condition="the coordinate is measured from its equilibrium value (the paper's x₁, x₂ "
        "are the centres' positions, and the angles have no stated origin before Sec. 5.2)",
        value_if=_subs(value, {P0: 0, D0: 0}),
        why="otherwise q oscillates about its equilibrium value qₑ ≠ 0",
        correction=r"\ddot{q}+\Omega^2\left(q-q_e\right)=0,\ q_e\ \text{the equilibrium value of}"
        r"\ q",
    )


def _phi_relation(b: _Bench, *, flip: bool) -> Derived:
    c = b.conserved("fig2")
    value = _tidy((P0 * t + D0 - c[0] * phi1) / c[1])
    if flip:  # Sec. 5.3: X-hat is the origin (stated): both constants vanish
        return Derived(
            value,
            "integrating the conserved c . phidot = P_0 (zero mode of K) twice",
            assumed=_subs(value, {P0: 0, D0: 0}),
            condition=_ORIENTATION,
            paper_if=_flip_first,
            why="in general c · φ = P₀t + D₀ with c = v₀ᵀM = (I'₁, I'₂)",
        )
    return Derived(
        value,
        "integrating the conserved c . phidot = P_0 (zero mode of K) twice",
        assumed=_subs(value, {P0: 0}),
        condition="the integration constant is zero: the angles measured from the equilibrium "
        "about X̂ (the paper takes X̂ as origin only from Sec. 5.2 on)",
        value_if=_subs(value, {P0: 0, D0: 0}),
        why="in general c · φ = P₀t + D₀ with c = v₀ᵀM = (I'₁, I'₂)",
        correction=r"2m_1\varphi_1+\frac{3}{2}m_2\varphi_2=\text{const}",
    )


def _substituted(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    ratio = _mode_ratio(b)
    rhs = sym.equations_of_motion()[0].rhs
    return Derived(
        _tidy(rhs.subs(phi2, ratio * phi1)),
        "the engine's Q_1 of (w2) with the mode's phi_2 = (phi_2/phi_1) phi_1",
    )


def _omega2(key: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        (w2,) = b.omega2(key)
        return Derived(w2, "the non-zero root of det(K - Omega^2 M) = 0 (engine's M, K)")

    return derive


def _clamped_terms(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(_tidy(sym.stiffness_matrix[i, i] / body.J) for i, body in enumerate(sym.bodies)),
        "K_ii/J_i from the engine's M and K: the squared frequency of each body alone with the "
        "other held fixed, the paper's subsystems; these are partial (clamped) frequencies, not "
        "frequencies of the coupled system, whose only non-zero one is Omega",
    )


def _speed_over_amplitude(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.sqrt(w2), sp.sqrt(w2)),
        "in the mode every coordinate is a cos(Omega t): speed amplitude over displacement "
        "amplitude is Omega (engine's Omega^2)",
        paper_subs={Omega: sp.sqrt(w2)},
    )


def _omega_from_sum(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    speeds = [sp.sqrt(w2) * amp for amp in b.amplitudes("fig2")]
    return Derived(
        (_tidy(sp.Add(*speeds)), _tidy(sp.Add(*speeds) / A)),
        "the sum of the derived largest speeds Omega A_i, and divided by A",
        paper_subs={Omega: sp.sqrt(w2)},
    )


def _energy(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    v = b.mode("fig2")
    deformation = sp.Abs(_tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))))
    scale = A / deformation
    kinetic = _tidy(w2 * scale**2 * (v.T * sym.mass_matrix * v)[0, 0] / 2)
    return Derived(
        kinetic,
        "largest kinetic energy sum J_i (Omega a v_i)^2 / 2 in the mode whose spring "
        "deformation is A",
    )


def _nu(b: _Bench) -> Derived:
    ratio = _mode_ratio(b)
    return Derived(
        ratio * Phid1,
        "Phidot_2 in terms of Phidot_1 in the oscillating mode",
        assumed=sp.Abs(ratio) * Phid1,
        why="signed, the two angular velocities have opposite signs (as in (rel1), a sum)",
    )


def _undeformed_at_top_speed(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    v = b.mode("fig2")
    (w2,) = b.omega2("fig2")
    phase = sp.Symbol("tau", real=True)  # Omega t; the mode: phi = v cos(tau)
    kinetic = w2 * (v.T * sym.mass_matrix * v)[0, 0] * sp.sin(phase) ** 2 / 2
    deformation = _tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))) * sp.cos(phase)
    tops = [
        p_
        for p_ in sp.solve(sp.diff(kinetic, phase), phase)
        if sp.diff(kinetic, phase, 2).subs(phase, p_).is_negative
    ]
    at_tops = {_tidy(deformation.subs(phase, p_)) for p_ in tops}
    return Derived(
        at_tops.pop() if len(at_tops) == 1 else tuple(at_tops),
        "the spring's deformation (b . v) cos(Omega t) at the phases where the kinetic energy of "
        "the engine's mode is largest (both speeds largest together)",
    )


def _orbital_spin(b: _Bench) -> Derived:
    body = b.sym("fig2").bodies[1]
    return Derived(
        (_tidy(body.m * body.s**2), body.I),
        "the cylinder's J = m R^2 + I split into the centre's (orbital) and the spin part (M4)",
    )


def _speed_over_rate(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(body.s for body in sym.bodies),
        "centre speed over angular speed: s_i = R of the engine's rolling constraint (M2)",
    )


def _speeds(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        tuple(_tidy(sp.sqrt(w2) * amp) for amp in b.amplitudes("fig2")),
        "v_i = Omega A_i: the mode's centre amplitudes times the derived Omega",
    )


def _omega_chain(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.sqrt(w2),) * 4,
        "square root of the non-zero root of det(K - Omega^2 M) = 0, for each form of the chain",
    )


def _isochronism(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    speeds = [sp.sqrt(w2) * amp for amp in b.amplitudes("fig2")]
    depends = all(sp.diff(s_, A) != 0 for s_ in speeds)
    return Derived(
        (sp.true if depends else sp.false, sp.diff(sp.sqrt(w2), A)),
        "d/dA of the derived largest speeds Omega A_i and of Omega",
    )


def _isotonic(b: _Bench) -> Derived:
    """The isotonic oscillator V = omega^2 x^2/2 + beta/(2 x^2): u = x^2 obeys
    uddot = 4E - 4 omega^2 u, a harmonic motion at 2 omega for every energy E."""
    force = -sp.diff(omega0**2 * xi**2 / 2 + beta0 / (2 * xi**2), xi)
    xdd = force  # unit mass
    u_dd = 2 * xid**2 + 2 * xi * xdd  # d2(x^2)/dt2
    e_mech = xid**2 / 2 + omega0**2 * xi**2 / 2 + beta0 / (2 * xi**2)
    residual = sp.simplify(u_dd - (4 * e_mech - 4 * omega0**2 * xi**2))
    if residual != 0:
        raise RuntimeError("isotonic oscillator: x^2 is expected to oscillate harmonically")
    return Derived(
        sp.false,
        "the isotonic oscillator V = ω²x²/2 + β/(2x²) (SymPy): u = x² obeys ü = 4E − 4ω²u",
        why="isochronism is not unique to harmonic oscillation: the isotonic oscillator "
        "V = ω²x²/2 + β/(2x²) is not harmonic, yet x² oscillates harmonically at 2ω for every "
        "energy, so its period π/ω does not depend on the amplitude",
        correction=r"T=\frac{\pi}{\omega}\ \text{at every amplitude for}\ "
        r"V=\frac{1}{2}\omega^2x^2+\frac{\beta}{2x^2}",
    )


def _amplitudes(b: _Bench) -> Derived:
    return Derived(
        tuple(b.amplitudes("fig2")),
        "centre amplitudes R|v_i| of the mode scaled to a spring deformation A (deformation "
        "b . v, b the engine's lever arms)",
    )


def _amplitude_sum(b: _Bench) -> Derived:
    return Derived(_tidy(sum(b.amplitudes("fig2"))), "sum of the derived centre amplitudes")


def _amplitudes_equal_masses(b: _Bench) -> Derived:
    return Derived(
        tuple(_tidy(amp.subs(m2, m1)) for amp in b.amplitudes("fig2")),
        "the derived A_i with m_1 = m_2",
    )


def _cm_equal_masses(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    v = b.mode("fig2")
    deformation = sp.Abs(_tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))))
    cm = sp.Add(*[body.m * body.s * v[i] for i, body in enumerate(sym.bodies)]) / (m1 + m2)
    amplitude = _tidy(sp.Abs(A * cm / deformation).subs(m2, m1))
    return Derived(
        sp.true if amplitude != 0 else sp.false,
        f"the centre of mass's amplitude in the mode with m_1 = m_2: {sp.sstr(amplitude)}",
    )


def _kinetic(b: _Bench) -> Derived:
    return Derived(b.sym("fig2").kinetic, "the engine's kinetic energy T (M5)")


def _lagrangian(b: _Bench) -> Derived:
    value = sp.expand(b.sym("fig2").lagrangian)
    return Derived(
        value,
        "the engine's Lagrangian T - V (M5)",
        condition=_ORIENTATION,
        paper_if=_flip_first,
        correction=r"\mathcal{L}=\frac{1}{2}I'_1\dot{\phi_1}^2+\frac{1}{2}I'_2\dot{\phi_2}^2-"
        r"\frac{1}{2}k\left(\varepsilon_2-\varepsilon_1\right)^2,\ \varepsilon_i=R\phi_i",
    )


def _parts_in_mode(b: _Bench) -> Derived:
    """(Q1), (Q2): in the mode, body i moves as if tied to X-hat by its part of the spring."""
    (w2,) = b.omega2("fig2")
    sym = b.sym("fig2")
    return Derived(
        tuple(-w2 * body.q for body in sym.bodies),
        "phiddot_i = -Omega^2 phi_i in the engine's mode, against -k_i R^2 phi_i / J_i with k_i "
        "= k/w_j the stiffness of the spring's part between body i and X-hat",
        paper_subs=dict(zip((k1, k2), _split(b), strict=True)),
    )


def _k_series(b: _Bench) -> Derived:
    first, second = _split(b)
    return Derived(
        _tidy(1 / first + 1 / second),
        "1/k_1 + 1/k_2 with the stiffnesses k_i = k/w_j of the spring's parts cut at X-hat",
    )


def _eom_flipped(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    Q = tuple(eq.rhs for eq in sym.equations_of_motion())
    return Derived(
        Q,
        "J_i phiddot_i = Q_i from the engine's Lagrangian (M7)",
        condition=_ORIENTATION,
        paper_if=_flip_first_rate,
    )


def _ga(b: _Bench) -> Derived:
    acc = b.accelerations("fig2")
    ratio = _tidy(acc[1] / acc[0])
    return Derived(
        ratio * phidd1,
        "phiddot_2 in terms of phiddot_1 from the engine's equations of motion",
        condition=_ORIENTATION,
        paper_if=_flip_first,
    )


def _mode_equation(index: int) -> Callable[[_Bench], Derived]:
    """J_i phiddot_i in the mode (phiddot = -Omega^2 phi), for (ep0) and (pe)."""

    def derive(b: _Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        return Derived(
            _tidy(-w2 * body.J * body.q),
            f"J_{index + 1} phiddot_{index + 1} = -Omega^2 J_{index + 1} phi_{index + 1} in the "
            "engine's mode (with the mode's ratio of the angles, in either orientation)",
        )

    return derive


def _k_parts(b: _Bench) -> Derived:
    return Derived(
        tuple(_split(b)),
        "k_i = k/w_j: the spring cut at X-hat (the engine's weights w), each part's stiffness "
        "inversely proportional to its length",
    )


def _k_inverse_sum(b: _Bench) -> Derived:
    spring_k = b.sym("fig2").springs[0].k
    return Derived(1 / spring_k, "1/k of the whole spring")


def _k_equal_masses(b: _Bench) -> Derived:
    return Derived(
        tuple(_tidy(v.subs(m2, m1)) for v in _split(b)),
        "the spring parts' k_i = k/w_j with m_1 = m_2",
    )


def _k_equal(b: _Bench) -> Derived:
    first, second = _split(b)
    (from_k,) = sp.solve(sp.Eq(first, second), m1)
    amp1, amp2 = b.amplitudes("fig2")
    (from_a,) = sp.solve(sp.Eq(amp1, amp2), m1)
    return Derived(
        (_tidy(from_k / m2), _tidy(from_a / m2)),
        "m_1/m_2 solving k_1 = k_2 and A_1 = A_2 with the spring parts' k_i and the derived A_i",
    )


def _xhat_left(b: _Bench) -> Derived:
    w = b.weights("fig2")
    # x_1 = 0, x_2 = l: X-hat = w_2 l, the length of the left part
    return Derived(_tidy(w[1].subs(m2, m1) * ell_total), "X-hat = w_2 l with the engine's weights")


def _xhat_right(b: _Bench) -> Derived:
    w = b.weights("fig2")
    return Derived(
        _tidy(ell_total - w[1].subs(m2, m1) * ell_total), "l - X-hat with the engine's weights"
    )


def _shorter_stiffer(b: _Bench) -> Derived:
    w = [_tidy(w_.subs(m2, m1)) for w_ in b.weights("fig2")]
    lengths = [w[1] * ell_total, w[0] * ell_total]  # the left part, the right part
    parts = [_tidy(v.subs(m2, m1)) for v in _split(b)]
    spring_k = b.sym("fig2").springs[0].k
    return Derived(
        (
            _tidy(parts[0] * lengths[0] / (spring_k * ell_total)),
            _tidy(parts[1] * lengths[1] / (spring_k * ell_total)),
            sp.true if (parts[0] - parts[1]).is_positive else sp.false,
        ),
        "k_i l_i / (k l) for the spring's parts cut at X-hat (m_1 = m_2), and k_1 > k_2",
    )


def _normal_oscillation(b: _Bench) -> Derived:
    v = b.mode("fig2")
    ratio = _mode_ratio(b)
    fixed = all(component != 0 for component in v) and ratio.is_real
    return Derived(
        sp.true if fixed else sp.false,
        f"the engine's mode: phi = v cos(Omega t) with v real, phi_2/phi_1 = {sp.sstr(ratio)}: "
        "one frequency and a fixed phase",
    )


def _sum_rule_fig2(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    clamped = sp.Add(*[sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)])
    return Derived(
        _tidy(w2 - clamped),
        "Omega^2 minus the sum of the clamped frequencies K_ii/J_ii (each body alone, the other "
        "held), all from the engine's M, K: equal because K has rank one (one spring, two bodies)",
    )


def _eigenvalues_2x2(M: sp.Matrix, K: sp.Matrix) -> list[sp.Expr]:
    """The non-zero eigenvalues of M^-1 K (2 x 2, M diagonal)."""
    trace = _tidy(K[0, 0] / M[0, 0] + K[1, 1] / M[1, 1])
    det = _tidy((K[0, 0] * K[1, 1] - K[0, 1] * K[1, 0]) / (M[0, 0] * M[1, 1]))
    if det == 0:
        return [trace] if trace != 0 else []
    root = sp.sqrt(sp.factor(trace**2 - 4 * det))
    return [_tidy((trace - root) / 2), _tidy((trace + root) / 2)]


def _consequently(b: _Bench) -> Derived:
    """Sec. 5.4's "consequently": a system with normal oscillations (a wall spring on the hoop,
    joined to the cylinder) whose modes do not obey the sum rule."""
    sym = b.sym("fig4a")
    roots = b.omega2("fig4a")
    K = sym.stiffness_matrix
    clamped = sp.Add(*[K[i, i] / body.J for i, body in enumerate(sym.bodies)])
    trace_ok = _same(sp.Add(*roots), clamped)
    return Derived(
        tuple(roots),
        "the roots of det(K - omega^2 M) = 0 for a hoop tied to a wall and joined to a cylinder "
        "(two normal oscillations), against the clamped sum K_11/J_1 + K_22/J_2",
        why="does not follow: a normal oscillation (one frequency, a fixed phase) does not make "
        "Ω² = Ω₁² + Ω₂²; a hoop tied to a wall and joined to the cylinder oscillates in two normal "
        "modes, neither with ω² = Ω₁² + Ω₂²"
        + ("; only their sum ω₁² + ω₂² equals Ω₁² + Ω₂²" if trace_ok else "")
        + ". For the paper's systems the equality holds because K has rank one (one spring, two "
        "bodies): Ω² = tr(M⁻¹K) = K₁₁/J₁ + K₂₂/J₂",
        correction=r"\Omega^2=\mathrm{tr}\left(M^{-1}K\right)=\Omega_1^2+\Omega_2^2\ \text{because}"
        r"\ K\ \text{has rank one (one spring, two bodies), not because the oscillation is normal}",
    )


def _clamped_is_not_coupled(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    frequencies = [sp.Integer(0), w2]
    clamped = [_tidy(sym.stiffness_matrix[i, i] / body.J) for i, body in enumerate(sym.bodies)]
    among = any(_same(c_, f_) for c_ in clamped for f_ in frequencies)
    return Derived(
        sp.true if among else sp.false,
        "the coupled system's squared frequencies {0, Omega^2} (det(K - omega^2 M) = 0) against "
        "the clamped K_ii/J_i",
        why=f"the clamped frequencies Ω₁² = {sp.sstr(clamped[0])}, Ω₂² = {sp.sstr(clamped[1])} "
        "(one body held) are partial frequencies, not natural frequencies of the coupled system, "
        f"whose own are 0 and Ω² = {sp.sstr(w2)} = Ω₁² + Ω₂²",
        correction=r"\Omega_1,\ \Omega_2\ \text{are partial (clamped) frequencies; the coupled "
        r"system's are}\ 0\ \text{and}\ \Omega=\sqrt{\Omega_1^2+\Omega_2^2}",
    )


def _quadratic_energy(b: _Bench) -> Derived:
    """Sec. 5.4: E = alpha qdot^2/2 + beta q^2/2 conserved gives qddot = -(beta/alpha) q: a
    harmonic oscillation only when beta/alpha > 0 (for any real constants, not in general)."""

    def harmonic(**assumptions: bool) -> bool:
        alpha, beta = sp.symbols("alpha beta", **assumptions)
        q, qd, qdd = sp.symbols("q qdot qddot", real=True)
        energy_ = alpha * qd**2 / 2 + beta * q**2 / 2
        rate = sp.diff(energy_, qd) * qdd + sp.diff(energy_, q) * qd  # dE/dt
        (acc,) = sp.solve(sp.Eq(rate, 0), qdd)
        ratio = _tidy(acc / q)
        return bool(ratio.free_symbols <= {alpha, beta} and ratio.is_negative)

    return Derived(
        sp.true if harmonic(real=True, nonzero=True) else sp.false,
        "dE/dt = 0 gives qddot = -(beta/alpha) q (SymPy): harmonic at Omega = sqrt(beta/alpha) "
        "when beta/alpha > 0; for beta/alpha < 0, q grows as exp(sqrt(-beta/alpha) t)",
        condition="β/α > 0 (the energy has a minimum at q = 0): a quadratic energy with β < 0, "
        "as an inverted pendulum's, has constant α and β and does not oscillate",
        value_if=sp.true if harmonic(positive=True) else sp.false,
        correction=r"\ddot q=-\frac{\beta}{\alpha}q\ \text{is a harmonic oscillation only for}"
        r"\ \beta/\alpha>0",
    )


def _friction_in_mode(b: _Bench) -> Derived:
    friction = b.along_mode(b.friction_linear("fig2"), "fig2")
    return Derived(
        sp.true if any(f_ != 0 for f_ in friction) else sp.false,
        f"the engine's linearised frictions (M8) in the mode: {sp.sstr(tuple(friction))}",
    )


_ZERO_SUM_NAMES = {
    "two-hoops": "two hoops joined at their centres (Sec. 3)",
    "zero-sum": "a hoop of radius 3R₂/4 beside the cylinder on one floor, the spring level with "
    "the hoop's centre",
}


def _friction_not_needed(b: _Bench) -> Derived:
    """Sec. 4's "We need to ensure that there is no static friction force on rigid bodies": the
    centre of mass stays at rest when the frictions cancel (M8, (m_1 + m_2) Xddot = f_1 + f_2),
    which does not need each to vanish: two hoops joined at their centres (the paper's own
    Sec. 3) and a hoop of radius 3R_2/4 beside the cylinder, the spring level with the hoop's
    centre."""
    found = []
    for key in ("two-hoops", "zero-sum"):
        sym = b.sym(key)
        friction = b.friction_linear(key)
        if key == "zero-sum":  # the engine names the radii: the hoop's is 3R_2/4
            radius = sym.bodies[0].s
            friction = [sp.factor(f_.subs(radius, sp.Rational(3, 4) * R2)) for f_ in friction]
        if _same(sp.Add(*friction), 0) and friction[0] != 0:
            found.append((key, friction[0]))
    return Derived(
        sp.false if found else sp.true,
        "the engine's linearised frictions (M8) of two hoops joined at their centres and of a "
        "hoop of radius 3R_2/4 beside the cylinder with the spring level with the hoop's centre: "
        "their sum (m_1 + m_2) Xddot, and f_1",
        why="not needed: the centre of mass stays at rest when f₁ + f₂ = 0 ((m₁ + m₂)Ẍ = f₁ + f₂), "
        "which does not need each friction to vanish: "
        + "; ".join(
            f"{_ZERO_SUM_NAMES[key]}: f₁ = −f₂ = {sp.sstr(sp.factor(f_))}" for key, f_ in found
        )
        + "; f₁ = f₂ = 0 is sufficient, not necessary",
        correction=r"\dot X=0\ \Leftrightarrow\ f_1+f_2=0\ \text{(each}\ f_i=0\ \text{is "
        r"sufficient, not necessary)}",
    )


def _contact_axis(b: _Bench) -> Derived:
    """Sec. 3: about the contact line z' the friction has no arm: I'_i phiddot_i is the spring's
    torque alone (the engine's M7, derived without the friction)."""
    sym = b.sym("fig2")
    accelerations = b.accelerations("fig2")
    forces = [force[0] for force in sym.body_forces]
    value = tuple(
        _tidy(body.J * acc - body.s * force)
        for body, acc, force in zip(sym.bodies, accelerations, forces, strict=True)
    )
    return Derived(
        value,
        "I'_i phiddot_i - R F_ix with the engine's equations of motion (M7, Lagrange's, in which "
        "no friction appears) and its spring forces: the friction's torque about z' is zero (its "
        "line passes through z'), and z' may be used although it accelerates (its acceleration "
        "R phidot^2 points through the centre)",
    )


def _canonical(b: _Bench) -> Derived:
    return Derived(
        tuple(b.canonical("fig2")),
        "q_i = sqrt(J_i/m_i) phi_i makes the engine's T = sum J_i phidot_i^2/2 equal to "
        "sum m_i qdot_i^2/2 (p_i = m_i qdot_i)",
    )


def _hamiltonian(key: str = "fig2") -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        H, _ = b.hamiltonian(key, (q1, q2), (p1, p2))
        return Derived(
            H,
            "H = sum p_i^2/(2m_i) + V with the engine's V in q_i = sqrt(J_i/m_i) phi_i",
            condition=_CANONICAL_ORIENTATION,
            paper_if=_flip_first,
        )

    return derive


def _hamilton_equations(b: _Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        (sp.expand(sp.diff(H, q1)), sp.expand(sp.diff(H, q2))),
        "-pdot_i = dH/dq_i with the derived H",
        condition=_CANONICAL_ORIENTATION,
        paper_if=_flip_first_rate,
    )


def _factor_2_sqrt3(b: _Bench) -> Derived:
    # the paper's own (h) right-hand sides: the ratio of the second to the first
    common = k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3))
    first, second = common / sp.sqrt(2), common * sp.sqrt(2) / sp.sqrt(3)
    return Derived(
        _tidy(second / first), "the ratio of the right-hand sides of the paper's (h) (SymPy)"
    )


def _q_ratio(b: _Bench) -> Derived:
    v = b.mode("fig2")
    canon = b.canonical("fig2")
    sym = b.sym("fig2")
    sub = {qq: v[i] for i, qq in enumerate(sym.q)}
    ratio = _tidy(canon[1].xreplace(sub) / canon[0].xreplace(sub))
    # the pair (pdot_2/pdot_1, q_2 as a multiple of q_1) in the mode
    masses = [body.m for body in sym.bodies]
    value = (_tidy(masses[1] * ratio / masses[0]) * pd1, ratio * q1)
    return Derived(
        value,
        "pdot_2/pdot_1 = m_2 q_2/(m_1 q_1) and q_2/q_1 in the oscillating mode "
        "(q_i = sqrt(J_i/m_i) phi_i)",
        assumed=value,
        condition=_CANONICAL_ORIENTATION,
        paper_if=_flip_first,
    )


def _hamilton_final(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        sp.expand(m1 * w2) * q1,
        "-pdot_1 = m_1 Omega^2 q_1 in the mode (qddot_1 = -Omega^2 q_1) with the derived Omega^2",
    )


def _hamilton_to_ep(b: _Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.diff(H, p1), w2),
        "qdot_1 = dH/dp_1 from the derived H (so pdot_1 = m_1 qddot_1), and the engine's Omega^2",
    )


def _qdot(b: _Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived((sp.diff(H, p1), sp.diff(H, p2)), "qdot_i = dH/dp_i with the derived H")


def _interchangeable(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(_tidy(sp.sqrt(body.J / body.m) * body.q) for body in sym.bodies),
        "the canonical coordinates sqrt(J_i/m_i) q_i of the two masses (J_i = m_i): the "
        "positions themselves",
    )


def _potential_q(key: str, qs: tuple[Any, ...], ps: tuple[Any, ...]) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        _, V = b.hamiltonian(key, qs, ps)
        return Derived(
            V,
            "the engine's V in q_i = sqrt(J_i/m_i) phi_i",
            condition=_CANONICAL_ORIENTATION,
            paper_if=_flip_first,
            why="the coefficients' magnitudes are Ωᵢ/√(k/mᵢ); counted one way, the first is "
            "negative",
        )

    return derive


def _potential_fig3(b: _Bench) -> Derived:
    """App. C (k02): the Fig. 3 potential in q_3, q_4: exact (the spring turns with the bodies)
    and quadratic (the paper's small angles)."""
    sym = b.sym("fig3")
    _, V = b.hamiltonian("fig3", (q3, q4), (p3, p4))
    to_q = {
        body.q: sp.sqrt(body.m / body.J) * qq for body, qq in zip(sym.bodies, (q3, q4), strict=True)
    }
    exact = sym.potential.xreplace(to_q).xreplace(_fig3_geometry(b))
    return Derived(
        exact,
        "the engine's exact V of Fig. 3 in q_i = sqrt(J_i/m_i) phi_i, and its quadratic form",
        assumed=V,
        condition="the first canonical coordinate is counted the other way (q₃ with the hoop "
        "anticlockwise); the paper's own Sec. 4 spring force F = k(3R₂φ₂/2 − 2R₁φ₁) counts both "
        "angles one way, which gives the coefficients (−Ω₃/√(k/m₁), +Ω₄/√(k/m₂))",
        paper_if=_flip_first,
    )


def _coefficients(b: _Bench) -> Derived:
    _, V = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        tuple(_tidy(sp.sqrt(sp.diff(V, qq, 2) / k)) for qq in (q1, q2)),
        "|c_i| = sqrt(d2V/dq_i^2 / k) of the engine's V in canonical coordinates",
    )


def _clamped(key: str, *, roots: bool) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym(key)
        values = [sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)]
        values = [sp.sqrt(v) if roots else v for v in values]
        return Derived(
            tuple(_tidy(v) for v in values),
            "clamped (partial) frequencies sqrt(K_ii/J_i): each body alone, the other held "
            "(engine's M, K)",
        )

    return derive


def _subsystem(index: int) -> Callable[[_Bench], Derived]:
    """App. B: (alpha_i, beta_i) and Omega_i = sqrt(beta_i/alpha_i) in its three forms."""

    def derive(b: _Bench) -> Derived:
        sym = b.sym("fig2")
        J = sym.mass_matrix[index, index]
        K = sym.stiffness_matrix[index, index]
        root = _tidy(sp.sqrt(K / J))
        return Derived(
            (J, K, root, root, root),
            f"alpha = J_{index + 1} and beta = K_{index + 1}{index + 1} of the engine's M and K; "
            "Omega = sqrt(K_ii/J_i), body i alone with the other held (a clamped frequency)",
        )

    return derive


def _subsystem_energy(index: int) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym("fig2")
        held = {}
        for j, body in enumerate(sym.bodies):
            if j != index:
                held.update({body.q: 0, body.qd: 0})
        energy_ = sym.kinetic + sym.quadratic_potential
        return Derived(
            sp.expand(energy_.xreplace(held)),
            "the engine's T + V (quadratic) with the other body held (its angle and rate zero)",
        )

    return derive


def _second_subsystem_mass(b: _Bench) -> Derived:
    return Derived(
        b.sym("fig2").bodies[1].m,
        "the mass of the engine's body 2, the cylinder",
        why="the cylinder is body 2, of mass m₂, as the paper's own α₂ = (3/2)m₂R² writes it; "
        "m is the pulled body of App. A",
        correction="m_2",
    )


def _app_a_rotation(index: int) -> Callable[[_Bench], Derived]:
    """App. A: -k_i (R phi_i) R = I'_i phiddot_i in the mode, k_i the spring part's stiffness."""

    def derive(b: _Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        value = -w2 * body.q
        return Derived(
            (value, value),
            "phiddot_i = -Omega^2 phi_i in the engine's mode, against the paper's forms with "
            "k_i = k/w_j, the spring part's stiffness",
            paper_subs=dict(zip((k1, k2), _split(b), strict=True)),
        )

    return derive


def _app_a_friction_torque(index: int) -> Callable[[_Bench], Derived]:
    """App. A: -f_i R = I_i phiddot_i: the friction's torque about the centre turns the body
    (the spring acts at the centre)."""

    def derive(b: _Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        friction = b.friction_linear("fig2")[index]
        value = -w2 * body.q
        return Derived(
            (value, value),
            "phiddot_i = -Omega^2 phi_i in the engine's mode, against -f_i R/I_i with the "
            "engine's friction (M8, positive along +x) in the mode",
            paper_subs={(f1, f2)[index]: _tidy(friction.subs(phi2, _mode_ratio(b) * phi1))}
            if index == 0
            else {(f1, f2)[index]: _tidy(friction.subs(phi1, phi2 / _mode_ratio(b)))},
        )

    return derive


def _app_a_friction(index: int, *, middle: bool = False) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym("fig2")
        v = b.mode("fig2")
        f = b.along_mode(b.friction_linear("fig2"), "fig2")[index]
        body = sym.bodies[index]
        coefficient = _tidy(f / (body.s * v[index]))
        value = coefficient * body.s * body.q
        return Derived(
            (value, value) if index == 0 else value,
            "the engine's linearised friction (M8) in the mode, per R phi_i"
            + (", against the spring part's k_1 = k/w_2" if index == 0 else ""),
            why="the cylinder's I₂ = m₂R²/2 gives, with (A.3) and (A.4), f₂ = (k₂/3)Rφ₂, "
            "not (k₂/2)Rφ₂"
            if middle
            else "",
            correction=r"f_2=\frac{k_2}{3}R\phi_2=" + sp.latex(value) if middle else None,
            paper_subs={k1: _split(b)[0], k2: _split(b)[1]},
        )

    return derive


def _app_a_phi_ratio(b: _Bench) -> Derived:
    c = b.conserved("fig2")
    general = _tidy((P0 * t + D0 - c[1] * phi2) / c[0])  # phi_1 from c . phi = P_0 t + D_0
    value = _tidy(general / phi2)
    return Derived(
        value,
        "phi_1/phi_2 from the conserved c . phi = P_0 t + D_0 (zero mode of K)",
        assumed=_subs(value, {P0: 0, D0: 0}),
        condition=_ORIENTATION,
        paper_if=lambda e: -e,
    )


def _pull_equations(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    acc = _tidy((eq.rhs / body.J).subs(body.q, 0))
    return Derived(
        (acc, _pulled_friction(b, "pulled")),
        "phiddot = Q/J at phi = 0 from the engine's equation of motion (M7), and minus the "
        "engine's friction (M8)",
        paper_subs={I_: body.I},
    )


def _pull_phiddot(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    acc = _tidy((eq.rhs / body.J).subs(body.q, 0))
    return Derived(
        (body.s, acc, acc),
        "the engine's rolling constraint a = s phiddot (M2) and phiddot = Q/J at phi = 0 (M7)",
        paper_subs={I_: body.I, fpull: _pulled_friction(b, "pulled")},
    )


def _pull_at_floor(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    friction = _tidy(_pulled_friction(b, "pulled").subs(y, 0))
    acceleration = _tidy((body.s * eq.rhs / body.J).subs(body.q, 0).subs(y, 0))
    return Derived(
        (friction, acceleration),
        "minus the engine's friction and the centre's acceleration R Q/J of the body (I = "
        "gamma m R^2, any gamma) pulled at y = 0",
    )


def _reversal(b: _Bench) -> Derived:
    cylinder = _zero_friction_height(b, "pulled-cylinder")
    hoop = _zero_friction_height(b, "pulled-hoop")
    top = 2 * R  # the point of application moves along the vertical diameter AB, 0 <= y <= 2R
    sign_at_top = sp.sign(_tidy(_pulled_friction(b, "pulled-cylinder").subs(y, top) / F))
    unchanged = (hoop - top).is_nonnegative
    return Derived(
        (cylinder, sign_at_top, sp.true if unchanged else sp.false),
        "the engine's f(y) of a pulled cylinder: its zero and its sign (against F) at the top; "
        f"a pulled hoop's f(y) vanishes only at y = {sp.sstr(hoop)}, the top of the diameter AB",
    )


def _no_work(b: _Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        _tidy((body.s - R) * body.qd),
        "velocity of the contact point s phidot - R phidot of the engine's rolling body (M2): "
        "the friction's power is f times it",
    )


def _fig5_cylinder(b: _Bench) -> Derived:
    return Derived(
        _tidy(_pulled_friction(b, "pulled-cylinder").subs(y, 2 * R)),
        "minus the engine's friction of a cylinder pulled at y = 2R",
    )


def _fig5_labels(b: _Bench) -> Derived:
    return Derived(
        (_pulled_friction(b, "pulled-hoop"), _pulled_friction(b, "pulled-cylinder")),
        "the engine's f(y) of a hoop (body 1 in the paper) and a cylinder (body 2)",
        why="the labels are swapped: everywhere else body 1 is the hoop; f₁(y) (zero at 2R) is "
        "the hoop's line, f₂(y) (zero at 3R/2) the cylinder's",
    )


def _sum_rule_fig3(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    (w2,) = b.omega2("fig3")
    clamped = sp.Add(*[sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)])
    return Derived(
        (w2, _tidy(w2 - clamped)),
        "the non-zero root of det(K - Omega^2 M) = 0 and its difference from the clamped sum "
        "K_11/J_1 + K_22/J_2 (engine's M, K)",
    )


def _fig3_equal_forces(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    (first, _), (second, _) = sym.body_forces
    ratio = sp.Abs(_tidy(second / first))
    return Derived(
        ratio,
        "|F_2x/F_1x| of the engine's exact spring forces on the two bodies (Fig. 3): the two "
        "ends of one spring",
    )


def _relative_rates(b: _Bench) -> Derived:
    """The rates of epsilon_i = x_i - X-hat, with X-hat of eq. (c) (the engine's weights)."""
    sym = b.sym("fig2")
    w = b.weights("fig2")
    c = b.conserved("fig2")
    centre = [body.s * body.qd for body in sym.bodies]
    xhat_rate = sp.Add(*[w_ * v_ for w_, v_ in zip(w, centre, strict=True)])
    # the weights are those of the conserved c . phidot = P_0: X-hat moves at s P_0 / sum c
    scale = _tidy(w[0] * sym.bodies[0].s / c[0])
    if not _same(_tidy(w[1] * sym.bodies[1].s / c[1]), scale):
        raise RuntimeError("fig2: X-hat's weights are expected to be the conserved combination's")
    value = tuple(_tidy(v_ - scale * P0) for v_ in centre)
    if not _same(
        xhat_rate.subs(sym.bodies[0].qd, (P0 - c[1] * sym.bodies[1].qd) / c[0]), scale * P0
    ):
        raise RuntimeError("fig2: X-hat is expected to move at s P_0 / sum c")
    return Derived(
        value,
        "d/dt (x_i - X-hat) with the rolling constraint x_i = R phi_i (M2) and X-hat's velocity "
        "from the engine's conserved combination (M14)",
        assumed=_subs(value, {P0: 0}),
        why="X̂ moves uniformly at RP₀/(I'₁ + I'₂); it is the stationary origin only for a start "
        "from rest",
    )


def _methods_agree(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (w2,) * 4,
        "the engine's Omega^2 (non-zero root of det(K - Omega^2 M) = 0), against the paper's "
        "Omega^2 of (QQ1), of the speeds' display (Sec. 5.2), of (ep) and of Sec. 5.6",
    )


def _pull_eliminated(b: _Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        sp.Integer(0),
        "the paper's equation with f the engine's friction (M8) at phi = 0: the two sides agree",
        paper_subs={I_: body.I, fpull: _pulled_friction(b, "pulled")},
    )


def _fig3_spring_force(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    geometry = _fig3_geometry(b)
    exact = sym.body_forces[0][0].xreplace(geometry)
    (linear,) = sym.linearized([exact])
    return Derived(
        exact,
        "the engine's exact spring force on the hoop along x (M7) in the paper's Fig. 3",
        assumed=_tidy(linear),
        paper_subs=geometry,
        why="the exact force differs at third order in the angles: the spring turns with the "
        "bodies",
    )


# -- the catalogue -----------------------------------------------------------------------------


def _hoop_cylinder_hamiltonian(
    qa: sp.Symbol, qb: sp.Symbol, pa: sp.Symbol, pb: sp.Symbol, ca: sp.Expr, cb: sp.Expr
) -> sp.Expr:
    return pa**2 / (2 * m1) + pb**2 / (2 * m2) + k / 2 * (ca * qa + cb * qb) ** 2


_J1, _J2 = 2 * m1 * R**2, sp.Rational(3, 2) * m2 * R**2  # the paper's I'_1, I'_2 (Fig. 2)
_Omega1, _Omega2 = sp.sqrt(k / (2 * m1)), sp.sqrt(2 * k / (3 * m2))
_Omega3, _Omega4 = sp.sqrt(2 * k / m1), sp.sqrt(3 * k / (2 * m2))
_k1_paper = k * (3 * m2 + 4 * m1) / (3 * m2)
_k2_paper = k * (3 * m2 + 4 * m1) / (4 * m1)
_F2 = k * (R * phi2 - R * phi1)  # the spring force of Fig. 2 (Sec. 3)
_F3 = k * (sp.Rational(3, 2) * R2 * phi2 - 2 * R1 * phi1)  # the spring force of Fig. 3
_J31, _J32 = 2 * m1 * R1**2, sp.Rational(3, 2) * m2 * R2**2  # I'_1, I'_2 of Fig. 3
_TRUE = sp.true
# Omega^2 as the paper's four methods give it: (QQ1), the speeds' display of Sec. 5.2, (ep),
# Sec. 5.6's -pdot_1 = k(q_1/2 + 2m_1 q_1/(3m_2)) with pdot_1 = m_1 qddot_1
_METHODS = (
    k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
    (k / (2 * m1) + 2 * k / (3 * m2)),
    k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
    k / m1 * (half + 2 * m1 / (3 * m2)),
)


def _c(
    key: str,
    location: str,
    quote: str,
    statement: str,
    latex: str,
    quantity: str,
    paper: Any,
    system: str,
    derive: Callable[[_Bench], Derived],
    *assumptions: Assumption,
) -> Claim:
    return Claim(
        key, location, statement, latex, quantity, paper, system, derive, quote, assumptions
    )


def paper_claims() -> list[Claim]:
    """Every quantitative statement of the paper, in the paper's order."""
    return [
        # ---- Abstract
        _c(
            "abstract-cm-moves",
            "Abstract, sentence 1",
            "during normal modes of an oscillatory system consisting of a hoop and a cylinder "
            "joining their centers by an ideal spring, its central mass does not remain at rest",
            "in a normal mode of the hoop-cylinder system the centre of mass moves",
            r"\dot X\neq 0\ \text{in the normal mode}",
            r"\dot X\neq 0",
            _TRUE,
            "fig2",
            _cm_moves("fig2"),
        ),
        _c(
            "abstract-friction-cause",
            "Abstract, sentence 2",
            "This effect is due to the resultant external static friction forces acting on the "
            "system",
            "the centre of mass moves because the resultant static friction is not zero",
            r"(m_1+m_2)\ddot X=f_1+f_2\neq 0",
            r"\left((m_1+m_2)\ddot X-(f_1+f_2),\ f_1+f_2\neq 0\right)",
            (sp.Integer(0), _TRUE),
            "fig2",
            _friction_cause,
        ),
        _c(
            "same-inertia",
            "Abstract, sentence 2",
            "static friction forces acting on the system which disappears when the coupled "
            "rigid bodies have the same moment of inertia",
            "the resultant friction disappears when the bodies have the same moment of inertia",
            r"f_1+f_2=0\ \text{when}\ I_1=I_2",
            r"f_1+f_2",
            sp.Integer(0),
            "fig2, two-hoops, two-cylinders",
            _same_inertia,
        ),
        _c(
            "abstract-fig3",
            "Abstract, sentence 3",
            "in case of different moment of inertia by proper positioning the two fixed end "
            "points of the spring vertically, it is shown that the central mass of the system "
            "remains at rest",
            "with the spring's ends at the right heights (Fig. 3) the centre of mass stays at rest",
            r"\dot X=0\ \text{(Fig. 3)}",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            _RELEASED,
            _SMALL_ANGLES,
        ),
        _c(
            "abstract-methods",
            "Abstract, sentence 4",
            "The equation of motion of the coupled system is derived using dynamic equations, "
            "Lagrange's equations, Hamilton's equations and even by applying the conservation laws "
            "of energy and angular momentum.",
            "the four methods give the same equation of motion (the same Omega^2)",
            r"\Omega^2_{\text{Newton}}=\Omega^2_{E,L}=\Omega^2_{\text{Lagrange}}="
            r"\Omega^2_{\text{Hamilton}}",
            r"\left(\Omega^2,\ \Omega^2,\ \Omega^2,\ \Omega^2\right)",
            _METHODS,
            "fig2",
            _methods_agree,
        ),
        # ---- Sec. 1
        _c(
            "cm-theorem",
            "Sec. 1, paragraph 1",
            "in the absence of external forces, the center of mass (CM) of a mechanical system is "
            "stationary (or in uniform motion in a straight line)",
            "without external forces the centre of mass moves uniformly (Fig. 1)",
            r"\ddot X=0",
            r"\ddot X",
            sp.Integer(0),
            "fig1",
            _cm_theorem,
        ),
        # ---- Sec. 2: two point masses (Fig. 1)
        _c(
            "fig1-caption",
            "Fig. 1 caption",
            "Coupling without resulting external forces.",
            "no resultant external force acts on the two masses",
            r"\sum f_i=0,\quad \sum\left(N_i-m_ig\right)=0",
            r"\left(\sum f_i,\ \sum (N_i-m_ig)\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig1",
            _fig1_no_external,
        ),
        _c(
            "fig1-cm-at-rest-text",
            "Sec. 2, paragraph 2",
            r"It is easy to prove that the center of mass of the system ($X$) remains at rest.",
            "the centre of mass of two point masses stays at rest",
            r"\dot X=0",
            r"\dot X",
            sp.Integer(0),
            "fig1",
            _cm_velocity(
                "fig1", "the zero mode of K gives sum m_i xdot_i = P_0 (M14); X-hat is the CM"
            ),
            _RELEASED_FIG1,
        ),
        _c(
            "fig1-equal-forces",
            "Sec. 2, paragraph 2",
            r"the two end points of an ideal spring always exert the same amount of force "
            r"($F_1=F_2$)",
            "the spring pulls both masses equally",
            r"F_1=F_2",
            r"F_2/F_1",
            sp.Integer(1),
            "fig1",
            _fig1_end_forces,
            _FORCE_AMOUNTS,
        ),
        _c(
            "fig1-equations",
            "Sec. 2, eqs. (f1), (f2)",
            r"k\left(x_2-x_1\right)=m_1\ddot{x_1}, -k\left(x_2-x_1\right)=m_2\ddot{x_2}",
            "equations of motion of two point masses joined by a spring",
            r"k\left(x_2-x_1\right)=m_1\ddot{x_1},\quad -k\left(x_2-x_1\right)=m_2\ddot{x_2}",
            r"\left(m_1\ddot x_1,\ m_2\ddot x_2\right)",
            (k * (x2 - x1), -k * (x2 - x1)),
            "fig1",
            _fig1_eom,
        ),
        _c(
            "fig1-potential",
            "Sec. 2, display after eq. (f2)",
            r"U=\frac{k}{2}\left(x_2-x_1\right)^2",
            "potential energy of the spring",
            r"U=\frac{k}{2}\left(x_2-x_1\right)^2",
            "U",
            k / 2 * (x2 - x1) ** 2,
            "fig1",
            _fig1_potential,
        ),
        _c(
            "fig1-forces-from-u",
            "Sec. 2, sentence after eq. (f2)",
            r"the correct sign can easily be deduced as $F_1=-\partial_{x_1}U$ and "
            r"$F_2=-\partial_{x_2}U$",
            "the forces are minus the gradient of U",
            r"F_1=-\partial_{x_1}U,\quad F_2=-\partial_{x_2}U",
            r"\left(F_1,\ F_2\right)",
            (-sp.diff(k / 2 * (x2 - x1) ** 2, x1), -sp.diff(k / 2 * (x2 - x1) ** 2, x2)),
            "fig1",
            _fig1_forces_from_u,
        ),
        _c(
            "fig1-momentum-sum",
            "Sec. 2, displays after 'After adding equations (f1) and (f2)'",
            r"m_1\ddot{x_1}+m_2\ddot{x_2}=0, (m_1+m_2)\ddot{X}=0",
            "adding (f1) and (f2): the centre of mass does not accelerate",
            r"m_1\ddot{x_1}+m_2\ddot{x_2}=0,\quad (m_1+m_2)\ddot{X}=0",
            r"\left(m_1\ddot x_1+m_2\ddot x_2,\ (m_1+m_2)\ddot X\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig1",
            _fig1_momentum_sum,
        ),
        _c(
            "fig1-cm-at-rest",
            "Sec. 2, display X-dot = 0 and the sentence before it",
            "After integration over time, the solution corresponding to the initial conditions "
            "is if CM of the system remains at rest",
            "integrated with the initial conditions: the centre of mass stays at rest",
            r"\dot{X}=0",
            r"\dot X",
            sp.Integer(0),
            "fig1",
            _cm_velocity(
                "fig1", "the zero mode of K gives sum m_i xdot_i = P_0 (M14); X-hat is the CM"
            ),
            _RELEASED_FIG1,
        ),
        _c(
            "fig1-vertical",
            "Sec. 2, last sentence",
            "the spring forces are internal forces and external forces in the vertical direction "
            "cancel each other out",
            "the floor's normal forces balance the weights",
            r"N_i=m_ig",
            r"\left(N_1-m_1g,\ N_2-m_2g\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig1",
            _fig1_vertical,
        ),
        # ---- Sec. 3: hoop and cylinder (Fig. 2)
        _c(
            "fig2-horizontal",
            "Sec. 3, paragraph 1",
            "Both bodies are placed on a horizontal surface so that the orientation of the spring "
            "is also horizontal.",
            "two bodies of one radius R on one floor: the spring between their centres is level",
            r"R_1=R_2=R\ \Rightarrow\ F_{1y}=F_{2y}=0",
            r"\left(F_{1y},\ F_{2y}\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig2",
            _fig2_horizontal,
        ),
        _c(
            "fig2-dof",
            "Sec. 3, paragraph after Fig. 2",
            "The system still has two degrees of freedom",
            "the rolling pair has two degrees of freedom",
            r"n=2",
            "n",
            sp.Integer(2),
            "fig2",
            _fig2_dof,
        ),
        _c(
            "fig2-constraints",
            "Sec. 3, constraint relations",
            r"g_1=x_1-R\varphi_1=0\,\rightarrow\, x_1=R\varphi_1, "
            r"g_2=x_2-R\varphi_2=0\,\rightarrow\, x_2=R\varphi_2",
            "rolling without slipping: the centres move by R times the angles",
            r"x_1=R\varphi_1,\quad x_2=R\varphi_2",
            r"\left(x_1,\ x_2\right)",
            (R * phi1, R * phi2),
            "fig2",
            _fig2_constraints,
        ),
        _c(
            "contact-axis",
            "Sec. 3, paragraph after the constraint relations",
            r"Static friction forces ($f_1$, $f_2$) can be eliminated by the proper choice of the "
            r"axis of rotation",
            "about the contact lines z' the friction has no torque: the spring's torque alone "
            "turns each body",
            r"I'_i\ddot\varphi_i=RF_{ix}\ \text{about}\ z'\ \text{(no}\ f_i\text{)}",
            r"\left(I'_1\ddot\varphi_1-RF_{1x},\ I'_2\ddot\varphi_2-RF_{2x}\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig2",
            _contact_axis,
        ),
        _c(
            "fig2-rotation",
            "Sec. 3, eqs. (e), (f)",
            r"F_1R=I'_1\ddot{\varphi_1}, -F_2R=I'_2\ddot{\varphi_2}",
            "rotation about the contact lines, F R the spring's torque",
            r"F_1R=I'_1\ddot{\varphi_1},\quad -F_2R=I'_2\ddot{\varphi_2},\quad F_1=F_2=F",
            r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            (_F2 * R / _J1, -_F2 * R / _J2),
            "fig2",
            _fig2_eom,
        ),
        _c(
            "fig2-spring-force",
            "Sec. 3, sentence after eq. (f)",
            r"The spring forces are equal in magnitude and can be expressed as "
            r"$F=k\left(R\varphi_2-R\varphi_1\right)$.",
            "the spring force on the hoop, and the same size on the cylinder",
            r"F=k\left(R\varphi_2-R\varphi_1\right),\quad \lvert F_2\rvert=\lvert F_1\rvert",
            r"\left(F_{1x},\ \lvert F_{2x}\rvert\right)",
            (_F2, sp.Abs(_F2)),
            "fig2",
            _fig2_spring_force,
        ),
        _c(
            "steiner",
            "Sec. 3, Steiner's theorem (display after eq. (f))",
            r"I'_1=m_1R^2+m_1d^2=2m_1R^2, I'_2=\frac{1}{2}m_2R^2+m_2d^2=\frac{3}{2}m_2R^2",
            "moments of inertia about the contact lines (d = R)",
            r"I'_1=m_1R^2+m_1d^2=2m_1R^2,\quad I'_2=\frac{1}{2}m_2R^2+m_2d^2=\frac{3}{2}m_2R^2",
            r"\left(I'_1,\ I'_1,\ I'_2,\ I'_2\right)",
            (m1 * R**2 + m1 * R**2, _J1, m2 * R**2 / 2 + m2 * R**2, _J2),
            "fig2",
            _steiner,
        ),
        _c(
            "fig2-equations",
            "Sec. 3, eqs. (w2), (w22)",
            r"k\left(R\varphi_2-R\varphi_1\right)R=2m_1R^2\ddot{\varphi_1}, "
            r"-k\left(R\varphi_2-R\varphi_1\right)R=\frac{3}{2}m_2R^2\ddot{\varphi_2}",
            "equations of rotation about the contact lines",
            r"k\left(R\varphi_2-R\varphi_1\right)R=2m_1R^2\ddot{\varphi_1},\quad "
            r"-k\left(R\varphi_2-R\varphi_1\right)R=\frac{3}{2}m_2R^2\ddot{\varphi_2}",
            r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            (_F2 * R / _J1, -_F2 * R / _J2),
            "fig2",
            _fig2_eom,
        ),
        _c(
            "fig2-sum",
            "Sec. 3, display after eq. (w22)",
            r"2m_1R^2\ddot{\varphi_1}+\frac{3}{2}m_2R^2\ddot{\varphi_2}=0",
            "adding (w2) and (w22)",
            r"2m_1R^2\ddot{\varphi_1}+\frac{3}{2}m_2R^2\ddot{\varphi_2}=0",
            r"I'_1\ddot\varphi_1+I'_2\ddot\varphi_2",
            sp.Integer(0),
            "fig2",
            _fig2_sum,
        ),
        _c(
            "angular-momentum",
            "Sec. 3, eqs. (rel1), (g)",
            r"I'_1\dot{\varphi_1}+I'_2\dot{\varphi_2}=0 , "
            r"\boldsymbol{L}_1+\boldsymbol{L}_2=0,\,\rightarrow\,\boldsymbol{L}_1=-\boldsymbol{L}_2",
            "integrated: the angular momenta about the contact lines cancel, L_1 = -L_2",
            r"I'_1\dot{\varphi_1}+I'_2\dot{\varphi_2}=0,\quad \boldsymbol{L}_1+\boldsymbol{L}_2=0",
            r"I'_1\dot\varphi_1+I'_2\dot\varphi_2",
            sp.Integer(0),
            "fig2",
            _momentum,
            _RELEASED,
        ),
        _c(
            "phase-opposition",
            "Sec. 3, sentence after eq. (g)",
            r"According to the equation (\ref{g}), the rolling bodies oscillate in phase "
            r"opposition.",
            "the bodies oscillate in phase opposition",
            r"\boldsymbol{L}_1=-\boldsymbol{L}_2\ \Rightarrow\ \text{phase opposition}",
            r"\operatorname{sign}\left(\varphi_2/\varphi_1\right)",
            sp.Integer(-1),
            "fig2",
            _phase_opposition,
        ),
        _c(
            "w-relation",
            "Sec. 3, eq. (w) and the line after it",
            r"2m_1R\dot{\varphi_1}+\frac{3}{2}m_2R\dot{\varphi_2}=0, "
            r"2m_1\dot{x_1}+\frac{3}{2}m_2\dot{x_2}=0",
            "(rel1) divided by R, in the centres' velocities",
            r"2m_1R\dot{\varphi_1}+\frac{3}{2}m_2R\dot{\varphi_2}=0,\quad "
            r"2m_1\dot{x_1}+\frac{3}{2}m_2\dot{x_2}=0",
            r"\left(2m_1R\dot\varphi_1+\tfrac32 m_2R\dot\varphi_2,\ "
            r"2m_1\dot x_1+\tfrac32 m_2\dot x_2\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig2",
            _w_relation,
            _RELEASED,
        ),
        _c(
            "cm-moves",
            "Sec. 3, sentence before eq. (w) and the line after it",
            r"shows that during the oscillation $X$ will not be at rest any longer",
            "the centre of mass moves during the oscillation",
            r"2m_1\dot{x_1}+\frac{3}{2}m_2\dot{x_2}=0\,\rightarrow\,\dot{X}\neq 0",
            r"\dot X\neq 0",
            _TRUE,
            "fig2",
            _cm_moves("fig2"),
        ),
        _c(
            "stationary-point",
            "Sec. 3, eq. (c)",
            r"\hat{X}=\frac{I'_1x_1+I'_2x_2}{I'_1+I'_2}",
            "the new stationary point X-hat",
            r"\hat{X}=\frac{I'_1x_1+I'_2x_2}{I'_1+I'_2}",
            r"\dot{\hat X}",
            sp.Integer(0),
            "fig2",
            _stationary_point,
            _RELEASED,
        ),
        _c(
            "same-spring-forces",
            "Sec. 3, paragraph after eq. (c)",
            "the bodies are subjected to the same spring forces (and their torques)",
            "the two bodies feel the same spring force and torque",
            r"F_2=F_1,\quad F_2R=F_1R",
            r"\left(F_{2x}/F_{1x},\ Q_2/Q_1\right)",
            (sp.Integer(1), sp.Integer(1)),
            "fig2",
            _same_spring_forces,
            _SPRING_MAGNITUDES,
        ),
        _c(
            "friction-ratio",
            "Sec. 3, paragraph after eq. (c)",
            r"different amounts of static friction forces ($f_1/f_2=3/2$)",
            "ratio of the static friction forces",
            r"f_1/f_2=3/2",
            r"f_1/f_2",
            sp.Rational(3, 2),
            "fig2",
            _friction_ratio,
            _FRICTION_AMOUNTS,
        ),
        _c(
            "two-hoops",
            "Sec. 3, display after eq. (c)",
            r"\hat{X}=\frac{2m_1R^2x_1+2m_2R^2x_2}{2m_1R^2+2m_2R^2}=\frac{m_1x_1+m_2x_2}{m_1+m_2}",
            "for two hoops X-hat is the centre of mass",
            r"\hat{X}=\frac{2m_1R^2x_1+2m_2R^2x_2}{2m_1R^2+2m_2R^2}=\frac{m_1x_1+m_2x_2}{m_1+m_2}",
            r"\left(w_1,\ w_2\right)",
            (m1 / (m1 + m2), m2 / (m1 + m2)),
            "two-hoops",
            _stationary("two-hoops"),
        ),
        _c(
            "two-cylinders",
            "Sec. 3, last paragraph",
            "The same is true for two cylinders.",
            "for two cylinders too X-hat is the centre of mass",
            r"\hat{X}=\frac{m_1x_1+m_2x_2}{m_1+m_2}\ \text{(two cylinders)}",
            r"\left(w_1,\ w_2\right)",
            (m1 / (m1 + m2), m2 / (m1 + m2)),
            "two-cylinders",
            _stationary("two-cylinders"),
        ),
        _c(
            "steady-cm",
            "Sec. 3, last sentence",
            "under the right conditions, the steady state of the CM can be achieved for different "
            "moments of inertia specifically with a hoop and a cylinder",
            "a hoop and a cylinder can keep the centre of mass at rest (Fig. 3)",
            r"\dot X=0\ \text{(hoop and cylinder, Fig. 3)}",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            _RELEASED,
            _SMALL_ANGLES,
        ),
        _c(
            "fig2-caption",
            "Fig. 2 caption",
            "Coupling in the presence of static friction forces.",
            "static friction acts on the hoop and the cylinder",
            r"f_i\neq 0",
            r"f\neq 0",
            _TRUE,
            "fig2",
            _friction_in_mode,
        ),
        # ---- Sec. 4: the frictionless system (Fig. 3)
        _c(
            "friction-must-vanish",
            "Sec. 4, paragraph 1",
            "We need to ensure that there is no static friction force on rigid bodies.",
            "a stationary centre of mass needs both static frictions to vanish",
            r"\dot X=0\ \Rightarrow\ f_1=f_2=0",
            r"\dot X=0\ \text{requires}\ f_1=f_2=0",
            _TRUE,
            "two-hoops, zero-sum",
            _friction_not_needed,
        ),
        _c(
            "fric",
            "Sec. 4, eq. (fric)",
            r"linearly decreasing function \begin{equation} "
            r"f(y)=F\left(1-\frac{mR}{I+mR^2}\,y\right)",
            "static friction of a body pulled horizontally at height y, linear and decreasing",
            r"f(y)=F\left(1-\frac{mR}{I+mR^2}\,y\right)",
            r"\left(f(y),\ f''(y),\ \operatorname{sign}(-f'(y)/F)\right)",
            (F * (1 - m * R * y / (I_ + m * R**2)), sp.Integer(0), sp.Integer(1)),
            "pulled",
            _fric,
        ),
        _c(
            "zero-friction-heights",
            "Sec. 4, paragraph after eq. (fric)",
            r"In the case of a thin ring (hoop), the static friction force turns to zero at the "
            r"position of the pulling force $y_1=2R$. Similarly, in the case of a homogeneous "
            r"cylinder the static friction force is eliminated if the position of the pulling "
            r"force $y_2=3/2R$.",
            "heights of a pull that needs no friction",
            r"y_1=2R,\quad y_2=3/2R",
            r"\left(y_1,\ y_2\right)",
            (2 * R, sp.Rational(3, 2) * R),
            "pulled-hoop, pulled-cylinder",
            _heights,
        ),
        _c(
            "fric-coupled",
            "Sec. 4, paragraph after eq. (fric)",
            r"it seems reasonable to assume that the equation (\ref{fric}) remains valid",
            "(fric) remains valid for the coupled system, with the varying spring force",
            r"f_i=-F_{ix}\left(1-\frac{m_iR_i\,y_i}{I_i+m_iR_i^2}\right):\ y_i=R\ "
            r"\text{(Fig. 2)},\ y_1=2R_1,\ y_2=\tfrac32R_2\ \text{(Fig. 3)}",
            r"\left(f_1,\ f_2\right)_{\text{Fig. 2}},\ \left(f_1,\ f_2\right)_{\text{Fig. 3}}",
            (
                -Fx1 * (1 - m1 * R * R / (m1 * R**2 + m1 * R**2)),
                -Fx2 * (1 - m2 * R * R / (m2 * R**2 / 2 + m2 * R**2)),
                -Fx1 * (1 - m1 * R1 * 2 * R1 / (m1 * R1**2 + m1 * R1**2)),
                -Fx2 * (1 - m2 * R2 * sp.Rational(3, 2) * R2 / (m2 * R2**2 / 2 + m2 * R2**2)),
            ),
            "fig2, fig3",
            _fric_coupled,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-no-friction",
            "Sec. 4, paragraph after eq. (fric)",
            "we have constructed a coupled system that is not subjected to static friction forces "
            "during oscillation yet it does not slip",
            "no static friction acts on the system of Fig. 3 during the oscillation",
            r"f_1=f_2=0",
            r"\left(f_1,\ f_2\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig3",
            _fig3_friction,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-geometry",
            "Sec. 4, sentence before Fig. 3",
            r"Since the spring must be horizontal and the centers of rigid bodies are at the same "
            r"height $R_1=R_2/2$.",
            "a horizontal spring between the zero-friction heights, centres level: R1 = R2/2",
            r"R_1=R_2/2",
            "R_1",
            R2 / 2,
            "pulled-hoop, pulled-cylinder",
            _geometry,
            _LEVEL,
        ),
        _c(
            "fig3-caption",
            "Fig. 3 caption",
            "Coupling without friction forces yet ensuring no-slip condition.",
            "the system of Fig. 3 needs no static friction",
            r"f_1=f_2=0",
            r"\left(f_1,\ f_2\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig3",
            _fig3_friction,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-equations",
            "Sec. 4, eqs. (a), (b)",
            r"F\left(2R_1\right)=I'_1\ddot{\varphi_1}, "
            r"-F\left(\frac{3}{2}R_2\right)=I'_2\ddot{\varphi_2}",
            "equations of rotation of the frictionless system",
            r"F\left(2R_1\right)=I'_1\ddot{\varphi_1},\quad -F\left(\frac{3}{2}R_2\right)="
            r"I'_2\ddot{\varphi_2}",
            r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            (_F3 * 2 * R1 / _J31, -_F3 * sp.Rational(3, 2) * R2 / _J32),
            "fig3",
            _fig3_eom,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-spring-force",
            "Sec. 4, display after eq. (b)",
            r"F=k\left(\frac{3}{2}R_2\varphi_2-2R_1\varphi_1\right)",
            "the spring force of the frictionless system",
            r"F=k\left(\frac{3}{2}R_2\varphi_2-2R_1\varphi_1\right)",
            r"F_{1x}",
            _F3,
            "fig3",
            _fig3_spring_force,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-forces",
            "Sec. 4, display after 'Dividing equation (a) and (b)'",
            r"F=\frac{I'_1}{2R_1}\ddot{\varphi_1}, -F=\frac{I'_2}{\frac{3}{2}R_2}\ddot{\varphi_2}",
            "(a) and (b) divided by the lever arms",
            r"F=\frac{I'_1}{2R_1}\ddot{\varphi_1},\quad -F=\frac{I'_2}{\frac{3}{2}R_2}"
            r"\ddot{\varphi_2}",
            r"\left(\frac{I'_1}{2R_1}\ddot\varphi_1,\ "
            r"\frac{I'_2}{\frac32 R_2}\ddot\varphi_2\right)",
            (_F3, -_F3),
            "fig3",
            _fig3_combination(
                lambda sym: [
                    (sym.bodies[0].J / (2 * R1), 0),
                    (0, sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
                ],
                "I'_i phiddot_i over the lever arms 2R_1, 3R_2/2, with the engine's equations of "
                "motion (exact, and linearised)",
            ),
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-sum",
            "Sec. 4, first two lines after 'the spring forces are eliminated'",
            r"\frac{I'_1}{2R_1}\ddot{\varphi_1}+\frac{I'_2}{\frac{3}{2}R_2}\ddot{\varphi_2}=0, "
            r"\frac{2m_1R_1^2}{2R_1}\ddot{\varphi_1}+\frac{\frac{3}{2}m_2R_2^2}{\frac{3}{2}R_2}"
            r"\ddot{\varphi_2}=0",
            "the two divided equations added, with I'_1 = 2m_1R_1^2, I'_2 = (3/2)m_2R_2^2",
            r"\frac{I'_1}{2R_1}\ddot{\varphi_1}+\frac{I'_2}{\frac{3}{2}R_2}\ddot{\varphi_2}=0",
            r"\left(\frac{I'_1}{2R_1}\ddot\varphi_1+\frac{I'_2}{\frac32 R_2}\ddot\varphi_2,\ "
            r"m_1R_1\ddot\varphi_1+m_2R_2\ddot\varphi_2\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig3",
            _fig3_combination(
                lambda sym: [
                    (sym.bodies[0].J / (2 * R1), sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
                    (_J31 / (2 * R1), _J32 / (sp.Rational(3, 2) * R2)),
                ],
                "the two sums with the engine's equations of motion (exact, and linearised)",
            ),
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-cm-acceleration",
            "Sec. 4, third line after 'the spring forces are eliminated'",
            r"m_1R_1\ddot{\varphi_1}+m_2R_2\ddot{\varphi_2}=0",
            "the spring forces cancel: m1 R1 phi1'' + m2 R2 phi2'' = 0",
            r"m_1R_1\ddot{\varphi_1}+m_2R_2\ddot{\varphi_2}=0",
            r"m_1R_1\ddot\varphi_1+m_2R_2\ddot\varphi_2",
            sp.Integer(0),
            "fig3",
            _fig3_combination(
                lambda sym: [(sym.bodies[0].m * R1, sym.bodies[1].m * R2)],
                "sum m_i R_i phiddot_i with the engine's equations of motion (exact, and "
                "linearised)",
            ),
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-cm-acceleration-x",
            "Sec. 4, display after 'taking into account the constraint relations'",
            r"taking into account the constraint relations of $x_1=R_1\varphi_1$ and "
            r"$x_2=R_2\varphi_2$ it is obtained that \begin{eqnarray} "
            r"m_1\ddot{x_1}+m_2\ddot{x_2}=0",
            "with x_i = R_i phi_i the centre of mass does not accelerate",
            r"x_1=R_1\varphi_1,\quad x_2=R_2\varphi_2,\quad m_1\ddot{x_1}+m_2\ddot{x_2}=0",
            r"\left(x_1,\ x_2,\ m_1\ddot x_1+m_2\ddot x_2\right)",
            (R1 * phi1, R2 * phi2, sp.Integer(0)),
            "fig3",
            _fig3_x,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-cm-at-rest",
            "Sec. 4, eq. (bb)",
            r"m_1\dot{x_1}+m_2\dot{x_2}=0\,\rightarrow\,\dot{X}=0",
            "integrated: the centre of mass is at rest",
            r"m_1\dot{x_1}+m_2\dot{x_2}=0\,\rightarrow\,\dot{X}=0",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            _RELEASED,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-cm-stationary-again",
            "Sec. 4, sentence after eq. (bb)",
            "As expected, in the absence of friction forces, the CM became stationary again.",
            "without friction the centre of mass is stationary again (Fig. 3)",
            r"\dot X=0\ \text{(Fig. 3)}",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            _RELEASED,
            _SMALL_ANGLES,
        ),
        _c(
            "fig3-equal-spring-forces",
            "Sec. 4, last paragraph",
            "the magnitude of the spring forces acting on the system are equal",
            "the spring pulls the two bodies equally hard",
            r"\lvert F_2\rvert=\lvert F_1\rvert",
            r"\lvert F_{2x}/F_{1x}\rvert",
            sp.Integer(1),
            "fig3",
            _fig3_equal_forces,
        ),
        _c(
            "fig3-torques-differ",
            "Sec. 4, last paragraph",
            r"as equations (\ref{a}) and (\ref{b}) shows the magnitudes of their torques are "
            r"different",
            "the spring's torques about the two contact lines differ",
            r"\lvert F\,2R_1\rvert\neq\lvert F\,\tfrac32 R_2\rvert",
            r"2R_1\neq\tfrac32 R_2",
            _TRUE,
            "fig3",
            _fig3_torques_differ,
        ),
        _c(
            "fig3-angular-momentum",
            "Sec. 4, last sentence",
            r"Therefore $\boldsymbol{L}$ is not constant of motion in this case.",
            "the torques differ, so angular momentum is not conserved",
            r"F\left(2R_1\right)\neq F\left(\tfrac{3}{2}R_2\right)\ \Rightarrow\ "
            r"\boldsymbol{L}\ \text{not constant}",
            r"\dot L",
            _F3 * (2 * R1 - sp.Rational(3, 2) * R2),
            "fig3",
            _fig3_angular_momentum,
        ),
        # ---- Sec. 5: the coupled system by several methods
        _c(
            "qq2",
            "Sec. 5, eq. (QQ2) and the sentence after it",
            r"where $q$ is any relevant coordinate ($x_1$, $x_2$, $\varphi_1$, $\varphi_2$,\dots)",
            "every coordinate oscillates harmonically",
            r"\ddot{q}+\Omega^2 q=0,\quad q=x_1,\ x_2,\ \varphi_1,\ \varphi_2,\dots",
            r"\ddot\varphi_1+\Omega^2\varphi_1",
            sp.Integer(0),
            "fig2",
            _qq2,
            _RELEASED,
        ),
        _c(
            "phi-relation",
            "Sec. 5.1, display after 'integration over time'",
            r"2m_1\varphi_1=-\frac{3}{2}m_2\varphi_2,\,\rightarrow\,"
            r"\varphi_2=-\frac{4m_1}{3m_2}\varphi_1",
            "integrating (w) gives the angle relation",
            r"2m_1\varphi_1=-\frac{3}{2}m_2\varphi_2,\,\rightarrow\,"
            r"\varphi_2=-\frac{4m_1}{3m_2}\varphi_1",
            r"\varphi_2",
            -4 * m1 / (3 * m2) * phi1,
            "fig2",
            lambda b: _phi_relation(b, flip=False),
            _RELEASED,
        ),
        _c(
            "phi-substituted",
            "Sec. 5.1, first line of the display ending with eq. (QQ1)",
            r"k\left(-R\frac{4m_1}{3m_2}\varphi_1-R\varphi_1\right)R=2m_1R^2\ddot{\varphi_1}",
            "phi_2 substituted into (w2)",
            r"k\left(-R\frac{4m_1}{3m_2}\varphi_1-R\varphi_1\right)R=2m_1R^2\ddot{\varphi_1}",
            r"2m_1R^2\ddot\varphi_1",
            k * (-R * 4 * m1 / (3 * m2) * phi1 - R * phi1) * R,
            "fig2",
            _substituted,
        ),
        _c(
            "qq1",
            "Sec. 5.1, eq. (QQ1)",
            r"\ddot{\varphi_1}+\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)\varphi_1=0",
            "equation of motion of the coupled system",
            r"\ddot{\varphi_1}+\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)\varphi_1=0",
            r"\Omega^2",
            k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
            "fig2",
            _omega2("fig2"),
        ),
        _c(
            "omega2-fig2",
            "Sec. 5.1, eq. (QQQ1)",
            r"\Omega^2=\left(\frac{k}{2m_1}+\frac{2k}{3m_2}\right)",
            "angular frequency of the coupled system",
            r"\Omega^2=\left(\frac{k}{2m_1}+\frac{2k}{3m_2}\right)",
            r"\Omega^2",
            k / (2 * m1) + 2 * k / (3 * m2),
            "fig2",
            _omega2("fig2"),
        ),
        _c(
            "omega2-terms",
            "Sec. 5.1, sentence after eq. (QQQ1)",
            "The terms in the angular frequency expression can be identified as the natural "
            "frequencies of the subsystems.",
            "the two terms of Omega^2 are the squared frequencies of the subsystems (each body "
            "alone, the other held)",
            r"\frac{k}{2m_1}=\Omega_1^2,\quad \frac{2k}{3m_2}=\Omega_2^2",
            r"\left(K_{11}/J_1,\ K_{22}/J_2\right)",
            (k / (2 * m1), 2 * k / (3 * m2)),
            "fig2",
            _clamped_terms,
        ),
        # ---- Sec. 5.2: conservation of E and L
        _c(
            "speeds-kinematics",
            "Sec. 5.2, paragraph 1",
            r"the kinematics of the harmonic motion tells us that $v_1=A_1\Omega$ and "
            r"$v_2=A_2\Omega$",
            "largest speed = amplitude times Omega",
            r"v_1=A_1\Omega,\quad v_2=A_2\Omega",
            r"\left(v_1/A_1,\ v_2/A_2\right)",
            (Omega, Omega),
            "fig2",
            _speed_over_amplitude,
        ),
        _c(
            "amplitude-sum",
            "Sec. 5.2, paragraph 1",
            r"Since their sum is equal to the maximal deformation of the spring $A=A_1+A_2$",
            "the amplitudes add up to the spring's deformation",
            r"A=A_1+A_2",
            r"A_1+A_2",
            A,
            "fig2",
            _amplitude_sum,
        ),
        _c(
            "omega-from-sum",
            "Sec. 5.2, paragraph 1",
            r"therefore $v_1+v_2=A\Omega$ and it implies that $\Omega=(v_1+v_2)/A$",
            "Omega from the sum of the largest speeds",
            r"v_1+v_2=A\Omega,\quad \Omega=(v_1+v_2)/A",
            r"\left(v_1+v_2,\ (v_1+v_2)/A\right)",
            (A * Omega, Omega),
            "fig2",
            _omega_from_sum,
        ),
        _c(
            "relative-coordinates",
            "Sec. 5.2, paragraph 1",
            r"these relative coordinates can be expressed in terms of angular coordinates as "
            r"$\varepsilon_1=R\phi_1$ and  $\varepsilon_2=R\phi_2$",
            "the coordinates about X-hat follow the angles: epsilon_i = R phi_i",
            r"\varepsilon_1=R\phi_1,\quad \varepsilon_2=R\phi_2",
            r"\left(\dot\varepsilon_1,\ \dot\varepsilon_2\right)",
            (R * phid1, R * phid2),
            "fig2",
            _relative_rates,
            _RELEASED,
        ),
        _c(
            "energy",
            "Sec. 5.2, eq. (mu)",
            r"\frac{k}{2}A^2=\frac{1}{2}\left(2m_1R^2\right)\dot{\Phi_1}^2+\frac{1}{2}"
            r"\left(\frac{3}{2}m_2R^2\right)\dot{\Phi_2}^2",
            "conservation of energy at the largest speeds",
            r"\frac{k}{2}A^2=\frac{1}{2}\left(2m_1R^2\right)\dot{\Phi_1}^2+\frac{1}{2}"
            r"\left(\frac{3}{2}m_2R^2\right)\dot{\Phi_2}^2",
            r"\tfrac12 I'_1\dot\Phi_1^2+\tfrac12 I'_2\dot\Phi_2^2",
            k / 2 * A**2,
            "fig2",
            _energy,
        ),
        _c(
            "nu",
            "Sec. 5.2, eq. (nu)",
            r"0=2m_1R^2\dot{\Phi_1}-\frac{3}{2}m_2R^2\dot{\Phi_2}",
            "angular momentum at the largest speeds",
            r"0=2m_1R^2\dot{\Phi_1}-\frac{3}{2}m_2R^2\dot{\Phi_2}",
            r"\dot\Phi_2",
            4 * m1 / (3 * m2) * Phid1,
            "fig2",
            _nu,
            _MAXIMAL,
        ),
        _c(
            "undeformed-at-top-speed",
            "Sec. 5.2, paragraph after eq. (nu)",
            "the maximum angular velocities are related to the undeformed state of the spring",
            "both bodies are fastest when the spring is undeformed",
            r"\text{deformation}=0\ \text{at}\ \dot\Phi_1,\ \dot\Phi_2",
            r"\text{deformation at the largest speeds}",
            sp.Integer(0),
            "fig2",
            _undeformed_at_top_speed,
        ),
        _c(
            "kinetic-rotational",
            "Sec. 5.2, paragraph after eq. (nu)",
            "Using the instantaneous axes of rotation, the kinetic energies appear to be purely "
            "rotational energies.",
            "about the contact lines the kinetic energy is purely rotational",
            r"T=\frac{1}{2}I'_1\dot\varphi_1^2+\frac{1}{2}I'_2\dot\varphi_2^2",
            "T",
            _J1 * phid1**2 / 2 + _J2 * phid2**2 / 2,
            "fig2",
            _kinetic,
        ),
        _c(
            "orbital-spin",
            "Sec. 5.2, paragraph after eq. (nu)",
            r"the angular momentum associated with its orbital motion ($mR^2\dot{\Phi}$) and spin "
            r"($1/2mR^2\dot{\Phi}$) are not separated",
            "the cylinder's angular momentum about the contact line: orbital plus spin",
            r"I'_2=mR^2+\tfrac12 mR^2",
            r"\left(m_2R^2,\ I_2\right)",
            (m2 * R**2, m2 * R**2 / 2),
            "fig2",
            _orbital_spin,
        ),
        _c(
            "phidot-relation",
            "Sec. 5.2, paragraph after eq. (nu)",
            r"it can be expressed $\dot{\Phi_2}=(4m_1/3m_2)\dot{\Phi_1}$ from equation (\ref{nu})",
            "(nu) solved for the cylinder's largest angular speed",
            r"\dot{\Phi_2}=(4m_1/3m_2)\dot{\Phi_1}",
            r"\dot\Phi_2",
            4 * m1 / (3 * m2) * Phid1,
            "fig2",
            _nu,
            _MAXIMAL,
        ),
        _c(
            "speeds-from-rates",
            "Sec. 5.2, paragraph after eq. (nu)",
            r"the maximal velocities of the centers of the rolling bodies are "
            r"$v_1=R\dot{\Phi_1}$ and $v_2=R\dot{\Phi_2}$",
            "largest centre speeds from the largest angular speeds",
            r"v_1=R\dot{\Phi_1},\quad v_2=R\dot{\Phi_2}",
            r"\left(v_1/\dot\Phi_1,\ v_2/\dot\Phi_2\right)",
            (R, R),
            "fig2",
            _speed_over_rate,
        ),
        _c(
            "speeds",
            "Sec. 5.2, eqs. (om), (pi)",
            r"v_1=A\left[\frac{3km_2}{2m_1\left(4m_1+3m_2\right)}\right]^{1/2}, "
            r"v_2=A\left[\frac{8km_1}{3m_2\left(4m_1+3m_2\right)}\right]^{1/2}",
            "largest speeds of the centres",
            r"v_1=A\left[\frac{3km_2}{2m_1\left(4m_1+3m_2\right)}\right]^{1/2},\quad "
            r"v_2=A\left[\frac{8km_1}{3m_2\left(4m_1+3m_2\right)}\right]^{1/2}",
            r"\left(v_1,\ v_2\right)",
            (
                A * sp.sqrt(3 * k * m2 / (2 * m1 * (4 * m1 + 3 * m2))),
                A * sp.sqrt(8 * k * m1 / (3 * m2 * (4 * m1 + 3 * m2))),
            ),
            "fig2",
            _speeds,
        ),
        _c(
            "omega-from-speeds",
            "Sec. 5.2, display after eq. (pi)",
            r"\Omega=\frac{v_1+v_2}{A}= \left(\sqrt{\frac{3m_2}{2m_1}}+\sqrt{\frac{8m_1}{3m_2}}"
            r"\right)\frac{\sqrt{k}}{\sqrt{4m_1+3m_2}}= \left({\frac{3m_2+4m_1}{\sqrt{2m_13m_2}}}"
            r"\right)\frac{\sqrt{k}}{\sqrt{4m_1+3m_2}}= \left[k\frac{3m_2+4m_1}{2m_13m_2}"
            r"\right]^{1/2}=\left[\frac{k}{2m_1}+\frac{2k}{3m_2}\right]^{1/2}",
            "Omega from the largest speeds, in four forms",
            r"\Omega=\left(\sqrt{\frac{3m_2}{2m_1}}+\sqrt{\frac{8m_1}{3m_2}}\right)"
            r"\frac{\sqrt{k}}{\sqrt{4m_1+3m_2}}=\left(\frac{3m_2+4m_1}{\sqrt{2m_1\,3m_2}}\right)"
            r"\frac{\sqrt{k}}{\sqrt{4m_1+3m_2}}=\left[k\frac{3m_2+4m_1}{2m_1\,3m_2}\right]^{1/2}"
            r"=\left[\frac{k}{2m_1}+\frac{2k}{3m_2}\right]^{1/2}",
            r"\left(\Omega,\ \Omega,\ \Omega,\ \Omega\right)",
            (
                (sp.sqrt(3 * m2 / (2 * m1)) + sp.sqrt(8 * m1 / (3 * m2)))
                * sp.sqrt(k)
                / sp.sqrt(4 * m1 + 3 * m2),
                (3 * m2 + 4 * m1)
                / sp.sqrt(2 * m1 * 3 * m2)
                * sp.sqrt(k)
                / sp.sqrt(4 * m1 + 3 * m2),
                sp.sqrt(k * (3 * m2 + 4 * m1) / (2 * m1 * 3 * m2)),
                sp.sqrt(k / (2 * m1) + 2 * k / (3 * m2)),
            ),
            "fig2",
            _omega_chain,
        ),
        _c(
            "omega-identical",
            "Sec. 5.2, sentence after the display for Omega",
            r"It is easy to recognize that $\Omega^2$ is identical to equation (\ref{QQQ1}).",
            "Omega^2 from the speeds equals (QQQ1)",
            r"\left[\frac{k}{2m_1}+\frac{2k}{3m_2}\right]=\Omega^2\ \text{of (QQQ1)}",
            r"\Omega^2",
            k / (2 * m1) + 2 * k / (3 * m2),
            "fig2",
            _omega2("fig2"),
        ),
        _c(
            "isochronism",
            "Sec. 5.2, paragraph after the display for Omega",
            r"although the maximum velocities of the centers of the bodies include the $A$ "
            r"amplitude of the motion, the angular frequency (and time period) does not",
            "the speeds depend on the amplitude, Omega does not",
            r"\partial v_i/\partial A\neq 0,\quad \partial\Omega/\partial A=0",
            r"\left(\partial v_i/\partial A\neq 0,\ \partial\Omega/\partial A\right)",
            (_TRUE, sp.Integer(0)),
            "fig2",
            _isochronism,
        ),
        _c(
            "isochronism-unique",
            "Sec. 5.2, paragraph after the display for Omega",
            "This phenomenon is unique to harmonic oscillation",
            "only a harmonic oscillator has a period independent of its amplitude",
            r"T\ \text{independent of the amplitude}\ \Rightarrow\ \text{harmonic}",
            r"T\ \text{of a non-harmonic oscillator depends on its amplitude}",
            _TRUE,
            "none",
            _isotonic,
        ),
        _c(
            "amplitudes",
            "Sec. 5.2, display after 'so their values can be determined'",
            r"v_1=A_1\Omega\,\rightarrow\,A_1=A\frac{3m_2}{4m_1+3m_2}, "
            r"v_2=A_2\Omega\,\rightarrow\,A_2=A\frac{4m_1}{4m_1+3m_2}",
            "amplitudes of the centres about X-hat",
            r"A_1=A\frac{3m_2}{4m_1+3m_2},\quad A_2=A\frac{4m_1}{4m_1+3m_2}",
            r"\left(A_1,\ A_2\right)",
            (A * 3 * m2 / (4 * m1 + 3 * m2), A * 4 * m1 / (4 * m1 + 3 * m2)),
            "fig2",
            _amplitudes,
        ),
        _c(
            "amplitudes-equal-masses",
            "Sec. 5.2, last sentence",
            r"For the same masses $A_1=(3/7)A$ and $A_2=(4/7)A$",
            "amplitudes for equal masses",
            r"A_1=(3/7)A,\quad A_2=(4/7)A",
            r"\left(A_1,\ A_2\right)",
            (sp.Rational(3, 7) * A, sp.Rational(4, 7) * A),
            "fig2",
            _amplitudes_equal_masses,
        ),
        _c(
            "cm-not-stationary-equal-masses",
            "Sec. 5.2, last sentence",
            "we also came to conclusion that the CM does not remain stationary",
            "with equal masses and unequal amplitudes the centre of mass moves",
            r"m_1=m_2,\ A_1\neq A_2\ \Rightarrow\ \dot X\neq 0",
            r"\dot X\neq 0\ (m_1=m_2)",
            _TRUE,
            "fig2",
            _cm_equal_masses,
        ),
        # ---- Sec. 5.3: Euler-Lagrange
        _c(
            "lagrangian",
            "Sec. 5.3, display after 'the Lagrangian can be written in the following form'",
            r"\mathcal{L}=\frac{1}{2}I'_1\dot{\phi_1}^2+\frac{1}{2}I'_2\dot{\phi_2}^2- "
            r"\frac{1}{2}k\left(\varepsilon_1+\varepsilon_2\right)^2",
            "the Lagrangian about X-hat",
            r"\mathcal{L}=\frac{1}{2}I'_1\dot{\phi_1}^2+\frac{1}{2}I'_2\dot{\phi_2}^2-"
            r"\frac{1}{2}k\left(\varepsilon_1+\varepsilon_2\right)^2,\quad "
            r"\varepsilon_i=R\phi_i",
            r"\mathcal{L}",
            _J1 * phid1**2 / 2 + _J2 * phid2**2 / 2 - k / 2 * (R * phi1 + R * phi2) ** 2,
            "fig2",
            _lagrangian,
        ),
        _c(
            "spring-part-equations",
            "Sec. 5.3, eqs. (Q1), (Q2)",
            r"-k_1\left(R\phi_1\right)R=I'_1\ddot{\phi_1}, -k_2\left(R\phi_2\right)R="
            r"I'_2\ddot{\phi_2}",
            "each body moves as if tied to X-hat by its part of the spring (k_1, k_2)",
            r"-k_1\left(R\phi_1\right)R=I'_1\ddot{\phi_1},\quad -k_2\left(R\phi_2\right)R="
            r"I'_2\ddot{\phi_2}",
            r"\left(\ddot\phi_1,\ \ddot\phi_2\right)",
            (-k1 * R**2 * phi1 / _J1, -k2 * R**2 * phi2 / _J2),
            "fig2",
            _parts_in_mode,
        ),
        _c(
            "spring-parts",
            "Sec. 5.3, eq. (part)",
            r"\frac{1}{k}=\frac{1}{k_1}+\frac{1}{k_2}",
            "the two spring parts in series",
            r"\frac{1}{k}=\frac{1}{k_1}+\frac{1}{k_2}",
            r"\frac{1}{k_1}+\frac{1}{k_2}",
            1 / k,
            "fig2",
            _k_series,
        ),
        _c(
            "lagrange-equations",
            "Sec. 5.3, eqs. (al), (be)",
            r"I'_1\ddot{\phi_1}=-k\left(R\phi_1+R\phi_2\right)R, "
            r"\frac{d}{d t}\left(\frac{\partial\mathcal{L}}{\partial\dot{\phi_2}}\right)="
            r"\frac{\partial\mathcal{L}}{\partial\phi_2}\rightarrow "
            r"I'_2\ddot{\phi_2}=-k\left(R\phi_1+R\phi_2\right)R",
            "Euler-Lagrange equations",
            r"I'_1\ddot{\phi_1}=-k\left(R\phi_1+R\phi_2\right)R,\quad "
            r"I'_2\ddot{\phi_2}=-k\left(R\phi_1+R\phi_2\right)R",
            r"\left(I'_1\ddot\phi_1,\ I'_2\ddot\phi_2\right)",
            (-k * (R * phi1 + R * phi2) * R, -k * (R * phi1 + R * phi2) * R),
            "fig2",
            _eom_flipped,
        ),
        _c(
            "ga",
            "Sec. 5.3, eq. (ga)",
            r"2m_1R^2\ddot{\phi_1}=\frac{3}{2}m_2R^2\ddot{\phi_2}",
            "the right-hand sides are equal",
            r"2m_1R^2\ddot{\phi_1}=\frac{3}{2}m_2R^2\ddot{\phi_2}",
            r"\ddot\phi_2",
            4 * m1 / (3 * m2) * phidd1,
            "fig2",
            _ga,
        ),
        _c(
            "de",
            "Sec. 5.3, eq. (de)",
            r"2m_1\phi_1=\frac{3}{2}m_2\phi_2\,\rightarrow\,\phi_2=\frac{4m_1}{3m_2}\phi_1",
            "(ga) integrated twice",
            r"2m_1\phi_1=\frac{3}{2}m_2\phi_2\,\rightarrow\,\phi_2=\frac{4m_1}{3m_2}\phi_1",
            r"\phi_2",
            4 * m1 / (3 * m2) * phi1,
            "fig2",
            lambda b: _phi_relation(b, flip=True),
            _RELEASED,
            _ORIGIN,
        ),
        _c(
            "ep0",
            "Sec. 5.3, eq. (ep0)",
            r"-k\left(R\phi_1+R\frac{4m_1}{3m_2}\phi_1\right)R=2m_1R^2\ddot{\phi_1}",
            "phi_2 of (de) substituted into (al)",
            r"-k\left(R\phi_1+R\frac{4m_1}{3m_2}\phi_1\right)R=2m_1R^2\ddot{\phi_1}",
            r"2m_1R^2\ddot\phi_1",
            -k * (R * phi1 + R * 4 * m1 / (3 * m2) * phi1) * R,
            "fig2",
            _mode_equation(0),
        ),
        _c(
            "ep",
            "Sec. 5.3, eq. (ep)",
            r"\ddot{\phi_1}+\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)\phi_1=0",
            "the differential equation of the oscillation",
            r"\ddot{\phi_1}+\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)\phi_1=0",
            r"\Omega^2",
            k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
            "fig2",
            _omega2("fig2"),
        ),
        _c(
            "ep-identical",
            "Sec. 5.3, sentence after eq. (ep)",
            r"One can see that equation (\ref{ep}) is identical to equation (\ref{QQ1}).",
            "(ep) and (QQ1) are the same equation",
            r"\text{(ep)}\equiv\text{(QQ1)}",
            r"\Omega^2",
            k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
            "fig2",
            _omega2("fig2"),
        ),
        _c(
            "pe",
            "Sec. 5.3, eq. (pe)",
            r"-k\left(R\frac{3m_2}{4m_1}\phi_2+R\phi_2\right)R=\frac{3}{2}m_2R^2\ddot{\phi_2}",
            "phi_1 in terms of phi_2 substituted into (be)",
            r"-k\left(R\frac{3m_2}{4m_1}\phi_2+R\phi_2\right)R=\frac{3}{2}m_2R^2\ddot{\phi_2}",
            r"\tfrac32 m_2R^2\ddot\phi_2",
            -k * (R * 3 * m2 / (4 * m1) * phi2 + R * phi2) * R,
            "fig2",
            _mode_equation(1),
        ),
        _c(
            "phi1-from-de",
            "Sec. 5.3, sentence before eq. (pe)",
            r"substitute $\phi_1=(3m_2/4m_1)\phi_2$ into equation (\ref{be})",
            "(de) solved for phi_1",
            r"\phi_1=(3m_2/4m_1)\phi_2",
            r"\phi_1/\phi_2",
            3 * m2 / (4 * m1),
            "fig2",
            _app_a_phi_ratio,
            _RELEASED,
            _ORIGIN,
        ),
        _c(
            "k1-k2",
            "Sec. 5.3, eqs. (k1), (k2)",
            r"k_1=k\frac{3m_2+4m_1}{3m_2}, k_2=k\frac{3m_2+4m_1}{4m_1}",
            "stiffnesses of the spring parts about X-hat",
            r"k_1=k\frac{3m_2+4m_1}{3m_2},\quad k_2=k\frac{3m_2+4m_1}{4m_1}",
            r"\left(k_1,\ k_2\right)",
            (_k1_paper, _k2_paper),
            "fig2",
            _k_parts,
        ),
        _c(
            "part-satisfied",
            "Sec. 5.3, sentence after eq. (k2)",
            r"thus equation (\ref{part}) is inherently satisfied using the analytical description",
            "(k1), (k2) satisfy (part)",
            r"\frac{1}{k_1}+\frac{1}{k_2}=\frac{1}{k}\ \text{with (k1), (k2)}",
            r"\frac{1}{k_1}+\frac{1}{k_2}",
            1 / _k1_paper + 1 / _k2_paper,
            "fig2",
            _k_inverse_sum,
        ),
        _c(
            "k-equal",
            "Sec. 5.3, second sentence after eq. (k2)",
            r"Note $k_1=k_2$ (and $A_1=A_2$) if $m_1/m_2=3/4$",
            "k1 = k2 (and A1 = A2) if m1/m2 = 3/4",
            r"k_1=k_2\ (A_1=A_2)\ \text{if}\ m_1/m_2=3/4",
            r"m_1/m_2\ \text{from}\ k_1=k_2,\ A_1=A_2",
            (sp.Rational(3, 4), sp.Rational(3, 4)),
            "fig2",
            _k_equal,
        ),
        _c(
            "k-equal-masses",
            "Sec. 5.3, display after eq. (k2) and the words before it",
            r"but they are not equal for the same masses: \begin{eqnarray} "
            r"k_1=\frac{7k}{3},\quad k_2=\frac{7k}{4}",
            "spring parts for equal masses",
            r"k_1=\frac{7k}{3},\quad k_2=\frac{7k}{4}",
            r"\left(k_1,\ k_2\right)",
            (7 * k / 3, 7 * k / 4),
            "fig2",
            _k_equal_masses,
        ),
        _c(
            "xhat-three-sevenths",
            "Sec. 5.3, last paragraph",
            r"if $m_1=m_2$ and $x_1=0$ the position of the stationary point is "
            r"$\hat{X}=(3/7)l$ which is actually the length of the left spring part",
            "for m1 = m2 and x1 = 0, X-hat = (3/7) l, the length of the left part",
            r"\hat{X}=(3/7)l",
            r"\hat X",
            sp.Rational(3, 7) * ell_total,
            "fig2",
            _xhat_left,
        ),
        _c(
            "right-part",
            "Sec. 5.3, last paragraph",
            r"the length of the right side spring part is therefore $l-\hat{X}=(4/7)l$",
            "the right part's length",
            r"l-\hat{X}=(4/7)l",
            r"l-\hat X",
            sp.Rational(4, 7) * ell_total,
            "fig2",
            _xhat_right,
        ),
        _c(
            "shorter-stiffer",
            "Sec. 5.3, last paragraph",
            r"The shorter the spring section, the greater its stiffness, therefore $k_1>k_2$",
            "a part's stiffness is inversely proportional to its length, so k1 > k2 (m1 = m2)",
            r"k_i\,l_i=k\,l,\quad k_1>k_2",
            r"\left(k_1l_1/(kl),\ k_2l_2/(kl),\ k_1>k_2\right)",
            (sp.Integer(1), sp.Integer(1), _TRUE),
            "fig2",
            _shorter_stiffer,
        ),
        # ---- Sec. 5.4: natural frequencies
        _c(
            "normal-oscillation",
            "Sec. 5.4, paragraph 1",
            "It means that both parts of the system move sinusoidally with the same frequency and "
            "with a fixed phase relation.",
            "in the normal oscillation both bodies move at one frequency with a fixed phase",
            r"\varphi_i=v_i\cos\Omega t",
            r"\text{one frequency, fixed phase}",
            _TRUE,
            "fig2",
            _normal_oscillation,
        ),
        _c(
            "sum-rule-consequently",
            "Sec. 5.4, paragraph 1",
            "Consequently the angular frequency squared of the system must be equal to the sum of "
            "the natural frequency squared of the two parts.",
            "a normal oscillation implies that Omega^2 is the sum of the parts' squared "
            "frequencies",
            r"\text{normal oscillation}\ \Rightarrow\ \Omega^2=\Omega_1^2+\Omega_2^2",
            r"\omega_n^2\ \text{of a system with normal oscillations}",
            (
                (k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2),
                (k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2),
            ),
            "fig4a",
            _consequently,
        ),
        _c(
            "clamped-is-coupled",
            "Sec. 5.4, paragraph 1",
            "The resulting vibration is one of the natural frequencies of the coupled system.",
            "a body's frequency with the other anchored is a natural frequency of the coupled "
            "system",
            r"\Omega_1,\ \Omega_2\in\{\text{natural frequencies of the coupled system}\}",
            r"\Omega_i^2\in\{0,\ \Omega^2\}",
            _TRUE,
            "fig2",
            _clamped_is_not_coupled,
        ),
        _c(
            "quadratic-energy",
            "Sec. 5.4, sentence after eq. (qee)",
            r"If the parameters $\alpha$ and $\beta$ are constants, this quadratic energy "
            r"expression guarantees the ability of the system to oscillate harmonically, "
            r"regardless of its construction.",
            "a conserved energy alpha qdot^2/2 + beta q^2/2 means harmonic oscillation",
            r"E=\frac{1}{2}\alpha\dot{q}^2+\frac{1}{2}\beta q^2\ \Rightarrow\ "
            r"\ddot q=-\frac{\beta}{\alpha}q",
            r"\text{harmonic}",
            _TRUE,
            "none",
            _quadratic_energy,
        ),
        _c(
            "sum-rule",
            "Sec. 5.4, display after eq. (qee)",
            r"\Omega_{f}^2=\frac{k}{2m_1}+\frac{2k}{3m_2}\equiv\Omega_1^2+\Omega_2^2",
            "Omega squared of Fig. 2 is the sum of the subsystems' squared frequencies",
            r"\Omega_{f}^2=\frac{k}{2m_1}+\frac{2k}{3m_2}\equiv\Omega_1^2+\Omega_2^2",
            r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            sp.Integer(0),
            "fig2",
            _sum_rule_fig2,
        ),
        # ---- Sec. 5.5: what the natural frequencies are for
        _c(
            "frequencies-detect-errors",
            "Sec. 5.5, paragraph 1",
            "knowledge of natural frequencies helps students to detect errors that may occur "
            "during the calculation",
            "the subsystems' frequencies check Omega^2 of the coupled system: Omega^2 = Omega_1^2 "
            "+ Omega_2^2",
            r"\Omega^2=\Omega_1^2+\Omega_2^2",
            r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            sp.Integer(0),
            "fig2",
            _sum_rule_fig2,
        ),
        # ---- Sec. 5.6: Hamilton
        _c(
            "lagrangian-hamilton",
            "Sec. 5.6, eq. (l)",
            r"\mathcal{L}=m_1R^2\dot{\phi_1}^2+\frac{3}{4}m_2R^2\dot{\phi_2}^2- "
            r"\frac{k}{2}\left(R\phi_1+R\phi_2\right)^2",
            "the Lagrangian compared with H",
            r"\mathcal{L}=m_1R^2\dot{\phi_1}^2+\frac{3}{4}m_2R^2\dot{\phi_2}^2-"
            r"\frac{k}{2}\left(R\phi_1+R\phi_2\right)^2",
            r"\mathcal{L}",
            m1 * R**2 * phid1**2
            + sp.Rational(3, 4) * m2 * R**2 * phid2**2
            - k / 2 * (R * phi1 + R * phi2) ** 2,
            "fig2",
            _lagrangian,
        ),
        _c(
            "hamiltonian",
            "Sec. 5.6, eq. (k)",
            r"\mathcal{H}=\frac{p_1^2}{2m_1}+\frac{p_2^2}{2m_2}+\frac{k}{2}\left(\frac{q_1}"
            r"{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)^2",
            "the Hamiltonian",
            r"\mathcal{H}=\frac{p_1^2}{2m_1}+\frac{p_2^2}{2m_2}+\frac{k}{2}\left(\frac{q_1}"
            r"{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)^2",
            r"\mathcal{H}",
            _hoop_cylinder_hamiltonian(q1, q2, p1, p2, 1 / sp.sqrt(2), sp.sqrt(2) / sp.sqrt(3)),
            "fig2",
            _hamiltonian(),
        ),
        _c(
            "canonical-coordinates",
            "Sec. 5.6, paragraph after eq. (k)",
            r"As a result of this we get $q_1=\sqrt{2}R\phi_1$ and $q_2=\sqrt{3/2}R\phi_2$.",
            "the canonical coordinates",
            r"q_1=\sqrt{2}R\phi_1,\quad q_2=\sqrt{3/2}R\phi_2",
            r"\left(q_1,\ q_2\right)",
            (sp.sqrt(2) * R * phi1, sp.sqrt(sp.Rational(3, 2)) * R * phi2),
            "fig2",
            _canonical,
        ),
        _c(
            "hamilton-equations",
            "Sec. 5.6, eq. (h) and the line after it",
            r"-\dot{p_1}=k\left(\frac{q_1}{\sqrt{2}}+ \frac{\sqrt{2}q_2}{\sqrt{3}}\right)"
            r"\frac{1}{\sqrt{2}}, -\dot{p_2}=\frac{\partial\mathcal{H}}{\partial q_2}\,"
            r"\rightarrow\, -\dot{p_2}=k\left(\frac{q_1}{\sqrt{2}}+ \frac{\sqrt{2}q_2}"
            r"{\sqrt{3}}\right)\frac{\sqrt{2}}{\sqrt{3}}",
            "Hamilton's equations",
            r"-\dot{p_1}=k\left(\frac{q_1}{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)"
            r"\frac{1}{\sqrt{2}},\quad -\dot{p_2}=k\left(\frac{q_1}{\sqrt{2}}+\frac{\sqrt{2}q_2}"
            r"{\sqrt{3}}\right)\frac{\sqrt{2}}{\sqrt{3}}",
            r"\left(-\dot p_1,\ -\dot p_2\right)",
            (
                sp.expand(k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) / sp.sqrt(2)),
                sp.expand(
                    k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) * sp.sqrt(2) / sp.sqrt(3)
                ),
            ),
            "fig2",
            _hamilton_equations,
        ),
        _c(
            "factor-two-over-root-three",
            "Sec. 5.6, sentence after eq. (h)",
            r"the right-hand sides of the two equations become equal if equation (\ref{h}) is "
            r"multiplied by $2/\sqrt{3}$",
            "(h) times 2/sqrt(3) has the second equation's right-hand side",
            r"\frac{1}{\sqrt{2}}\cdot\frac{2}{\sqrt{3}}=\frac{\sqrt{2}}{\sqrt{3}}",
            r"\text{ratio of the right-hand sides}",
            2 / sp.sqrt(3),
            "none",
            _factor_2_sqrt3,
        ),
        _c(
            "canonical-ratio",
            "Sec. 5.6, display after eq. (h)",
            r"\dot{p_2}=\dot{p_1}\frac{2}{\sqrt{3}}\,\rightarrow\,q_2=\frac{m_1}{m_2}"
            r"\frac{2}{\sqrt{3}}q_1",
            "the canonical coordinates in the mode",
            r"\dot{p_2}=\dot{p_1}\frac{2}{\sqrt{3}}\,\rightarrow\,q_2=\frac{m_1}{m_2}"
            r"\frac{2}{\sqrt{3}}q_1",
            r"\left(\dot p_2,\ q_2\right)",
            (2 / sp.sqrt(3) * pd1, m1 / m2 * 2 / sp.sqrt(3) * q1),
            "fig2",
            _q_ratio,
            _RELEASED,
            _ORIGIN,
        ),
        _c(
            "hamilton-motion",
            "Sec. 5.6, display after 'Substituting q_2 into equation (h)'",
            r"-\dot{p_1}=k\left(\frac{q_1}{2}+ \frac{2m_1}{3m_2}q_1\right)",
            "the equation of motion in canonical coordinates",
            r"-\dot{p_1}=k\left(\frac{q_1}{2}+\frac{2m_1}{3m_2}q_1\right)",
            r"-\dot p_1",
            sp.expand(k * (q1 / 2 + 2 * m1 / (3 * m2) * q1)),
            "fig2",
            _hamilton_final,
        ),
        _c(
            "hamilton-is-ep",
            "Sec. 5.6, sentence after the equation of motion in canonical coordinates",
            r"Since $\dot{p_1}=m_1\ddot{q_1}$ this equation of motion is equivalent to equation "
            r"(\ref{ep}).",
            "with pdot_1 = m_1 qddot_1 it is (ep)",
            r"\dot{p_1}=m_1\ddot{q_1},\quad \frac{k}{m_1}\left(\frac12+\frac{2m_1}{3m_2}\right)"
            r"=\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)",
            r"\left(\dot q_1,\ \Omega^2\right)",
            (p1 / m1, k / m1 * (half + 2 * m1 / (3 * m2))),
            "fig2",
            _hamilton_to_ep,
        ),
        _c(
            "qdot",
            "Sec. 5.6, the other two Hamilton's equations",
            r"\dot{q_1}=\frac{p_1}{m_1}, \dot{q_2}=\frac{\partial\mathcal{H}}{\partial p_2}\,"
            r"\rightarrow\,\dot{q_2}=\frac{p_2}{m_2}",
            "the other two Hamilton's equations",
            r"\dot{q_1}=\frac{p_1}{m_1},\quad \dot{q_2}=\frac{p_2}{m_2}",
            r"\left(\dot q_1,\ \dot q_2\right)",
            (p1 / m1, p2 / m2),
            "fig2",
            _qdot,
        ),
        _c(
            "point-masses-canonical",
            "Sec. 5.6, last paragraph",
            r"the coordinates in $U$ term of the Lagrangian and the Hamiltonian are "
            r"interchangeable",
            "for two point masses the canonical coordinates are the positions",
            r"q_i=x_i",
            r"\left(q_1,\ q_2\right)",
            (x1, x2),
            "fig1",
            _interchangeable,
        ),
        # ---- Sec. 7: conclusion
        _c(
            "conclusion-cm-moves",
            "Sec. 7, sentence 1",
            "during normal modes of an oscillatory system consisting of a hoop and a cylinder "
            "joining their centers by an ideal spring, its CM does not remain at rest",
            "in a normal mode of the hoop-cylinder system the centre of mass moves",
            r"\dot X\neq 0\ \text{in the normal mode}",
            r"\dot X\neq 0",
            _TRUE,
            "fig2",
            _cm_moves("fig2"),
        ),
        _c(
            "conclusion-friction-cause",
            "Sec. 7, sentence 2",
            "This effect is due to the resultant external forces acting on the system",
            "the centre of mass moves because the resultant external force is not zero",
            r"(m_1+m_2)\ddot X=f_1+f_2\neq 0",
            r"\left((m_1+m_2)\ddot X-(f_1+f_2),\ f_1+f_2\neq 0\right)",
            (sp.Integer(0), _TRUE),
            "fig2",
            _friction_cause,
        ),
        _c(
            "conclusion-same-inertia",
            "Sec. 7, sentence 2",
            "resultant external forces acting on the system which disappears when the coupled "
            "rigid bodies have the same moment of inertia",
            "the resultant external force disappears when the bodies have the same moment of "
            "inertia",
            r"f_1+f_2=0\ \text{when}\ I_1=I_2",
            r"f_1+f_2",
            sp.Integer(0),
            "fig2, two-hoops, two-cylinders",
            _same_inertia,
        ),
        _c(
            "conclusion-fig3",
            "Sec. 7, sentence 3",
            "in case of different moment of inertia by proper positioning the two fixed end points "
            "of the spring vertically, it was shown that the CM of the system remains at rest",
            "with the spring's ends at the right heights (Fig. 3) the centre of mass stays at rest",
            r"\dot X=0\ \text{(Fig. 3)}",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            _RELEASED,
            _SMALL_ANGLES,
        ),
        _c(
            "conclusion-methods",
            "Sec. 7, sentence 4",
            "The equation of motion of the coupled system has also been derived using dynamic "
            "equations, Lagrange's equations, Hamilton's equations and even by applying the "
            "conservation laws of energy and angular momentum.",
            "the four methods give the same equation of motion (the same Omega^2)",
            r"\Omega^2_{\text{Newton}}=\Omega^2_{E,L}=\Omega^2_{\text{Lagrange}}="
            r"\Omega^2_{\text{Hamilton}}",
            r"\left(\Omega^2,\ \Omega^2,\ \Omega^2,\ \Omega^2\right)",
            _METHODS,
            "fig2",
            _methods_agree,
        ),
        _c(
            "conclusion-check",
            "Sec. 7, sentence 5",
            "the natural frequencies of the subsystems are easy to calculate and therefore provide "
            "a way to check the equations of motion obtained by other methods",
            "the subsystems' frequencies check Omega^2 of the coupled system: Omega^2 = Omega_1^2 "
            "+ Omega_2^2",
            r"\Omega^2=\Omega_1^2+\Omega_2^2",
            r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            sp.Integer(0),
            "fig2",
            _sum_rule_fig2,
        ),
        # ---- App. A: static friction
        _c(
            "relative-coordinates-app-a",
            "App. A, paragraph 1",
            r"we can introduce angular coordinates by taking into account the constraint relations "
            r"as $\varepsilon_1=R\phi_1$ and $\varepsilon_2=R\phi_2$",
            "the coordinates about X-hat follow the angles: epsilon_i = R phi_i",
            r"\varepsilon_1=R\phi_1,\quad \varepsilon_2=R\phi_2",
            r"\left(\dot\varepsilon_1,\ \dot\varepsilon_2\right)",
            (R * phid1, R * phid2),
            "fig2",
            _relative_rates,
            _RELEASED,
        ),
        _c(
            "app-a-hoop-rotation",
            "App. A, first display, line 1",
            r"-k_1\left(R\phi_1\right)R=I'_1\ddot{\phi_1}\,\rightarrow\,\ddot{\phi_1}="
            r"-\frac{k_1}{2m_1}\phi_1",
            "the hoop about its contact line, tied to X-hat by k_1",
            r"-k_1\left(R\phi_1\right)R=I'_1\ddot{\phi_1}\,\rightarrow\,\ddot{\phi_1}="
            r"-\frac{k_1}{2m_1}\phi_1",
            r"\left(\ddot\phi_1,\ \ddot\phi_1\right)",
            (-k1 * R**2 * phi1 / _J1, -k1 / (2 * m1) * phi1),
            "fig2",
            _app_a_rotation(0),
        ),
        _c(
            "app-a-hoop-friction-torque",
            "App. A, first display, line 2",
            r"-f_1R=I_1\ddot{\phi_1}\,\rightarrow\,\ddot{\phi_1}=-\frac{f_1}{m_1R}",
            "the hoop about its centre, turned by the friction alone",
            r"-f_1R=I_1\ddot{\phi_1}\,\rightarrow\,\ddot{\phi_1}=-\frac{f_1}{m_1R}",
            r"\left(\ddot\phi_1,\ \ddot\phi_1\right)",
            (-f1 * R / (m1 * R**2), -f1 / (m1 * R)),
            "fig2",
            _app_a_friction_torque(0),
        ),
        _c(
            "app-a-cylinder-rotation",
            "App. A, first display, line 3",
            r"-k_2\left(R\phi_2\right)R=I'_2\ddot{\phi_2}\,\rightarrow\,\ddot{\phi_2}="
            r"-\frac{2k_2}{3m_2}\phi_2",
            "the cylinder about its contact line, tied to X-hat by k_2",
            r"-k_2\left(R\phi_2\right)R=I'_2\ddot{\phi_2}\,\rightarrow\,\ddot{\phi_2}="
            r"-\frac{2k_2}{3m_2}\phi_2",
            r"\left(\ddot\phi_2,\ \ddot\phi_2\right)",
            (-k2 * R**2 * phi2 / _J2, -2 * k2 / (3 * m2) * phi2),
            "fig2",
            _app_a_rotation(1),
        ),
        _c(
            "app-a-cylinder-friction-torque",
            "App. A, first display, line 4",
            r"-f_2R=I_2\ddot{\phi_2}\,\rightarrow\,\ddot{\phi_2}=-\frac{2f_2}{m_2R}",
            "the cylinder about its centre, turned by the friction alone",
            r"-f_2R=I_2\ddot{\phi_2}\,\rightarrow\,\ddot{\phi_2}=-\frac{2f_2}{m_2R}",
            r"\left(\ddot\phi_2,\ \ddot\phi_2\right)",
            (-f2 * R / (m2 * R**2 / 2), -2 * f2 / (m2 * R)),
            "fig2",
            _app_a_friction_torque(1),
        ),
        _c(
            "friction-hoop",
            "App. A, second display, line 1",
            r"f_1=\frac{k_1}{2}R\phi_1=k\frac{3m_2+4m_1}{6m_2}R\phi_1",
            "friction on the hoop in the mode",
            r"f_1=\frac{k_1}{2}R\phi_1=k\frac{3m_2+4m_1}{6m_2}R\phi_1",
            r"\left(f_1,\ f_1\right)",
            (k1 / 2 * R * phi1, _k1_paper / 2 * R * phi1),
            "fig2",
            _app_a_friction(0),
        ),
        _c(
            "friction-cylinder-k2",
            "App. A, second display, line 2 (first equality)",
            r"f_2=\frac{k_2}{2}R\phi_2",
            "friction on the cylinder, via k2",
            r"f_2=\frac{k_2}{2}R\phi_2",
            r"f_2",
            k2 / 2 * R * phi2,
            "fig2",
            _app_a_friction(1, middle=True),
        ),
        _c(
            "friction-cylinder",
            "App. A, second display, line 2 (final form)",
            r"=k\frac{3m_2+4m_1}{12m_1}R\phi_2",
            "friction on the cylinder, final form",
            r"f_2=k\frac{3m_2+4m_1}{12m_1}R\phi_2",
            r"f_2",
            k * (3 * m2 + 4 * m1) / (12 * m1) * R * phi2,
            "fig2",
            _app_a_friction(1),
        ),
        _c(
            "app-a-phi-ratio",
            "App. A, sentence before the friction ratio",
            r"Using equation (\ref{de}) which gives $\phi_1/\phi_2=3m_2/4m_1$",
            "the angle ratio of (de)",
            r"\phi_1/\phi_2=3m_2/4m_1",
            r"\phi_1/\phi_2",
            3 * m2 / (4 * m1),
            "fig2",
            _app_a_phi_ratio,
            _RELEASED,
            _ORIGIN_APP_A,
        ),
        _c(
            "friction-ratio-app-a",
            "App. A, display of the friction ratio",
            r"\frac{f_1}{f_2}=\frac{3}{2}\,\rightarrow\,f_1>f_2",
            "ratio of the static friction forces: the hoop's is larger",
            r"\frac{f_1}{f_2}=\frac{3}{2}\,\rightarrow\,f_1>f_2",
            r"f_1/f_2",
            sp.Rational(3, 2),
            "fig2",
            _friction_ratio,
            _FRICTION_AMOUNTS,
        ),
        _c(
            "pull-equations",
            "App. A, eqs. (a1), (a2)",
            r"F-f=ma, Fy=\left(I+mR^2\right)\ddot{\varphi}",
            "translation and rotation of the pulled body",
            r"F-f=ma,\quad Fy=\left(I+mR^2\right)\ddot{\varphi}",
            r"\left(\ddot\varphi,\ f\right)",
            (F * y / (I_ + m * R**2), F - m * R * F * y / (I_ + m * R**2)),
            "pulled",
            _pull_equations,
        ),
        _c(
            "pull-phiddot",
            "App. A, display after eq. (a2)",
            r"Exploiting the constraint relation $a=R\ddot{\varphi}$ due to the no-slip condition "
            r"the angular acceleration can be expressed from both (\ref{a1}) and (\ref{a2}) "
            r"equations, so \begin{eqnarray} \ddot{\varphi}=\frac{F}{mR}-\frac{f}{mR}, "
            r"\ddot{\varphi}=\frac{F y}{\left(I+mR^2\right)}",
            "the angular acceleration from (a1) with a = R phi'' and from (a2)",
            r"\ddot{\varphi}=\frac{F}{mR}-\frac{f}{mR},\quad \ddot{\varphi}=\frac{F y}"
            r"{\left(I+mR^2\right)}",
            r"\left(a/\ddot\varphi,\ \ddot\varphi,\ \ddot\varphi\right)",
            (R, F / (m * R) - fpull / (m * R), F * y / (I_ + m * R**2)),
            "pulled",
            _pull_phiddot,
        ),
        _c(
            "pull-eliminated",
            "App. A, display after 'By eliminating'",
            r"\frac{F}{mR}-\frac{f}{mR}=\frac{F y}{\left(I+mR^2\right)}",
            "the two angular accelerations equated",
            r"\frac{F}{mR}-\frac{f}{mR}=\frac{F y}{\left(I+mR^2\right)}",
            r"\text{left}-\text{right}",
            F / (m * R) - fpull / (m * R) - F * y / (I_ + m * R**2),
            "pulled",
            _pull_eliminated,
        ),
        _c(
            "fric-app-a",
            "App. A, display after 'and finally we get'",
            r"f\left(y\right)=F-\frac{FmR}{\left(I+mR^2\right)}y",
            "static friction of the pulled body",
            r"f\left(y\right)=F-\frac{FmR}{\left(I+mR^2\right)}y",
            "f(y)",
            F - F * m * R / (I_ + m * R**2) * y,
            "pulled",
            _fric_app_a,
        ),
        _c(
            "fig5-labels",
            "App. A, sentence after the last display of the friction",
            r"This linearly decreasing function is plotted in Fig.~\ref{fig5} for both cylinder "
            r"($f_1(y)$) and hoop ($f_2(y)$).",
            "the lines of Fig. 5",
            r"f_1(y)\ \text{(cylinder)},\quad f_2(y)\ \text{(hoop)}",
            r"\left(f_1(y),\ f_2(y)\right)",
            (F * (1 - 2 * y / (3 * R)), F * (1 - y / (2 * R))),
            "pulled-hoop, pulled-cylinder",
            _fig5_labels,
        ),
        _c(
            "friction-reversal",
            "App. A, last paragraph",
            r"in the case of a cylinder, if $y>1.5R$ the orientation of $\boldsymbol{f}$ is "
            r"reversed (pointing to the right), whereas in the case of a hoop its orientation is "
            r"unchanged (always points left)",
            "the cylinder's friction turns round above 1.5R, the hoop's never (0 <= y <= 2R)",
            r"f_{\mathrm{cyl}}(y)<0\ \text{for}\ y>1.5R,\quad f_{\mathrm{hoop}}(y)\geq 0",
            r"\left(y\ \text{where}\ f_{\mathrm{cyl}}=0,\ \operatorname{sign}f_{\mathrm{cyl}}(2R)"
            r"/F,\ f_{\mathrm{hoop}}\geq 0\right)",
            (sp.Rational(3, 2) * R, sp.Integer(-1), _TRUE),
            "pulled-hoop, pulled-cylinder",
            _reversal,
        ),
        _c(
            "pull-at-floor",
            "App. A, last paragraph",
            r"in the case where $y=0$, the magnitude of the static friction force (irrespective "
            r"of the current value of $I$) is equal to $F$, so the acceleration of the rigid body "
            r"is zero",
            "a pull at y = 0 is all taken by friction, whatever I",
            r"y=0:\quad f=F,\ a=0",
            r"\left(f,\ a\right)",
            (F, sp.Integer(0)),
            "pulled",
            _pull_at_floor,
        ),
        _c(
            "friction-no-work",
            "App. A, last sentence",
            "the static friction force not being able to do work if its point of application is "
            "stationary",
            "static friction does no work on a body rolling without slipping",
            r"P_f=f\,v_{\mathrm{contact}}=0",
            r"v_{\mathrm{contact}}",
            sp.Integer(0),
            "pulled",
            _no_work,
        ),
        _c(
            "fig5-cylinder",
            "App. A, Fig. 5 (axis label)",
            r"\psfrag{F3}[cc][cc]{$-\frac{F}{3}$}",
            "the cylinder's friction at the top, y = 2R",
            r"f(2R)=-\frac{F}{3}\ \text{(cylinder)}",
            r"f(2R)",
            -F / 3,
            "pulled-cylinder",
            _fig5_cylinder,
        ),
        # ---- App. B: natural frequencies
        _c(
            "app-b-energy-1",
            "App. B, paragraph 1",
            r"$E_1=\left(I'_1/2\right)\dot{\phi_1}^2+k/2(R\phi_1)^2$",
            "energy of the first subsystem (the hoop, the cylinder held)",
            r"E_1=\left(I'_1/2\right)\dot{\phi_1}^2+k/2(R\phi_1)^2",
            r"E_1",
            _J1 / 2 * phid1**2 + k / 2 * (R * phi1) ** 2,
            "fig2",
            _subsystem_energy(0),
        ),
        _c(
            "app-b-subsystem-1",
            "App. B, first display",
            r"\alpha_1=2m_1R^2,\quad \beta_1=kR^2, \Omega_1=\sqrt{\frac{\beta_1}{\alpha_1}}="
            r"\sqrt{\frac{kR^2}{2m_1R^2}}=\sqrt{\frac{k}{2m_1}}",
            "parameters and natural frequency of the first subsystem",
            r"\alpha_1=2m_1R^2,\ \beta_1=kR^2,\quad \Omega_1=\sqrt{\frac{\beta_1}{\alpha_1}}="
            r"\sqrt{\frac{kR^2}{2m_1R^2}}=\sqrt{\frac{k}{2m_1}}",
            r"\left(\alpha_1,\ \beta_1,\ \Omega_1,\ \Omega_1,\ \Omega_1\right)",
            (
                _J1,
                k * R**2,
                sp.sqrt(k * R**2 / _J1),
                sp.sqrt(k * R**2 / (2 * m1 * R**2)),
                _Omega1,
            ),
            "fig2",
            _subsystem(0),
        ),
        _c(
            "app-b-mass-m",
            "App. B, paragraph 2",
            r"Our second subsystem consists of a cylinder of radius $R$ and mass $m$",
            "the cylinder's mass in the second subsystem",
            r"\text{mass}\ m",
            r"m_{\mathrm{cylinder}}",
            m,
            "fig2",
            _second_subsystem_mass,
        ),
        _c(
            "app-b-energy-2",
            "App. B, paragraph 2",
            r"$E_2=\left(I'_2/2\right)\dot{\phi_2}^2+k/2(R\phi_2)^2$",
            "energy of the second subsystem (the cylinder, the hoop held)",
            r"E_2=\left(I'_2/2\right)\dot{\phi_2}^2+k/2(R\phi_2)^2",
            r"E_2",
            _J2 / 2 * phid2**2 + k / 2 * (R * phi2) ** 2,
            "fig2",
            _subsystem_energy(1),
        ),
        _c(
            "app-b-subsystem-2",
            "App. B, second display",
            r"\alpha_2=\frac{3}{2}m_2R^2,\quad \beta_2=kR^2, \Omega_2=\sqrt{\frac{\beta_2}"
            r"{\alpha_2}}=\sqrt{\frac{kR^2}{3/2m_2R^2}}=\sqrt{\frac{2k}{3m_2}}",
            "parameters and natural frequency of the second subsystem",
            r"\alpha_2=\frac{3}{2}m_2R^2,\ \beta_2=kR^2,\quad \Omega_2=\sqrt{\frac{\beta_2}"
            r"{\alpha_2}}=\sqrt{\frac{kR^2}{3/2m_2R^2}}=\sqrt{\frac{2k}{3m_2}}",
            r"\left(\alpha_2,\ \beta_2,\ \Omega_2,\ \Omega_2,\ \Omega_2\right)",
            (
                _J2,
                k * R**2,
                sp.sqrt(k * R**2 / _J2),
                sp.sqrt(k * R**2 / (sp.Rational(3, 2) * m2 * R**2)),
                _Omega2,
            ),
            "fig2",
            _subsystem(1),
        ),
        _c(
            "sum-rule-app-b",
            "App. B, third display and the sentence after it",
            r"\Omega_{f}^2=\frac{k}{2m_1}+\frac{2k}{3m_2}, \end{eqnarray} where $\Omega_{f}^2$ is "
            r"indeed the sum of the eigen frequency squares of the individual system components",
            "Omega_f^2 = k/(2m_1) + 2k/(3m_2) is the sum of the subsystems' squared frequencies",
            r"\Omega_{f}^2=\frac{k}{2m_1}+\frac{2k}{3m_2}=\Omega_1^2+\Omega_2^2",
            r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            sp.Integer(0),
            "fig2",
            _sum_rule_fig2,
        ),
        _c(
            "omega2-fig3",
            "App. B, last display",
            r"\Omega_{\bcancel{f}}^2=\frac{2k}{m_1}+\frac{3k}{2m_2}\equiv\Omega_3^2+\Omega_4^2",
            "angular frequency of the frictionless system (Fig. 3)",
            r"\Omega_{\bcancel{f}}^2=\frac{2k}{m_1}+\frac{3k}{2m_2}\equiv\Omega_3^2+\Omega_4^2",
            r"\left(\Omega^2,\ \Omega^2-\Omega_3^2-\Omega_4^2\right)",
            (2 * k / m1 + 3 * k / (2 * m2), sp.Integer(0)),
            "fig3",
            _sum_rule_fig3,
        ),
        # ---- App. C: the Hamiltonian
        _c(
            "hamiltonian-app-c",
            "App. C, eq. (k0) (the Hamiltonian H_f)",
            r"\mathcal{H}_{f}=\frac{p_1^2}{2m_1}+\frac{p_2^2}{2m_2}+\frac{k}{2}\left(\frac{q_1}"
            r"{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)^2",
            "the Hamiltonian of the coupled system",
            r"\mathcal{H}_{f}=\frac{p_1^2}{2m_1}+\frac{p_2^2}{2m_2}+\frac{k}{2}\left(\frac{q_1}"
            r"{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)^2",
            r"\mathcal{H}_f",
            _hoop_cylinder_hamiltonian(q1, q2, p1, p2, 1 / sp.sqrt(2), sp.sqrt(2) / sp.sqrt(3)),
            "fig2",
            _hamiltonian(),
        ),
        _c(
            "potential-coefficients",
            "App. C, sentence after the first eq. (k0)",
            r"the coefficients $1/\sqrt{2}$ and $\sqrt{2/3}$ of coordinates $q_1$, $q_2$ can also "
            r"be obtained from the normal frequencies of the subsystems",
            "the coefficients 1/sqrt(2), sqrt(2/3) are Omega_i / sqrt(k/m_i)",
            r"\frac{1}{\sqrt{2}}=\frac{\Omega_1}{\sqrt{k/m_1}},\quad \sqrt{\frac{2}{3}}="
            r"\frac{\Omega_2}{\sqrt{k/m_2}}",
            r"\left(\lvert c_1\rvert,\ \lvert c_2\rvert\right)",
            (_Omega1 / sp.sqrt(k / m1), _Omega2 / sp.sqrt(k / m2)),
            "fig2",
            _coefficients,
        ),
        _c(
            "potential-fig2",
            "App. C, second eq. labelled (k0) (U_f)",
            r"U_{f}=\frac{k}{2}\left(\frac{\Omega_1}{\sqrt{k/m_1}}\,q_1+\frac{\Omega_2}"
            r"{\sqrt{k/m_2}}\,q_2\right)^2",
            "the Hamiltonian's potential from the subsystems' natural frequencies",
            r"U_{f}=\frac{k}{2}\left(\frac{\Omega_1}{\sqrt{k/m_1}}\,q_1+\frac{\Omega_2}"
            r"{\sqrt{k/m_2}}\,q_2\right)^2",
            r"U_f",
            k / 2 * (_Omega1 / sp.sqrt(k / m1) * q1 + _Omega2 / sp.sqrt(k / m2) * q2) ** 2,
            "fig2",
            _potential_q("fig2", (q1, q2), (p1, p2)),
        ),
        _c(
            "omega1-omega2",
            "App. C, sentence after the second eq. (k0)",
            r"where $\Omega_1=\sqrt{k/2m_1}$ and $\Omega_2=\sqrt{2k/3m_2}$",
            "natural frequencies of the subsystems of Fig. 2",
            r"\Omega_1=\sqrt{k/2m_1},\quad \Omega_2=\sqrt{2k/3m_2}",
            r"\left(\Omega_1,\ \Omega_2\right)",
            (_Omega1, _Omega2),
            "fig2",
            _clamped("fig2", roots=True),
        ),
        _c(
            "potential-fig3",
            "App. C, eq. (k02)",
            r"U_{\bcancel{f}}=\frac{k}{2}\left(\frac{\Omega_3}{\sqrt{k/m_1}}\,q_3+\frac{\Omega_4}"
            r"{\sqrt{k/m_2}}\,q_4\right)^2",
            "the frictionless system's potential from its natural frequencies",
            r"U_{\bcancel{f}}=\frac{k}{2}\left(\frac{\Omega_3}{\sqrt{k/m_1}}\,q_3+\frac{\Omega_4}"
            r"{\sqrt{k/m_2}}\,q_4\right)^2",
            r"U_{\bcancel{f}}",
            k / 2 * (_Omega3 / sp.sqrt(k / m1) * q3 + _Omega4 / sp.sqrt(k / m2) * q4) ** 2,
            "fig3",
            _potential_fig3,
            _SMALL_ANGLES,
        ),
        _c(
            "omega3-omega4",
            "App. C, last sentence",
            r"where $\Omega_{3}=\sqrt{2k/m_1}$ and $\Omega_4=\sqrt{3k/2m_2}$",
            "natural frequencies of the subsystems of Fig. 3",
            r"\Omega_{3}=\sqrt{2k/m_1},\quad \Omega_4=\sqrt{3k/2m_2}",
            r"\left(\Omega_3,\ \Omega_4\right)",
            (_Omega3, _Omega4),
            "fig3",
            _clamped("fig3", roots=True),
        ),
    ]
