"""Hostile inputs (issue 13, point 4): nothing misbehaves on the input side.

Every malformed or hostile input to ``analyze``, ``simulate``, ``report``, ``animate``,
``export`` and ``derive`` — a file's syntax, types, NaN/inf/negative/huge values, unknown keys,
missing references, empty and binary files, directories, devices and FIFOs, huge files, deep
nesting, bad options and output paths, runs too large to start — gets exactly one line on
stderr, ``error: ...`` naming the field or the option, exit code 2, nothing on stdout, no
traceback and no warning. Each is refused before any long work starts (the cases run in well
under a second each; a few run as real processes, with a timeout, to check the exit code and the
stream as a user sees them).

Extreme but valid systems run correctly or are refused with the range that works (the ranges:
docs/system-files.md); what a user wrote is printed as text (no Rich markup, no control
characters); a run interrupted leaves no partial file; the Python API raises the CLI's errors.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import ModelError, RollspringError
from rollspring.model import LIMITS, MAX_FILE_BYTES, RANGES, load_system, preset_path

runner = CliRunner()
GOOD = preset_path("hoop-cylinder").read_text(encoding="utf-8")
COMMANDS = ("analyze", "simulate", "report", "animate", "export", "derive")

Expected = str | tuple[str, ...]


def variant(old: str, new: str, text: str = GOOD) -> str:
    """The paper's hoop and cylinder with the first ``old`` replaced by ``new``."""
    assert old in text, old
    return text.replace(old, new, 1)


def with_spring_line(line: str) -> str:
    return GOOD + line + "\n"


def chain(n: int, *, springs: bool = True) -> str:
    bodies = [
        {"id": f"b{i}", "shape": "cylinder", "mass": 1.0, "radius": 0.1, "x": 0.5 * i}
        for i in range(n)
    ]
    links = [
        {"ends": [f"b{i}", f"b{i + 1}"], "stiffness": 100.0, "rest_length": 0.49}
        for i in range(n - 1)
    ]
    return json.dumps({"bodies": bodies, "springs": links if springs else []})


def nested(depth: int) -> str:
    return "x = " + "[" * depth + "]" * depth + "\n"


# ------------------------------------------------------------------------------ the contents
# (file name, content, expected words): each is a system file the user gives to a command

CONTENTS: list[tuple[str, str | bytes, tuple[Expected, ...]]] = [
    # the file itself
    ("empty.toml", "", ("bodies", "missing")),
    ("blank.toml", "   \n\n\t\n", ("bodies", "missing")),
    ("only-a-comment.toml", "# nothing here\n", ("bodies", "missing")),
    ("only-a-bom.toml", b"\xef\xbb\xbf", ("bodies", "missing")),
    ("binary.toml", bytes(range(256)) * 4, ("UTF-8",)),
    ("random-bytes.json", np.random.default_rng(1).bytes(4096), ("UTF-8",)),
    ("nul-in-text.toml", variant('name = "', 'name = "\x00'), ("TOML syntax error",)),
    ("utf16.toml", GOOD.encode("utf-16"), ("UTF-8",)),
    ("latin1.toml", variant("Hoop", "H\xf6\xf6p").encode("latin-1"), ("UTF-8",)),
    ("huge.toml", "#" * (MAX_FILE_BYTES + 10), ("too large", str(MAX_FILE_BYTES))),
    ("unknown-type.yaml", GOOD, ("unknown file type", ".yaml")),
    # syntax
    ("toml-syntax.toml", GOOD + "\n[[bodies]\n", ("TOML syntax error",)),
    ("toml-unterminated.toml", 'name = "open\n', ("TOML syntax error",)),
    ("toml-duplicate-key.toml", variant("mass = 1.0", "mass = 1.0\nmass = 2.0"), ("TOML",)),
    ("json-syntax.json", '{"bodies": [}', ("JSON syntax error",)),
    ("json-trailing-comma.json", '{"bodies": [],}', ("JSON syntax error",)),
    ("json-array.json", "[]", ("top level", "JSON object")),
    ("json-null.json", "null", ("top level", "JSON object")),
    ("json-number.json", "42", ("top level", "JSON object")),
    ("json-string.json", '"bodies"', ("top level", "JSON object")),
    ("json-duplicate-key.json", '{"name": "a", "name": "b"}', ("duplicate key", "name")),
    ("toml-deep.toml", nested(5000), (("nest", "deep"),)),
    ("json-deep.json", '{"x": ' + "[" * 100000 + "]" * 100000 + "}", (("nest", "deep"),)),
    ("toml-5000-digits.toml", variant("x = 0.0", "x = " + "9" * 5000), ("digits",)),
    ("json-5000-digits.json", '{"x": ' + "9" * 5000 + "}", ("digits",)),
    # types
    ("mass-string.toml", variant("mass = 1.0", 'mass = "1"'), ("bodies[0].mass", "number")),
    ("mass-bool.toml", variant("mass = 1.0", "mass = true"), ("bodies[0].mass", "number")),
    ("mass-array.toml", variant("mass = 1.0", "mass = [1.0]"), ("bodies[0].mass", "number")),
    ("mass-table.toml", variant("mass = 1.0", "mass = {a = 1}"), ("bodies[0].mass", "number")),
    ("mass-date.toml", variant("mass = 1.0", "mass = 1979-05-27"), ("bodies[0].mass", "number")),
    ("bodies-string.toml", 'bodies = "hoop"\n', ("bodies", "list")),
    ("bodies-table.toml", "[bodies]\nid = 'a'\n", ("bodies", "list")),
    ("body-integer.json", '{"bodies": [1]}', ("bodies[0]", "table")),
    ("springs-string.toml", variant("[[springs]]", 'springs = "x"\n[[nothing]]'), ("springs",)),
    ("ends-string.toml", variant('ends = ["hoop", "cylinder"]', 'ends = "hoop"'), ("ends",)),
    (
        "ends-three.toml",
        variant('ends = ["hoop", "cylinder"]', 'ends = ["hoop", "a", "b"]'),
        ("ends", "two"),
    ),
    ("at-string.toml", variant("rest_length = 0.5", 'rest_length = 0.5\nat = "top"'), ("at",)),
    ("id-integer.toml", variant('id = "hoop"', "id = 7"), ("bodies[0].id", "string")),
    ("id-spaces.toml", variant('id = "hoop"', 'id = "my hoop"'), ("bodies[0].id", "letters")),
    ("id-65-chars.toml", variant('id = "hoop"', f'id = "{"h" * 65}"'), ("bodies[0].id", "64")),
    (
        "id-50k.toml",
        variant('id = "hoop"', f'id = "{"h" * 50000}"'),
        ("bodies[0].id", "characters"),
    ),
    ("shape-integer.toml", variant('shape = "hoop"', "shape = 3"), ("bodies[0].shape",)),
    (
        "shape-unknown.toml",
        variant('shape = "hoop"', 'shape = "disc"'),
        ("bodies[0].shape", "disc"),
    ),
    (
        "shape-10k.toml",
        variant('shape = "hoop"', f'shape = "{"d" * 10000}"'),
        ("bodies[0].shape", "characters"),
    ),
    (
        "name-integer.toml",
        variant('name = "Hoop and cylinder joined at their centres"', "name = 5"),
        ("name", "string"),
    ),
    ("name-10k.toml", variant('name = "', 'name = "' + "n" * 10000), ("name", "200")),
    (
        "name-escape.toml",
        variant('name = "', 'name = "\\u001b[2J'),
        ("name", "control characters", "\\x1b"),
    ),
    (
        "name-newline.toml",
        variant('name = "', 'name = "two\\nlines '),
        ("name", "control characters"),
    ),
    ("name-bidi.toml", variant('name = "', 'name = "\\u202e'), ("name", "control characters")),
    (
        "description-ansi.toml",
        variant('description = "', 'description = "\\u001b[31m'),
        ("description", "control"),
    ),
    (
        "description-1mb.toml",
        variant('description = "', 'description = "' + "d" * 1_000_000),
        ("description", "5000"),
    ),
    ("gravity-string.toml", variant("gravity = 9.81", 'gravity = "9.81"'), ("gravity", "number")),
    # NaN and infinity
    ("mass-nan.toml", variant("mass = 1.0", "mass = nan"), ("bodies[0].mass", "NaN")),
    ("x-inf.toml", variant("x = 0.0", "x = inf"), ("bodies[0].x", "finite")),
    ("v-minus-inf.toml", variant("x = 0.0", "x = 0.0\nv = -inf"), ("bodies[0].v", "finite")),
    (
        "stiffness-inf.toml",
        variant("stiffness = 100.0", "stiffness = inf"),
        ("springs[0].stiffness", "finite"),
    ),
    ("gravity-nan.toml", variant("gravity = 9.81", "gravity = nan"), ("gravity", "NaN")),
    (
        "rest-nan.toml",
        variant("rest_length = 0.5", "rest_length = nan"),
        ("springs[0].rest_length", "NaN"),
    ),
    ("damping-inf.toml", with_spring_line("damping = inf"), ("springs[0].damping", "finite")),
    (
        "mu-kinetic-inf.toml",
        variant("mu_static = 1.0", "mu_static = 1.0\nmu_kinetic = inf"),
        ("bodies[0].mu_kinetic", "finite"),
    ),
    (
        "mu-static-nan.toml",
        variant("mu_static = 1.0", "mu_static = nan"),
        ("bodies[0].mu_static", "NaN"),
    ),
    (
        "angle-nan.toml",
        with_spring_line("at = [{radius = 0.05, angle = nan}, {}]"),
        ("springs[0].at[0].angle", "NaN"),
    ),
    (
        "json-nan.json",
        '{"bodies": [{"id": "a", "shape": "hoop", "mass": NaN, "radius": 0.1, "x": 0}]}',
        ("bodies[0].mass", "NaN"),
    ),
    (
        "json-infinity.json",
        '{"bodies": [{"id": "a", "shape": "hoop", "mass": 1, "radius": Infinity, "x": 0}]}',
        ("bodies[0].radius", "finite"),
    ),
    (
        "json-overflow.json",
        '{"bodies": [{"id": "a", "shape": "hoop", "mass": 1, "radius": 1e999, "x": 0}]}',
        ("bodies[0].radius", "finite"),
    ),
    # negative values
    ("mass-negative.toml", variant("mass = 1.0", "mass = -1.0"), ("bodies[0].mass", "between")),
    (
        "radius-negative.toml",
        variant("radius = 0.1", "radius = -0.1"),
        ("bodies[0].radius", "between"),
    ),
    (
        "stiffness-negative.toml",
        variant("stiffness = 100.0", "stiffness = -5.0"),
        ("springs[0].stiffness", "between"),
    ),
    (
        "damping-negative.toml",
        with_spring_line("damping = -1.0"),
        ("springs[0].damping", "between"),
    ),
    (
        "rest-negative.toml",
        variant("rest_length = 0.5", "rest_length = -0.5"),
        ("springs[0].rest_length", "between"),
    ),
    ("gravity-negative.toml", variant("gravity = 9.81", "gravity = -9.81"), ("gravity", "between")),
    (
        "height-negative.toml",
        with_spring_line("at = [{height = -0.1}, {}]"),
        ("springs[0].at[0].height", "between"),
    ),
    (
        "at-radius-negative.toml",
        with_spring_line("at = [{radius = -0.1, angle = 0.0}, {}]"),
        ("springs[0].at[0].radius", "between"),
    ),
    (
        "mu-static-negative.toml",
        variant("mu_static = 1.0", "mu_static = -1.0"),
        ("bodies[0].mu_static", ">= 0"),
    ),
    (
        "mu-kinetic-negative.toml",
        variant("mu_static = 1.0", "mu_static = 1.0\nmu_kinetic = -0.5"),
        ("bodies[0].mu_kinetic", "between"),
    ),
    (
        "inertia-negative.toml",
        variant('shape = "hoop"', 'shape = "custom"\ninertia_factor = -0.5'),
        ("bodies[0].inertia_factor",),
    ),
    # huge and tiny values: each refused with the range that works
    (
        "mass-1e300.toml",
        variant("mass = 1.0", "mass = 1e300"),
        ("bodies[0].mass", "between 1e-06 and 1e+06 kg"),
    ),
    (
        "mass-1e-300.toml",
        variant("mass = 1.0", "mass = 1e-300"),
        ("bodies[0].mass", "between 1e-06 and 1e+06 kg"),
    ),
    (
        "mass-1e-308.toml",
        variant("mass = 1.0", "mass = 1e-308"),
        ("bodies[0].mass", "between 1e-06 and 1e+06 kg"),
    ),
    ("mass-subnormal.toml", variant("mass = 1.0", "mass = 5e-324"), ("bodies[0].mass", "between")),
    (
        "mass-1e-9.toml",
        variant("mass = 1.0", "mass = 1e-9"),
        ("bodies[0].mass", "between 1e-06 and 1e+06 kg"),
    ),
    (
        "radius-1e-300.toml",
        variant("radius = 0.1", "radius = 1e-300"),
        ("bodies[0].radius", "between 0.001 and 1000 m"),
    ),
    (
        "radius-1e300.toml",
        variant("radius = 0.1", "radius = 1e300"),
        ("bodies[0].radius", "between 0.001 and 1000 m"),
    ),
    (
        "x-1e300.toml",
        variant("x = 0.49", "x = 1e300"),
        ("bodies[1].x", "between -10000 and 10000 m"),
    ),
    (
        "x-max-float.toml",
        variant("x = 0.0", "x = -1.7976931348623157e308"),
        ("bodies[0].x", "between"),
    ),
    (
        "track-1e300.toml",
        variant("x = 0.0", "x = 0.0\ntrack_height = 1e300"),
        ("bodies[0].track_height", "between"),
    ),
    (
        "v-1e300.toml",
        variant("x = 0.0", "x = 0.0\nv = 1e300"),
        ("bodies[0].v", "between -10000 and 10000 m/s"),
    ),
    (
        "rest-1e300.toml",
        variant("rest_length = 0.5", "rest_length = 1e300"),
        ("springs[0].rest_length", "between 0 and 10000 m"),
    ),
    (
        "stiffness-1e300.toml",
        variant("stiffness = 100.0", "stiffness = 1e300"),
        ("springs[0].stiffness", "between 1e-06 and 1e+09 N/m"),
    ),
    (
        "stiffness-1e-300.toml",
        variant("stiffness = 100.0", "stiffness = 1e-300"),
        ("springs[0].stiffness", "between"),
    ),
    (
        "damping-1e300.toml",
        with_spring_line("damping = 1e300"),
        ("springs[0].damping", "between 0 and 1e+06 N s/m"),
    ),
    (
        "gravity-1e300.toml",
        variant("gravity = 9.81", "gravity = 1e300"),
        ("gravity", "between 0 and 1000"),
    ),
    (
        "angle-1e308.toml",
        with_spring_line("at = [{radius = 0.05, angle = 1e308}, {}]"),
        ("springs[0].at[0].angle", "between -360 and 360 degrees"),
    ),
    (
        "height-1e300.toml",
        with_spring_line("at = [{height = 1e300}, {}]"),
        ("springs[0].at[0].height", "between 0 and 10000 m"),
    ),
    (
        "mu-static-1e300.toml",
        variant("mu_static = 1.0", "mu_static = 1e300"),
        ("bodies[0].mu_static", "or inf"),
    ),
    (
        "force-1e300.toml",
        GOOD + '[[forces]]\nbody = "hoop"\nfx = 1e300\n',
        ("forces[0].fx", "between -1e+09 and 1e+09 N"),
    ),
    (
        "anchor-1e300.toml",
        GOOD + '[[anchors]]\nid = "wall"\nx = 0.0\ny = 1e300\n',
        ("anchors[0].y", "between"),
    ),
    ("integer-huge.toml", variant("x = 0.0", "x = " + "9" * 400), ("bodies[0].x",)),
    # unknown keys
    ("unknown-top.toml", "gravitation = 9.81\n" + GOOD, ("unknown key", "gravitation")),
    (
        "unknown-body-key.toml",
        variant("mass = 1.0", 'mass = 1.0\ncolour = "red"'),
        ("bodies[0]", "unknown key", "colour"),
    ),
    ("unknown-spring-key.toml", with_spring_line("colour = 1"), ("springs[0]", "unknown key")),
    (
        "unknown-at-key.toml",
        with_spring_line("at = [{angel = 3}, {}]"),
        ("springs[0].at[0]", "unknown key", "angel"),
    ),
    (
        "unknown-key-escape.toml",
        variant("mass = 1.0", 'mass = 1.0\n"\\u001b[2Jk" = 1'),
        ("bodies[0]", "unknown key", "\\x1b"),
    ),
    (
        "unknown-key-10k.toml",
        variant("mass = 1.0", f"mass = 1.0\n{'k' * 10000} = 1"),
        ("bodies[0]", "unknown key", "characters"),
    ),
    # missing values and references
    ("bodies-missing.toml", 'name = "nothing"\n', ("bodies", "missing")),
    ("bodies-empty.toml", "bodies = []\n", ("bodies", "at least one body")),
    ("mass-missing.toml", variant("mass = 1.0\n", ""), ("bodies[0].mass", "missing")),
    (
        "x-missing.json",
        '{"bodies": [{"id": "a", "shape": "hoop", "mass": 1, "radius": 0.1}]}',
        ("bodies[0].x", "missing"),
    ),
    (
        "x-null.json",
        '{"bodies": [{"id": "a", "shape": "hoop", "mass": 1, "radius": 0.1, "x": null}]}',
        ("bodies[0].x", "number"),
    ),
    (
        "spring-unknown-end.toml",
        variant('ends = ["hoop", "cylinder"]', 'ends = ["hoop", "ghost"]'),
        ("springs[0].ends", "unknown id", "ghost"),
    ),
    (
        "spring-to-itself.toml",
        variant('ends = ["hoop", "cylinder"]', 'ends = ["hoop", "hoop"]'),
        ("springs[0].ends", "itself"),
    ),
    (
        "force-unknown-body.toml",
        GOOD + '[[forces]]\nbody = "ghost"\nfx = 1.0\n',
        ("forces[0].body", "ghost"),
    ),
    ("duplicate-id.toml", variant('id = "cylinder"', 'id = "hoop"'), ("bodies[1].id", "duplicate")),
    (
        "anchors-both-ends.toml",
        GOOD.replace('ends = ["hoop", "cylinder"]', 'ends = ["w1", "w2"]')
        + '[[anchors]]\nid = "w1"\nx = 0\ny = 0\n[[anchors]]\nid = "w2"\nx = 1\ny = 0\n',
        ("springs[0].ends", "anchors"),
    ),
    (
        "angle-without-radius.toml",
        with_spring_line("at = [{angle = 30.0}, {}]"),
        ("springs[0].at[0]", "radius"),
    ),
    ("spring-zero-length.toml", variant("x = 0.49", "x = 0.0"), ("springs[0]", "coincide")),
    (
        "mu-kinetic-above.toml",
        variant("mu_static = 1.0", "mu_static = 1.0\nmu_kinetic = 2.0"),
        ("bodies[0]", "mu_kinetic"),
    ),
    # too many
    (
        "bodies-too-many.json",
        chain(LIMITS["bodies"] + 1, springs=False),
        ("bodies", f"at most {LIMITS['bodies']}"),
    ),
    (
        "springs-too-many.json",
        json.dumps(
            {
                "bodies": [
                    {"id": "a", "shape": "hoop", "mass": 1, "radius": 0.1, "x": 0},
                    {"id": "b", "shape": "hoop", "mass": 1, "radius": 0.1, "x": 1},
                ],
                "springs": [{"ends": ["a", "b"], "stiffness": 1}] * (LIMITS["springs"] + 1),
            }
        ),
        ("springs", f"at most {LIMITS['springs']}"),
    ),
    ("bodies-25000.json", chain(25000, springs=False), ("bodies", "at most 20000", "25000")),
]

#: the content cases each of the other four commands is also given (the rest, through analyze
#: and simulate, reach the same loader)
SAMPLED = (
    "binary.toml",
    "huge.toml",
    "toml-syntax.toml",
    "json-deep.json",
    "mass-1e300.toml",
    "radius-1e-300.toml",
    "angle-1e308.toml",
    "name-escape.toml",
    "unknown-key-10k.toml",
    "spring-unknown-end.toml",
    "bodies-25000.json",
)


@dataclass(frozen=True)
class Hostile:
    """One case: ``make(folder)`` writes its files into ``folder`` and returns the command line;
    ``expected``: substrings of the error line (a tuple: any one of them)."""

    id: str
    make: Callable[[Path], list[str]]
    expected: tuple[Expected, ...]


def _options(command: str, folder: Path) -> list[str]:
    """Valid options for ``command`` (so that the system is what fails)."""
    return {
        "analyze": [],
        "simulate": ["-T", "1"],
        "report": ["-T", "1", "--no-derivation", "-o", str(folder / "r.html")],
        "animate": ["-T", "0.5", "-o", str(folder / "a.gif")],
        "export": ["-o", str(folder / "m.xml")],
        "derive": ["-m", "newton"],
    }[command]


def _content_case(command: str, name: str, content: str | bytes, expected) -> Hostile:
    def make(folder: Path) -> list[str]:
        path = folder / name
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content, encoding="utf-8")
        return [command, str(path), *_options(command, folder)]

    return Hostile(f"{command}-{Path(name).stem}", make, (name, *expected))


def _fifo(folder: Path) -> Path:
    path = folder / "fifo.toml"
    os.mkfifo(path)
    return path


def _socket(folder: Path) -> Path:
    # a socket's path must be short (108 bytes): in a folder of its own under /tmp
    path = Path(tempfile.mkdtemp(prefix="rs-", dir="/tmp")) / "s.toml"
    server = socket.socket(socket.AF_UNIX)
    server.bind(str(path))
    _SOCKETS.append(server)
    return path


_SOCKETS: list[socket.socket] = []


def _loop(folder: Path) -> Path:
    path = folder / "loop.toml"
    os.symlink(path.name, path)
    return path


def _dangling(folder: Path) -> Path:
    path = folder / "dangling.toml"
    os.symlink(folder / "nowhere.toml", path)
    return path


def _folder(folder: Path) -> Path:
    path = folder / "a-folder.toml"
    path.mkdir()
    return path


#: (id, a function of the folder that gives the SYSTEM argument, expected words)
PATHS: list[tuple[str, Callable[[Path], object], tuple[Expected, ...]]] = [
    ("missing-file", lambda f: f / "no-such-file.toml", ("no-such-file.toml", "file not found")),
    ("unknown-preset", lambda f: "hoop-cylindre", ("hoop-cylindre", "neither a file nor a preset")),
    ("empty-argument", lambda f: "", ("system", "must not be empty")),
    ("a-folder", _folder, ("a-folder.toml", "folder")),
    ("dev-zero", lambda f: "/dev/zero", ("/dev/zero", "character device")),
    ("dev-null", lambda f: "/dev/null", ("/dev/null", "character device")),
    ("dev-urandom", lambda f: "/dev/urandom", ("/dev/urandom", "character device")),
    ("fifo", _fifo, ("fifo.toml", "FIFO")),
    ("socket", _socket, ("s.toml", "socket")),
    ("symlink-loop", _loop, ("loop.toml", "cannot read")),
    ("dangling-symlink", _dangling, ("dangling.toml", "cannot read")),
    ("nul-in-path", lambda f: str(f / "a\x00b.toml"), ("\\x00",)),
    ("path-10k", lambda f: str(f / ("p" * 10000 + ".toml")), ("characters",)),
    ("escape-in-path", lambda f: str(f / "\x1b[2Jx.toml"), ("\\x1b[2Jx.toml", "file not found")),
    ("proc-self-mem", lambda f: "/proc/self/mem", (("/proc/self/mem",),)),
]


def _path_case(command: str, case_id: str, system: Callable[[Path], object], expected) -> Hostile:
    def make(folder: Path) -> list[str]:
        return [command, str(system(folder)), *_options(command, folder)]

    return Hostile(f"{command}-{case_id}", make, expected)


def _blocker(folder: Path) -> Path:
    path = folder / "a-file"
    path.write_text("not a folder")
    return path


def _case(case_id: str, args: Callable[[Path], list[str]], *expected: Expected) -> Hostile:
    return Hostile(case_id, args, expected)


OPTIONS: list[Hostile] = [
    # simulate
    _case("simulate-T-0", lambda f: ["simulate", "-T", "0"], "duration"),
    _case("simulate-T-negative", lambda f: ["simulate", "-T", "-1"], "duration"),
    _case("simulate-T-nan", lambda f: ["simulate", "-T", "nan"], "duration"),
    _case("simulate-T-inf", lambda f: ["simulate", "-T", "inf"], "duration"),
    _case("simulate-T-text", lambda f: ["simulate", "-T", "abc"], "--duration"),
    _case("simulate-T-empty", lambda f: ["simulate", "-T", ""], "--duration"),
    _case("simulate-T-1e9", lambda f: ["simulate", "-T", "1e9"], "days", "--yes"),
    # beyond what double precision time resolves: refused even with --yes (issue 24: 1e308 was a
    # ZeroDivisionError, 1e300 --yes "about inf years" then an OverflowError)
    _case("simulate-T-1e300", lambda f: ["simulate", "-T", "1e300"], "duration", "precision"),
    _case(
        "simulate-T-1e300-yes",
        lambda f: ["simulate", "-T", "1e300", "--yes"],
        "duration",
        "precision",
    ),
    _case("simulate-T-1e308", lambda f: ["simulate", "-T", "1e308"], "duration", "precision"),
    _case("simulate-T-1e12-yes", lambda f: ["simulate", "-T", "1e12", "--yes"], "1.7e+15 steps"),
    _case("simulate-rtol-0", lambda f: ["simulate", "--rtol", "0"], "rtol"),
    _case("simulate-rtol-1", lambda f: ["simulate", "--rtol", "1"], "rtol"),
    _case("simulate-rtol-1e-300", lambda f: ["simulate", "--rtol", "1e-300"], "rtol", "1e-14"),
    _case("simulate-rtol-nan", lambda f: ["simulate", "--rtol", "nan"], "rtol"),
    _case("simulate-rtol-negative", lambda f: ["simulate", "--rtol", "-1e-8"], "rtol"),
    _case("simulate-outputs-1", lambda f: ["simulate", "--outputs", "1"], "n_output"),
    _case("simulate-outputs-negative", lambda f: ["simulate", "--outputs", "-5"], "n_output"),
    _case("simulate-outputs-float", lambda f: ["simulate", "--outputs", "1e3"], "--outputs"),
    _case("simulate-outputs-missing", lambda f: ["simulate", "--outputs"], "--outputs"),
    _case(
        "simulate-outputs-1e9",
        lambda f: ["simulate", "--outputs", "1000000000"],
        "memory",
        "--outputs",
    ),
    _case(
        "simulate-outputs-1e9-yes",
        lambda f: ["simulate", "--outputs", "1000000000", "--yes"],
        "memory",
    ),
    _case("simulate-outputs-huge", lambda f: ["simulate", "--outputs", "9" * 30], "memory"),
    _case(
        "simulate-integrator",
        lambda f: ["simulate", "--integrator", "euler"],
        "integrator",
        "euler",
    ),
    _case("simulate-integrator-empty", lambda f: ["simulate", "--integrator", ""], "integrator"),
    _case("simulate-on-slip", lambda f: ["simulate", "--on-slip", "skid"], "on_slip", "skid"),
    _case("simulate-unknown-option", lambda f: ["simulate", "--frobnicate"], "--frobnicate"),
    _case("simulate-extra-argument", lambda f: ["simulate", "hoop-cylinder", "two"], "two"),
    _case(
        "simulate-out-a-file", lambda f: ["simulate", "--out", str(_blocker(f))], "--out", "a file"
    ),
    _case(
        "simulate-out-under-a-file",
        lambda f: ["simulate", "--out", str(_blocker(f) / "run")],
        "--out",
        "not a directory",
    ),
    _case(
        "simulate-out-proc",
        lambda f: ["simulate", "--out", "/proc/rollspring-hostile"],
        "--out",
        "/proc",
    ),
    _case(
        "simulate-out-dev-null", lambda f: ["simulate", "--out", "/dev/null"], "--out", "/dev/null"
    ),
    _case("simulate-out-empty", lambda f: ["simulate", "--out", ""], "--out", "empty"),
    _case("simulate-out-nul", lambda f: ["simulate", "--out", str(f / "a\x00b")], "--out", "\\x00"),
    _case(
        "simulate-out-name-too-long",
        lambda f: ["simulate", "--out", str(f / ("n" * 300))],
        "--out",
        "too long",
    ),
    _case(
        "simulate-25000-bodies",
        lambda f: ["simulate", _write(f, "c.json", chain(25000))],
        "at most 20000",
    ),
    _case(
        "simulate-10000-bodies",
        lambda f: ["simulate", _write(f, "c.json", chain(10000))],
        "this run",
        "--yes",
    ),
    # analyze
    _case("analyze-unknown-option", lambda f: ["analyze", "--frob"], "--frob"),
    _case("analyze-extra-argument", lambda f: ["analyze", "hoop-cylinder", "extra"], "extra"),
    _case(
        "analyze-6000-bodies-every-mode",
        lambda f: ["analyze", _write(f, "c.json", chain(6000)), "--modes", "6000"],
        "the analysis",
        "--yes",
    ),
    _case("analyze-modes-form", lambda f: ["analyze", "--modes", "a-b"], "--modes", "'a-b'"),
    _case("analyze-modes-range", lambda f: ["analyze", "--modes", "3"], "modes", "1 to 2"),
    _case("no-such-command", lambda f: ["analyse"], "analyse"),
    # report
    _case(
        "report-format",
        lambda f: ["report", "-f", "docx", "-o", str(f / "r.docx")],
        "--format",
        "docx",
    ),
    _case("report-T-0", lambda f: ["report", "-T", "0", "-o", str(f / "r.html")], "--duration"),
    _case("report-T-nan", lambda f: ["report", "-T", "nan", "-o", str(f / "r.html")], "--duration"),
    _case("report-T-inf", lambda f: ["report", "-T", "inf", "-o", str(f / "r.html")], "--duration"),
    _case("report-T-1e9", lambda f: ["report", "-T", "1e9", "-o", str(f / "r.html")], "--yes"),
    _case("report-out-a-folder", lambda f: ["report", "-o", str(f)], "--out", "directory"),
    _case(
        "report-out-under-a-file",
        lambda f: ["report", "-o", str(_blocker(f) / "r.html")],
        "--out",
        "not a directory",
    ),
    _case(
        "report-out-dev-null",
        lambda f: ["report", "-o", "/dev/null"],
        "--out",
        "not a regular file",
    ),
    _case(
        "report-chromium-missing",
        lambda f: ["report", "-f", "pdf", "--chromium", str(f / "none"), "-o", str(f / "r.pdf")],
        "Chromium",
    ),
    _case(
        "report-10000-bodies",
        lambda f: ["report", _write(f, "c.json", chain(10000)), "-o", str(f / "r.html")],
        "--yes",
    ),
    # animate
    _case("animate-no-out", lambda f: ["animate", "hoop-cylinder"], "--out"),
    _case(
        "animate-out-suffix",
        lambda f: ["animate", "hoop-cylinder", "-o", str(f / "a.txt")],
        "--out",
        ".txt",
    ),
    _case(
        "animate-T-0",
        lambda f: ["animate", "hoop-cylinder", "-T", "0", "-o", str(f / "a.gif")],
        "--duration",
    ),
    _case(
        "animate-T-nan",
        lambda f: ["animate", "hoop-cylinder", "-T", "nan", "-o", str(f / "a.gif")],
        "--duration",
    ),
    _case(
        "animate-T-1e6",
        lambda f: ["animate", "hoop-cylinder", "-T", "1e6", "-o", str(f / "a.gif")],
        "--duration",
        "frames",
    ),
    _case(
        "animate-speed-0",
        lambda f: ["animate", "hoop-cylinder", "--speed", "0", "-o", str(f / "a.gif")],
        "--speed",
    ),
    _case(
        "animate-speed-inf",
        lambda f: ["animate", "hoop-cylinder", "--speed", "inf", "-o", str(f / "a.gif")],
        "--speed",
    ),
    _case(
        "animate-fps-0",
        lambda f: ["animate", "hoop-cylinder", "--fps", "0", "-o", str(f / "a.gif")],
        "--fps",
    ),
    _case(
        "animate-fps-1e6",
        lambda f: ["animate", "hoop-cylinder", "--fps", "1000000", "-o", str(f / "a.gif")],
        "--fps",
    ),
    _case(
        "animate-dpi-1",
        lambda f: ["animate", "hoop-cylinder", "--dpi", "1", "-o", str(f / "a.gif")],
        "--dpi",
    ),
    _case(
        "animate-dpi-huge",
        lambda f: ["animate", "hoop-cylinder", "--dpi", "100000", "-o", str(f / "a.gif")],
        "--dpi",
    ),
    _case(
        "animate-on-slip",
        lambda f: ["animate", "hoop-cylinder", "--on-slip", "x", "-o", str(f / "a.gif")],
        "--on-slip",
    ),
    _case(
        "animate-steps-huge",
        lambda f: [
            "animate",
            "hoop-cylinder",
            "-T",
            "1e9",
            "--speed",
            "1e9",
            "-o",
            str(f / "a.gif"),
        ],
        "--yes",
    ),
    _case(
        "animate-out-a-folder",
        lambda f: ["animate", "hoop-cylinder", "-o", _mkdir(f, "d.gif")],
        "--out",
        "directory",
    ),
    _case(
        "animate-out-under-a-file",
        lambda f: ["animate", "hoop-cylinder", "-o", str(_blocker(f) / "a.gif")],
        "--out",
        "not a directory",
    ),
    # export
    _case(
        "export-format",
        lambda f: ["export", "hoop-cylinder", "-f", "usd", "-o", str(f / "m.usd")],
        "--format",
        "usd",
    ),
    _case("export-no-out", lambda f: ["export", "hoop-cylinder"], "--out"),
    _case(
        "export-out-a-folder",
        lambda f: ["export", "hoop-cylinder", "-o", str(f)],
        "--out",
        "directory",
    ),
    _case(
        "export-out-under-a-file",
        lambda f: ["export", "hoop-cylinder", "-o", str(_blocker(f) / "m.xml")],
        "--out",
        "not a directory",
    ),
    _case(
        "export-out-dev-null",
        lambda f: ["export", "hoop-cylinder", "-o", "/dev/null"],
        "--out",
        "not a regular file",
    ),
    _case(
        "export-timestep-negative",
        lambda f: ["export", "hoop-cylinder", "-o", "-", "--timestep", "-1"],
        "timestep",
    ),
    _case(
        "export-timestep-nan",
        lambda f: ["export", "hoop-cylinder", "-o", "-", "--timestep", "nan"],
        "timestep",
    ),
    _case(
        "export-timestep-huge",
        lambda f: ["export", "hoop-cylinder", "-o", "-", "--timestep", "1e300"],
        "timestep",
    ),
    # derive
    _case(
        "derive-method", lambda f: ["derive", "hoop-cylinder", "-m", "magic"], "--method", "magic"
    ),
    _case("derive-format", lambda f: ["derive", "hoop-cylinder", "-f", "docx"], "--format", "docx"),
    _case(
        "derive-out-a-folder",
        lambda f: ["derive", "hoop-cylinder", "-o", str(f)],
        "--out",
        "directory",
    ),
    _case(
        "derive-out-under-a-file",
        lambda f: ["derive", "hoop-cylinder", "-o", str(_blocker(f) / "d.txt")],
        "--out",
        "not a directory",
    ),
    _case("derive-1000-bodies", lambda f: ["derive", _write(f, "c.json", chain(1000))], "--yes"),
]


def _mkdir(folder: Path, name: str) -> str:
    (folder / name).mkdir()
    return str(folder / name)


def _write(folder: Path, name: str, text: str) -> str:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _cases() -> list[Hostile]:
    cases = [_content_case(c, *content) for content in CONTENTS for c in ("analyze", "simulate")]
    sampled = [content for content in CONTENTS if content[0] in SAMPLED]
    assert len(sampled) == len(SAMPLED)
    cases += [_content_case(c, *content) for content in sampled for c in COMMANDS[2:]]
    cases += [_path_case("analyze", *path) for path in PATHS]
    cases += [_path_case(c, *path) for path in PATHS[3:9] for c in ("simulate", "report", "derive")]
    return cases + OPTIONS


CASES = _cases()


@pytest.fixture
def folder() -> Iterator[Path]:
    """A short folder of its own (a socket's path is limited to 108 bytes)."""
    path = Path(tempfile.mkdtemp(prefix="rs-hostile-"))
    try:
        yield path
    finally:
        import shutil

        shutil.rmtree(path, ignore_errors=True)
        for server in _SOCKETS:
            server.close()
        _SOCKETS.clear()


def assert_one_line_error(result, expected: tuple[Expected, ...]) -> str:
    everything = result.stdout + result.stderr
    assert "Traceback" not in everything
    assert result.exit_code == 2, everything
    assert result.stdout == ""
    assert result.stderr.startswith("error: "), result.stderr
    assert result.stderr.endswith("\n") and result.stderr.count("\n") == 1, result.stderr
    assert "\x1b" not in result.stderr and "\x00" not in result.stderr
    assert len(result.stderr) <= 2000, len(result.stderr)
    for item in expected:
        options = (item,) if isinstance(item, str) else item
        assert any(o in result.stderr for o in options), f"{result.stderr!r} lacks {options}"
    return result.stderr


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_every_hostile_input_is_one_line_exit_2_and_no_warning(case: Hostile, folder) -> None:
    args = case.make(folder)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = runner.invoke(app, args)
    assert_one_line_error(result, case.expected)
    assert [str(w.message) for w in caught] == []
    # nothing written beside the inputs
    assert not [
        p for p in folder.iterdir() if p.is_file() and p.suffix in (".html", ".gif", ".xml")
    ]


def test_there_are_at_least_150_cases_over_every_command() -> None:
    assert len(CASES) >= 150
    assert len({c.id for c in CASES}) == len(CASES)
    for command in COMMANDS:
        assert sum(c.id.startswith(command) for c in CASES) >= 10, command


# -------------------------------------------------------------------- as a real process


def _rollspring(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", "from rollspring.cli import main; main()", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, "PYTHONWARNINGS": "error::RuntimeWarning"},
    )


@pytest.mark.parametrize(
    ("make", "expected"),
    [
        (lambda f: ["analyze", str(_fifo(f))], "FIFO"),
        (lambda f: ["analyze", "/dev/zero"], "character device"),
        (lambda f: ["simulate", _write(f, "huge.toml", "#" * (MAX_FILE_BYTES + 1))], "too large"),
        (lambda f: ["simulate", "-T", "1e9"], "--yes"),
        (lambda f: ["simulate", "--outputs", "1000000000"], "memory"),
        (lambda f: ["simulate", "-T", "abc"], "--duration"),
        (lambda f: ["animate", "hoop-cylinder", "-o", str(_blocker(f) / "a.gif")], "--out"),
        (lambda f: ["export", _write(f, "m.toml", variant("mass = 1.0", "mass = 1e300"))], "--out"),
    ],
    ids=["fifo", "dev-zero", "huge-file", "long-run", "memory", "bad-number", "out", "export"],
)
def test_as_a_real_process_one_line_exit_2(make, expected, folder) -> None:
    """The exit code and stderr as a shell sees them; a FIFO never hangs (the timeout)."""
    started = time.perf_counter()
    result = _rollspring(*make(folder))
    assert time.perf_counter() - started < 60
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    assert "Traceback" not in result.stderr and "Warning" not in result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and expected in lines[0], lines


# ------------------------------------------------------------------------ user text as text


def test_markup_in_a_name_is_printed_as_text() -> None:
    text = variant("Hoop and cylinder joined at their centres", "[/bold] [red]oops[bold]")
    with tempfile.TemporaryDirectory() as folder:
        path = _write(Path(folder), "markup.toml", text)
        analyzed = runner.invoke(app, ["analyze", path])
        simulated = runner.invoke(app, ["simulate", path, "-T", "0.5"])
    for result in (analyzed, simulated):
        assert result.exit_code == 0, result.output
        assert "[/bold] [red]oops[bold]" in result.stdout


def test_a_long_message_is_cut_to_one_bounded_line() -> None:
    """A 50 MB id gave a 52 MB line; the value is cut in the message itself (the API's too)."""
    data = json.loads(chain(2))
    data["bodies"][0]["id"] = "x" * 50_000_000
    with pytest.raises(ModelError) as info:
        rollspring.system_from_dict(data)
    assert len(str(info.value)) < 400
    assert "50000000 characters" in str(info.value)


def test_overlapping_bodies_are_warned_about() -> None:
    text = variant("x = 0.49", "x = 0.05").replace("rest_length = 0.5", "rest_length = 0.06")
    with tempfile.TemporaryDirectory() as folder:
        result = runner.invoke(app, ["analyze", _write(Path(folder), "overlap.toml", text)])
    assert result.exit_code == 0, result.output
    assert result.stderr.startswith("warning: bodies 'hoop' and 'cylinder' overlap")
    assert not load_system("hoop-cylinder").overlaps


# ------------------------------------------------------------- extreme values that are valid


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("stiffness = 100.0", "stiffness = 1e9"),
        ("mass = 1.0", "mass = 1e-6"),
        ("mass = 1.0", "mass = 1e6"),
        ("radius = 0.1", "radius = 0.001"),
        ("gravity = 9.81", "gravity = 1000.0"),
        ("x = 0.0", "x = -0.5\ntrack_height = 9999.0"),
    ],
    ids=["stiffness-1e9", "mass-1e-6", "mass-1e6", "radius-1mm", "gravity-1000", "track-1e4"],
)
def test_extremes_within_the_ranges_run_without_warnings(old, new) -> None:
    """At the ends of the ranges: the analysis and a short run give numbers (no NaN, no null
    where a number belongs) and no warning of NumPy or SciPy."""
    system = rollspring.system_from_dict(_toml(variant(old, new)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = rollspring.analyze(system)
        oscillating = [m for m in result.modes if m.kind == "oscillating"]
        assert oscillating and all(np.isfinite(m.omega) and m.omega > 0 for m in oscillating)
        run = rollspring.simulate(system, min(1.0, 3 * oscillating[0].period), n_output=51)
    assert np.all(np.isfinite(run.x)) and np.isfinite(run.summary["energy"])


@pytest.mark.parametrize("mass", [1e-6, 1e6])
@pytest.mark.parametrize("stiffness", [1e-6, 1e9])
@pytest.mark.parametrize("size", [1e-3, 1e3])
def test_corners_of_the_ranges_give_numbers_or_say_why(mass, stiffness, size) -> None:
    """Every extreme at once (a wall, an off-centre spring, gravity): the analysis' JSON (what
    analyze --json prints) holds no NaN or infinity, nothing warns, and a short run ends with a
    status of its own (finished, slip, lift-off; an energy error is a status, not a crash). Some
    corners have no equilibrium the search can find (a stiffness of 1e-06 N/m on 1e+06 kg):
    said as the analysis' warning (docs/system-files.md)."""
    scale = size / 0.1
    data = {
        "anchors": [{"id": "wall", "x": -0.5 * scale, "y": 0.15 * scale}],
        "bodies": [
            {"id": "hoop", "shape": "hoop", "mass": mass, "radius": size, "x": 0.0},
            {"id": "cyl", "shape": "cylinder", "mass": mass, "radius": size, "x": 0.49 * scale},
        ],
        "springs": [
            {
                "ends": ["wall", "hoop"],
                "stiffness": stiffness,
                "rest_length": 0.5 * scale,
                "at": [{}, {"height": 0.15 * scale}],
            },
            {"ends": ["hoop", "cyl"], "stiffness": stiffness, "rest_length": 0.5 * scale},
        ],
    }
    from rollspring.simulate.costs import simulation_cost

    system = rollspring.system_from_dict(data)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = rollspring.analyze(system)
        json.dumps(result.to_dict(), allow_nan=False)
        if not result.equilibrium.found:
            assert any("no equilibrium" in w for w in result.warnings)
        oscillating = [m for m in result.modes if m.kind == "oscillating"]
        duration = min(1.0, 3 * oscillating[0].period) if oscillating else 1.0
        if simulation_cost(system, duration, outputs=51).seconds < 5:
            run = rollspring.simulate(system, duration, n_output=51)
            json.dumps(rollspring.outputs.summary_json(run), allow_nan=False)
            assert run.status in ("finished", "slip", "liftoff", "energy_error")


def _toml(text: str) -> dict:
    import tomllib

    return tomllib.loads(text)


def test_every_range_is_stated_in_the_docs() -> None:
    docs = (Path(__file__).resolve().parents[1] / "docs" / "system-files.md").read_text()
    for low, high, unit in RANGES.values():
        assert f"{low:g}" in docs and f"{high:g}" in docs and unit in docs
    for limit in LIMITS.values():
        assert str(limit) in docs


# ------------------------------------------------------------------ interrupted, killed runs


def test_a_terminated_run_leaves_the_earlier_set_and_no_temporary_file(folder) -> None:
    """SIGTERM (as Ctrl-C) in the middle of a long run: the folder keeps the earlier run's
    three files, unchanged, and nothing else."""
    out = folder / "out"
    first = _rollspring("simulate", "hoop-cylinder", "-T", "1", "--out", str(out))
    assert first.returncode == 0, first.stderr
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    process = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "from rollspring.cli import main; main()",
            "simulate",
            "hoop-cylinder",
            "-T",
            "1e5",
            "--yes",
            "--out",
            str(out),
        ],
        stderr=subprocess.PIPE,
        text=True,
    )
    assert process.stderr is not None
    note = process.stderr.readline()  # the estimate, printed before the run starts
    assert note.startswith("note: this run will take"), note
    time.sleep(1.0)
    process.send_signal(signal.SIGTERM)
    _, rest = process.communicate(timeout=60)
    assert process.returncode == 130, rest
    assert "interrupted" in rest and "Traceback" not in rest
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in folder.iterdir()) == ["out"]


# --------------------------------------------------------------------------- the Python API


@pytest.mark.parametrize(
    "value",
    [None, 3, 2.5, ["hoop-cylinder"], b"hoop-cylinder"],
    ids=["None", "int", "float", "list", "bytes"],
)
def test_the_api_raises_the_clis_error_for_what_is_not_a_system(value) -> None:
    with pytest.raises(ModelError, match=r"^system: must be "):
        rollspring.model.as_system(value)
    with pytest.raises(RollspringError):
        rollspring.build_report(value)


def test_the_api_and_the_cli_give_the_same_message(folder) -> None:
    path = _write(folder, "bad.toml", variant("mass = 1.0", "mass = 1e300"))
    with pytest.raises(ModelError) as info:
        rollspring.load_system(path)
    result = runner.invoke(app, ["analyze", path])
    assert result.stderr == f"error: {info.value}\n"
    with pytest.raises(ModelError) as preset:
        rollspring.model.as_system("hoop-cylindre")
    assert runner.invoke(app, ["analyze", "hoop-cylindre"]).stderr == f"error: {preset.value}\n"


def test_the_api_takes_numpy_counts_and_refuses_booleans() -> None:
    system = load_system("hoop-cylinder")
    run = rollspring.simulate(system, np.float64(0.5), n_output=np.int64(11))
    assert run.t.size == 11
    with pytest.raises(RollspringError, match="duration"):
        rollspring.simulate(system, True)
    with pytest.raises(RollspringError, match="n_output"):
        rollspring.simulate(system, 0.5, n_output=True)
