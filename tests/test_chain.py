"""The chain generator (``rollspring.chain``, ``rollspring chain``): geometry, walls, initial
conditions, validation, and the lattice frequencies of a chain between two walls."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import rollspring
from rollspring import analyze
from rollspring.cli import app
from rollspring.errors import ModelError
from rollspring.model import INERTIA_FACTORS, load_system, system_from_dict, system_to_json
from rollspring.model.chains import chain


def _oscillating(system):
    return [m for m in analyze(system).modes if m.kind == "oscillating"]


def test_the_chain_is_exported_lazily() -> None:
    assert rollspring.chain is chain
    assert rollspring.model.chain is chain


def test_a_free_diatomic_chain_alternates_its_unit_at_rest() -> None:
    system = chain("hoop,cylinder", 6, mass=[1.0, 2.0], radius=[0.1, 0.05], spacing=0.4)
    assert [b.shape for b in system.bodies] == ["hoop", "cylinder"] * 3
    assert [b.mass for b in system.bodies] == [1.0, 2.0] * 3
    assert [b.radius for b in system.bodies] == [0.1, 0.05] * 3
    assert [b.x for b in system.bodies] == pytest.approx([0.4 * i for i in range(6)])
    assert not system.anchors
    assert [s.ends for s in system.springs] == [
        [system.bodies[i].id, system.bodies[i + 1].id] for i in range(5)
    ]
    # at rest: the placement is the equilibrium, every spring at its initial length (the
    # centres are 0.05 m apart in height: the springs are tilted)
    assert system.rest_lengths == pytest.approx([math.hypot(0.4, 0.05)] * 5, rel=1e-15)
    result = analyze(system)
    assert result.equilibrium.found
    np.testing.assert_allclose(result.equilibrium.q, 0.0, atol=1e-15)
    assert sum(m.kind == "zero" for m in result.modes) == 1


@pytest.mark.parametrize(("walls", "anchors", "springs"), [("left", 1, 5), ("both", 2, 6)])
def test_walls_are_anchors_where_the_missing_neighbours_would_be(
    walls: str, anchors: int, springs: int
) -> None:
    system = chain("hoop,cylinder", 5, height=[0.15, 0.02], walls=walls, spacing=0.5)
    assert len(system.anchors) == anchors and len(system.springs) == springs
    left = system.anchor_map["wall-left"]
    # the element before body 0 is a cylinder (attached at 0.02 m), at x = -spacing
    assert (left.x, left.y) == (-0.5, 0.02)
    if walls == "both":
        right = system.anchor_map["wall-right"]
        # after body 4 (a hoop) comes body 5, a cylinder, at 5 spacings
        assert (right.x, right.y) == (2.5, 0.02)
    result = analyze(system)
    assert result.equilibrium.found and not any("pre-tension" in w for w in result.warnings)
    np.testing.assert_allclose(result.spring_tension, 0.0, atol=1e-12)
    assert all(m.kind == "oscillating" for m in result.modes)


@pytest.mark.parametrize("shape", ["hoop", "cylinder", "sphere", "shell", "slider"])
@pytest.mark.parametrize("n", [2, 3, 10, 25, 50])
def test_equal_bodies_between_two_walls_have_the_lattice_frequencies(shape: str, n: int) -> None:
    """omega_n = 2 sqrt(k/M) sin(n pi/(2(N+1))), M = (1 + gamma) m: the dense analysis."""
    rng = np.random.default_rng(n)
    mass, radius, k = rng.uniform(0.2, 5.0), rng.uniform(0.02, 0.2), rng.uniform(10.0, 1e4)
    system = chain(shape, n, mass=mass, radius=radius, stiffness=k, spacing=0.5, walls="both")
    gamma = 0.0 if shape == "slider" else INERTIA_FACTORS[shape]
    rolling_mass = (1.0 + gamma) * mass
    omegas = np.array([m.omega for m in _oscillating(system)])
    expected = (
        2.0 * math.sqrt(k / rolling_mass) * np.sin(np.arange(1, n + 1) * math.pi / (2 * (n + 1)))
    )
    np.testing.assert_allclose(omegas, expected, rtol=1e-10, atol=0.0)


def test_pluck_displaces_one_body_and_keeps_the_rest_lengths() -> None:
    at_rest = chain("hoop,cylinder", 6, walls="both")
    plucked = chain("hoop,cylinder", 6, walls="both", pluck=3, amplitude=0.02)
    moved = [b.x - a.x for a, b in zip(at_rest.bodies, plucked.bodies, strict=True)]
    assert moved == pytest.approx([0, 0, 0.02, 0, 0, 0], abs=1e-15)
    assert plucked.rest_lengths == pytest.approx(at_rest.rest_lengths, abs=1e-15)
    assert all(b.v == 0.0 for b in plucked.bodies)


def test_mode_starts_along_the_analysed_normal_mode() -> None:
    """Off-centre attachments: the generator's closed-form K is the analysis' exact one."""
    kwargs = {"pattern": "hoop,cylinder,sphere", "n": 7, "height": [0.18, 0.03, 0.1]}
    at_rest = chain(**kwargs, walls="both")
    modes = _oscillating(at_rest)
    for n in (1, 4, 7):
        started = chain(**kwargs, walls="both", mode=n, amplitude=0.01)
        moved = np.array([b.x - a.x for a, b in zip(at_rest.bodies, started.bodies, strict=True)])
        np.testing.assert_allclose(moved, 0.01 * modes[n - 1].shape_x, atol=1e-12)
    # a free chain: mode 1 is the lowest oscillating one, the zero mode is not counted
    free = chain("hoop", 4)
    moved = np.array(
        [b.x - a.x for a, b in zip(free.bodies, chain("hoop", 4, mode=1).bodies, strict=True)]
    )
    expected = 0.01 * _oscillating(free)[0].shape_x
    assert moved[0] == pytest.approx(0.01)  # the leftmost of the two largest is +amplitude
    np.testing.assert_allclose(
        moved * np.sign(expected[0]) * np.sign(moved[0]), expected, atol=1e-12
    )


def test_a_packet_is_a_gaussian_travelling_wave_of_the_branch() -> None:
    n, q, width, amplitude, k, spacing = 40, 3.0, 1.5, 0.005, 200.0, 0.5
    system = chain(
        "cylinder", n, stiffness=k, spacing=spacing, packet=(q, width), amplitude=amplitude
    )
    x = spacing * np.arange(n)
    envelope = amplitude * np.exp(-((x - x[-1] / 2) ** 2) / (2 * width**2))
    omega = 2 * math.sqrt(k / 1.5) * math.sin(q * spacing / 2)  # M = 1.5 m
    moved = np.array([b.x for b in system.bodies]) - x
    np.testing.assert_allclose(moved, envelope * np.cos(q * x), atol=1e-15)
    velocity = np.array([b.v for b in system.bodies])
    np.testing.assert_allclose(velocity, omega * envelope * np.sin(q * x), atol=1e-14)


def test_written_files_load_back_as_the_same_system() -> None:
    system = chain("hoop,sphere", 5, height=0.12, walls="left", pluck=2)
    again = system_from_dict(json.loads(json.dumps(system_to_json(system))))
    assert again == system


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"pattern": "hoop,cyl"}, "pattern: unknown shape 'cyl'"),
        ({"pattern": ""}, "pattern: give one or more shapes"),
        ({"n": 1}, "n: must be from 2 to 20000"),
        ({"n": 20001}, "n: must be from 2 to 20000"),
        ({"n": 2.5}, "n: must be a whole number"),
        ({"mass": [1.0, 2.0, 3.0]}, "mass: give one value or one per element of the pattern (2)"),
        ({"radius": -0.1}, "radius: must be positive"),
        ({"stiffness": math.nan}, "stiffness: must be a finite number"),
        ({"spacing": 0.0}, "spacing: must be positive"),
        ({"walls": "right"}, "walls: must be one of none, left, both"),
        ({"pluck": 0}, "pluck: must be a body from 1 to 10"),
        ({"pluck": 11}, "pluck: must be a body from 1 to 10"),
        ({"mode": 10}, "mode: must be from 1 to 9"),
        ({"packet": (10.0, 1.0)}, "packet: the wavenumber must lie in the first Brillouin zone"),
        ({"packet": (1.0, -1.0)}, "packet width: must be positive"),
        ({"packet": (1.0, 1.0), "branch": 3}, "branch: must be from 1 to 2"),
        ({"pluck": 1, "mode": 1}, "mode: give at most one initial condition (also pluck)"),
        ({"pluck": 1, "amplitude": 0.0}, "amplitude: must be positive"),
        ({"pattern": "hoop,slider", "height": [0.15, 0.05]}, "height: element 2 is a slider"),
        ({"mass": 1e9}, "chain: bodies[0].mass: must be between"),
    ],
)
def test_invalid_arguments_are_one_line_errors_naming_the_argument(kwargs, message: str) -> None:
    with pytest.raises(ModelError) as raised:
        chain(**kwargs)
    text = str(raised.value)
    assert message in text and "\n" not in text


runner = CliRunner()


def test_cli_prints_the_toml_file_and_writes_toml_or_json(tmp_path) -> None:
    done = runner.invoke(
        app, ["chain", "--pattern", "hoop,cylinder", "--n", "6", "--walls", "both"]
    )
    assert done.exit_code == 0, done.output
    path = tmp_path / "printed.toml"
    path.write_text(done.stdout)
    assert load_system(path) == chain("hoop,cylinder", 6, walls="both")
    for name in ("c.toml", "c.json"):
        done = runner.invoke(
            app,
            ["chain", "--pattern", "cylinder", "--n", "8", "--mass", "2", "--radius", "0.05",
             "--height", "0.07", "--stiffness", "300", "--spacing", "0.3", "--pluck", "1",
             "-o", str(tmp_path / name)],
        )  # fmt: skip
        assert done.exit_code == 0, done.output
        expected = chain(
            "cylinder", 8, mass=2, radius=0.05, height=0.07, stiffness=300, spacing=0.3, pluck=1
        )
        assert load_system(tmp_path / name) == expected
    assert (tmp_path / "c.json").read_text().lstrip().startswith("{")
    done = runner.invoke(app, ["chain", "--n", "4", "--packet", "1,0.5", "--json"])
    assert done.exit_code == 0
    assert len(json.loads(done.stdout)["bodies"]) == 4


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--pattern", "hoop,cyl"], "error: --pattern: unknown shape 'cyl'"),
        (["--mass", "1,x"], "error: --mass: '1,x' is not a comma-separated list of numbers"),
        (["--n", "0"], "error: --n: must be from 2 to 20000"),
        (["--packet", "1"], "error: --packet: give q,width"),
        (["--pluck", "2", "--mode", "1"], "error: --mode: give at most one initial condition"),
        (["--walls", "up"], "error: --walls: must be one of none, left, both"),
        (["-o", "chain.txt"], "error: --out: chain.txt: a system file ends in .toml or .json"),
        (["-o", "chain.json", "--json"], "error: --json: prints the file on stdout"),
    ],
)
def test_cli_errors_are_one_line_with_exit_code_2(args: list[str], message: str) -> None:
    done = runner.invoke(app, ["chain", *args])
    assert done.exit_code == 2
    assert done.stderr.strip().startswith(message), done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert done.stdout == ""


def test_the_largest_chain_written_is_a_file_every_command_reads(tmp_path) -> None:
    """chain --n 20000 --pluck 1 -o x.json wrote 7.8 MB, and every other command refused any
    system file above 4 MiB: the file limit now holds the model's largest chain."""
    from rollspring.model import MAX_FILE_BYTES, load_system
    from rollspring.model.chains import chain
    from rollspring.service.chains import system_text

    system = chain(("hoop", "cylinder"), 20000, pluck=1)
    for suffix in ("json", "toml"):
        path = tmp_path / f"big.{suffix}"
        path.write_text(system_text(system, suffix))
        assert path.stat().st_size <= MAX_FILE_BYTES
        assert len(load_system(path).bodies) == 20000
