"""The README's "Lab" walk-through, run again: a video, its tracks, the fit, the figure.

Makes the synthetic recording of the paper's hoop and cylinder that the README films (the
spring 30 % stiffer than the preset's 100 N/m and damped, 0.2 N s/m), runs ``rollspring track``
and ``rollspring fit`` on it as the README does, prints what they print, compares the fit with
the truth the video was rendered from, then does the same with the recording filmed against a
plain wall (in ``plain/``: the README's comparison of the two walls). With ``--image`` it copies
the fit's figure to ``docs/images/lab-fit.png`` (the README's figure). ``--report`` also runs
``rollspring report hoop-cylinder --data tracks.csv`` (about a minute: the derivations).

    .venv/bin/python tools/lab_walkthrough.py                 # into build/lab, about 30 s
    .venv/bin/python tools/lab_walkthrough.py --image         # and update the README's figure

Needs the ``lab`` and ``plot`` extras (OpenCV, Matplotlib). ``tests/test_readme.py`` runs it and
checks that the README shows its output.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rollspring.model import System

ROOT = Path(__file__).resolve().parents[1]
IMAGE = ROOT / "docs" / "images" / "lab-fit.png"
CLI = [sys.executable, "-c", "import sys; from rollspring.cli import main; sys.exit(main())"]
FREE = ["--free", "springs.0.stiffness", "--free", "springs.0.damping"]
OUTPUTS = ["-o", "fitted.toml", "--figure", "fit.png"]
#: The truth the video is rendered from: the paper's system with this spring.
STIFFNESS, DAMPING = 130.0, 0.2


def truth_system() -> System:
    """The paper's system (the preset ``hoop-cylinder``) with the real spring: the README's
    snippet builds the same one."""
    import rollspring
    from rollspring.model import system_to_json

    paper = system_to_json(rollspring.load_system("hoop-cylinder"))
    paper["springs"][0].update(stiffness=STIFFNESS, damping=DAMPING)
    return rollspring.system_from_dict(paper)


def make_video(path: Path, seconds: float = 6.0, *, texture: bool = True) -> None:
    """The README's snippet: the paper's system with a stiffer, damped spring, filmed (against
    a textured wall and table; ``texture=False``: plain ones)."""
    from rollspring.lab.synthetic import Camera, exact_motion, write_video

    truth = truth_system()
    camera = Camera(
        fps=60, roll_deg=2.0, noise=4.0, blur=1.0, flicker=0.03, texture=texture, seed=1
    )
    motion = exact_motion(truth, camera.frame_times(seconds))  # t, x (m), phi (rad)
    write_video(path, truth, motion, camera)  # 640×360, MP4


def truth_claims(seconds: float = 6.0) -> dict[str, float]:
    """The CM's and X̂'s peak-to-peak of the rendered motion (m), sampled as the fit samples
    its model (four times the frame rate)."""
    from rollspring.analysis import analyze
    from rollspring.lab.synthetic import exact_motion

    truth = truth_system()
    frames = round(seconds * 60) + 1
    motion = exact_motion(truth, np.linspace(0.0, seconds, 4 * frames))
    masses = np.array([body.mass for body in truth.bodies])
    weights = np.asarray(analyze(truth).stationary_weights)
    return {
        "cm_peak_to_peak": float(np.ptp(motion.x @ masses / masses.sum())),
        "stationary_peak_to_peak": float(np.ptp(motion.x @ weights)),
    }


def run(args: list[str], where: Path, env: dict[str, str]) -> str:
    """``rollspring ARGS`` in ``where``: what it printed on stdout (its stderr echoed)."""
    done = subprocess.run(
        [*CLI, *args], cwd=where, env=env, capture_output=True, text=True, check=False
    )
    sys.stderr.write(done.stderr)
    if done.returncode != 0:
        sys.exit(f"lab_walkthrough: rollspring {' '.join(args)} failed ({done.returncode})")
    return done.stdout


def read_tracks(path: Path) -> dict[str, np.ndarray]:
    """The columns of a track CSV, by name."""
    header = path.read_text().split("\n", 1)[0].split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1)
    return {name: table[:, k] for k, name in enumerate(header)}


def hand_marked(where: Path) -> None:
    """The README's examples of the other formats, from every third frame of ``tracks.csv``
    (20 frames/s, as a hand marking in Tracker might be): ``plain.csv`` and the Tracker files
    ``hoop.txt`` (the hoop's track alone) and ``both.txt`` (two tracks named ``mass A`` and
    ``mass B``, the second unmarked in two frames)."""
    table = read_tracks(where / "tracks.csv")
    table = np.column_stack([table[name] for name in ("t", "x_hoop", "x_cylinder")])[::3]
    skipped = (4, 5)
    plain, hoop, both = ["t,x_hoop,x_cylinder"], ["hoop", "t\tx\ty"], ["#multi:"]
    both += ["mass A\t\t\tmass B\t\t", "t\tx\ty\tt\tx\ty"]
    for row, (t, x1, x2) in enumerate(table):
        second = ("", "") if row in skipped else (f"{x2:.5f}", "0.1000")
        plain.append(f"{t:.4g},{x1:.5f},{second[0]}")
        hoop.append(f"{t:.4g}\t{x1:.5f}\t0.1000")
        both.append(f"{t:.4g}\t{x1:.5f}\t0.1000\t{t:.4g}\t{second[0]}\t{second[1]}")
    for name, lines in (("plain.csv", plain), ("hoop.txt", hoop), ("both.txt", both)):
        (where / name).write_text("\n".join(lines) + "\n")


def walk(where: Path, *, report: bool = False) -> dict[str, str]:
    """The walk-through in ``where``: the outputs of each command, by name."""
    where.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, NO_COLOR="1", COLUMNS="100")
    make_video(where / "film.mp4")
    out = {
        "track": run(
            ["track", "film.mp4", "--system", "hoop-cylinder", "-o", "tracks.csv", "--json"],
            where,
            env,
        ),
        "fit": run(
            ["fit", "tracks.csv", "--system", "hoop-cylinder", *FREE, "--json", *OUTPUTS],
            where,
            env,
        ),
        "fit table": run(["fit", "tracks.csv", "--system", "hoop-cylinder", *FREE], where, env),
    }
    hand_marked(where)
    mapped = ["--map", "mass A=hoop", "--map", "mass B=cylinder"]
    for name, extra in (("plain.csv", []), ("hoop.txt", []), ("both.txt", mapped)):
        out[f"fit {name}"] = run(
            ["fit", name, "--system", "hoop-cylinder", *FREE, *extra], where, env
        )
    if report:
        report_args = ["report", "hoop-cylinder", "--data", "tracks.csv", "-o", "report.html"]
        out["report"] = run(report_args, where, env)
    return out


def plain_wall(where: Path) -> dict[str, str]:
    """The same recording filmed against a plain wall and table, tracked and fitted in
    ``where`` as the walk-through does: the outputs of ``track`` and ``fit --json``."""
    where.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, NO_COLOR="1", COLUMNS="100")
    make_video(where / "film.mp4", texture=False)
    track = ["track", "film.mp4", "--system", "hoop-cylinder", "-o", "tracks.csv", "--json"]
    fit = ["fit", "tracks.csv", "--system", "hoop-cylinder", *FREE, "--json"]
    return {"track": run(track, where, env), "fit": run(fit, where, env)}


def tracking_errors(tracks: Path) -> list[str]:
    """The tracks against the motion the video was rendered from: RMS errors, and the gain
    (the tracked displacement over the rendered one, by least squares)."""
    from rollspring.lab.synthetic import exact_motion

    table = read_tracks(tracks)
    motion = exact_motion(truth_system(), table["t"])
    lines = []
    for column, body in enumerate(motion.ids):
        x, phi = table[f"x_{body}"], table[f"phi_{body}"]
        true_x = motion.x[:, column]
        rms_x = np.sqrt(np.mean((x - true_x) ** 2))
        rms_phi = np.sqrt(np.mean((phi - motion.phi[:, column]) ** 2))
        swing = true_x - true_x.mean()
        gain = np.dot(swing, x - x.mean()) / np.dot(swing, swing)
        lines.append(
            f"{body}: x {1e3 * rms_x:.3f} mm RMS, phi {rms_phi:.4f} rad RMS, "
            f"displacement × {gain:.4f}"
        )
    return lines


def against_truth(fit_json: str) -> list[str]:
    """Each fitted spring value and claim against the truth, in standard errors."""
    fitted = json.loads(fit_json)
    truth = {"springs.0.stiffness": STIFFNESS, "springs.0.damping": DAMPING}
    truth |= truth_claims()
    lines = []
    for name, value in truth.items():
        entry = fitted["parameters"].get(name) or fitted["claims"][name]
        off = (entry["value"] - value) / entry["stderr"]
        lines.append(f"{name}: {entry['value']:.6g} ± {entry['stderr']:.2g}, truth {value:.6g}")
        lines[-1] += f" ({off:+.1f} standard errors)"
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("where", nargs="?", type=Path, default=ROOT / "build" / "lab")
    parser.add_argument("--image", action="store_true", help=f"copy the figure to {IMAGE}")
    parser.add_argument("--report", action="store_true", help="also the report with --data")
    args = parser.parse_args()
    out = walk(args.where.resolve(), report=args.report)
    for name, text in out.items():
        print(f"--- {name}\n{text}")
    print("--- the tracks against the motion the video was rendered from")
    print("\n".join(tracking_errors(args.where / "tracks.csv")))
    print("--- the fit against the truth")
    print("\n".join(against_truth(out["fit"])))
    plain = plain_wall(args.where.resolve() / "plain")
    print("--- the same recording against a plain wall: the tracks against the motion")
    print("\n".join(tracking_errors(args.where / "plain" / "tracks.csv")))
    print("--- the same recording against a plain wall: the fit against the truth")
    print("\n".join(against_truth(plain["fit"])))
    print("\n".join(json.loads(plain["fit"])["warnings"]) or "(no warnings)")
    if args.image:
        shutil.copyfile(args.where / "fit.png", IMAGE)
        print(f"copied the figure to {IMAGE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
