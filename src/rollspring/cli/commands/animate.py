"""``rollspring animate SYSTEM -o motion.gif|mp4|html``: the simulated motion as an animation.

Simulates the system (as ``rollspring simulate``) for ``--duration`` seconds and renders it with
:mod:`rollspring.outputs.animation`, with a progress bar on stderr. The command is added to an
app by :func:`register`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from rollspring.cli.common import ProgressBar, add_command, confirm_cost, load, say
from rollspring.cli.options import SystemArg, out_option, yes_option

if TYPE_CHECKING:
    from rich.progress import ProgressColumn

# rollspring.outputs.animation (Matplotlib) is imported when the command runs, not when the CLI
# starts: every other command would pay for it.

__all__ = ["animate", "register"]


def animate(
    system: SystemArg,
    out: Annotated[
        str | None, out_option("Output file: .gif (Pillow), .mp4 (H.264) or .html (JS player).")
    ] = None,
    duration: Annotated[
        float, typer.Option("--duration", "-T", help="Simulated time to show, s.")
    ] = 4.0,
    speed: Annotated[
        float, typer.Option(help="Playback speed: 1 real time, 0.5 slow motion.")
    ] = 1.0,
    fps: Annotated[int, typer.Option(help="Frames per second of playback.")] = 25,
    dpi: Annotated[int, typer.Option(help="Resolution: 80 gives frames 640 pixels wide.")] = 80,
    forces: Annotated[
        bool, typer.Option("--forces/--no-forces", help="Draw spring, friction and normal forces.")
    ] = True,
    on_slip: Annotated[
        str, typer.Option("--on-slip", help="stop: end at the first slip; continue: stick-slip.")
    ] = "stop",
    yes: Annotated[bool, yes_option()] = False,
) -> None:
    """Animate the exact motion: the bodies roll, the springs stretch, force arrows to scale,
    the CM and X-hat on the floor, and a clock."""
    target = _check(out, duration, speed, fps, dpi, on_slip)
    from rollspring.outputs.animation import AnimationError, frame_times, write_animation
    from rollspring.service.costs import request_cost
    from rollspring.service.runs import run_request
    from rollspring.simulate.request import simulation_request

    model = load(system)
    frames = math.floor(duration / speed * fps) + 1
    # the arguments checked once, the cost estimated once: the run checks nothing again
    request = simulation_request(duration, on_slip=on_slip, n_output=max(2001, 2 * frames))
    confirm_cost(request_cost(model, request, what="the simulation"), yes=yes)
    with ProgressBar(delay=0.0, columns=_columns) as bar:  # shown at once
        bar.start("simulating")
        trajectory = run_request(model, request, progress=bar).trajectory
        bar.start(f"rendering {target.name}")
        try:
            write_animation(
                trajectory,
                target,
                speed=speed,
                fps=fps,
                dpi=dpi,
                forces=forces,
                progress=bar,
            )
        except OSError as exc:
            raise AnimationError(f"{target}: cannot write ({exc.strerror or exc})") from None
    if trajectory.status != "finished":
        say(f"note: {trajectory.message}")
    shown = float(trajectory.t[-1] - trajectory.t[0])
    count = frame_times(trajectory, speed=speed, fps=fps).size
    say(f"wrote {target} ({count} frames, {shown:g} s of motion at speed {speed:g})")


def _check(
    out: str | None, duration: float, speed: float, fps: int, dpi: int, on_slip: str
) -> Path:
    """Every option checked before any work: one line naming the option."""
    from rollspring.outputs.animation import FORMATS, MAX_FRAMES, AnimationError

    if out is None:
        raise AnimationError("--out/-o is required: a .gif, .mp4 or .html file")
    target = Path(out)
    if target.suffix.lower() not in FORMATS:
        raise AnimationError(
            f"--out: unknown format '{target.suffix or '(no suffix)'}' of {out} "
            f"(use .gif, .mp4 or .html)"
        )
    for name, value in (("--duration", duration), ("--speed", speed)):
        if not (math.isfinite(value) and value > 0):
            raise AnimationError(f"{name}: must be a positive number, got {value:g}")
    if not 1 <= fps <= 120:
        raise AnimationError(f"--fps: must be between 1 and 120, got {fps}")
    if not 10 <= dpi <= 600:
        raise AnimationError(f"--dpi: must be between 10 and 600, got {dpi}")
    if on_slip not in ("stop", "continue"):
        raise AnimationError(f"--on-slip: must be 'stop' or 'continue', got '{on_slip}'")
    count = duration / speed * fps  # inf for a speed far below the duration
    if not count < MAX_FRAMES:
        raise AnimationError(
            f"--duration: {duration:g} s at --speed {speed:g} and --fps {fps} is {count:.3g} "
            f"frames (at most {MAX_FRAMES}); shorten it, raise --speed or lower --fps"
        )
    from rollspring.outputs.atomic import writable_file

    return writable_file(target)  # an unwritable --out fails now, not after the work


def _columns() -> tuple[ProgressColumn, ...]:
    """The progress bar's columns: the stage (simulating, rendering), the bar, the percentage
    and the time left."""
    from rich.progress import BarColumn, TextColumn, TimeRemainingColumn

    return (
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeRemainingColumn(),
    )


def register(app: typer.Typer) -> None:
    """Add the ``animate`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, animate, "animate", extras="plot")
