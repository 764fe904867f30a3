"""A video tracked into files, as ``rollspring track`` asks for it: the tracks' CSV and, on
request, the overlay video, written as a set.

:func:`track_to_files` checks both output places first (a regular file or a new one, as every
output: :func:`~rollspring.outputs.atomic.writable_file`), then tracks the video
(:func:`rollspring.lab.tracking.track_video`) while it writes each frame with what was found
drawn on it (:func:`~rollspring.lab.tracking.draw_overlay`) into a temporary file beside the
overlay's place, and writes the CSV into another. Only when the whole video is tracked are both
renamed into place (:func:`~rollspring.outputs.atomic.atomic_path`): a failure — a body lost,
an unreadable frame, Ctrl-C — leaves neither file half-written and the earlier ones as they
were. :func:`tracking_estimate` is the cost the command line checks before that
(:func:`rollspring.lab.costs.tracking_cost`, from the video's header).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from contextlib import ExitStack
from pathlib import Path

import numpy as np

from rollspring.errors import OutputError, TrackingError
from rollspring.lab.costs import LabCost, tracking_cost, video_header
from rollspring.lab.tracking import FrameTrack, TrackResult, draw_overlay, track_video
from rollspring.model import System
from rollspring.outputs.atomic import atomic_path, same_file, writable_file

__all__ = ["check_places", "track_to_files", "tracking_estimate"]


def check_places(
    out: str | os.PathLike[str] | None,
    overlay: str | os.PathLike[str] | None,
    video: str | os.PathLike[str] | None = None,
) -> tuple[Path | None, Path | None]:
    """``-o`` and ``--overlay`` checked before any work: each a regular file or a new one in
    a writable folder, the overlay an ``.mp4``, neither the other nor the ``video`` read."""
    csv = None if out is None else writable_file(out, "--out")
    drawn = None if overlay is None else writable_file(overlay, "--overlay")
    if drawn is not None and drawn.suffix.lower() != ".mp4":
        raise OutputError(f"--overlay {overlay}: must be an .mp4 file")
    if csv is not None and drawn is not None and same_file(csv, drawn):
        raise OutputError(f"--overlay {overlay}: the same file as --out")
    for option, place in (("--out", csv), ("--overlay", drawn)):
        if place is not None and video is not None and same_file(place, Path(video)):
            raise OutputError(f"{option} {place}: the same file as the video read")
    return csv, drawn


def tracking_estimate(
    video: str | os.PathLike[str],
    system: System,
    *,
    start: float | None = None,
    stop: float | None = None,
    overlay: bool = False,
) -> LabCost:
    """The estimated cost of :func:`track_to_files` (:func:`rollspring.lab.costs.tracking_cost`
    of the video's header, :func:`~rollspring.lab.costs.video_header`): the frames from
    ``start`` to ``stop`` × their pixels, the ``overlay`` written too; in the command line's
    words. A one-line :class:`~rollspring.errors.TrackingError` for a video that cannot be
    read."""
    header = video_header(video)
    return tracking_cost(header, len(system.bodies), start=start, stop=stop, overlay=overlay)


def track_to_files(
    video: str | os.PathLike[str],
    system: System,
    *,
    out: str | os.PathLike[str] | None,
    overlay: str | os.PathLike[str] | None = None,
    scale: float | None = None,
    start: float | None = None,
    stop: float | None = None,
    origin: float | None = None,
    progress: Callable[[float], None] | None = None,
) -> tuple[TrackResult, list[Path]]:
    """Track ``video`` (:func:`~rollspring.lab.tracking.track_video` with ``scale``,
    ``start``, ``stop``, ``origin``, ``progress``) and write the CSV to ``out`` and the
    overlay to ``overlay`` as a set (either may be None). Returns the result and the paths
    written."""
    import cv2

    csv, drawn = check_places(out, overlay, video)
    written: list[Path] = []
    with ExitStack() as stack:
        csv_part = None if csv is None else stack.enter_context(atomic_path(csv))
        on_frame = None
        if drawn is not None:
            video_part = stack.enter_context(atomic_path(drawn, suffix=".part.mp4"))
            writers: list[cv2.VideoWriter] = []

            def on_frame(frame: np.ndarray, found: FrameTrack) -> None:
                image = draw_overlay(frame, found)
                if not writers:
                    fps = _fps(video)
                    height, width = image.shape[:2]
                    writer = cv2.VideoWriter(
                        str(video_part), cv2.VideoWriter.fourcc(*"mp4v"), fps, (width, height)
                    )
                    if not writer.isOpened():
                        raise OutputError(f"--overlay {overlay}: OpenCV cannot write an mp4 here")
                    writers.append(writer)
                    stack.callback(writer.release)
                writers[0].write(image)

        result = track_video(
            video,
            system,
            scale=scale,
            start=start,
            stop=stop,
            origin=origin,
            progress=progress,
            on_frame=on_frame,
        )
        if csv_part is not None:
            assert csv is not None
            csv_part.write_text(result.to_csv(), encoding="utf-8")
            written.append(csv)
        if drawn is not None:
            written.append(drawn)
    return result, written


def _fps(video: str | os.PathLike[str]) -> float:
    """The frame rate of ``video`` (30 when the container does not say)."""
    import cv2

    capture = cv2.VideoCapture(str(video))
    try:
        fps = float(capture.get(cv2.CAP_PROP_FPS))
    finally:
        capture.release()
    if not fps > 0:
        return 30.0
    if fps > 1000:
        raise TrackingError(f"{video}: a frame rate of {fps:g} fps cannot be written")
    return fps
