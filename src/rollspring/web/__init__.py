"""The web interface: ``rollspring serve`` — the interactive page and its JSON API.

``create_app()`` returns the ASGI app (FastAPI); the computations run in worker processes
(:mod:`rollspring.web.workers`) through the orchestration layer (:mod:`rollspring.service`).
"""

from rollspring.web.app import create_app

__all__ = ["create_app"]
