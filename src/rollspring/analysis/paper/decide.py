"""The decision procedure: a claim's verdict, computed from the engine's derivation.

``simplify(paper - derived) == 0`` gives :attr:`Verdict.VERIFIED`; otherwise agreement under the
assumptions the paper states gives :attr:`Verdict.HOLDS_STATED`; otherwise agreement under a
condition the recipe names (one the paper does not state) gives :attr:`Verdict.HOLDS_ONLY_IF`;
otherwise :attr:`Verdict.WRONG`, with the derived value, in the paper's terms, as the correction.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable, Sequence

from rollspring.analysis.paper.algebra import latex_of, same, substitute
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.catalogue import paper_claims
from rollspring.analysis.paper.types import (
    Assumption,
    Claim,
    ClaimCheck,
    Verdict,
)


def _words_of(assumptions: Sequence[Assumption]) -> str:
    return "; ".join(a.words for a in assumptions)


def check_claim(claim: Claim, bench: Bench | None = None) -> ClaimCheck:
    """Derive the claim's quantity with the engine and compare (see the module docstring)."""
    bench = bench or Bench()
    derived = claim.derive(bench)
    paper = substitute(claim.paper, derived.paper_subs)
    if same(paper, derived.value):
        return ClaimCheck(claim, Verdict.VERIFIED, None, derived.how, paper, derived.value)
    stated = claim.assumptions
    if bool(stated) != (derived.assumed is not None):
        raise RuntimeError(
            f"{claim.key}: the claim's stated assumptions and the recipe's value under them "
            "go together"
        )
    assumption = "; ".join(a.text() for a in stated) or None
    if stated:
        paper_assumed = derived.paper_assumed(paper) if derived.paper_assumed else paper
        if same(paper_assumed, derived.assumed):
            reason = f"holds under the paper's stated assumption: {_words_of(stated)}"
            if derived.why:
                reason += f"; {derived.why}"
            return ClaimCheck(
                claim,
                Verdict.HOLDS_STATED,
                None,
                reason,
                paper,
                derived.value,
                assumption=assumption,
            )
    # the correction in the paper's own terms: under the assumptions it states
    own = derived.assumed if stated else derived.value
    correction = derived.correction or f"{claim.quantity} = {latex_of(own)}"
    if derived.condition is not None:
        paper_if = derived.paper_if(paper) if derived.paper_if is not None else paper
        value_if = derived.value_if if derived.value_if is not None else own
        if same(paper_if, value_if):
            reason = f"holds only if {derived.condition}"
            if stated:
                reason += f" (besides the paper's stated assumption: {_words_of(stated)})"
            if derived.why:
                reason += f"; {derived.why}"
            return ClaimCheck(
                claim, Verdict.HOLDS_ONLY_IF, correction, reason, paper, derived.value, assumption
            )
    reason = derived.why or derived.how
    return ClaimCheck(claim, Verdict.WRONG, correction, reason, paper, derived.value, assumption)


def check_claims(claims: Iterable[Claim]) -> tuple[ClaimCheck, ...]:
    """Each of ``claims`` with its verdict; the claims share the symbolic systems they are
    derived on (each built once)."""
    bench = Bench()
    return tuple(check_claim(claim, bench) for claim in claims)


@functools.cache
def check_paper() -> tuple[ClaimCheck, ...]:
    """Every claim of :func:`paper_claims` with its verdict (computed once per process).

    Returns
    -------
    tuple of ClaimCheck
        In the paper's order: the claim (its key, location, quote and statement), the
        verdict (:class:`Verdict`), the condition it needs or the correction, and the
        derivation's value.
    """
    return check_claims(paper_claims())
