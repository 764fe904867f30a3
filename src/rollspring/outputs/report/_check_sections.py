"""Sections of the report that check and document: the derivation by the paper's five methods
with its cross-check, the paper's claims checked, the warnings and conventions, and the
embedded data.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Sequence
from typing import Any

from rollspring.analysis.conventions import CONVENTIONS
from rollspring.analysis.derivation import Derivation, Section
from rollspring.analysis.paper import (
    HOLDS_ONLY_IF,
    HOLDS_STATED,
    VERIFIED,
    WRONG,
    ClaimCheck,
    verdict_counts,
)
from rollspring.outputs.report._html import Markup, esc, table
from rollspring.outputs.report._page import Page, _json_script, _verdict
from rollspring.outputs.report._tex_text import claim_html
from rollspring.outputs.trajectory import summary_json, trajectory_csv


def derivation_sections(derivation: Derivation) -> list[Section]:
    """The sections of ``derivation`` shown as steps: every one but the cross-check's own
    (shown as a table of verdicts instead)."""
    own_table = derivation.cross_check.section().title
    return [s for s in derivation.sections if s.title != own_table]


def section_derivation(page: Page, derivation: Derivation | None, error: str | None) -> Markup:
    title = "Derivation by the paper's five methods"
    if derivation is None:
        return page.section(
            "derivation",
            title,
            Markup(f'<p class="verdict-bad">No derivation for this system: {esc(error)}</p>'),
        )
    return page.section("derivation", title, *_derivation_parts(page, derivation))


def _derivation_parts(page: Page, derivation: Derivation) -> list[object]:
    check = derivation.cross_check
    parts: list[object] = [
        Markup(
            f"<p>{esc(derivation.subtitle)} SymPy derives the equations of motion by each "
            "method (the paper's Sec. 2 to 4 and appendices) and the cross-check compares them "
            "with the structure route (exact Q = −∂V/∂φ, K, det(K − Ω²M) = 0).</p>"
            '<p id="cross-check-verdict">Cross-check: '
            + _verdict(check.agree, "all methods that apply agree", "the methods differ")
            + f" ({esc(', '.join(check.applied))} applied"
            + (
                f"; not applicable: {esc(', '.join(check.not_applicable))}"
                if check.not_applicable
                else ""
            )
            + ").</p>"
        )
    ]
    undecided = Markup('<span class="verdict-other">undecided (time budget)</span>')
    rows = [
        [
            c.method,
            c.what,
            undecided if c.agrees is None else _verdict(c.agrees, "agrees", "differs"),
        ]
        for c in check.checks
    ]
    rows += [
        [name, reason, Markup('<span class="verdict-other">not applicable</span>')]
        for name, reason in check.not_applicable.items()
    ]
    parts.append(
        table(
            ["method", "compared", "verdict"],
            rows,
            caption="Cross-check of the methods",
            table_id="cross-check",
        )
    )
    for number, section in enumerate(derivation_sections(derivation), 1):
        steps = []
        for step in section.steps:
            ref = f' <span class="ref">[{esc(step.ref)}]</span>' if step.ref else ""
            steps.append(
                Markup(
                    f'<div class="step"><p class="why">{esc(step.words)}{ref}'
                    f'</p><div class="formula">{page.math(step.latex)}</div>'
                    "</div>"
                )
            )
        note = f'<p class="note">{esc(section.note)}</p>' if section.note else ""
        parts.append(
            Markup(
                f'<div class="method" id="derivation-{number}">'
                f"<h3>{esc(section.title)}</h3>{note}" + "".join(steps) + "</div>"
            )
        )
    return parts


def section_paper_check(page: Page, label: str, checks: Sequence[ClaimCheck]) -> Markup:
    css_class = {VERIFIED: "ok", HOLDS_STATED: "ok", HOLDS_ONLY_IF: "other", WRONG: "bad"}
    rows = []
    for check in checks:
        text, css = f"{check.verdict.mark} {check.verdict.words}", css_class[check.verdict]
        shown = claim_html(check, failures=page.failures)
        rows.append(
            [
                check.claim.location,
                Markup(
                    f"{esc(check.claim.statement)}<br>"
                    f'<span class="cellmath">{shown["claim"]}</span>'
                    f'<q class="quote">{shown["quote"]}</q>'
                ),
                Markup(
                    f'<span class="verdict-{css}" data-verdict="{esc(check.verdict)}">'
                    f"{esc(text)}</span>"
                ),
                Markup(f'<span class="cellmath">{shown["correction"]}</span>')
                if check.correction
                else "–",
                check.reason,
            ]
        )
    intro = Markup(
        f"<p>This system is the paper's {esc(label)}. Each quantitative statement the paper "
        "makes about it (quoted from its source) is derived again by rollspring's derivation "
        "engine, on the paper's system with its parameters as symbols (m₁, m₂, R, k …), and "
        "compared with <code>simplify(paper − derived) == 0</code>: "
        f"{verdict_counts(c.verdict for c in checks)}. "
        "(<code>rollspring paper-check</code> lists every statement of the paper.)</p>"
    )
    return page.section(
        "paper-check",
        "The paper's claims, checked",
        intro,
        table(
            ["where", "claim", "verdict", "correction", "reason"],
            rows,
            caption=f"Claims about the paper's {label}",
            table_id="paper-claims",
        ),
    )


def section_warnings(page: Page) -> Markup:
    warnings = page.analysis.warnings
    body = (
        Markup('<ul class="warnings">' + "".join(f"<li>{esc(w)}</li>" for w in warnings) + "</ul>")
        if warnings
        else Markup("<p>None.</p>")
    )
    conventions = Markup(
        "<dl>"
        + "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in CONVENTIONS.items())
        + "</dl>"
    )
    return page.section(
        "warnings",
        "Warnings and conventions",
        body,
        Markup("<h3>Conventions</h3>"),
        conventions,
    )


def section_data(page: Page) -> Markup:
    def encoded(text: str) -> str:
        return base64.b64encode(text.encode("utf-8")).decode("ascii")

    def as_json(data: Any) -> str:
        return json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False)

    csv = encoded(trajectory_csv(page.trajectory))
    summary = encoded(as_json(summary_json(page.trajectory)))
    analysis = encoded(as_json(page.analysis.to_dict()))
    links = Markup(
        '<p class="download">Embedded in this file: '
        f'<a download="analysis.json" href="data:application/json;base64,{analysis}">'
        "analysis.json</a> (as <code>rollspring analyze --json</code>), "
        f'<a download="trajectory.csv" href="data:text/csv;base64,{csv}">trajectory.csv</a>'
        f' and <a download="summary.json" href="data:application/json;base64,{summary}">'
        "summary.json</a> (as <code>rollspring simulate --out</code>).</p>"
    )
    return page.section(
        "data", "Data", links, _json_script("analysis-data", page.analysis.to_dict())
    )
