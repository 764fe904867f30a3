"""``rollspring serve [SYSTEM]``: the interactive page and its JSON API on a local web server.

The app is :func:`rollspring.web.create_app` on uvicorn. It binds to 127.0.0.1 unless told
otherwise (another address is allowed, with a warning: the page has no log-in). ``--port 0``
takes a free port; the URL printed on stdout is the one to open.
"""

from __future__ import annotations

import ipaddress
import socket
from typing import Annotated

import typer

from rollspring.cli.common import add_command, say
from rollspring.cli.options import system_argument
from rollspring.errors import ServeError
from rollspring.model import DEFAULT_PRESET, preset_names

__all__ = ["ServeError", "register", "serve"]


def serve(
    system: Annotated[
        str,
        system_argument(
            f"The system the page opens with: a file (.toml or .json) or a preset name "
            f"({', '.join(preset_names())})."
        ),
    ] = DEFAULT_PRESET,
    host: Annotated[
        str, typer.Option(help="Address to listen on (127.0.0.1: this machine only).")
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option(help="Port (0: any free port).")] = 8000,
    open_browser: Annotated[
        bool, typer.Option("--open", help="Open the page in a browser.")
    ] = False,
    budget: Annotated[
        float, typer.Option(help="Time budget of one computation, s (longer: HTTP 503).")
    ] = 10.0,
    workers: Annotated[
        int, typer.Option(help="Worker processes for the computations (0: one per core).")
    ] = 0,
    limit_concurrency: Annotated[
        int,
        typer.Option(
            "--limit-concurrency", help="Connections at once; more are answered 503 at once."
        ),
    ] = 64,
) -> None:
    """Serve the interactive page: drag the bodies, move the sliders, watch every force."""
    if not 0 <= port <= 65535:
        raise ServeError(f"--port: must be 0 to 65535, got {port}")
    from rollspring.web.workers import check_pool

    check_pool(workers, budget, option="--")
    if limit_concurrency < 1:
        raise ServeError(f"--limit-concurrency: must be at least 1, got {limit_concurrency}")
    from rollspring.model import load_system  # pydantic: not for --help

    model = load_system(system)
    listener = _listen(host, port)
    if not _is_loopback(host):
        say(
            f"warning: serving on {host}, reachable from other machines; the page has no "
            "log-in, anyone who reaches it can use it"
        )
    bound = listener.getsockname()[1]
    shown = f"[{host}]" if ":" in host else host
    url = f"http://{shown}:{bound}/"

    import uvicorn

    from rollspring.web import create_app

    app = create_app(
        model,
        preset=system if system in preset_names() else None,
        budget=budget,
        workers=workers or None,
    )
    config = uvicorn.Config(
        app, log_level="warning", limit_concurrency=limit_concurrency, timeout_graceful_shutdown=2
    )
    server = uvicorn.Server(config)
    typer.echo(f"rollspring: {model.name or system} at {url} (Ctrl-C stops)")
    if open_browser:
        import threading
        import webbrowser

        threading.Timer(1.0, webbrowser.open, args=(url,)).start()
    server.run(sockets=[listener])


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def _listen(host: str, port: int) -> socket.socket:
    """A bound, listening socket (so that ``--port 0`` knows its port before serving)."""
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except socket.gaierror as exc:
        raise ServeError(f"--host: cannot listen on {host!r} ({exc.strerror})") from None
    family, kind, proto, _, address = infos[0]
    listener = socket.socket(family, kind, proto)
    listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        listener.bind(address)
    except OSError as exc:
        listener.close()
        raise ServeError(f"--port: cannot listen on {host}:{port} ({exc.strerror})") from None
    listener.listen(2048)
    return listener


def register(app: typer.Typer) -> None:
    """Add the ``serve`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, serve, "serve", extras="web")
