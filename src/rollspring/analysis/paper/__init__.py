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
* ``key``: a short, stable name (``sec3.phase-opposition``: the section, then what it says);
* ``system``: which system(s) it is checked on (keys of :data:`SYSTEMS`, comma-separated: the
  paper's Fig. 1, 2, 3 systems built as rollspring systems and turned symbolic by
  :func:`rollspring.analysis.derivation.symbolic_system` with ``symbols=True``);
* ``assumptions``: the assumptions the paper itself states that the claim relies on
  (:class:`Assumption`: our words, the paper's words verbatim, where it says them);
* ``derive``: the recipe: computes, from the engine's SymPy objects (M, K, V, the Lagrangian,
  the friction and force expressions, the zero mode, the closed-form frequencies), the same
  quantity in general, under the paper's stated assumptions, and under a condition the paper
  does not state where the claim needs one.

The verdict (:class:`Verdict`) is computed (:func:`check_claim`): ``simplify(paper - derived) ==
0`` gives ``"verified"``; otherwise, if the claim agrees with the value derived under the
assumptions the paper states (released from rest, magnitudes, small angles, the centres level,
X-hat as origin), ``"holds-under-stated-assumption"``; otherwise, if the recipe names a condition
the paper does not state (an angle counted the other way, a coordinate measured from its
equilibrium, ...) and the two agree under it, ``"holds-only-if"``; otherwise ``"wrong"``, with the
derived expression, in the paper's own terms (under its stated assumptions), as the correction.
Nothing in a verdict is typed in: the words (``reason``) explain, the engine decides.

Sign conventions (docs/physics.md): :math:`\varphi_i` clockwise positive (rolling to the right), in
one common orientation for all bodies, measured from the equilibrium; friction :math:`f_i` is
the force of the floor on body i, positive along +x.

The package: :mod:`~.types` (the data types), :mod:`~.symbols` and :mod:`~.notation` (the
engine's symbols and the paper's own), :mod:`~.systems` (the paper's systems), :mod:`~.bench`
(their symbolic forms and derived objects, built once), :mod:`~.algebra` (the exact comparisons),
:mod:`~.decide` (the verdict), :mod:`~.assumptions` (the assumptions the paper states),
:mod:`~.recipes` (the derivations, one module per section or group of sections) and
:mod:`~.catalogue` (reads the claims, in the paper's order, from ``claims.toml``: the paper's
words and values, the systems, the recipe and the stated assumptions, by claim key).
"""

from rollspring.analysis.paper.catalogue import paper_claims
from rollspring.analysis.paper.decide import check_claim, check_claims, check_paper
from rollspring.analysis.paper.systems import SYSTEMS, paper_figure, paper_system
from rollspring.analysis.paper.types import (
    HOLDS_ONLY_IF,
    HOLDS_STATED,
    VERDICTS,
    VERIFIED,
    WRONG,
    Assumption,
    Claim,
    ClaimCheck,
    Counterexample,
    Derived,
    Verdict,
    quote_key,
    verdict_counts,
)

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
    "Counterexample",
    "Derived",
    "Verdict",
    "check_claim",
    "check_claims",
    "check_paper",
    "paper_claims",
    "paper_figure",
    "paper_system",
    "quote_key",
    "verdict_counts",
]
