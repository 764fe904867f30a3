"""Atomic file writing: a temporary file in the target's directory, then ``os.replace``; sets
of files (a run's ``trajectory.csv``, ``trajectory.npz`` and ``summary.json``) written as a set.

A run killed at any moment leaves either the previous file or the complete new one, never a
half-written file (``os.replace`` is atomic on POSIX and Windows within one filesystem), and a
folder never holds a new run's files beside an earlier run's (:func:`write_file_set`). A set
replacing another is journalled: staged whole and marked complete before the first rename, so a
writer killed at any instant (SIGKILL, a power cut) leaves a complete set, the earlier one in
place or the new one staged with its mark, and the next write into the folder finishes or drops
what it left (tests/test_write_faults.py kills a writer before each of its file operations).
Every temporary name carries the writer's process id: the leftovers of a process that no longer
runs are finished or removed, never those of a process still running.
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
    "same_file",
    "writable_directory",
    "writable_file",
    "write_file_set",
]

#: Folders :func:`write_file_set` stages a set in (new files) and parks the set it replaces in
#: (old files), inside the target folder; a folder that does not exist yet is staged beside it.
_STAGING, _PARKED = ".rollspring-part-", ".rollspring-old-"
#: The journal's mark in a staging folder: written when the staged set is complete; a staged set
#: with it is finished by the next write, one without it dropped.
_COMPLETE = ".complete"


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
    """Finish or undo what killed writers left in ``folder``, then remove it: a set that
    :func:`write_file_set` had staged completely (its journal mark written) is moved in, one that
    was not is dropped, and a parked earlier set is removed once the new one is whole; temporary
    files of :func:`atomic_path` for ``names`` (and every ``.part`` of the set names) are
    removed. Only leftovers of processes that no longer run are touched. Returns what was
    removed; a folder that cannot be listed is left alone."""
    removed: list[Path] = []
    try:
        entries = sorted(os.scandir(folder), key=lambda entry: not entry.name.startswith(_STAGING))
    except OSError:
        return removed
    for entry in entries:  # the staged sets first: a parked set goes only after its new one
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
            if name.startswith(_STAGING) and (path / _COMPLETE).exists():
                _move_in(path, Path(folder))  # the killed writer's new set was whole: finish
            if name.startswith(_PARKED):  # an earlier file with no new one in its place returns
                for parked in os.listdir(path):
                    if not os.path.lexists(Path(folder) / parked):
                        os.replace(path / parked, Path(folder) / parked)
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


def _fsync_folder(folder: Path) -> None:
    """Make the renames inside ``folder`` durable (where the platform allows opening a folder)."""
    with contextlib.suppress(OSError):
        descriptor = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(descriptor)
        finally:
            os.close(descriptor)


def _move_in(staging: Path, target: Path) -> None:
    """Move every file of a completely staged set into ``target`` (each rename replaces the
    earlier file of its name); the journal mark stays last, so a move interrupted here is
    finished by the next one."""
    for name in sorted(os.listdir(staging)):  # what is still staged (a second call: the rest)
        if name != _COMPLETE:
            os.replace(staging / name, target / name)
    _fsync_folder(target)


def _replace_set(target: Path, writers: Mapping[str, Callable[[Path], None]]) -> list[Path]:
    """The set replaces the files of its names in the existing folder ``target``.

    The journal is the staging folder itself: until every new file is written and flushed it
    holds no mark, and a kill leaves the earlier set untouched (the next write drops the
    staging folder). Then the mark :data:`_COMPLETE` is written, and from that instant the new
    set is the one that counts: the earlier files are parked, the new ones moved in; a kill at
    any point of that is finished by the next write into the folder
    (:func:`remove_leftovers`), an exception here (Ctrl-C) finishes it first, then goes on.
    The parked set is removed only when the new one is whole. So at every instant a complete
    set exists: the earlier one (in place) or the new one (staged with its mark, or in place)."""
    remove_leftovers(target, tuple(writers))
    staging = Path(tempfile.mkdtemp(prefix=f"{_STAGING}{os.getpid()}-", dir=target))
    try:
        for name, write in writers.items():
            write(staging / name)
            _fsync(staging / name)
        with open(staging / _COMPLETE, "wb") as mark:  # the new set is whole: the journal's mark
            os.fsync(mark.fileno())
        _fsync_folder(staging)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    parked: Path | None = None
    interrupted: BaseException | None = None
    try:
        parked = Path(tempfile.mkdtemp(prefix=f"{_PARKED}{os.getpid()}-", dir=target))
        for name in writers:  # the earlier set leaves first (a reader never sees a mix) ...
            if os.path.lexists(target / name):
                os.replace(target / name, parked / name)
    except BaseException as exc:  # noqa: BLE001 - an interruption waits until the new set is in place
        interrupted = exc
    for attempt in (1, 2):  # ... then the new one arrives, whatever happened to the parking
        try:
            _move_in(staging, target)
            break
        except BaseException as exc:
            if attempt == 2:  # left, marked, to the next write's recovery
                raise
            interrupted = interrupted or exc
    for folder in (parked, staging):  # the new set is whole: the earlier one can go
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)
    if interrupted is not None:
        raise interrupted
    return [target / name for name in writers]


def _check_text(path: str | os.PathLike[str], option: str, shown: str, give: str) -> None:
    """A path's text: not empty (the message says what to ``give``), no NUL character."""
    if os.fspath(path) == "":
        raise OutputError(f"{option}: must not be empty ({give})")
    if "\x00" in str(os.fspath(path)):
        raise OutputError(f"{option} {shown}: not a valid path (a NUL character)")


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
    _check_text(path, option, shown, "give a folder, or . for this one")
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


def same_file(a: str | os.PathLike[str], b: str | os.PathLike[str]) -> bool:
    """Whether two paths name one file (the same inode when both exist, else the same absolute
    path): two outputs of a command, or an output and the file it reads."""
    first, second = Path(a), Path(b)
    try:
        if first.exists() and second.exists():
            return os.path.samefile(first, second)
    except OSError:
        pass
    return first.absolute() == second.absolute()


def writable_file(path: str | os.PathLike[str], option: str = "--out") -> Path:
    """Check, before any long computation, that the file ``path`` can be written (its directory,
    as :func:`writable_directory`; the path itself neither a directory nor a device, FIFO or
    socket, which a rename would replace)."""
    shown = _shown(path)
    _check_text(path, option, shown, "give a file name")
    if os.fspath(path).endswith(("/", os.sep)):  # Path() drops the slash: a file "wdir" then
        raise OutputError(f"{option} {shown}: ends in '/', a folder's name (give a file name)")
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
