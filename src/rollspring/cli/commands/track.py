"""``rollspring track VIDEO --system SYSTEM -o tracks.csv``: a video of rolling bodies tracked.

Finds each body of the system in every frame (:mod:`rollspring.lab.tracking`: the floor line
and the camera roll, each body's outline and its rim marker) and writes the CSV
``t,x_<id>,phi_<id>,...`` (s, m, rad; one row per frame) with
:func:`rollspring.service.tracking.track_to_files`, ``--overlay`` the video with what was found
drawn on it, both as a set. ``--json`` prints the summary (frames, fps, scale, roll, per-body
residuals) as one JSON object. Before any work the run is estimated from the video's header
(:func:`rollspring.service.tracking.tracking_estimate`: the frames from ``--from`` to ``--to``
× their pixels, the overlay) and refused above 5 minutes or 2 GiB unless ``--yes``. The
command is added to an app by :func:`register`.
"""

from __future__ import annotations

from typing import Annotated

import typer

from rollspring.cli.common import (
    ProgressBar,
    add_command,
    confirm_cost,
    load,
    print_json,
    say,
    stdout_console,
)
from rollspring.cli.options import SYSTEM_HELP, JsonOpt, out_option, yes_option

__all__ = ["register", "track"]


def track(
    video: Annotated[str, typer.Argument(help="The video file (any format OpenCV reads).")],
    system: Annotated[str, typer.Option("--system", "-s", help=SYSTEM_HELP, show_default=False)],
    out: Annotated[
        str | None, out_option("The tracks: CSV t,x_<id>,phi_<id>,... (s, m, rad).")
    ] = None,
    scale: Annotated[
        float | None,
        typer.Option("--scale", help="Pixels per metre (default: from the bodies' radii)."),
    ] = None,
    start: Annotated[
        float | None, typer.Option("--from", help="Track from this time of the video, s.")
    ] = None,
    stop: Annotated[
        float | None, typer.Option("--to", help="Track up to this time of the video, s.")
    ] = None,
    origin: Annotated[
        float | None,
        typer.Option(
            "--origin",
            help="x of the first body in the first tracked frame, m (default: its x in the "
            "system file).",
        ),
    ] = None,
    overlay: Annotated[
        str | None,
        typer.Option("--overlay", help="Also write the video with what was found drawn (.mp4)."),
    ] = None,
    as_json: JsonOpt = False,
    yes: Annotated[
        bool,
        yes_option(note=" (a long video: its frames from --from to --to × their pixels)"),
    ] = False,
) -> None:
    """Track a video of the system's rolling bodies: each body's centre x (m) and rotation
    phi (rad, clockwise positive) in every frame, the floor line and the camera roll found."""
    import os

    from rollspring.errors import TrackingError

    # FFmpeg (inside OpenCV) would print its own complaints about a bad file on stderr, beside
    # the command's one line: quiet, unless the user asked otherwise
    os.environ.setdefault("OPENCV_FFMPEG_LOGLEVEL", "-8")
    if out is None and not as_json:
        raise TrackingError("--out/-o is required: the CSV file of the tracks")
    from rollspring.lab.tracking import check_options
    from rollspring.service.tracking import check_places, track_to_files, tracking_estimate

    check_options(scale=scale, start=start, stop=stop, origin=origin)
    check_places(out, overlay, video)  # an unwritable place fails now, not after the work
    model = load(system)
    cost = tracking_estimate(video, model, start=start, stop=stop, overlay=overlay is not None)
    confirm_cost(cost, yes=yes)
    with ProgressBar("tracking") as bar:
        result, written = track_to_files(
            video,
            model,
            out=out,
            overlay=overlay,
            scale=scale,
            start=start,
            stop=stop,
            origin=origin,
            progress=bar,
        )
    for path in written:
        say(f"wrote {path}")
    if as_json:
        print_json(result.summary())
        return
    _print_summary(result)


def _print_summary(result: object) -> None:
    """The summary as text: one line, then the per-body residuals as a table."""
    from rich.table import Table

    from rollspring.cli.text import markup
    from rollspring.lab.tracking import TrackResult

    assert isinstance(result, TrackResult)
    summary = result.summary()
    console = stdout_console()
    console.print(
        f"{summary['frames']} frames, t = {summary['t_start']:.4g} … {summary['t_end']:.4g} s "
        f"at {summary['fps']:.4g} fps; scale {summary['scale']:.6g} px/m "
        f"({summary['scale_source']}); camera roll {summary['roll_deg']:.3f}°"
    )
    table = Table("body", "circle fit RMS (mm)", "height RMS (mm)", "marker contrast")
    for name, values in summary["residuals"].items():
        table.add_row(
            markup(name),
            f"{values['circle_rms'] * 1e3:.3g}",
            f"{values['height_rms'] * 1e3:.3g}",
            f"{values['marker_contrast']:.2f}",
        )
    console.print(table)


def register(app: typer.Typer) -> None:
    """Add the ``track`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, track, "track", extras="lab")
