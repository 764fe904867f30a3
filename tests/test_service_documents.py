"""The derivation as the web API's ``POST /api/derive`` answers it (docs/web-api.md):
``rollspring.service.documents.derivation_payload``."""

from __future__ import annotations

import json

import pytest

from rollspring import load_system
from rollspring.analysis.paper import VERDICTS, check_paper, paper_figure
from rollspring.service.documents import derivation_payload
from tests.test_paper_check import CLAIM_KEYS

STEP_KEYS = {"words", "latex", "mathml", "ref"}
# beside paper-check's keys, what the report shows (the quote as HTML, the formulas as MathML)
SHOWN_KEYS = {"quote_html", "claim_mathml", "correction_mathml"}


@pytest.fixture(scope="module")
def hoop_cylinder() -> dict:
    return derivation_payload(load_system("hoop-cylinder"))


def test_the_payload_has_the_contracts_keys_and_is_plain_json(hoop_cylinder: dict) -> None:
    assert set(hoop_cylinder) == {"title", "subtitle", "sections", "cross_check", "claims"}
    assert hoop_cylinder["title"] == "Derivation: " + load_system("hoop-cylinder").name
    assert hoop_cylinder["subtitle"]
    text = json.dumps(hoop_cylinder, allow_nan=False)  # only str, float, bool, None, list, dict
    assert json.loads(text) == hoop_cylinder


def test_every_step_has_its_mathml(hoop_cylinder: dict) -> None:
    sections = hoop_cylinder["sections"]
    assert len(sections) >= 6
    assert "Euler-Lagrange equations" in {s["title"] for s in sections}
    for section in sections:
        assert set(section) == {"title", "note", "steps"}
        assert section["steps"], section["title"]  # every method applies to Fig. 2
        for step in section["steps"]:
            assert set(step) == STEP_KEYS
            assert step["latex"] and step["words"]
            assert "<math" in step["mathml"], step["latex"][:80]
    # the cross-check is its own object, not a section of steps
    assert "Cross-check of the methods" not in {s["title"] for s in sections}


def test_the_cross_check_agrees(hoop_cylinder: dict) -> None:
    check = hoop_cylinder["cross_check"]
    assert set(check) == {"agree", "applied", "not_applicable", "checks"}
    assert check["not_applicable"] == {}  # every method applies to Fig. 2
    assert check["agree"] is True
    assert len(check["checks"]) >= 5
    methods = {c["method"] for c in check["checks"]}
    assert methods >= {"newton", "conservation", "lagrange", "natural-frequencies", "hamilton"}
    for item in check["checks"]:
        assert set(item) == {"method", "what", "agree", "residual"}
        assert item["agree"] is True and item["what"]
        assert isinstance(item["residual"], str)


def test_the_papers_claims_as_paper_check_json_gives_them(hoop_cylinder: dict) -> None:
    claims = hoop_cylinder["claims"]
    assert claims and len(claims) >= 20
    for claim in claims:
        assert set(claim) == CLAIM_KEYS | SHOWN_KEYS
        assert claim["verdict"] in VERDICTS
        assert claim["claim_mathml"].startswith("<math")
    assert {"location": "Sec. 5.1, eq. (QQQ1)", "verdict": "verified"}.items() <= next(
        c for c in claims if c["location"] == "Sec. 5.1, eq. (QQQ1)"
    ).items()
    _, keys = paper_figure(load_system("hoop-cylinder"))
    expected = [
        c.to_dict()
        for c in check_paper()
        if keys & {key.strip() for key in c.claim.system.split(",")}
    ]
    assert [{key: c[key] for key in CLAIM_KEYS} for c in claims] == expected


def test_no_claims_for_a_system_that_is_none_of_the_papers() -> None:
    system = load_system("three-bodies")  # a free chain of three bodies
    assert paper_figure(system) is None
    payload = derivation_payload(system, "lagrange")
    assert payload["claims"] is None
    assert [s["title"] for s in payload["sections"]][1] == "Euler-Lagrange equations"
    assert payload["cross_check"]["agree"] is True


def test_a_method_that_does_not_apply_says_why() -> None:
    """The conservation method needs a zero mode; a chain tied to a wall has none."""
    payload = derivation_payload(load_system("wall-hoop-cylinder"), "conservation")
    reason = payload["cross_check"]["not_applicable"]["conservation"]
    assert "conservation" not in payload["cross_check"]["applied"]
    assert reason
    notes = [s["note"] for s in payload["sections"] if not s["steps"]]
    assert any(reason in note or note in reason for note in notes if note), notes
