"""Frames per second of ``rollspring track`` on a 640×360 video, on one core (issue 27, point 2).

The video is made here: the paper's hoop and cylinder (the preset ``hoop-cylinder`` started
with the hoop at 0.3 m/s and the cylinder at -0.4 m/s, so that both roll and turn by tens of
centimetres and radians), rendered from its exact motion by :mod:`rollspring.lab.synthetic` as a
camera films it (textured wall and table, noise 4 grey levels, blur 1 px, camera roll 2°,
flicker 3 %, MP4 ``mp4v``), 640×360 at 60 fps, ``--seconds`` long.

Timed, each the best of ``--repeats`` runs after one untimed warm-up, in one process pinned to
one core (``os.sched_setaffinity``) with OpenCV's own threads off (``cv2.setNumThreads(1)``):

* the baseline: decoding every frame with OpenCV (``VideoCapture.read``), nothing else;
* :func:`rollspring.lab.tracking.track_video`: decoding, the floor line and the bodies found in
  the first frame, every body's outline and marker in every frame, the CSV's arrays.

Printed: both in frames per second of wall time and of CPU time (on a machine shared with other
work the CPU time is the steadier figure), the ratio of the wall times (what tracking adds to
the decoding), the tracking's own CPU cost per frame (the difference), and the accuracy of
that run against the truth the video was rendered from. Target: ``track`` ≥ 60 frames/s of
wall time (✔/✘). Every number is measured in this run.

Run: ``python bench/bench_track.py`` (about 30 s on a busy machine, most of it rendering the
video). Exit status 0 when it ran.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import machine_note, one_core_opencv

TARGET_FPS = 60.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=4.0, help="video length, s")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

    cv2 = one_core_opencv()
    import rollspring
    from rollspring.lab.synthetic import Camera, exact_motion, write_video
    from rollspring.lab.tracking import track_video

    print(machine_note())
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else "?"
    print(f"pinned to {cores} core(s); cv2.getNumThreads() = {cv2.getNumThreads()}")
    data = rollspring.load_system("hoop-cylinder").model_dump()
    data["bodies"][0]["v"], data["bodies"][1]["v"] = 0.3, -0.4
    system = rollspring.system_from_dict(data)
    camera = Camera(fps=60, roll_deg=2.0, noise=4.0, blur=1.0, flicker=0.03, seed=7)
    motion = exact_motion(system, camera.frame_times(args.seconds))
    with tempfile.TemporaryDirectory() as folder:
        video = Path(folder) / "hoop-cylinder.mp4"
        began = time.perf_counter()
        write_video(video, system, motion, camera)
        print(
            f"video: {camera.width}×{camera.height}, {motion.t.size} frames at {camera.fps:g} "
            f"fps, {video.stat().st_size / 1e6:.1f} MB (rendered in "
            f"{time.perf_counter() - began:.1f} s)"
        )

        def decode() -> int:
            capture = cv2.VideoCapture(str(video))
            frames = 0
            while capture.read()[0]:
                frames += 1
            capture.release()
            return frames

        def track() -> rollspring.TrackResult:
            return track_video(video, system)

        decode_time, decode_cpu = _best(decode, args.repeats)
        track_time, track_cpu = _best(track, args.repeats)
        result = track()
    frames = motion.t.size
    x_rms = np.sqrt(np.mean((result.x - motion.x) ** 2, axis=0))
    phi_rms = np.sqrt(np.mean((result.phi - motion.phi) ** 2, axis=0))
    fps = frames / track_time
    rows = [
        ("decode only (OpenCV)", decode_time, decode_cpu),
        ("rollspring track", track_time, track_cpu),
    ]
    print()
    print(
        f"{'':24} {'wall (s)':>9} {'frames/s':>9} {'× decode':>9} {'CPU (s)':>9} "
        f"{'frames/CPU s':>13}"
    )
    for label, seconds, cpu in rows:
        print(
            f"{label:24} {seconds:9.3f} {frames / seconds:9.0f} {seconds / decode_time:9.2f} "
            f"{cpu:9.3f} {frames / cpu:13.0f}"
        )
    extra = (track_cpu - decode_cpu) / frames * 1e3
    print(f"tracking's own CPU cost: {extra:.2f} ms a frame ({len(result.ids)} bodies)")
    mark = "✔" if fps >= TARGET_FPS else "✘"
    print(f"target: track ≥ {TARGET_FPS:g} frames/s on one core: {fps:.0f} {mark}")
    print(
        "accuracy of this run: x RMS "
        + ", ".join(f"{i} {v * 1e3:.3f} mm" for i, v in zip(result.ids, x_rms, strict=True))
        + "; phi RMS "
        + ", ".join(f"{i} {v:.4f} rad" for i, v in zip(result.ids, phi_rms, strict=True))
    )
    print(machine_note().replace("at start", "at end"))


def _best(run, repeats: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """The best wall time and the best CPU time (this process, user + system) of ``repeats``
    runs of ``run`` after one untimed warm-up."""
    run()
    walls, cpus = [], []
    for _ in range(repeats):
        began, used = time.perf_counter(), time.process_time()
        run()
        walls.append(time.perf_counter() - began)
        cpus.append(time.process_time() - used)
    return min(walls), min(cpus)


if __name__ == "__main__":
    main()
