"""Atomic file writing: a temporary file in the target's directory, then ``os.replace``; sets
of files (a run's ``trajectory.csv``, ``trajectory.npz`` and ``summary.json``) written as a set.

A run killed at any moment leaves either the previous file or the complete new one, never a
half-written file (``os.replace`` is atomic on POSIX and Windows within one filesystem), and a
folder never holds a new run's files beside an earlier run's (:func:`write_file_set`). Every
temporary name carries the writer's process id: one left by a process that was killed outright
(SIGKILL, a power cut) is removed by the next write to the same place, never one of a process
still running.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import stat
import tempfile
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import IO

from rollspring.errors import OutputError

__all__ = [
    "atomic_path",
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_text",
    "remove_leftovers",
    "writable_directory",
    "writable_file",
    "write_file_set",
]

#: Folders :func:`write_file_set` stages a set in (new files) and parks the set it replaces in
#: (old files), inside the target folder; a folder that does not exist yet is staged beside it.
_STAGING, _PARKED = ".rollspring-part-", ".rollspring-old-"


def _alive(pid: int) -> bool:
    """Whether process ``pid`` still runs (unsure counts as yes: nothing of it is removed)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (OSError, ValueError, OverflowError):  # another user's process; no such pid on Windows
        return True
    return True


def _stale(rest: str) -> bool:
    """Whether a temporary name whose part after its prefix is ``rest`` ("<pid>-..." or
    "<pid>.<random>...") was left by a process that no longer runs (a name without a process
    id, from an older rollspring, is stale too)."""
    digits = ""
    for char in rest:
        if not char.isdigit():
            break
        digits += char
    return not digits or not _alive(int(digits))


def remove_leftovers(folder: str | os.PathLike[str], names: tuple[str, ...] = ()) -> list[Path]:
    """Remove what killed writers left in ``folder``: staging folders of
    :func:`write_file_set` and temporary files of :func:`atomic_path` for ``names`` (and every
    ``.part`` of the set names), whose process no longer runs. Returns what was removed; a
    folder that cannot be listed is left alone."""
    removed: list[Path] = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        name = entry.name
        stale = False
        for prefix in (_STAGING, _PARKED):
            if name.startswith(prefix):
                stale = _stale(name.removeprefix(prefix))
        for target in names:
            head = f".{target}."
            if name.startswith(head) and ".part" in name:
                stale = _stale(name.removeprefix(head))
        if not stale:
            continue
        path = Path(entry.path)
        with contextlib.suppress(OSError):
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(path)
            else:
                path.unlink()
            removed.append(path)
    return removed


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str], suffix: str = ".part") -> Iterator[Path]:
    """A temporary path next to ``path`` for a writer that wants a file name (an encoder, a
    browser printing a PDF); on success it is renamed onto ``path``, on any exception removed,
    leaving ``path`` untouched. ``suffix`` ends the temporary name (some writers go by it)."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_leftovers(target.parent, (target.name,))
    descriptor, temporary = tempfile.mkstemp(
        prefix=f".{target.name}.{os.getpid()}.", suffix=suffix, dir=target.parent
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


def write_file_set(
    directory: str | os.PathLike[str], writers: Mapping[str, Callable[[Path], None]]
) -> list[Path]:
    """Write a set of files into ``directory`` as one: ``writers`` maps each file name to a
    function that writes that file at the path it is given. Every file is written first into a
    staging folder; only when all are complete does the set replace the files of those names in
    ``directory`` (a folder that does not exist yet appears whole, by one rename). A failure or
    an interruption at any point removes the staging folder and leaves the earlier set as it
    was, so ``directory`` never holds some new files beside some old ones. Leftovers of killed
    earlier writes are removed first (:func:`remove_leftovers`). Returns the paths written;
    an ``OSError`` becomes :class:`~rollspring.errors.OutputError`."""
    target = Path(directory)
    names = tuple(writers)
    try:
        if target.is_dir():
            return _replace_set(target, writers)
        parent = target.absolute().parent
        parent.mkdir(parents=True, exist_ok=True)
        remove_leftovers(parent, (target.name,))
        staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.{os.getpid()}.part-", dir=parent))
        try:
            for name, write in writers.items():
                write(staging / name)
                _fsync(staging / name)
            os.chmod(staging, 0o755)
            os.rename(staging, target)  # the whole folder at once
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
    except OSError as exc:
        raise OutputError(f"{directory}: cannot write ({exc.strerror or exc})") from None
    return [target / name for name in names]


def _fsync(path: Path) -> None:
    """Flush a written file to the disk before it is renamed into place."""
    descriptor = os.open(path, os.O_RDONLY)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)


def _replace_set(target: Path, writers: Mapping[str, Callable[[Path], None]]) -> list[Path]:
    remove_leftovers(target, tuple(writers))
    staging = Path(tempfile.mkdtemp(prefix=f"{_STAGING}{os.getpid()}-", dir=target))
    parked: Path | None = None
    moved_old: list[str] = []
    moved_new: list[str] = []
    try:
        for name, write in writers.items():
            write(staging / name)
            _fsync(staging / name)
        parked = Path(tempfile.mkdtemp(prefix=f"{_PARKED}{os.getpid()}-", dir=target))
        for name in writers:  # the earlier set leaves first ...
            if os.path.lexists(target / name):
                os.replace(target / name, parked / name)
                moved_old.append(name)
        for name in writers:  # ... then the new one arrives
            os.replace(staging / name, target / name)
            moved_new.append(name)
    except BaseException:
        for name in moved_new:  # back to the earlier set, as far as it goes
            with contextlib.suppress(OSError):
                os.unlink(target / name)
        if parked is not None:
            for name in moved_old:
                with contextlib.suppress(OSError):
                    os.replace(parked / name, target / name)
            shutil.rmtree(parked, ignore_errors=True)
        shutil.rmtree(staging, ignore_errors=True)
        raise
    shutil.rmtree(parked, ignore_errors=True)
    shutil.rmtree(staging, ignore_errors=True)
    return [target / name for name in writers]


def _name_too_long(folder: Path, parts: tuple[str, ...]) -> str | None:
    """The first of ``parts`` (names to be created under ``folder``) too long for its
    filesystem, or None."""
    try:
        limit = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        limit = 255
    return next((part for part in parts if len(os.fsencode(part)) > limit), None)


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
    shown = _shown(path if named is None else named)
    if os.fspath(path) == "":
        raise OutputError(f"{option}: must not be empty (give a folder, or . for this one)")
    if "\x00" in str(os.fspath(path)):
        raise OutputError(f"{option} {shown}: not a valid path (a NUL character)")
    try:
        directory = Path(path)
        probe = directory.absolute()
        missing: list[str] = []
        while not probe.exists() and probe.parent != probe:
            missing.append(probe.name)
            probe = probe.parent
        if not probe.is_dir():
            reason = (
                f"{_shown(probe)} is not a directory"
                if Path(path if named is None else named).absolute() != probe
                else "it is a file, not a directory"
            )
            raise OutputError(f"{option} {shown}: cannot write there ({reason})")
        long_name = _name_too_long(probe, tuple(missing))
        if long_name is not None:
            raise OutputError(
                f"{option} {shown}: cannot write there (a name is too long: {_shown(long_name)})"
            )
        descriptor, temporary = tempfile.mkstemp(prefix=".rollspring-check-", dir=probe)
    except OutputError:
        raise
    except ValueError as exc:  # a NUL character in the path
        raise OutputError(f"{option} {shown}: not a valid path ({exc})") from None
    except OSError as exc:
        raise OutputError(
            f"{option} {shown}: cannot write there ({exc.strerror or exc}: {_shown(probe)})"
        ) from None
    os.close(descriptor)
    os.unlink(temporary)
    return directory


def writable_file(path: str | os.PathLike[str], option: str = "--out") -> Path:
    """Check, before any long computation, that the file ``path`` can be written (its directory,
    as :func:`writable_directory`; the path itself neither a directory nor a device, FIFO or
    socket, which a rename would replace)."""
    shown = _shown(path)
    if os.fspath(path) == "":
        raise OutputError(f"{option}: must not be empty (give a file name)")
    if "\x00" in str(os.fspath(path)):
        raise OutputError(f"{option} {shown}: not a valid path (a NUL character)")
    try:
        target = Path(path)
        info = os.stat(target) if os.path.lexists(target) else None
    except ValueError as exc:
        raise OutputError(f"{option} {shown}: not a valid path ({exc})") from None
    except OSError as exc:
        raise OutputError(f"{option} {shown}: cannot write there ({exc.strerror or exc})") from None
    if info is not None and stat.S_ISDIR(info.st_mode):
        raise OutputError(f"{option} {shown}: cannot write there (it is a directory)")
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise OutputError(
            f"{option} {shown}: cannot write there (it is not a regular file: a device, FIFO "
            "or socket)"
        )
    long_name = _name_too_long(target.absolute().parent, (target.name,))
    if long_name is not None and target.absolute().parent.is_dir():
        raise OutputError(
            f"{option} {shown}: cannot write there (the name is too long: {_shown(long_name)})"
        )
    writable_directory(target.parent, option, named=path)
    return target


def _shown(path: str | os.PathLike[str]) -> str:
    """A path for a one-line message: control characters escaped, at most 200 characters."""
    text = os.fspath(path)
    if isinstance(text, bytes):
        text = text.decode("utf-8", "backslashreplace")
    text = "".join(char if char.isprintable() or char == " " else repr(char)[1:-1] for char in text)
    return text if len(text) <= 200 else f"{text[:170]}… ({len(text)} characters)"
