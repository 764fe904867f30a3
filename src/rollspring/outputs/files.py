"""Atomic file writing: a temporary file in the target's directory, then ``os.replace``.

A run killed at any moment leaves either the previous file or the complete new one, never a
half-written file (``os.replace`` is atomic on POSIX and Windows within one filesystem).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from rollspring.errors import OutputError

__all__ = [
    "atomic_path",
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_text",
    "writable_directory",
    "writable_file",
]


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str], suffix: str = ".part") -> Iterator[Path]:
    """A temporary path next to ``path`` for a writer that wants a file name (an encoder, a
    browser printing a PDF); on success it is renamed onto ``path``, on any exception removed,
    leaving ``path`` untouched. ``suffix`` ends the temporary name (some writers go by it)."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(
        prefix=f".{target.name}.", suffix=suffix, dir=target.parent
    )
    os.close(descriptor)
    try:
        yield Path(temporary)
        os.chmod(temporary, 0o644)
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "w", **open_kwargs) -> Iterator[IO]:
    """Open a temporary file next to ``path``; on success flush, fsync and rename it onto
    ``path``; on any exception remove it and leave ``path`` untouched."""
    with atomic_path(path) as temporary, open(temporary, mode, **open_kwargs) as handle:
        yield handle
        handle.flush()
        os.fsync(handle.fileno())


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_write(path, "w", encoding="utf-8", newline="\n") as handle:
        handle.write(text)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_write(path, "wb") as handle:
        handle.write(data)


def writable_directory(
    path: str | os.PathLike[str],
    option: str = "--out",
    *,
    named: str | os.PathLike[str] | None = None,
) -> Path:
    """Check, before any long computation, that files can be written into the directory
    ``path`` (which may not exist yet: then into its nearest existing ancestor, where it will be
    created). Creates nothing; raises :class:`~rollspring.errors.OutputError` naming ``option``,
    the path (``named``, default ``path``) and the reason."""
    directory = Path(path)
    shown = path if named is None else named
    probe = directory.absolute()
    try:
        while not probe.exists() and probe.parent != probe:
            probe = probe.parent
        if not probe.is_dir():
            reason = (
                f"{probe} is not a directory"
                if Path(shown).absolute() != probe
                else "it is a file, not a directory"
            )
            raise OutputError(f"{option} {shown}: cannot write there ({reason})")
        descriptor, temporary = tempfile.mkstemp(prefix=".rollspring-check-", dir=probe)
    except OSError as exc:
        raise OutputError(
            f"{option} {shown}: cannot write there ({exc.strerror or exc}: {probe})"
        ) from None
    os.close(descriptor)
    os.unlink(temporary)
    return directory


def writable_file(path: str | os.PathLike[str], option: str = "--out") -> Path:
    """Check, before any long computation, that the file ``path`` can be written (its directory,
    as :func:`writable_directory`; the path itself not a directory)."""
    target = Path(path)
    if target.is_dir():
        raise OutputError(f"{option} {path}: cannot write there (it is a directory)")
    writable_directory(target.parent, option, named=path)
    return target
