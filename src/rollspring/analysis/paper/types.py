"""The paper check's data types: verdicts, claims, stated assumptions, derivations, checks.

:class:`Verdict` is a :class:`~enum.StrEnum` whose values are the words the JSON output carries
(``"verified"``, ...); :class:`Claim` is one statement of the paper with its recipe,
:class:`Derived` what a recipe derives, :class:`ClaimCheck` a claim with its computed verdict.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rollspring.analysis.paper.bench import Bench


class Verdict(StrEnum):
    """What the derivation engine finds of a claim, in the order the verdicts are counted."""

    VERIFIED = "verified"
    """The paper's expression equals the derived one."""
    HOLDS_STATED = "holds-under-stated-assumption"
    """It holds under an assumption the paper itself states (quoted)."""
    HOLDS_ONLY_IF = "holds-only-if"
    """It holds only under a condition the paper does not state (named in the reason)."""
    WRONG = "wrong"
    """It does not hold; the correction gives the derived value."""

    @property
    def mark(self) -> str:
        """The verdict's sign: ✔ ☑ ⚠ ✘."""
        return _MARKS[self]

    @property
    def words(self) -> str:
        """The verdict in words ("holds under the paper's stated assumption", ...)."""
        return _WORDS[self]


_MARKS = {
    Verdict.VERIFIED: "✔",
    Verdict.HOLDS_STATED: "☑",
    Verdict.HOLDS_ONLY_IF: "⚠",
    Verdict.WRONG: "✘",
}
_WORDS = {
    Verdict.VERIFIED: "verified",
    Verdict.HOLDS_STATED: "holds under the paper's stated assumption",
    Verdict.HOLDS_ONLY_IF: "holds only if",
    Verdict.WRONG: "wrong",
}


def verdict_counts(verdicts: Iterable[str]) -> str:
    """'a verified, b hold under an assumption the paper states, c hold only under a condition
    the paper does not state, d wrong' (the words of every summary of the paper check)."""
    counts = Counter(Verdict(v) for v in verdicts)
    return (
        f"{counts[Verdict.VERIFIED]} verified, {counts[Verdict.HOLDS_STATED]} hold under an "
        f"assumption the paper states, {counts[Verdict.HOLDS_ONLY_IF]} hold only under a "
        f"condition the paper does not state, {counts[Verdict.WRONG]} wrong"
    )


# The verdicts by name (a Verdict compares and hashes as its word: the command line, which does
# not load this package to start, keys its tables by the words).
VERIFIED = Verdict.VERIFIED
HOLDS_STATED = Verdict.HOLDS_STATED
HOLDS_ONLY_IF = Verdict.HOLDS_ONLY_IF
WRONG = Verdict.WRONG
#: The four verdicts, in the order they are counted.
VERDICTS: tuple[Verdict, ...] = tuple(Verdict)


def quote_key(text: str) -> str:
    r"""The form in which a quote is looked up in the paper's LaTeX source: ``\label{...}``,
    ``\nonumber``, ``&`` and ``\\`` removed, no white space."""
    text = re.sub(r"\\label\{[^}]*\}", "", text)
    text = text.replace("\\nonumber", "").replace("\\\\", " ").replace("&", "")
    return re.sub(r"\s+", "", text)


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
class Counterexample:
    """A system the engine *runs* (the exact nonlinear motion) to show what a verdict says: where
    the paper's statement fails, or holds only under a condition it leaves unstated.

    ``system`` is a key of :data:`~rollspring.analysis.paper.systems.SYSTEMS`; ``start`` is
    ``"file"`` (as the file places the bodies: the spring compressed, then released) or
    ``"mode"`` (from the placement, which is the equilibrium, with the velocities of the
    oscillating mode whose last angle has the amplitude ``amplitude``, rad); the run lasts
    ``periods`` periods of that mode. ``measure`` names what is measured on the run (the
    runner's table of measures, :mod:`rollspring.service.paper_runs`); ``paper`` is the value the
    paper's statement gives for it; the run disagrees when the measured value differs from it by
    more than ``tolerance``. ``words`` says what the run shows, in a sentence."""

    system: str
    measure: str
    paper: float
    tolerance: float
    words: str
    start: str = "file"
    amplitude: float = 0.05
    periods: float = 10.0

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: every field."""
        return {
            "system": self.system,
            "start": self.start,
            "amplitude": self.amplitude,
            "periods": self.periods,
            "measure": self.measure,
            "paper": self.paper,
            "tolerance": self.tolerance,
            "words": self.words,
        }


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
    derive: Callable[[Bench], Derived] = field(repr=False, compare=False)
    quote: str = ""
    assumptions: tuple[Assumption, ...] = ()
    counterexample: Counterexample | None = None


@dataclass(frozen=True)
class ClaimCheck:
    """A claim with its computed verdict; ``assumption`` names the paper's stated assumptions
    the verdict relies on (None for a claim verified without them)."""

    claim: Claim
    verdict: Verdict  # a str enum: compared and written as its value
    correction: str | None
    reason: str
    paper: Any
    derived: Any
    assumption: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: ``key`` (the claim's), ``location``, ``claim`` (LaTeX), ``quote`` (the
        paper's words),
        ``verdict``, ``assumption`` (the paper's stated assumptions the verdict relies on, or
        None), ``correction`` (LaTeX or None), ``reason``, ``counterexample`` (the system the engine
        runs to show the verdict, :class:`Counterexample`, or None)."""
        return {
            "key": self.claim.key,
            "location": self.claim.location,
            "claim": self.claim.latex,
            "quote": self.claim.quote,
            "verdict": self.verdict,
            "assumption": self.assumption,
            "correction": self.correction,
            "reason": self.reason,
            "counterexample": (
                self.claim.counterexample.to_dict() if self.claim.counterexample else None
            ),
        }
