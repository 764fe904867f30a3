"""Numba's on-disk cache of this package, kept in step with its sources.

Numba checks a cached kernel against the stamp of one file only, the file of the function it
compiled. A kernel here inlines the force law of ``law.py``, reads the columns of ``model.py``
and calls the kernels of the other modules: after an edit to any of those files alone, its
cached machine code would be stale, silently. Imported first by the package (its ``__init__``),
this module hashes every source file of the package and, when the digest differs from the one
stored beside the cache, removes the package's cached kernels (``*.nbi``, ``*.nbc``) so that
they compile again from the current sources, then stores the new digest. A matching digest
costs one hash of the sources (about 0.1 ms) and keeps every cached kernel.

Only the cache beside the sources (``__pycache__``, Numba's default) is managed; a cache that
Numba keeps elsewhere (``NUMBA_CACHE_DIR``, a read-only installation) is left alone: an
installed release replaces every file, so all of its stamps change.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["STAMP", "source_digest", "sync_cache"]

#: The file, in the package's ``__pycache__``, that holds the digest the cache was built from.
STAMP = "kernels-sources.sha256"


def source_digest(package: Path) -> str:
    """SHA-256 over the names and contents of the package's ``*.py`` files, in name order."""
    digest = hashlib.sha256()
    for source in sorted(package.glob("*.py")):
        digest.update(source.name.encode())
        digest.update(source.read_bytes())
    return digest.hexdigest()


def sync_cache(package: Path) -> bool:
    """Remove the package's cached kernels when its sources changed since they were cached;
    True when it did. Best effort: an unwritable cache folder is left as it is."""
    cache = package / "__pycache__"
    stamp = cache / STAMP
    digest = source_digest(package)
    try:
        if stamp.read_text(encoding="ascii") == digest:
            return False
    except (OSError, UnicodeDecodeError):
        pass
    try:
        cache.mkdir(exist_ok=True)
        for compiled in (*cache.glob("*.nbi"), *cache.glob("*.nbc")):
            compiled.unlink(missing_ok=True)
        partial = cache / f"{STAMP}.{os.getpid()}.tmp"
        partial.write_text(digest, encoding="ascii")
        os.replace(partial, stamp)
    except OSError:
        return False
    return True


sync_cache(Path(__file__).resolve().parent)
