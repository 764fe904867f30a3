"""``rollspring serve [SYSTEM]``: the interactive page and its JSON API on a local web server.

The app is :func:`rollspring.web.create_app` on uvicorn. It binds to 127.0.0.1 unless told
otherwise (another address is allowed, with a warning: the page has no log-in). ``--port 0``
takes a free port. The worker processes warm up first (a progress line on stderr); the URL is
printed on stdout, and ``--open`` opens it, only once the server answers.
"""

from __future__ import annotations

import ipaddress
import socket
import sys
from collections.abc import Callable
from typing import Annotated, Any

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
    from rollspring.web.workers import pool_size

    total = pool_size(workers)
    warming = f"rollspring: warming up {total} worker process{'es' if total > 1 else ''} …"
    tty = sys.stderr.isatty()

    def progress(ready: int, total: int) -> None:
        if tty:  # the line, updated in place as each worker is ready
            end = "\n" if ready == total else ""
            sys.stderr.write(f"\r{warming} {ready}/{total} ready{end}")
            sys.stderr.flush()
        elif ready == total:  # a log: the line again, finished
            say(f"{warming} {ready}/{total} ready")

    app = create_app(
        model,
        preset=system if system in preset_names() else None,
        budget=budget,
        workers=workers or None,
        progress=progress,
    )
    if not tty:
        say(warming)

    def serving() -> None:
        typer.echo(f"rollspring: {model.name or system} at {url} (Ctrl-C stops)")
        if open_browser:  # a browser may take its time to start: not on the server's loop
            import threading
            import webbrowser

            threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()

    config = uvicorn.Config(
        app, log_level="warning", limit_concurrency=limit_concurrency, timeout_graceful_shutdown=2
    )
    _server(config, serving).run(sockets=[listener])


def _server(config: Any, serving: Callable[[], None]) -> Any:
    """uvicorn's server, calling ``serving()`` once it answers: after its start-up (every
    worker process warm) and once it accepts on its socket, not before."""
    import uvicorn

    class Server(uvicorn.Server):
        async def startup(self, sockets: Any = None) -> None:
            await super().startup(sockets=sockets)
            if self.started and not self.should_exit:
                serving()

    return Server(config)


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
