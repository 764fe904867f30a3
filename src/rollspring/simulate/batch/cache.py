"""The on-disk cache of generated batch kernels.

A generated module is written once, named by the hash of its source, so Numba's ``cache=True``
keeps its compiled code between processes: the first call for a new system or set of parameter
keys compiles for several seconds, later ones load in a fraction of a second.

The directory (:func:`kernel_dir`) is ``$ROLLSPRING_CACHE_DIR/batch-kernels``, else
``$ROLLSPRING_KERNEL_DIR`` (the older variable, naming the kernels' directory itself), else
``$XDG_CACHE_HOME/rollspring/batch-kernels``, else ``~/.cache/rollspring/batch-kernels``
(a temporary directory if none is writable); inside it one subdirectory per rollspring and Numba
version (:func:`version_tag`). Subdirectories of other versions, and kernels left directly in it
by versions before the subdirectories, are stale: the first load in a process removes them
(one directory listing; only names this module writes are touched).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import re
import shutil
import tempfile
import threading
from importlib import metadata
from pathlib import Path
from typing import Any

from rollspring.errors import SimulationError
from rollspring.simulate.modules import exec_spec

__all__ = ["kernel_dir", "load_kernel", "load_module", "prune", "version_tag"]

_KERNELS: dict[str, Any] = {}
_KERNELS_LOCK = threading.Lock()
_PRUNED: set[Path] = set()
_TAG = re.compile(r"^rollspring-.+-numba-.+$")
_LOOSE = re.compile(r"^\.?rollspring_batch_[0-9a-f]{20}(\.py|\..*\.tmp)$")


def version_tag() -> str:
    """``rollspring-<version>-numba-<version>``: the subdirectory of this installation."""
    try:
        mine = metadata.version("rollspring")
    except metadata.PackageNotFoundError:  # pragma: no cover - running from a source tree
        mine = "unknown"
    import numba

    return f"rollspring-{mine}-numba-{numba.__version__}"


def cache_root() -> Path:
    """The directory holding the per-version subdirectories (see the module's docstring)."""
    env = os.environ.get("ROLLSPRING_CACHE_DIR")
    if env:
        return Path(env) / "batch-kernels"
    env = os.environ.get("ROLLSPRING_KERNEL_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "rollspring" / "batch-kernels"


def kernel_dir() -> Path:
    """Where this installation's generated kernels go: ``cache_root() / version_tag()``."""
    return cache_root() / version_tag()


def prune(root: Path, keep: str) -> list[Path]:
    """Remove the stale entries of ``root``: version subdirectories other than ``keep`` and
    kernels written directly in it (the layout before version subdirectories, with their
    ``__pycache__``). Returns what was removed; errors (another process, permissions) are
    ignored."""
    removed: list[Path] = []
    try:
        entries = list(root.iterdir())
    except OSError:
        return removed
    loose = False
    for entry in entries:
        try:
            if entry.is_dir() and _TAG.match(entry.name) and entry.name != keep:
                shutil.rmtree(entry, ignore_errors=True)
                removed.append(entry)
            elif entry.is_file() and _LOOSE.match(entry.name):
                entry.unlink(missing_ok=True)
                removed.append(entry)
                loose = True
        except OSError:
            continue
    cache = root / "__pycache__"
    if loose and cache.is_dir():
        for entry in cache.iterdir():
            if entry.name.startswith("rollspring_batch_"):
                try:
                    entry.unlink(missing_ok=True)
                    removed.append(entry)
                except OSError:
                    continue
    return removed


def _folders() -> list[Path]:
    tag = version_tag()
    root = cache_root()
    if root not in _PRUNED:
        _PRUNED.add(root)
        prune(root, tag)
    fallback = Path(tempfile.gettempdir()) / f"rollspring-batch-kernels-{os.getuid()}"
    return [root / tag, fallback / tag]


def load_module(source: str) -> Any:
    """The generated module of ``source``, imported from the cache directory (written once,
    named by its hash, so Numba's on-disk cache applies)."""
    digest = hashlib.sha256(source.encode()).hexdigest()[:20]
    with _KERNELS_LOCK:
        if digest in _KERNELS:
            return _KERNELS[digest]
        name = f"rollspring_batch_{digest}"
        path = None
        for folder in _folders():
            try:
                folder.mkdir(parents=True, exist_ok=True)
                candidate = folder / f"{name}.py"
                if not candidate.exists() or candidate.read_text() != source:
                    tmp = folder / f".{name}.{os.getpid()}.tmp"
                    tmp.write_text(source)
                    os.replace(tmp, candidate)
                path = candidate
                break
            except OSError:
                continue
        if path is None:
            raise SimulationError(
                "cannot write the generated batch kernel: no writable cache "
                "directory (set ROLLSPRING_CACHE_DIR)"
            )
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None
        module = exec_spec(spec)
        _KERNELS[digest] = module
        return module


def load_kernel(source: str, *, serial: bool = False) -> Any:
    """The compiled ``run`` of the generated module of ``source`` (every block on Numba's
    threads), or with ``serial`` its ``run_serial`` (every block on the calling thread, the GIL
    released)."""
    module = load_module(source)
    return module.run_serial if serial else module.run
