"""System files: the documented example, TOML = JSON, attachments, defaults, presets."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import pytest

from rollspring.model import load_system, preset_names, preset_path, system_from_dict
from tests.conftest import body, make_system, spring

ROOT = Path(__file__).resolve().parents[1]

ISSUE_EXAMPLE = """\
name = "Hoop and cylinder joined at their centres"
gravity = 9.81

[[bodies]]
id = "hoop"
shape = "hoop"
mass = 1.0
radius = 0.1
x = 0.0
mu_static = 1.0

[[bodies]]
id = "cylinder"
shape = "cylinder"
mass = 1.0
radius = 0.1
x = 0.49          # the 0.5 m spring starts compressed by 0.01 m
mu_static = 1.0

[[springs]]
ends = ["hoop", "cylinder"]
stiffness = 100.0
rest_length = 0.5
# at = [{ height = 0.2 }, { radius = 0.05, angle = 0.0 }]   # one entry per end
"""


def test_the_documented_example_loads_as_it_is(tmp_path: Path) -> None:
    path = tmp_path / "example.toml"
    path.write_text(ISSUE_EXAMPLE)
    system = load_system(path)
    assert [b.id for b in system.bodies] == ["hoop", "cylinder"]
    assert system.bodies[0].contact_inertia == pytest.approx(2 * 1.0 * 0.1**2)  # I'_1 = 2 m1 R^2
    assert system.bodies[1].contact_inertia == pytest.approx(1.5 * 1.0 * 0.1**2)  # I'_2
    assert system.rest_lengths == [0.5]


def test_json_and_toml_describe_the_same_system(tmp_path: Path) -> None:
    data = tomllib.loads(ISSUE_EXAMPLE)
    path = tmp_path / "example.json"
    path.write_text(json.dumps(data))
    toml_path = tmp_path / "example.toml"
    toml_path.write_text(ISSUE_EXAMPLE)
    assert load_system(path) == load_system(toml_path)


def test_anchors_forces_and_attachments_of_the_documented_forms() -> None:
    system = system_from_dict(
        tomllib.loads(
            ISSUE_EXAMPLE
            + """
[[anchors]]
id = "wall"
x = -0.3
y = 0.1

[[springs]]
ends = ["wall", "hoop"]
stiffness = 50.0
at = [{}, { radius = 0.05, angle = 90.0 }]

[[forces]]
body = "cylinder"
at = { height = 0.15 }
fx = 1.0
fy = 0.0
"""
        )
    )
    wall_spring = system.springs[1]
    hoop = system.bodies[0]
    r, alpha = wall_spring.attachments[1].polar(hoop)
    assert (r, alpha) == (0.05, pytest.approx(math.pi / 2))
    # default rest length: the initial length, from (-0.3, 0.1) to (0.05, 0.1)
    assert system.rest_lengths[1] == pytest.approx(0.35)
    cylinder = system.bodies[1]
    assert system.forces[0].at.polar(cylinder) == (pytest.approx(0.05), 0.0)


def test_height_below_the_centre_points_down() -> None:
    system = make_system(
        [body("c", "cylinder", radius=0.2)],
        forces=[{"body": "c", "at": {"height": 0.05}, "fx": 1.0}],
    )
    r, alpha = system.forces[0].at.polar(system.bodies[0])
    assert r == pytest.approx(0.15)
    assert alpha == pytest.approx(math.pi)


def test_defaults() -> None:
    system = make_system(
        [
            body("a", "sphere", x=0.0),
            body("b", "custom", inertia_factor=0.3, x=1.0, mu_static=math.inf),
        ],
        [spring("a", "b")],
    )
    a, b = system.bodies
    assert system.gravity == 9.81
    assert (a.v, a.track_height, a.mu_static, a.mu_kinetic_value) == (0.0, 0.0, 1.0, 1.0)
    assert a.gamma == pytest.approx(0.4)
    assert b.gamma == 0.3
    assert b.mu_static == math.inf and b.mu_kinetic_value == 0.0
    assert system.springs[0].damping == 0.0
    assert system.rest_lengths == [1.0]


@pytest.mark.parametrize(
    "shape,gamma,height",
    [("hoop", 1.0, 2.0), ("cylinder", 0.5, 1.5), ("sphere", 0.4, 1.4), ("shell", 2 / 3, 5 / 3)],
)
def test_inertia_and_percussion_height_of_each_shape(shape, gamma, height) -> None:
    b = make_system([body("b", shape, mass=2.0, radius=0.5)]).bodies[0]
    assert b.central_inertia == pytest.approx(gamma * 2.0 * 0.25)
    assert b.contact_inertia == pytest.approx((1 + gamma) * 2.0 * 0.25)  # Steiner (M4)
    assert b.percussion_height == pytest.approx(height * 0.5)  # paper: 2R hoop, 1.5R cylinder


def test_every_preset_is_also_a_file_in_examples() -> None:
    examples = sorted(p.stem for p in (ROOT / "examples").glob("*.toml"))
    assert examples == preset_names()
    for name in examples:
        assert (ROOT / "examples" / f"{name}.toml").read_text() == preset_path(name).read_text()
        assert load_system(ROOT / "examples" / f"{name}.toml") == load_system(name)


@pytest.mark.parametrize("name", ["chain-monatomic", "chain-diatomic"])
def test_chain_presets_are_what_their_command_writes(name: str) -> None:
    """A chain preset is the output of the ``rollspring chain`` command its first line names,
    with a description written by hand (run here in-process, its output compared line by line)."""
    import shlex

    from typer.testing import CliRunner

    from rollspring.cli import app

    text = preset_path(name).read_text()
    first, second, *rest = text.splitlines(keepends=True)
    assert first.startswith("# Written by `rollspring chain ") and second.startswith("# ")
    command = shlex.split(first.removeprefix("# Written by `").rstrip().removesuffix("`"))
    assert command[:2] == ["rollspring", "chain"]
    result = CliRunner().invoke(app, command[1:])
    assert result.exit_code == 0, result.output
    written = result.stdout.splitlines(keepends=True)
    assert len(written) == len(rest)
    for mine, theirs in zip(rest, written, strict=True):
        if theirs.startswith("description = "):
            assert mine.startswith("description = ") and len(mine) > len(theirs)
        else:
            assert mine == theirs
    system = load_system(name)
    assert len(system.bodies) == 8 and [a.id for a in system.anchors] == ["wall-left", "wall-right"]
    assert all(s.rest_length == pytest.approx(0.5) for s in system.springs)  # before the pluck
    assert system.bodies[0].x == pytest.approx(0.01)  # the struck end body
