"""The lab's cost estimates against the time measured: ``track`` at two frame sizes (with and
without ``--overlay``) and ``fit`` on both of its routes (rollspring.lab.costs).

The constants of :mod:`rollspring.lab.costs` come from this script. Tracking: the paper's hoop
and cylinder (both set rolling, as bench_track.py does) rendered by :mod:`rollspring.lab.synthetic`
at 640×360 (700 px/m) and 1280×720 (1400 px/m: the same scene, twice as fine), 60 fps,
``--seconds`` long, tracked in one process pinned to one core with OpenCV's threads off. Timed
(CPU time of the process, the best of ``--repeats`` after a warm-up): OpenCV's ``grab`` of every
frame (what a frame before ``--from`` costs), :func:`rollspring.lab.tracking.track_video`, and
:func:`rollspring.service.tracking.track_to_files` with the overlay. From the two sizes: the
cost per pixel and per frame (a straight line through the two). Memory: the Python heap's peak
(``tracemalloc``, which sees NumPy's arrays) tracking the whole video and its first half, the
difference per frame.

Fitting: the README's walk-through recording (tools/lab_walkthrough.py's system, 60 fps, 0.02 mm
noise) fitted freeing the spring (the exact linear route: 6 s, and 60 s with ``t0`` fitted, whose
start time is scanned) and the spring with both bodies' rolling resistance (the simulated route,
6 s), timed once each after a warm-up.

Printed: each measurement, the constant it gives, and the estimate of rollspring.lab.costs
against the measured time (estimate / measured: the estimates are rounded up, so mostly above
1, and meant to be right within a factor of a few). Every number is measured in this run.

Run: ``python bench/bench_lab_costs.py`` (about a minute and a half, most of it rendering).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))

from common import machine_note, one_core_opencv


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3.0, help="video length, s")
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    one_core_opencv()
    print(machine_note())
    with tempfile.TemporaryDirectory() as folder:
        rows = [_track_size(Path(folder), w, h, s, args) for w, h, s in _SIZES]
    (p1, d1, t1, o1), (p2, d2, t2, o2) = ((r[0], r[1], r[2], r[3]) for r in rows)
    print()
    print("per pixel (the line through the two sizes), CPU:")
    for label, a, b in (("decode", d1, d2), ("track", t1, t2), ("overlay", o1, o2)):
        slope = (b - a) / (p2 - p1)
        print(f"  {label:8} {slope * 1e9:6.2f} ns/px, {(a - slope * p1) * 1e3:6.2f} ms/frame apart")
    _fits()
    print(machine_note().replace("at start", "at end"))


#: width, height, scale (px/m)
_SIZES = ((640, 360, 700.0), (1280, 720, 1400.0))


def _system():  # type: ignore[no-untyped-def]
    import rollspring

    data = rollspring.load_system("hoop-cylinder").model_dump()
    data["bodies"][0]["v"], data["bodies"][1]["v"] = 0.3, -0.4
    return rollspring.system_from_dict(data)


def _track_size(
    folder: Path, width: int, height: int, scale: float, args: argparse.Namespace
) -> tuple[float, float, float, float]:
    """One size: (pixels, decode s/frame, track s/frame, overlay's extra s/frame), printed with
    the estimate against the measured times."""
    import cv2

    from rollspring.lab.costs import tracking_cost, video_header
    from rollspring.lab.synthetic import Camera, exact_motion, write_video
    from rollspring.lab.tracking import track_video
    from rollspring.service.tracking import track_to_files

    system = _system()
    camera = Camera(
        width=width,
        height=height,
        scale=scale,
        fps=60,
        roll_deg=2.0,
        noise=4.0,
        blur=1.0 * scale / 700.0,
        flicker=0.03,
        seed=7,
    )
    motion = exact_motion(system, camera.frame_times(args.seconds))
    video = folder / f"v{width}.mp4"
    write_video(video, system, motion, camera)
    frames = motion.t.size
    pixels = float(width * height)

    def decode() -> None:
        capture = cv2.VideoCapture(str(video))
        while capture.grab():
            pass
        capture.release()

    decoded = _best_cpu(decode, args.repeats) / frames
    tracked = _best_cpu(lambda: track_video(video, system), args.repeats) / frames
    drawn = (
        _best_cpu(
            lambda: track_to_files(video, system, out=None, overlay=folder / "o.mp4"), args.repeats
        )
        / frames
    )
    header = video_header(video)
    print(f"\n{width}×{height}, {frames} frames ({header.frames} in the header), 2 bodies:")
    print(f"  decode (grab) {decoded * 1e3:7.2f} ms/frame CPU")
    print(f"  track         {tracked * 1e3:7.2f} ms/frame CPU ({1 / tracked:.0f} frames/s)")
    print(f"  + overlay     {drawn * 1e3:7.2f} ms/frame CPU")
    for overlay, measured in ((False, tracked), (True, drawn)):
        estimate = tracking_cost(header, 2, overlay=overlay)
        print(
            f"  estimate{' with overlay' if overlay else ''}: {estimate.seconds:.3f} s against "
            f"{measured * frames:.3f} s measured: × {estimate.seconds / (measured * frames):.2f}"
        )
    skipped = tracking_cost(header, 2, start=header.frames / header.fps)
    print(
        f"  all skipped (--from the end): estimate {skipped.seconds:.3f} s against "
        f"{decoded * frames:.3f} s decoding: × {skipped.seconds / (decoded * frames):.2f}"
    )
    half = round(args.seconds / 2, 3)
    held = []
    for stop in (half, None):
        # the heap when the last frame is tracked: every frame's measurements still held
        seen: list[int] = []

        def at_end(fraction: float, seen: list[int] = seen) -> None:
            if fraction >= 1:
                seen.append(tracemalloc.get_traced_memory()[0])

        tracemalloc.start()
        track_video(video, system, stop=stop, progress=at_end)
        tracemalloc.stop()
        held.append(seen[-1])
    per_frame = (held[1] - held[0]) / (frames - tracked_half(header, half))
    estimate = tracking_cost(header, 2).memory
    print(
        f"  memory held at the last frame: {held[1] / 2**20:.2f} MiB (half the video "
        f"{held[0] / 2**20:.2f} MiB): {per_frame:.0f} bytes per frame; estimate "
        f"{estimate / 2**20:.2f} MiB: × {estimate / held[1]:.2f}"
    )
    return pixels, decoded, tracked, drawn - tracked


def tracked_half(header: object, stop: float) -> int:
    from rollspring.lab.costs import tracked_frames

    return tracked_frames(header, None, stop)[1]  # type: ignore[arg-type]


def _fits() -> None:
    from lab_walkthrough import truth_system

    import rollspring
    from rollspring.lab.costs import fit_cost
    from rollspring.lab.data import match_bodies, parse_data
    from rollspring.lab.synthetic import exact_motion

    truth = truth_system()
    system = rollspring.load_system("hoop-cylinder")

    def table(seconds: float):  # type: ignore[no-untyped-def]
        t = np.arange(round(seconds * 60) + 1) / 60
        x = exact_motion(truth, t).x + np.random.default_rng(1).normal(0, 2e-5, (t.size, 2))
        rows = [f"{ti:.17g},{a:.17g},{b:.17g}" for ti, (a, b) in zip(t, x, strict=True)]
        return match_bodies(parse_data("\n".join(["t,x_hoop,x_cylinder", *rows]), "w.csv"), system)

    print("\nfit, the walk-through's recording (60 fps; 6 s: 722 points):")
    spring = ["springs.0.stiffness", "springs.0.damping"]
    resisted = [*spring, "bodies.hoop.rolling_resistance", "bodies.cylinder.rolling_resistance"]
    walk, long = table(6.0), table(60.0)
    for label, data, free, held in (
        ("linear, 6 s", walk, spring, False),
        ("linear, 60 s, t0", long, spring, True),
        ("simulated, 6 s", walk, resisted, False),
    ):
        rollspring.fit(data, system, free, fix_initial=held, claims=False, confirm=True)  # warm
        began = time.process_time()
        result = rollspring.fit(data, system, free, fix_initial=held, claims=False, confirm=True)
        measured = time.process_time() - began
        estimate = fit_cost(data, system, free, fix_initial=held)
        print(
            f"  {label:16} {measured:7.2f} s CPU ({result.evaluations} evaluations of the "
            f"solver, {len(result.fitted)} parameters); estimate {estimate.seconds:.2f} s: "
            f"× {estimate.seconds / measured:.2f}  ({estimate.describe()})"
        )


def _best_cpu(run, repeats: int) -> float:  # type: ignore[no-untyped-def]
    """The least CPU time (this process) of ``repeats`` runs after one untimed warm-up."""
    run()
    best = float("inf")
    for _ in range(repeats):
        used = time.process_time()
        run()
        best = min(best, time.process_time() - used)
    return best


if __name__ == "__main__":
    main()
