"""The ``rollspring`` command: parses arguments, calls the library, formats the results."""

from rollspring.cli.app import app, main

__all__ = ["app", "main"]
