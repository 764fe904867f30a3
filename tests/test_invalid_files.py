"""Invalid system files: each gets a one-line message naming the field and the reason, exit code 2.

Every file under ``tests/invalid/`` is one case of the table below (plus a file that does not
exist). For each, ``load_system`` raises :class:`ModelError` with a one-line message that names
the file, the field and the reason, and ``rollspring analyze FILE`` prints ``error: <message>``
on stderr, nothing on stdout, exits with code 2 and never shows a traceback.

An expected entry is a substring of the message; a tuple of strings means "any one of these".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.errors import ModelError
from rollspring.model import load_system
from tests.test_model import ISSUE_EXAMPLE

INVALID = Path(__file__).parent / "invalid"
EXAMPLES = Path(__file__).parent.parent / "examples"
MISSING = "no-such-file.toml"  # deliberately absent from tests/invalid/

Expected = str | tuple[str, ...]


@dataclass(frozen=True)
class Case:
    file: str  # a name in tests/invalid/
    expected: tuple[Expected, ...]  # substrings of the message: the field, then the reason

    @property
    def path(self) -> Path:
        return INVALID / self.file


def case(file: str, *expected: Expected) -> Case:
    return Case(file, expected)


FINITE = "must be a finite number"

CASES: list[Case] = [
    # --- the file itself ------------------------------------------------------------------------
    case(MISSING, "file not found"),
    case("a-folder.toml", "folder"),
    case("unknown-extension.yaml", "unknown file type", ".yaml"),
    case("not-utf8.toml", "UTF-8"),
    case("empty.toml", "bodies", "missing"),
    # --- syntax ---------------------------------------------------------------------------------
    case("toml-syntax-error.toml", "TOML syntax error", "line 5"),
    case("toml-duplicate-key.toml", "TOML syntax error", "line 6"),
    case("json-syntax-error.json", "JSON syntax error", "line 3"),
    case("json-duplicate-key.json", "duplicate key", "mass"),
    case("json-top-level-array.json", "top level", "JSON object"),
    case("json-top-level-null.json", "top level", "JSON object"),
    case("toml-nested-too-deep.toml", ("nest", "deep", "depth")),
    case("json-nested-too-deep.json", ("nest", "deep", "depth")),
    case("toml-integer-5000-digits.toml", ("digits", "too long", "too large")),
    case("json-integer-5000-digits.json", ("digits", "too long", "too large")),
    # --- unknown keys and values ----------------------------------------------------------------
    case("unknown-top-level-key.toml", "unknown key", "'gravitation'"),
    case("unknown-body-key.toml", "bodies[0]", "unknown key", "'colour'"),
    case("unknown-attachment-key.toml", "springs[0].at[0]", "unknown key", "'angel'"),
    case("unknown-key-with-newline.toml", "bodies[0]", "unknown key", "col"),
    case("unknown-shape.toml", "bodies[0].shape", "unknown value", "'disc'", "'hoop'"),
    # --- structure and types --------------------------------------------------------------------
    case("bodies-missing.toml", "bodies", "missing"),
    case("bodies-empty.toml", "bodies", "at least one body"),
    case("bodies-not-a-list.toml", "bodies", "must be a list"),
    case("body-not-a-table.toml", "bodies[0]", "must be a table"),
    case("mass-missing.toml", "bodies[0].mass", "missing"),
    case("mass-string.toml", "bodies[0].mass", "must be a number", "'1'"),
    case("json-mass-string.json", "bodies[0].mass", "must be a number", "'1'"),
    case("mass-bool.toml", "bodies[0].mass", "must be a number"),
    case("x-integer-too-large.toml", "bodies[0].x", "number"),
    case("name-not-a-string.toml", "name", "must be a string"),
    case("spring-end-not-a-string.toml", "springs[0].ends[1]", "must be a string"),
    # --- ids ------------------------------------------------------------------------------------
    case("id-bad-characters.toml", "bodies[0].id", "letters, digits", "'my hoop'"),
    case("id-empty.toml", "bodies[0].id", "must not be empty"),
    case("duplicate-body-id.toml", "bodies[1].id", "duplicate", "'hoop'", "bodies[0]"),
    case("json-duplicate-id.json", "bodies[1].id", "duplicate", "'hoop'"),
    case("duplicate-id-body-and-anchor.toml", "anchors[0].id", "duplicate", "'cyl'", "bodies[1]"),
    # --- positive quantities --------------------------------------------------------------------
    # (each quantity has a range that works, docs/system-files.md; the message states it)
    case("mass-zero.toml", "bodies[0].mass", "must be between 1e-06 and 1e+06 kg", "0"),
    case("mass-negative.toml", "bodies[1].mass", "must be between 1e-06 and 1e+06 kg", "-2.0"),
    case("radius-zero.toml", "bodies[0].radius", "must be between 0.001 and 1000 m"),
    case("radius-negative.toml", "bodies[0].radius", "must be between 0.001 and 1000 m"),
    case("stiffness-zero.toml", "springs[0].stiffness", "must be between 1e-06 and 1e+09 N/m"),
    case("stiffness-negative.toml", "springs[0].stiffness", "must be between 1e-06 and 1e+09"),
    case("rest-length-negative.toml", "springs[0].rest_length", "must be between 0 and 10000 m"),
    case("damping-negative.toml", "springs[0].damping", "must be between 0 and 1e+06 N s/m"),
    case("gravity-negative.toml", "gravity", "must be between 0 and 1000 m/s²"),
    case("mu-static-negative.toml", "bodies[0].mu_static", "must be >= 0"),
    case("height-negative.toml", "springs[0].at[1].height", "must be between 0 and 10000 m"),
    # --- NaN anywhere ---------------------------------------------------------------------------
    case("mass-nan.toml", "bodies[0].mass", "NaN"),
    case("json-mass-nan.json", "bodies[0].mass", "NaN"),
    case("stiffness-nan.toml", "springs[0].stiffness", "NaN"),
    case("anchor-y-nan.toml", "anchors[0].y", "NaN"),
    case("angle-nan.toml", "springs[0].at[0].angle", "NaN"),
    case("mu-static-nan.toml", "bodies[0].mu_static", "NaN"),
    case("json-mu-static-nan.json", "bodies[0].mu_static", "NaN"),
    # --- infinity anywhere except mu_static -----------------------------------------------------
    case("x-inf.toml", "bodies[0].x", FINITE),
    case("json-x-minus-infinity.json", "bodies[0].x", FINITE),
    case("mass-inf.toml", "bodies[0].mass", FINITE),
    case("json-radius-overflow.json", "bodies[0].radius", FINITE),
    case("mu-kinetic-inf.toml", "bodies[0].mu_kinetic", FINITE),
    case("force-fx-inf.toml", "forces[0].fx", FINITE),
    case("gravity-minus-inf.toml", "gravity", FINITE),
    case("spring-length-overflows.toml", "bodies[0].x", "must be between -10000 and 10000 m"),
    # --- friction and inertia -------------------------------------------------------------------
    case("mu-kinetic-above-static.toml", "bodies[0]", "mu_kinetic", "must not exceed", "mu_static"),
    case("custom-without-inertia-factor.toml", "bodies[0]", "custom", "needs `inertia_factor`"),
    case("inertia-factor-on-hoop.toml", "bodies[0]", "`inertia_factor`", "only for shape 'custom'"),
    case("inertia-factor-above-one.toml", "bodies[0].inertia_factor", "must be <= 1"),
    case("inertia-factor-zero.toml", "bodies[0].inertia_factor", "must be > 0"),
    # --- springs --------------------------------------------------------------------------------
    case("spring-one-end.toml", "springs[0].ends", "exactly two"),
    case("spring-three-ends.toml", "springs[0].ends", "exactly two"),
    case("unknown-spring-end.toml", "springs[0].ends", "unknown id", "'ghost'"),
    case("spring-to-itself.toml", "springs[0].ends", "'hoop'", "itself"),
    case("spring-between-anchors.toml", "springs[0].ends", "both ends are anchors"),
    case("spring-zero-length.toml", "springs[0]", "coincide", "length 0"),
    case("at-one-entry.toml", "springs[0].at", "one entry per end"),
    # --- attachments and forces -----------------------------------------------------------------
    case("anchor-end-with-attachment.toml", "springs[0].at[1]", "'wall'", "anchor", "{}"),
    case("angle-without-radius.toml", "springs[0].at[0]", "`angle` needs `radius`"),
    case("height-and-radius.toml", "springs[0].at[0]", "either", "not both"),
    case("slider-off-centre-spring.toml", "springs[0].at[0]", "'block'", "slider", "centre"),
    case("slider-off-centre-force.toml", "forces[0].at", "'block'", "slider", "centre"),
    case("force-unknown-body.toml", "forces[0].body", "unknown body", "'ghost'"),
]

IDS = [Path(c.file).stem for c in CASES]

runner = CliRunner()


def assert_mentions(message: str, expected: tuple[Expected, ...]) -> None:
    for item in expected:
        options = (item,) if isinstance(item, str) else item
        assert any(o in message for o in options), f"{message!r} lacks {' or '.join(options)!r}"


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_load_system_gives_a_one_line_message(case: Case) -> None:
    with pytest.raises(ModelError) as info:
        load_system(case.path)
    message = str(info.value)
    assert "\n" not in message and "\r" not in message, f"not one line: {message!r}"
    assert message.startswith(str(case.path)), f"does not name the file: {message!r}"
    assert_mentions(message, case.expected)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_cli_prints_one_line_and_exits_with_2(case: Case) -> None:
    result = runner.invoke(app, ["analyze", str(case.path)])
    everything = result.stdout + result.stderr + result.output
    assert "Traceback" not in everything
    assert result.exit_code == 2, everything
    assert result.stdout == ""
    assert result.stderr.startswith("error: ")
    assert result.stderr.count("\n") == 1 and result.stderr.endswith("\n"), result.stderr
    assert case.path.name in result.stderr
    assert_mentions(result.stderr, case.expected)


def test_every_fixture_is_a_case_and_every_case_is_distinct() -> None:
    on_disk = {p.name for p in INVALID.iterdir()}
    in_table = [c.file for c in CASES]
    assert not (INVALID / MISSING).exists()
    assert len(in_table) == len(set(in_table))
    assert on_disk == set(in_table) - {MISSING}
    contents = [c.path.read_bytes() for c in CASES if c.path.is_file()]
    assert len(contents) == len(set(contents))
    assert len(CASES) >= 35


# --- what must still be accepted ----------------------------------------------------------------

HOOP_CYLINDER_WITH_COMMENTED_AT = ISSUE_EXAMPLE.replace(
    "# at = [{ height = 0.2 }, { radius = 0.05, angle = 0.0 }]   # one entry per end",
    "# at = [{ height = 0.1 }, { height = 0.15 }]",
)


def test_the_issues_example_with_a_commented_out_at_line_loads(tmp_path: Path) -> None:
    path = tmp_path / "hoop-cylinder.toml"
    path.write_text(HOOP_CYLINDER_WITH_COMMENTED_AT, encoding="utf-8")
    system = load_system(path)
    assert [b.id for b in system.bodies] == ["hoop", "cylinder"]
    assert system.springs[0].at is None
    assert system.rest_lengths == [0.5]
    result = runner.invoke(app, ["analyze", str(path)])
    assert result.exit_code == 0, result.output
    assert result.stderr == ""


def test_the_example_file_loads() -> None:
    system = load_system(EXAMPLES / "hoop-cylinder.toml")
    assert [b.shape for b in system.bodies] == ["hoop", "cylinder"]
    assert system.springs[0].stiffness == 100.0


@pytest.mark.parametrize(
    ("name", "text"),
    [
        (
            "rolling.toml",
            '[[bodies]]\nid = "gear"\nshape = "cylinder"\nmass = 1.0\n'
            "radius = 0.1\nx = 0.0\nmu_static = inf\n",
        ),
        (
            "rolling.json",
            '{"bodies": [{"id": "gear", "shape": "cylinder", "mass": 1.0, '
            '"radius": 0.1, "x": 0.0, "mu_static": Infinity}]}',
        ),
    ],
    ids=["toml-inf", "json-Infinity"],
)
def test_mu_static_inf_is_accepted_and_enforces_rolling(
    tmp_path: Path, name: str, text: str
) -> None:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    (gear,) = load_system(path).bodies
    assert gear.mu_static == math.inf
    assert gear.mu_kinetic_value == 0.0


def test_mu_static_inf_analyses_from_the_cli(tmp_path: Path) -> None:
    path = tmp_path / "rack.toml"
    path.write_text(
        HOOP_CYLINDER_WITH_COMMENTED_AT.replace("mu_static = 1.0", "mu_static = inf"),
        encoding="utf-8",
    )
    assert all(b.mu_static == math.inf for b in load_system(path).bodies)
    result = runner.invoke(app, ["analyze", str(path)])
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output


def test_a_byte_order_mark_is_accepted(tmp_path: Path) -> None:
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + (EXAMPLES / "hoop-cylinder.toml").read_bytes())
    assert [b.id for b in load_system(path).bodies] == ["hoop", "cylinder"]


def test_a_path_with_a_line_break_stays_on_one_line(tmp_path: Path) -> None:
    path = tmp_path / "two\nlines.toml"
    with pytest.raises(ModelError) as info:
        load_system(path)
    assert "\n" not in str(info.value) and "file not found" in str(info.value)
