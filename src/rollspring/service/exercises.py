r"""The exercises of the worksheet levels: a seeded random system, its setting in words, and
the questions with the numeric answers its analysis gives.

:func:`rollspring.service.documents.worksheet` draws a sheet with :func:`draw`, analyses the
system, asks :func:`questions_and_answers` and hands the lot to
:mod:`rollspring.outputs.worksheet`, which renders it. The same level and seed always draw the
same system.

Levels (paper Sec. 5 and Fig. 4: "complexity ... can be built up gradually, step-by-step"):

1. two point masses joined by a spring on a frictionless floor (the paper's Fig. 1);
2. two round bodies of equal radius joined at their centres (Fig. 2: the hoop and the cylinder,
   and the other shapes);
3. walls and chains: a wall spring, two walls, or a free chain of three bodies (Fig. 4 (a), (b));
4. off-centre attachments: horizontal springs attached above or below the centres, between two
   bodies or to a wall hook (Fig. 3 and Fig. 4 (c)); friction depends on the height.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from rollspring.analysis import LinearAnalysis
from rollspring.analysis.exercises import SHAPE_WORDS, Answer, end_words

__all__ = ["draw", "questions_and_answers"]

_MASSES = (0.5, 0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0)
_RADII = (0.05, 0.06, 0.08, 0.1, 0.12, 0.15)
_STIFFNESSES = (40.0, 50.0, 60.0, 80.0, 100.0, 120.0, 150.0, 200.0)
_COMPRESSIONS = (0.005, 0.01, 0.015, 0.02)
_REST = 0.5
_SHAPES = ("hoop", "cylinder", "sphere", "shell")


# -- random systems ------------------------------------------------------------------------------


def _pick(rng: np.random.Generator, values: tuple) -> Any:
    return values[int(rng.integers(len(values)))]


def _body(id_: str, shape: str, mass: float, radius: float, x: float, **extra: Any) -> dict:
    return {"id": id_, "shape": shape, "mass": mass, "radius": radius, "x": _clean(x), **extra}


def _clean(value: float) -> float:
    """A decimal input without binary noise: 0.49 rather than 0.49000000000000005."""
    return float(f"{value:.12g}")


def _level1(rng: np.random.Generator) -> tuple[str, dict, list[str]]:
    m1, m2 = _pick(rng, _MASSES), _pick(rng, _MASSES)
    k, A = _pick(rng, _STIFFNESSES), _pick(rng, _COMPRESSIONS)
    data = {
        "name": "Two blocks and a spring",
        "bodies": [
            _body("m1", "slider", m1, 0.05, 0.0),
            _body("m2", "slider", m2, 0.05, _REST - A),
        ],
        "springs": [{"ends": ["m1", "m2"], "stiffness": k, "rest_length": _REST}],
    }
    setting = [
        f"Two small blocks of masses $m_1 = {m1:g}$ kg and $m_2 = {m2:g}$ kg lie on a frictionless "
        f"horizontal floor, joined by a horizontal spring of stiffness $k = {k:g}$ N/m and rest "
        f"length $L = {_REST:g}$ m (the paper's Fig. 1).",
        f"The spring is compressed by $A = {A:g}$ m and the blocks are released from rest.",
    ]
    return "two-blocks", data, setting


def _level2(rng: np.random.Generator) -> tuple[str, dict, list[str]]:
    s1, s2 = _pick(rng, _SHAPES), _pick(rng, _SHAPES)
    m1, m2 = _pick(rng, _MASSES), _pick(rng, _MASSES)
    R, k, A = _pick(rng, _RADII), _pick(rng, _STIFFNESSES), _pick(rng, _COMPRESSIONS)
    ids = ("b1", "b2")
    data = {
        "name": f"A {SHAPE_WORDS[s1][0]} and a {SHAPE_WORDS[s2][0]} joined at their centres",
        "bodies": [_body(ids[0], s1, m1, R, 0.0), _body(ids[1], s2, m2, R, _REST - A)],
        "springs": [{"ends": list(ids), "stiffness": k, "rest_length": _REST}],
    }
    setting = [
        f"Body 1 is a {SHAPE_WORDS[s1][0]} (${SHAPE_WORDS[s1][1]}$) of mass $m_1 = {m1:g}$ kg, "
        f"body 2 a {SHAPE_WORDS[s2][0]} (${SHAPE_WORDS[s2][1]}$) of mass $m_2 = {m2:g}$ kg; "
        f"both have radius $R = {R:g}$ m and stand on one horizontal floor, body 1 on the left.",
        f"Their centres are joined by a horizontal spring of stiffness $k = {k:g}$ N/m and rest "
        f"length $L = {_REST:g}$ m (the paper's Fig. 2). They roll without slipping.",
        f"The spring is compressed by $A = {A:g}$ m and the bodies are released from rest.",
    ]
    return f"{s1}-{s2}", data, setting


def _level3(rng: np.random.Generator) -> tuple[str, dict, list[str]]:
    variant = ("wall", "two-walls", "chain")[int(rng.integers(3))]
    R, A = _pick(rng, _RADII), _pick(rng, _COMPRESSIONS)
    n = 3 if variant == "chain" else 2
    shapes = [_pick(rng, _SHAPES) for _ in range(n)]
    masses = [_pick(rng, _MASSES) for _ in range(n)]
    ids = [f"b{i + 1}" for i in range(n)]
    x = [0.0, _REST - A] + ([2 * _REST] if n == 3 else [])  # only body 2 is displaced
    bodies = [_body(ids[i], shapes[i], masses[i], R, x[i]) for i in range(n)]
    anchors = []
    ends = [(ids[i], ids[i + 1]) for i in range(n - 1)]
    if variant in ("wall", "two-walls"):
        anchors.append({"id": "left", "x": -_REST, "y": R})
        ends.insert(0, ("left", ids[0]))
    if variant == "two-walls":
        anchors.append({"id": "right", "x": 2 * _REST, "y": R})
        ends.append((ids[-1], "right"))
    stiffness = [_pick(rng, _STIFFNESSES) for _ in ends]
    data: dict[str, Any] = {
        "name": {
            "wall": "A wall, two bodies and two springs",
            "two-walls": "Two bodies between two walls",
            "chain": "A free chain of three bodies",
        }[variant],
        "bodies": bodies,
        "springs": [
            {"ends": list(e), "stiffness": k, "rest_length": _REST}
            for e, k in zip(ends, stiffness, strict=True)
        ],
    }
    if anchors:
        data["anchors"] = anchors
    parts = [
        f"body {i + 1} a {SHAPE_WORDS[shapes[i]][0]} of mass $m_{i + 1} = {masses[i]:g}$ kg"
        for i in range(n)
    ]
    springs = "; ".join(
        f"spring {s + 1} (${'k_' + str(s + 1)} = {k:g}$ N/m) joins "
        + " and ".join(end_words(e) for e in pair)
        for s, (pair, k) in enumerate(zip(ends, stiffness, strict=True))
    )
    setting = [
        "On one horizontal floor, from left to right: "
        + "; ".join(parts)
        + f"; all of radius $R = {R:g}$ m. They roll without slipping.",
        f"Horizontal springs, all of rest length $L = {_REST:g}$ m, at the height of the centres: "
        f"{springs}"
        + (" (the walls are fixed)" if anchors else "")
        + "; the paper's Fig. 4 (a), (b).",
        f"Body 2 is pushed {A:g} m to the left (every spring at rest before) and the bodies are "
        "released from rest.",
    ]
    return variant, data, setting


def _level4(rng: np.random.Generator) -> tuple[str, dict, list[str]]:
    variant = ("pair", "wall")[int(rng.integers(2))]
    shapes = [_pick(rng, ("hoop", "cylinder", "sphere")) for _ in range(2)]
    masses = [_pick(rng, _MASSES) for _ in range(2)]
    radii = [_pick(rng, _RADII) for _ in range(2)]
    k = [_pick(rng, _STIFFNESSES) for _ in range(2)]
    low = min(radii)
    # a common attachment height on the body pair: 0.01 m steps in (0, 2 min R]
    steps = int(round(2 * low / 0.01))
    height = 0.01 * int(rng.integers(1, steps + 1))
    height = _clean(height)
    ids = ["b1", "b2"]
    speed = _pick(rng, (0.02, 0.03, 0.04, 0.05))
    if variant == "pair":
        # zero pseudo-momentum: sum w_i v_i = 0 with w_i = (1 + gamma_i) m_i R_i
        # (docs/physics.md M16)
        gammas = [Fraction(g).limit_denominator(10) for g in (1.0, 0.5, 0.4)]
        factor = dict(zip(("hoop", "cylinder", "sphere"), gammas, strict=True))
        w = [
            (1 + factor[s]) * Fraction(str(m)) * Fraction(str(r))
            for s, m, r in zip(shapes, masses, radii, strict=True)
        ]
        scale = Fraction(_pick(rng, ("0.1", "0.2", "0.3")))  # v_i = -/+ c w_j: exact decimals
        v = [_clean(float(-w[1] * scale)), _clean(float(w[0] * scale))]
        bodies = [
            _body(ids[0], shapes[0], masses[0], radii[0], 0.0, v=v[0]),
            _body(ids[1], shapes[1], masses[1], radii[1], _REST, v=v[1]),
        ]
        springs = [{"ends": ids, "stiffness": k[0], "at": [{"height": height}, {"height": height}]}]
        anchors: list[dict] = []
        setting = [
            f"Body 1 is a {SHAPE_WORDS[shapes[0]][0]} (mass $m_1 = {masses[0]:g}$ kg, radius "
            f"$R_1 = {radii[0]:g}$ m), body 2 a {SHAPE_WORDS[shapes[1]][0]} ($m_2 = "
            f"{masses[1]:g}$ kg, $R_2 = {radii[1]:g}$ m), on one horizontal floor, body 1 on the "
            "left. They roll without slipping.",
            f"A horizontal spring ($k = {k[0]:g}$ N/m) joins a point of body 1 to a point of "
            f"body 2, both on the vertical through the centre, $y = {height:g}$ m above the "
            f"floor; it is at its rest length, {_REST:g} m (the paper's Fig. 3 idea).",
            f"The bodies are set moving with centre velocities $v_1 = {v[0]:g}$ m/s and "
            f"$v_2 = {v[1]:g}$ m/s (chosen so that the stationary point does not move).",
        ]
    else:
        wall_height = _clean(0.01 * int(rng.integers(1, int(round(2 * radii[0] / 0.01)) + 1)))
        bodies = [
            _body(ids[0], shapes[0], masses[0], radii[0], 0.0),
            _body(ids[1], shapes[1], masses[1], radii[1], _REST, v=speed),
        ]
        anchors = [{"id": "wall", "x": -_REST, "y": wall_height}]
        springs = [
            {"ends": ["wall", ids[0]], "stiffness": k[0], "at": [{}, {"height": wall_height}]},
            {"ends": ids, "stiffness": k[1], "at": [{"height": height}, {"height": height}]},
        ]
        setting = [
            f"Body 1 is a {SHAPE_WORDS[shapes[0]][0]} (mass $m_1 = {masses[0]:g}$ kg, radius "
            f"$R_1 = {radii[0]:g}$ m), body 2 a {SHAPE_WORDS[shapes[1]][0]} ($m_2 = "
            f"{masses[1]:g}$ kg, $R_2 = {radii[1]:g}$ m), on one horizontal floor. They roll "
            "without slipping.",
            f"Spring 1 ($k_1 = {k[0]:g}$ N/m) joins a hook on a wall, {_REST:g} m to the left "
            f"of body 1's centre and $y_w = {wall_height:g}$ m above the floor, to the point of "
            f"body 1 at the same height on its centre vertical. Spring 2 ($k_2 = {k[1]:g}$ N/m) "
            f"joins the points of bodies 1 and 2 at $y = {height:g}$ m on their centre verticals. "
            f"Both are horizontal and at rest length, {_REST:g} m (the paper's Fig. 4 (c)).",
            f"Body 2 is given a velocity $v_2 = {speed:g}$ m/s to the right; body 1 starts at "
            "rest.",
        ]
    data = {
        "name": {
            "pair": "Two bodies joined above their centres",
            "wall": "A wall hook and two bodies, off-centre springs",
        }[variant],
        "bodies": bodies,
        "springs": springs,
    }
    if anchors:
        data["anchors"] = anchors
    return variant, data, setting


_GENERATORS = {1: _level1, 2: _level2, 3: _level3, 4: _level4}


def draw(level: int, seed: int) -> tuple[str, dict, list[str]]:
    """The exercise of ``level`` (1-4) drawn from ``numpy.random.default_rng(seed)``:
    ``(variant, system data, setting)``; the data is a system file's dictionary (with a
    description naming the level and seed), the setting its paragraphs of words."""
    variant, data, setting = _GENERATORS[level](np.random.default_rng(seed))
    data["description"] = f"rollspring worksheet, level {level}, seed {seed}"
    return variant, data, setting


# -- questions and answers -----------------------------------------------------------------------


def _by_body(analysis: LinearAnalysis) -> tuple[str, ...]:
    return tuple(f"body {i + 1}" for i in range(analysis.arrays.n_bodies))


#: Answers whose numbers come from the derivation (filled in by
#: :attr:`rollspring.analysis.exercises.Worksheet.answers`).
_DERIVED = ("omega2_exact", "percussion")


def questions_and_answers(
    level: int, analysis: LinearAnalysis
) -> tuple[list[str], list[Answer], dict[int, str]]:
    """The questions of a sheet of ``level`` on the system of ``analysis``: the questions, the
    answers the analysis gives (and places for those of the derivation, :data:`_DERIVED`) and
    answers in words, by question number."""
    asked, answers, notes = _questions(level, analysis)
    return asked, [a for a in answers if a.values or a.key in _DERIVED], notes


def _questions(
    level: int, analysis: LinearAnalysis
) -> tuple[list[str], list[Answer], dict[int, str]]:
    """:func:`questions_and_answers`, every answer included (also those without values)."""
    names = _by_body(analysis)
    oscillating = analysis.oscillating
    omegas = tuple(m.omega for m in oscillating)
    modes = tuple(f"mode {n + 1}" for n in range(len(oscillating)))
    rolling = level > 1
    J = tuple(float(v) for v in np.diag(analysis.mass))
    K = analysis.stiffness
    n = len(names)
    entries = [(i, j) for i in range(n) for j in range(i, n)]
    K_values = tuple(float(K[i, j]) for i, j in entries)
    K_names = tuple(f"K{i + 1}{j + 1}" for i, j in entries)
    questions: list[str] = []
    answers: list[Answer] = []
    notes: dict[int, str] = {}

    def ask(text: str) -> int:
        questions.append(text)
        return len(questions)

    def give(
        key: str,
        question: int,
        label: str,
        values: Any,
        unit: str,
        value_names: tuple[str, ...] = (),
    ) -> None:
        answers.append(
            Answer(key, question, label, tuple(float(v) for v in values), unit, value_names)
        )

    free = analysis.stationary_weights is not None
    if level == 1:
        q = ask(
            "Write the equations of motion of the two blocks (Newton's second law, or the "
            "Lagrangian $L = \\tfrac12 m_1\\dot x_1^2 + \\tfrac12 m_2\\dot x_2^2 - "
            "\\tfrac12 k (x_2 - x_1 - L)^2$)."
        )
        give("omega2_exact", q, "$\\Omega^2$ of the oscillation", (), "1/s^2")
        q = ask(
            "Show that the centre of mass stays at rest. What are the weights of $x_1$ and "
            "$x_2$ in it?"
        )
        give(
            "weights",
            q,
            "weights of the stationary point (the centre of mass)",
            analysis.stationary_weights,
            "",
            names,
        )
        q = ask("Find the angular frequency $\\Omega$ and the period $T$.")
        give("omega", q, "$\\Omega$", omegas, "rad/s")
        give("period", q, "$T$", [m.period for m in oscillating], "s")
        q = ask("Find each block's amplitude about the centre of mass and its largest speed.")
        give("amplitude", q, "amplitudes", analysis.amplitude, "m", names)
        give("max_speed", q, "largest speeds", analysis.velocity_amplitude, "m/s", names)
        return questions, answers, notes
    q = ask(
        "Find each body's moment of inertia about its contact line, "
        "$I'_i = I_i + m_i R_i^2$"
        + (
            ", and the stiffness matrix $K$ of the linearised "
            "equations $M\\ddot\\varphi = -K\\varphi$ "
            "(angles $\\varphi_i$ clockwise)."
            if level > 2
            else "."
        )
    )
    give("inertia", q, "$I'_i$", J, "kg m^2", names)
    if level > 2:
        give("stiffness", q, "entries of $K$", K_values, "N m", K_names)
    if level == 2:
        q = ask(
            "Write the equations of motion with the rotation angles $\\varphi_1$, "
            "$\\varphi_2$ (rolling: $x_i = R\\varphi_i$) and find the angular frequency "
            "$\\Omega$ and the period $T$."
        )
    else:
        q = ask(
            "Find the normal-mode frequencies and the mode shapes (centre displacements, the "
            "largest set to 1)."
        )
    give("omega2_exact", q, "$\\Omega^2$ from the closed form", (), "1/s^2")
    give(
        "omega",
        q,
        "$\\Omega$" if len(omegas) == 1 else "$\\omega_n$",
        omegas,
        "rad/s",
        modes if len(omegas) > 1 else (),
    )
    give(
        "period",
        q,
        "periods",
        [m.period for m in oscillating],
        "s",
        modes if len(omegas) > 1 else (),
    )
    if level > 2:
        for number, mode in enumerate(oscillating, 1):
            give(f"shape{number}", q, f"shape of mode {number}", mode.shape_x, "", names)
        q = ask(
            "Check the trace identity: the sum of the squared frequencies equals the sum of "
            "the squared frequencies of each body alone (the others held), "
            "$\\sum_n\\omega_n^2 = \\sum_i K_{ii}/I'_i$."
        )
        give(
            "trace",
            q,
            "$\\sum_n \\omega_n^2$ and $\\sum_i K_{ii}/I'_i$",
            (
                sum(m.eigenvalue for m in oscillating),
                float(np.sum(np.diag(K) / np.diag(analysis.mass))),
            ),
            "1/s^2",
            ("sum of squares", "sum of clamped"),
        )
    if free:
        q = ask(
            "Which point stays at rest? Give the weights of the centres in it, "
            "$\\hat X = \\sum_i w_i x_i$, and compare with the centre of mass."
        )
        give("weights", q, "weights $w_i$", analysis.stationary_weights, "", names)
        give(
            "cm_weights",
            q,
            "the centre of mass's weights $m_i/\\sum m$ for comparison",
            analysis.arrays.mass / analysis.arrays.mass.sum(),
            "",
            names,
        )
    elif level > 2:
        q = ask("Why does no point of this system stay at rest? (Hint: the walls.)")
        notes[q] = (
            "The wall springs hold the system: $K$ has no null vector (no zero mode), so "
            "no combination of the velocities is conserved and every body oscillates "
            "about its equilibrium."
        )
    if level == 4:
        q = ask(
            "Find the static friction each body needs in each mode, per metre of the largest "
            "centre displacement. At which height would a spring attachment need no "
            "friction?"
        )
        for number, mode in enumerate(oscillating, 1):
            give(f"friction{number}", q, f"friction in mode {number}", mode.friction, "N/m", names)
        give(
            "percussion",
            q,
            "no friction for an attachment at the percussion height "
            "$(1 + \\gamma_i) R_i$ above the floor",
            (),
            "m",
            names,
        )
    q = ask(
        "Find the amplitude of each centre and its largest speed"
        + (", and the amplitude of the centre of mass." if free else ".")
    )
    give("amplitude", q, "amplitudes", analysis.amplitude, "m", names)
    give("max_speed", q, "largest speeds", analysis.velocity_amplitude, "m/s", names)
    if free:
        give("cm_amplitude", q, "amplitude of the centre of mass", (analysis.cm_amplitude,), "m")
    if rolling:
        q = ask(
            "Find the largest static friction force on each body during the motion and the "
            "smallest coefficient of static friction for which nothing slips."
        )
        give(
            "friction_amplitude",
            q,
            "largest friction amplitudes",
            analysis.friction_amplitude,
            "N",
            names,
        )
        give("required_mu", q, "smallest $\\mu_s$", analysis.required_mu, "", names)
    return questions, answers, notes
