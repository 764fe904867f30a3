r"""The paper's words as HTML with MathML (``rollspring.outputs.report.tex_text_html``): text-mode
LaTeX becomes HTML text, every formula MathML, and nothing of the LaTeX is left in what a reader
sees. Every claim the paper check has (whatever claims.toml holds when this runs) is converted:
its quote, its formula and its correction, with no fallback to LaTeX source.

The HTML is read with the standard library's parser: the visible text is every text node outside
``<math>``; the MathML is parsed as XML (well-formed, in the MathML namespace).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from html.parser import HTMLParser

import pytest

from rollspring.analysis.paper import ClaimCheck, check_paper
from rollspring.outputs.report import claim_html, tex_text_html

MATHML = "http://www.w3.org/1998/Math/MathML"
# what must never show as text: a LaTeX command, a math delimiter, a brace of a group
LEFT_OVER = re.compile(r"\\[A-Za-z]+|\\[,;:!()\[\]{}$%&#_ ]|\$|[{}]")


@dataclass
class Shown:
    """What an HTML fragment shows: its visible text (outside ``<math>``), its ``<math>``
    elements (their source, to parse as XML) and its not-converted ``tex-source`` fragments."""

    text: str = ""
    maths: list[str] = field(default_factory=list)
    sources: list[str] = field(default_factory=list)


class _Reader(HTMLParser):
    def __init__(self, html: str) -> None:
        super().__init__(convert_charrefs=True)
        self.shown = Shown()
        self._depth = 0  # inside <math>
        self._source = False
        self._html = html
        self.feed(html)
        self.close()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "math":
            self._depth += 1
        if "tex-source" in (dict(attrs).get("class") or ""):
            self._source = True

    def handle_endtag(self, tag: str) -> None:
        if tag == "math":
            self._depth -= 1
        elif tag in ("code", "pre"):
            self._source = False

    def handle_data(self, data: str) -> None:
        if self._source:
            self.shown.sources.append(data)
        elif self._depth == 0:
            self.shown.text += data


def shown(html: str) -> Shown:
    result = _Reader(html).shown
    result.maths = re.findall(r"<math\b.*?</math>", html, flags=re.DOTALL)
    return result


def assert_mathml(fragment: str) -> None:
    """Well-formed XML whose root is a MathML ``<math>`` with at least one child."""
    root = ET.fromstring(fragment)
    assert root.tag == f"{{{MATHML}}}math"
    assert len(root) >= 1


def formula_count(latex: str) -> int:
    """How many formulas a quote holds by its delimiters (a lower bound of the MathML
    elements it must give): ``$...$``/``\\(...\\)``, ``$$``/``\\[``, math environments."""
    inline = len(re.findall(r"(?<!\\)\$(?!\$)", latex.replace("$$", ""))) // 2
    display = latex.count("$$") // 2 + latex.count("\\[") + latex.count("\\(")
    environments = len(re.findall(r"\\(?:begin|end)\{(?:equation|eqnarray|align)", latex))
    return inline + display + min(environments, 1)


# -- every claim of the paper check ------------------------------------------------------------


@pytest.fixture(scope="module")
def checks() -> tuple[ClaimCheck, ...]:
    return check_paper()


def test_every_claim_converts_with_no_latex_left_and_no_fallback(
    checks: tuple[ClaimCheck, ...],
) -> None:
    assert len(checks) >= 100  # the whole catalogue, not a sample
    failures: list[str] = []
    for check in checks:
        parts = claim_html(check, failures=failures)
        pieces = {"quote": check.claim.quote, "claim": check.claim.latex}
        if check.correction:
            pieces["correction"] = check.correction
        for name, latex in pieces.items():
            seen = shown(parts[name])
            where = f"{check.claim.key} {name}: {latex[:70]!r}"
            assert LEFT_OVER.search(seen.text) is None, f"{where} shows {seen.text!r}"
            assert seen.sources == [], where
            for fragment in seen.maths:
                assert_mathml(fragment)
            if name != "quote":  # a formula: one MathML element, nothing else to read
                assert len(seen.maths) == 1 and seen.text.strip() == "", where
            else:
                assert len(seen.maths) >= formula_count(latex), where
                assert seen.maths or seen.text.strip(), where
        assert (parts["correction"] == "") == (not check.correction)
    assert failures == []  # no fallback to the LaTeX source for the current claims


def test_a_quote_from_inside_an_equation_is_one_formula(checks: tuple[ClaimCheck, ...]) -> None:
    # the quotes the catalogue takes as the formula itself (no latex of their own)
    formulas = [c.claim.quote for c in checks if c.claim.quote == c.claim.latex]
    assert formulas
    for quote in formulas:
        seen = shown(tex_text_html(quote))
        assert len(seen.maths) >= 1 and seen.text.strip(" ,") == "", quote


def test_a_quote_in_words_stays_words(checks: tuple[ClaimCheck, ...]) -> None:
    words = [c.claim.quote for c in checks if not re.search(r"[\\$_^=~%{}]|--|``", c.claim.quote)]
    assert words
    for quote in words:
        seen = shown(tex_text_html(quote))
        assert seen.maths == []
        assert seen.text == quote


# -- the constructs one by one -----------------------------------------------------------------


def test_inline_math_between_words() -> None:
    html = tex_text_html(r"the force ($F_1=F_2$) and \(x\) and \[y\] and $$z$$.")
    seen = shown(html)
    assert seen.text == "the force () and  and  and ."
    assert len(seen.maths) == 4
    assert "<mi>F</mi>" in seen.maths[0] and "<mo>&#x0003D;</mo>" in seen.maths[0]
    for fragment in seen.maths:
        assert_mathml(fragment)
        assert 'display="inline"' in fragment


def test_text_mode_markup_becomes_html() -> None:
    html = tex_text_html(
        r"\emph{rolls} -- see Fig.~\ref{fig5}, eq.~\eqref{g} \cite{a, b}: 50\% \textbf{more}"
        r" \textit{and} \dots{} ``so'' --- Nyitray\'{a}"
    )
    assert "<em>rolls</em>" in html and "<strong>more</strong>" in html and "<i>and</i>" in html
    seen = shown(html)
    assert (
        seen.text == "rolls – see Fig.\u00a05, eq.\u00a0(g) [a, b]: 50% more and … “so” — Nyitrayá"
    )
    assert seen.maths == []


def test_math_inside_a_commands_argument() -> None:
    seen = shown(tex_text_html(r"\emph{the mass $m_1$} and \psfrag{F3}[cc][cc]{$-\frac{F}{3}$}"))
    assert seen.text == "the mass  and "
    assert len(seen.maths) == 2 and "<mfrac>" in seen.maths[1]


def test_a_quote_that_starts_or_stops_inside_an_environment() -> None:
    stops = shown(tex_text_html(r"so \begin{eqnarray} a &=& b \\ c &=& d"))
    assert stops.text == "so " and len(stops.maths) == 2
    starts = shown(tex_text_html(r"a=b, \end{eqnarray} where $a$ is"))
    assert starts.text == " where  is" and len(starts.maths) == 2
    whole = shown(tex_text_html(r"as \begin{equation} E=mc^2 \label{e} \end{equation} shows"))
    assert whole.text == "as  shows" and len(whole.maths) == 1
    assert "label" not in whole.maths[0]


def test_escaped_dollars_and_html_are_text() -> None:
    seen = shown(tex_text_html(r"costs \$5 <b> & $x$"))
    assert seen.text == "costs $5 <b> & "
    assert len(seen.maths) == 1
    assert "<b>" not in tex_text_html(r"costs \$5 <b> & $x$")


def test_what_cannot_be_converted_is_marked_source_and_counted() -> None:
    failures: list[str] = []
    html = tex_text_html(r"a $\frac{1}{$ b \frobnicate c", failures=failures)
    seen = shown(html)
    assert seen.sources == [r"\frac{1}{", r"\frobnicate"]
    assert len(failures) == 2
    assert "b" in seen.text and "c" in seen.text


def test_a_formula_written_in_text_mode_converts() -> None:
    # a symbol command in the words (\alpha) is math, not a failure
    failures: list[str] = []
    seen = shown(tex_text_html(r"the angle \alpha grows as $t$", failures=failures))
    assert failures == [] and len(seen.maths) == 2 and seen.text == "the angle  grows as "
