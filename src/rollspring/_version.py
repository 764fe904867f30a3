"""The installed distribution's version: written once, in pyproject.toml, and read from the
package's metadata (``rollspring.__version__``)."""

from __future__ import annotations

import functools

__all__ = ["version"]


@functools.cache
def version() -> str:
    """``rollspring``'s version from its installed metadata (``0+unknown`` when it is run from a
    source tree that is not installed)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("rollspring")
    except PackageNotFoundError:
        return "0+unknown"
