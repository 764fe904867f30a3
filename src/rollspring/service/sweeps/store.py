"""The sweep's Zarr v3 store: the template, chunk regions, done markers, the fingerprint.

The template (every variable's metadata, the coordinates and the attrs, consolidated) is made
from Zarr's metadata classes, without its event loop, and written as files, the group's
document last (:func:`write_template`);
each finished chunk is then written as one Zarr chunk of every variable, encoded by the
array's own codecs and stored as its file whole or not at all (:class:`RegionWriter`; the
regions are the Zarr chunks, so concurrent writers never share a file), and followed by its
done marker ``<store>/.rollspring-done/<chunk index>``, an empty file created atomically.
Every chunk is written to disk, even one equal to the fill value (Zarr's
``write_empty_chunks``), so a resume checks the chunks its markers vouch for
(:func:`verified_done`): a marked chunk whose file is gone is run again, and what killed
writers left (``.partial`` files, half-made markers) is removed first. Nothing is synced to
the disk (nor does Zarr's own local store sync): the guarantees are against a killed process,
not a machine losing power.
"""

from __future__ import annotations

import base64
import contextlib
import hashlib
import json
import os
import shutil
import stat
import threading
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from rollspring.errors import StoreMismatchError, SweepError
from rollspring.service.sweeps.grid import Grid, unit_of

__all__ = [
    "MARKERS",
    "VARIABLES",
    "RegionWriter",
    "StoreMismatchError",
    "check_place",
    "discard",
    "done_chunks",
    "fingerprint",
    "mark_done",
    "read_attrs",
    "store_lock",
    "verified_done",
    "write_template",
]

MARKERS = ".rollspring-done"
#: The chunk files of a variable named ``c.<i>.<j>...`` in its folder (Zarr v3's default
#: encoding with the "." separator): Zarr's "/" makes a folder per chunk and level (85 folders
#: for 65 536 runs in four chunks), and a folder costs the file system more than a file (about
#: 0.3-0.7 ms of CPU each here, the largest part of writing a sweep's store). Stores made with
#: "/" (before 29 Nov 2026) are read and resumed by their own metadata's encoding.
CHUNK_KEYS: dict[str, Any] = {"name": "default", "separator": "."}

#: name -> (extra dimension or None, units, long_name)
VARIABLES: dict[str, tuple[str | None, str, str]] = {
    "omega": ("mode", "rad/s", "linear angular frequency of each mode (zero modes exactly 0)"),
    "stationary_weight": ("body", "1", "weight of each body in the stationary point X-hat"),
    "required_mu_linear": ("body", "1", "max |f|/N of the linear response"),
    "period_measured": (None, "s", "measured period"),
    "max_friction_ratio": ("body", "1", "max |f|/N over the run"),
    "min_normal_force": ("body", "N", "min normal force over the run"),
    "first_slip_time": (None, "s", "instant of the first slip (NaN: none)"),
    "first_slip_body": (None, "1", "index into body of the first slip (-1: none)"),
    "first_liftoff_time": (None, "s", "instant of the first lift-off (NaN: none)"),
    "cm_amplitude": (None, "m", "half the range of the centre of mass"),
    "stationary_amplitude": (None, "m", "half the range of X-hat, its uniform motion removed"),
    "energy_error": (None, "1", "max relative energy error"),
    "status": (None, "1", "how the run ended"),
    "energy_dissipated": (None, "J", "energy dissipated by kinetic friction"),
    "time_slipping": (None, "s", "time during which a body slips"),
}
_INTEGER = {"first_slip_body": "int16", "status": "int8"}


def fingerprint(
    system_toml: str,
    grid: Grid,
    duration: float,
    rtol: float,
    on_slip: str,
    metrics: tuple[str, ...],
    extra: dict[str, Any],
) -> str:
    """sha256 of everything that decides the store's content."""
    data = {
        "system": system_toml,
        "paths": list(grid.paths),
        "values": [[float(v).hex() for v in values] for values in grid.values],
        "duration": float(duration).hex(),
        "rtol": float(rtol).hex(),
        "on_slip": on_slip,
        "metrics": list(metrics),
        "chunks": list(grid.chunks),
        **extra,
    }
    return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()


def read_attrs(path: Path) -> dict[str, Any] | None:
    """The attrs of the store at ``path``; None when there is no store there."""
    if not path.exists():
        return None
    import zarr

    try:
        group = zarr.open_group(str(path), mode="r")
    except Exception as exc:  # noqa: BLE001 - any unreadable store
        raise StoreMismatchError(
            f"--out {path}: exists and is not a rollspring sweep store "
            f"({type(exc).__name__}); use --overwrite to replace it"
        ) from None
    return dict(group.attrs)


def check_place(out: Any, overwrite: bool) -> Path:
    """``--out`` checked before any work: a folder name (not empty, ``.`` or ``..``) in a
    folder this process can write into; what is there already never a device, FIFO or socket;
    with ``overwrite``, only a sweep's store, an empty folder or a regular file is replaced,
    never another folder. One-line :class:`SweepError`."""
    from rollspring.errors import OutputError
    from rollspring.model.files import not_regular
    from rollspring.outputs.atomic import writable_directory

    if not isinstance(out, str | os.PathLike) or isinstance(out, bytes):
        raise SweepError(f"--out: expected a folder's path, got {type(out).__name__}")
    path = Path(out)
    if not os.fspath(out).strip() or path.name in ("", ".", ".."):
        raise SweepError(f"--out {os.fspath(out)!r}: give the store's own folder name (x.zarr)")
    try:
        writable_directory(path.parent, "--out", named=path)
        info = path.stat() if path.exists() else None
    except OutputError as exc:
        raise SweepError(str(exc)) from None
    except (OSError, ValueError) as exc:
        raise SweepError(f"--out {path}: cannot be used ({exc})") from None
    if info is None:
        return path
    if not stat.S_ISDIR(info.st_mode):
        kind = not_regular(info.st_mode)
        if kind is not None:  # a device, FIFO or socket: never replaced
            raise SweepError(
                f"--out {path}: is {kind}, not a folder (a sweep's store is a folder); choose "
                "another --out"
            )
        if not overwrite:
            raise StoreMismatchError(
                f"--out {path}: exists and is not a rollspring sweep store (a file); use "
                "--overwrite to replace it"
            )
        return path
    if overwrite:
        entries = {entry.name for entry in path.iterdir()}
        if entries and not _a_sweeps_store(path, entries):
            shown = ", ".join(sorted(entries)[:3]) + (", ..." if len(entries) > 3 else "")
            raise SweepError(
                f"--out {path}: a folder that is not a sweep's store (it holds {shown}); "
                "--overwrite replaces only a sweep's store"
            )
    return path


def _a_sweeps_store(path: Path, entries: set[str]) -> bool:
    """Whether the folder ``path`` (holding ``entries``) is a rollspring sweep's store: its
    done markers, or a Zarr group whose attributes hold a grid fingerprint (another Zarr
    dataset is not one)."""
    if MARKERS in entries:
        return True
    try:
        attrs = read_attrs(path)
    except StoreMismatchError:
        return False
    return attrs is not None and "grid_fingerprint" in attrs


@contextlib.contextmanager
def store_lock(path: Path) -> Iterator[None]:
    """Hold the store at ``path`` for one sweep: an exclusive lock (``flock``) on a hidden file
    beside it, ``.<name>.lock``, removed when the sweep ends (a lock is taken only on the file
    the name still names, so a file removed meanwhile is never locked by two). A second sweep
    on the same store, in this process or another, is a one-line :class:`SweepError` at once:
    two writers left a store whose chunks were one sweep's and whose attributes the other's."""
    import fcntl

    real = path.resolve()  # a link and its target are one store: one lock
    lock = real.parent / f".{real.name}.lock"
    while True:
        try:
            lock.parent.mkdir(parents=True, exist_ok=True)
            handle = open(lock, "a")  # noqa: SIM115 - closed below, after the sweep
        except OSError as exc:
            raise SweepError(
                f"--out {path}: cannot lock the store ({exc.strerror or exc})"
            ) from None
        try:
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            raise SweepError(
                f"--out {path}: another sweep is writing this store; wait for it to end, or "
                "choose another --out"
            ) from None
        try:
            current = os.stat(lock).st_ino
        except FileNotFoundError:
            current = None
        if current == os.fstat(handle.fileno()).st_ino:
            break
        handle.close()  # removed by the sweep that held it, after this opened it: again
    try:
        yield
    finally:
        with contextlib.suppress(OSError):
            lock.unlink()
        handle.close()  # the lock goes with it


def remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    elif path.exists() or path.is_symlink():
        path.unlink()


def discard(path: Path) -> threading.Thread | None:
    """Free ``path`` at once and remove what was there in a thread (joined by the caller): a
    folder is renamed to a hidden sibling first (removing a store's folders waits on the disk,
    up to 0.3 s for 65 536 runs here, while the first chunks step). A kill before the removal
    ends leaves that sibling, ``.<name>.<pid>-<thread>.discarded``; the next discard of the
    same path removes it (:func:`_stale_discarded`)."""
    if not path.is_dir() or path.is_symlink():
        remove(path)
        return None
    aside = path.with_name(f".{path.name}.{os.getpid()}-{threading.get_ident()}.discarded")
    try:
        path.rename(aside)
    except OSError:  # pragma: no cover - e.g. a folder this user may not rename
        remove(path)
        return None
    thread = threading.Thread(
        target=_remove_discarded,
        args=(aside, _stale_discarded(path)),
        name="rollspring-sweep-discard",
        daemon=True,
    )
    thread.start()
    return thread


def _remove_discarded(aside: Path, stale: list[Path]) -> None:
    for folder in (aside, *stale):
        shutil.rmtree(folder, ignore_errors=True)


def _stale_discarded(path: Path) -> list[Path]:
    """Earlier discards of ``path`` that a killed process left (``.<name>.<pid>-<thread>
    .discarded`` siblings whose process is gone): removed with this one."""
    stale = []
    for sibling in path.parent.glob(f".{path.name}.*.discarded"):
        pid = sibling.name[len(path.name) + 2 :].split("-", 1)[0]
        if pid.isdigit() and not _alive(int(pid)):
            stale.append(sibling)
    return stale


def _alive(pid: int) -> bool:
    """Whether a process ``pid`` exists (signal 0: nothing is sent)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # it exists, owned by someone else
        return True
    return True


def write_template(
    path: Path,
    grid: Grid,
    ids: list[str],
    n_modes: int,
    metrics: tuple[str, ...],
    attrs: dict[str, Any],
) -> dict[str, Any]:
    """Every variable's metadata, the coordinates and the attrs (no data), as xarray's
    ``Dataset.to_zarr(compute=False)`` makes them (the same arrays, ``dimension_names``,
    attributes with xarray's ``_FillValue`` of a float, consolidated metadata; a test holds the
    documents equal), in a small part of its time: it is written while the first chunks step.
    Returns each array's Zarr metadata (``zarr.core.metadata.ArrayV3Metadata``), from which
    :class:`RegionWriter` encodes the chunks.

    Each array's document is Zarr's own: its data type, fill value and codecs are those Zarr
    gives a new array of that data type and fill value (:func:`_defaults`, asked once a
    process), validated and put in order by Zarr's metadata class, written as compact JSON;
    nothing goes through Zarr's event loop (a store's asynchronous calls cost ten times the
    CPU here). The coordinates'
    chunks are encoded by their arrays' codecs. The files are written with the group's own
    ``zarr.json`` last: a folder that a kill left without it is refused as not a store, never
    resumed as a sweep missing variables. An earlier store at ``path`` is replaced."""
    coordinates: list[tuple[str, np.ndarray, dict[str, Any]]] = [
        (p, np.asarray(values, dtype=np.float64), {"units": unit_of(p), "long_name": p})
        for p, values in zip(grid.paths, grid.values, strict=True)
    ]
    coordinates.append(
        (
            "mode",
            np.arange(n_modes, dtype=np.int64),
            {"units": "1", "long_name": "mode, sorted by omega"},
        )
    )
    coordinates.append(("body", np.array(ids, dtype=str), {"units": "1", "long_name": "body id"}))
    arrays: dict[str, Any] = {}
    files: dict[str, bytes] = {}
    with warnings.catch_warnings():
        # the body ids' fixed-length UTF-32 is not yet in the Zarr v3 specification (xarray
        # writes it so)
        warnings.simplefilter("ignore")
        for name, values, coordinate_attrs in coordinates:
            arrays[name] = _array_metadata(
                values.dtype,
                values.shape,
                values.shape,
                _fill(values.dtype),
                _with_fill(coordinate_attrs, values.dtype),
                [name],
                None,
            )
            encoder = ChunkEncoder(arrays[name])
            files[f"{name}/{encoder.key((0,) * values.ndim)}"] = bytes(encoder(values))
        for name in metrics:
            extra, units, long_name = VARIABLES[name]
            dims = (*grid.paths, *([extra] if extra else []))
            shape = (*grid.shape, *([n_modes if extra == "mode" else len(ids)] if extra else []))
            chunks = (*grid.chunks, *([shape[-1]] if extra else []))
            dtype = np.dtype(_INTEGER.get(name, "float64"))
            var_attrs: dict[str, Any] = {"units": units, "long_name": long_name}
            if name == "status":
                from rollspring.simulate.status import FLAG_MEANINGS, FLAG_VALUES

                var_attrs["flag_values"] = list(FLAG_VALUES)
                var_attrs["flag_meanings"] = FLAG_MEANINGS
            fill = -1 if name == "first_slip_body" else (5 if name == "status" else _fill(dtype))
            arrays[name] = _array_metadata(
                dtype, shape, chunks, fill, _with_fill(var_attrs, dtype), list(dims), CHUNK_KEYS
            )
        consolidated = {name: arrays[name].to_dict() for name in sorted(arrays)}
    # compact JSON (Zarr indents its documents, which takes Python's slow encoder; readers
    # parse either)
    documents = {
        f"{name}/zarr.json": json.dumps(document, allow_nan=True).encode()
        for name, document in consolidated.items()
    }
    group = {
        "attributes": attrs,
        "zarr_format": 3,
        "consolidated_metadata": {
            "kind": "inline",
            "must_understand": False,
            "metadata": consolidated,
        },
        "node_type": "group",
    }
    if path.exists() or path.is_symlink():
        remove(path)
    (path / MARKERS).mkdir(parents=True)
    for key, data in {**documents, **files}.items():
        target = path / key
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    (path / "zarr.json").write_bytes(json.dumps(group, allow_nan=True).encode())  # last
    return arrays


_DEFAULTS: dict[tuple[str, str], dict[str, Any]] = {}
#: The compressor of a new store's arrays: Blosc with LZ4 at level 5 on the bytes shuffled by
#: their place in an element (Zarr v2's default; Zarr v3's is zstd). A sweep's variables are
#: mostly float64 results whose low bytes do not compress and whose high bytes do: on 65 536
#: runs of ``hoop-cylinder`` (k x v) it encodes in 1.3 ms of CPU where zstd took 5.5 ms at
#: Zarr's default level and 3.6 ms at level 1, for a store 16 % smaller (36 % of the raw bytes
#: against 43 % and 46 %). A store resumed keeps its own codecs.
COMPRESSOR: dict[str, Any] = {"cname": "lz4", "clevel": 5, "shuffle": "shuffle"}


def _defaults(dtype: str, fill: Any) -> dict[str, Any]:
    """``data_type``, ``fill_value`` and ``codecs`` of the document Zarr writes for a new
    array of ``dtype`` (a NumPy type string) with ``fill`` and the :data:`COMPRESSOR` (asked
    of Zarr once a process, in a memory store)."""
    key = (dtype, repr(fill))
    if key not in _DEFAULTS:
        import zarr
        from zarr.codecs import BloscCodec
        from zarr.storage import MemoryStore

        array = zarr.create_array(
            MemoryStore(),
            shape=(1,),
            dtype=np.dtype(dtype),
            fill_value=fill,
            zarr_format=3,
            compressors=[BloscCodec(**COMPRESSOR)],
        )
        document = array.metadata.to_dict()
        _DEFAULTS[key] = {name: document[name] for name in ("data_type", "fill_value", "codecs")}
    return _DEFAULTS[key]


def _array_metadata(
    dtype: np.dtype[Any],
    shape: tuple[int, ...],
    chunks: tuple[int, ...],
    fill: Any,
    attributes: dict[str, Any],
    dims: list[str],
    chunk_keys: dict[str, Any] | None,
) -> Any:
    """The Zarr v3 metadata of an array (``ArrayV3Metadata``, validated by Zarr)."""
    from zarr.core.metadata import ArrayV3Metadata

    separator = "/" if chunk_keys is None else chunk_keys["separator"]
    return ArrayV3Metadata.from_dict(
        {
            "zarr_format": 3,
            "node_type": "array",
            "shape": list(shape),
            "chunk_grid": {"name": "regular", "configuration": {"chunk_shape": list(chunks)}},
            "chunk_key_encoding": {"name": "default", "configuration": {"separator": separator}},
            **_defaults(dtype.str, fill),
            "attributes": attributes,
            "dimension_names": dims,
            "storage_transformers": [],
        }
    )


def _fill(dtype: np.dtype[Any]) -> Any:
    """The fill value xarray gives an array of ``dtype`` it writes: NaN for a float, else
    Zarr's default (0, the empty string)."""
    if dtype.kind == "f":
        return np.nan
    return "" if dtype.kind == "U" else 0


def _with_fill(attrs: dict[str, Any], dtype: np.dtype[Any]) -> dict[str, Any]:
    """``attrs`` with xarray's ``_FillValue`` attribute of a float array (the fill value's
    bytes, base64: how xarray reads a float's missing value back)."""
    if dtype.kind != "f":
        return attrs
    return {**attrs, "_FillValue": base64.b64encode(np.array(np.nan, dtype).tobytes()).decode()}


class RegionWriter:
    """Finished chunks into the store at ``path``, each followed by its done marker.

    Each chunk of the grid is one Zarr chunk of every variable, so a chunk's arrays are
    encoded by the array's own codecs (their synchronous encoders: the bytes Zarr itself
    stores, which a test holds equal) and written straight to the chunk's file, whole or not
    at all (a ``.partial`` file renamed over it, as Zarr's local store writes): a tenth of the
    CPU of Zarr's asynchronous write of a small chunk, most of which is its event loop. An
    array whose codecs need that loop (sharding) is written through Zarr."""

    def __init__(self, path: Path, grid: Grid, arrays: dict[str, Any] | None = None) -> None:
        """``arrays``: every array's Zarr metadata (what :func:`write_template` returns), else
        read from the store's documents."""
        self.path, self.grid = path, grid
        # a store resumed may hold files of an earlier attempt at a chunk that now writes none
        self.resumed = arrays is None
        metadata = arrays if arrays is not None else _read_metadata(path)
        self.encoders = {name: ChunkEncoder.of(m) for name, m in metadata.items()}
        self.arrays: dict[str, Any] = {}  # Zarr's arrays, opened for those it must write
        if any(encoder is None for encoder in self.encoders.values()):
            import zarr

            # every chunk on disk, even one equal to the fill value (their markers list none,
            # so a resume checks every file): an array takes the setting when it is opened
            with zarr.config.set({"array.write_empty_chunks": True}):
                group = zarr.open_group(str(path), mode="r+")
                self.arrays = dict(group.arrays())
        self.folders = {path, *(path / name for name in metadata)}  # known to exist

    def write(self, items: list[tuple[int, dict[str, np.ndarray]]]) -> None:
        """The chunks ``items`` (index, arrays) into their chunk files, then their markers. A
        chunk equal to its array's fill value throughout gets no file (as Zarr leaves such
        chunks out: they read as the fill value); its marker lists it."""
        through_zarr: list[tuple[tuple[slice, ...], str, np.ndarray]] = []
        filled: dict[int, list[str]] = {}
        for index, arrays in items:
            region = self.grid.region(index)
            coords = tuple(s.start // c for s, c in zip(region, self.grid.chunks, strict=True))
            filled[index] = []
            for name, values in arrays.items():
                encoder = self.encoders[name]
                if encoder is None:
                    through_zarr.append((region, name, values))
                    continue
                whole = (0,) * (values.ndim - len(coords))  # mode / body: one chunk
                target = self.path / name / encoder.key((*coords, *whole))
                if encoder.only_fill(values):
                    filled[index].append(name)
                    if self.resumed:  # as Zarr deletes the key of a chunk it leaves out
                        target.unlink(missing_ok=True)
                    continue
                self._put(target, encoder(values))
        if through_zarr:
            self._send(through_zarr)
        for index, _ in items:
            mark_done(self.path, index, filled[index])

    def _put(self, target: Path, data: memoryview) -> None:
        """``data`` as the file ``target``, whole or not at all: a ``.partial`` file (removed
        by :func:`verified_done` when a kill leaves it) renamed over the target."""
        self._folder(target.parent)
        partial = target.parent / f"{target.name}.{os.getpid()}-{threading.get_ident()}.partial"
        with open(partial, "wb") as handle:
            handle.write(data)
        os.replace(partial, target)

    def _folder(self, folder: Path) -> None:
        """Make ``folder`` and its missing parents, each once (a folder costs the file system
        more than a file: here about 0.3 ms of CPU; ``mkdir(parents=True)`` also tries each
        missing one before its parent)."""
        missing = []
        while folder not in self.folders:
            missing.append(folder)
            folder = folder.parent
        for folder in reversed(missing):
            with contextlib.suppress(FileExistsError):  # a resumed store's
                os.mkdir(folder)
            self.folders.add(folder)

    def _send(self, writes: list[tuple[tuple[slice, ...], str, np.ndarray]]) -> None:
        import asyncio

        from zarr.core.sync import sync

        async def every() -> None:
            await asyncio.gather(
                *(
                    self.arrays[name].async_array.setitem(region, values)
                    for region, name, values in writes
                )
            )

        sync(every())


class ChunkEncoder:
    """One whole chunk of a Zarr v3 array as the bytes of its file: the array's codecs applied
    in order by their synchronous encoders; a chunk at the grid's edge is padded with the fill
    value to the full chunk shape, as Zarr pads it. ``key``: the chunk's file, relative to the
    array's folder, from its chunk coordinates."""

    def __init__(self, metadata: Any) -> None:
        from zarr.buffer import default_buffer_prototype
        from zarr.core.array_spec import parse_array_config

        self.codecs = tuple(metadata.codecs)
        self.spec = metadata.get_chunk_spec(
            (0,) * metadata.ndim, parse_array_config(None), default_buffer_prototype()
        )
        self.key = metadata.encode_chunk_key
        self.shape = tuple(self.spec.shape)
        self.dtype = self.spec.dtype.to_native_dtype()

    @classmethod
    def of(cls, metadata: Any) -> ChunkEncoder | None:
        """The encoder of an array of Zarr ``metadata``, or None when its codecs need Zarr's
        event loop (taken: the plain bytes serialiser, then byte codecs with synchronous
        encoders)."""
        from zarr.abc.codec import BytesBytesCodec, SupportsSyncCodec
        from zarr.codecs import BytesCodec

        codecs = getattr(metadata, "codecs", None)
        if (
            metadata.zarr_format != 3
            or not codecs
            or not isinstance(codecs[0], BytesCodec)
            or not all(isinstance(c, BytesBytesCodec) for c in codecs[1:])
            or not all(_synchronous(type(c), SupportsSyncCodec) for c in codecs)
        ):
            return None
        return cls(metadata)

    def only_fill(self, values: np.ndarray) -> bool:
        """Whether every value of a chunk is the fill value (a NaN fill: any NaN; a float
        fill: its sign too, so that the chunk reads back bit for bit)."""
        values = np.asarray(values, dtype=self.dtype)
        fill = np.asarray(self.spec.fill_value, dtype=self.dtype)
        if values.dtype.kind == "f" and np.isnan(fill):
            return bool(np.all(np.isnan(values)))
        same = values == fill
        if values.dtype.kind in "fc":
            same &= np.signbit(values) == np.signbit(fill)
        return bool(np.all(same))

    def __call__(self, values: np.ndarray) -> memoryview:
        values = np.asarray(values, dtype=self.dtype)
        if values.shape != self.shape:  # a chunk at the grid's edge
            whole = np.full(self.shape, self.spec.fill_value, dtype=self.dtype)
            whole[tuple(slice(0, n) for n in values.shape)] = values
            values = whole
        data: Any = self.spec.prototype.nd_buffer.from_numpy_array(np.ascontiguousarray(values))
        for codec in self.codecs:
            data = codec._encode_sync(data, self.spec)
        return memoryview(data.as_numpy_array())


_SYNCHRONOUS: dict[type, bool] = {}


def _synchronous(codec: type, protocol: Any) -> bool:
    """Whether a codec class has synchronous encoders (Zarr's ``SupportsSyncCodec``), asked
    once a class: a protocol's ``isinstance`` inspects every member, each time."""
    if codec not in _SYNCHRONOUS:
        _SYNCHRONOUS[codec] = issubclass(codec, protocol)
    return _SYNCHRONOUS[codec]


def _read_metadata(path: Path) -> dict[str, Any]:
    """The Zarr metadata of every array of the store at ``path``, read from its documents
    (the group's consolidated metadata, else each array's ``zarr.json``) without Zarr's event
    loop; a version 2 array's is Zarr's own (its writes then go through Zarr)."""
    from zarr.core.metadata import ArrayV2Metadata, ArrayV3Metadata

    group = json.loads((path / "zarr.json").read_text())
    consolidated = (group.get("consolidated_metadata") or {}).get("metadata")
    if consolidated is None:
        names = [p.parent.name for p in path.glob("*/zarr.json")]
        consolidated = {n: json.loads((path / n / "zarr.json").read_text()) for n in names}
    out: dict[str, Any] = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the body ids' type (see write_template)
        for name, document in consolidated.items():
            if document.get("node_type") != "array":
                continue
            if document.get("zarr_format") == 3:
                out[name] = ArrayV3Metadata.from_dict(dict(document))
            else:  # pragma: no cover - a sweep store is Zarr v3
                out[name] = ArrayV2Metadata.from_dict(dict(document))
    return out


def mark_done(path: Path, index: int, filled: Sequence[str] = ()) -> None:
    """The done marker of chunk ``index``: a file listing, a line each, the variables whose
    chunk is the fill value throughout and has no file (empty when none). A marker a kill cut
    short lists fewer of them (a name counts once its line is ended), so its chunk runs again
    (markers were once made as ``.<index>.<pid>.tmp`` files renamed: :func:`verified_done`
    still removes those a kill left)."""
    marker = path / MARKERS / str(index)
    if filled:
        marker.write_bytes("".join(f"{name}\n" for name in filled).encode())
    else:
        marker.touch()


def _filled(marker: Path) -> set[str]:
    """The variables a done marker lists (those of its chunk with no file)."""
    try:
        text = marker.read_bytes().decode(errors="replace")
    except OSError:
        return set()
    return set(text.split("\n")[:-1])


def done_chunks(path: Path) -> set[int]:
    """Indices of the chunks whose done marker exists."""
    folder = path / MARKERS
    if not folder.is_dir():
        return set()
    return {int(p.name) for p in folder.iterdir() if p.name.isdigit()}


def verified_done(path: Path, grid: Grid, done: set[int]) -> set[int]:
    """The chunks of ``done`` (their markers exist) whose chunk files are all in the store, but
    those their marker lists as the fill value throughout (:func:`mark_done`); the
    marker of any other is removed, so the chunk runs again. Stale writes are removed first:
    Zarr's ``*.partial`` files (a writer killed inside a chunk's write) and half-made markers."""
    import zarr

    for leftover in [*path.rglob("*.partial"), *(path / MARKERS).glob(".*.tmp")]:
        leftover.unlink(missing_ok=True)
    group = zarr.open_group(str(path), mode="r")
    dims = len(grid.shape)
    arrays = [
        (name, array)
        for name, array in group.arrays()
        if array.shape[:dims] == tuple(grid.shape) and array.ndim > 0
    ]
    kept: set[int] = set()
    for index in sorted(done):
        starts = [region.start for region in grid.region(index)]
        filled = _filled(path / MARKERS / str(index))
        present = all(
            name in filled
            or (
                path
                / name
                / array.metadata.encode_chunk_key(
                    tuple(
                        start // size
                        for start, size in zip(
                            starts + [0] * (array.ndim - dims), array.chunks, strict=True
                        )
                    )
                )
            ).is_file()
            for name, array in arrays
        )
        if present:
            kept.add(index)
        else:
            (path / MARKERS / str(index)).unlink(missing_ok=True)
    return kept
