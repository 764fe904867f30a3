"""The sweep's store written without Zarr's event loop: the chunk files are the bytes Zarr
writes, and a writer killed at any file operation leaves a store that the next run resumes
(or, killed inside the template, refuses as not a store until ``--overwrite``) into the same
numbers as a sweep never interrupted."""

from __future__ import annotations

import builtins
import os
import pathlib
import threading
from pathlib import Path

import numpy as np
import pytest

import rollspring
from rollspring.service.sweeps import StoreMismatchError, sweep
from rollspring.service.sweeps import store as store_module
from tests.test_sweep import same

SYSTEM = "hoop-cylinder"


@pytest.fixture(scope="module")
def system():
    return rollspring.load_system(SYSTEM)


def _files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in root.rglob("*") if p.is_file()}


def test_chunk_files_are_the_bytes_zarr_writes(system, tmp_path, monkeypatch):
    """A grid of 7 x 5 runs in chunks of 3 x 5 (the last chunk at the grid's edge, padded by
    the fill value), some runs slipping: every file of the store, chunks of every variable and
    metadata, equals the store written through Zarr's own ``setitem``, but the chunks equal to
    the fill value throughout: those have no file, and the chunk's done marker lists them."""
    vary = {
        "springs.0.stiffness": np.linspace(50.0, 150.0, 7),
        "bodies.hoop.mu_static": np.geomspace(0.02, 1.0, 5),
    }
    ours = sweep(system, vary, 1.0, chunk=15, out=tmp_path / "ours.zarr").load()
    assert ours.attrs["chunk_shape"] == [3, 5] and ours.attrs["n_chunks"] == 3
    statuses = np.bincount(ours["status"].values.ravel(), minlength=7)
    assert statuses[0] > 0 and statuses[2] > 0  # some roll throughout, some slip
    monkeypatch.setattr(store_module.ChunkEncoder, "of", classmethod(lambda cls, array: None))
    zarrs = sweep(system, vary, 1.0, chunk=15, out=tmp_path / "zarr.zarr").load()
    same(ours, zarrs)
    mine, theirs = _files(tmp_path / "ours.zarr"), _files(tmp_path / "zarr.zarr")
    markers = ".rollspring-done/"
    listed = {
        (variable, int(name[len(markers) :]))
        for name, text in mine.items()
        if name.startswith(markers)
        for variable in text.decode().split("\n")[:-1]
    }
    assert {name for name in theirs if name.startswith(markers)} == {
        name for name in mine if name.startswith(markers)
    }
    assert not any(theirs[name] for name in theirs if name.startswith(markers))  # Zarr's: all
    missing = {
        (name.split("/")[0], int(name.split("/c.")[1].split(".")[0]))
        for name in set(theirs) - set(mine)
    }
    assert set(mine) <= set(theirs) and missing == listed
    assert ("first_liftoff_time", 0) in listed  # nothing lifts off: no file of that chunk
    for variable, index in listed:
        region = ours[variable].isel({"springs.0.stiffness": slice(3 * index, 3 * index + 3)})
        assert region.isnull().all() or (region == region.attrs.get("_FillValue", -1)).all()
    assert sum("/c." in name for name in mine) == 3 * len(ours.data_vars) - len(listed)
    for name in mine:
        if not name.startswith(markers):
            assert mine[name] == theirs[name], name


class Killed(BaseException):
    """The writer stops here: nothing after it runs (a ``BaseException``, so that no
    ``except Exception`` on the way takes it)."""


def _kill_at(monkeypatch, kill_at: int) -> list[int]:
    """Count the store's file operations in this thread (opening a file, making a folder,
    writing or touching a file, renaming over a file) and raise :class:`Killed` before the
    ``kill_at``-th; returns the counter."""
    count = [0]
    main = threading.get_ident()

    def killed_before(function):
        def counted(*args, **kwargs):
            if threading.get_ident() == main:
                count[0] += 1
                if count[0] == kill_at:
                    raise Killed
            return function(*args, **kwargs)

        return counted

    monkeypatch.setattr(store_module, "open", killed_before(builtins.open), raising=False)
    for name in ("replace", "mkdir"):
        monkeypatch.setattr(os, name, killed_before(getattr(os, name)))
    for name in ("mkdir", "write_bytes", "touch"):
        monkeypatch.setattr(pathlib.Path, name, killed_before(getattr(pathlib.Path, name)))
    return count


def test_a_writer_killed_at_any_file_operation_is_resumed_into_the_same_store(
    system, tmp_path, monkeypatch
):
    """Two metrics, three chunks (one at the grid's edge): the sweep killed before each of its
    file operations in turn, from the template's first to the last marker's; the next run
    resumes the store (or refuses a template cut short, which ``overwrite`` then replaces) and
    gives the numbers of the sweep never killed, with no ``.partial`` file or half-made marker
    left."""
    vary = {"springs.0.stiffness": [60.0, 90.0, 120.0, 150.0, 180.0], "bodies.hoop.mass": [1, 2]}
    metrics = ["period_measured"]
    reference = sweep(system, vary, 0.5, chunk=4, metrics=metrics)
    kill_at, outcomes = 1, set()
    while True:
        out = tmp_path / f"kill-{kill_at}.zarr"
        with monkeypatch.context() as patch:
            count = _kill_at(patch, kill_at)
            try:
                sweep(system, vary, 0.5, chunk=4, metrics=metrics, out=out, threads=1)
            except Killed:
                pass
            else:
                assert count[0] < kill_at  # every operation was a kill point
                break
        try:
            again = sweep(system, vary, 0.5, chunk=4, metrics=metrics, out=out)
            outcomes.add("resumed")
        except StoreMismatchError as exc:
            assert "not a rollspring sweep store" in str(exc), kill_at
            again = sweep(system, vary, 0.5, chunk=4, metrics=metrics, out=out, overwrite=True)
            outcomes.add("refused")
        same(reference, again.load())
        assert not list(out.rglob("*.partial")) and not list(out.rglob(".*.tmp")), kill_at
        kill_at += 1
    assert kill_at > 20 and outcomes == {"resumed", "refused"}


def test_a_store_with_a_folder_a_chunk_is_resumed_in_its_own_layout(system, tmp_path, monkeypatch):
    """Stores made before 29 Nov 2026 name their chunk files with Zarr's "/" separator (a folder
    per chunk): a resume writes the chunks it reruns where that store's metadata says, and the
    store equals one written in the layout of today."""
    vary = {"springs.0.stiffness": np.linspace(50.0, 150.0, 6), "bodies.hoop.mass": [0.5, 1.0]}
    old = tmp_path / "old.zarr"
    with monkeypatch.context() as patch:
        patch.setattr(store_module, "CHUNK_KEYS", {"name": "default", "separator": "/"})
        sweep(system, vary, 1.0, chunk=4, out=old)
    rerun = old / "period_measured" / "c" / "1" / "0"
    assert rerun.is_file() and not list(old.glob("*/c.*"))
    rerun.unlink()
    (old / ".rollspring-done" / "1").unlink()
    resumed = sweep(system, vary, 1.0, out=old).load()
    assert rerun.is_file() and not list(old.glob("*/c.*"))
    same(resumed, sweep(system, vary, 1.0, chunk=4, out=tmp_path / "new.zarr").load())
    assert (tmp_path / "new.zarr" / "period_measured" / "c.1.0").is_file()


def test_a_replace_removes_what_a_killed_replace_left(system, tmp_path):
    """A process killed while removing a replaced store leaves its hidden sibling
    ``.<name>.<pid>-<thread>.discarded``; the next replace of the same store removes it (its
    process is gone), and leaves a live process's alone."""
    out = tmp_path / "s.zarr"
    vary = {"springs.0.stiffness": [50.0, 101.0]}
    sweep(system, vary, 0.5, out=out)
    gone = tmp_path / f".s.zarr.{2**22 + 12345}-7.discarded"  # above Linux's largest pid
    live = tmp_path / f".s.zarr.{os.getpid()}-1.discarded"
    for left in (gone, live):
        (left / "springs.0.stiffness").mkdir(parents=True)
        (left / "springs.0.stiffness" / "c.0").write_bytes(b"\0" * 8)
    again = sweep(system, vary, 0.5, out=out, overwrite=True)
    assert again.sizes["springs.0.stiffness"] == 2
    assert not gone.exists() and live.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["s.zarr", live.name])


@pytest.mark.parametrize("cut", ["", "first_liftoff_t", "first_liftoff_time"])
def test_a_marker_cut_short_reruns_its_chunk(system, tmp_path, cut):
    """A done marker lists the variables whose chunk is the fill value throughout (no file):
    one cut short by a kill (empty, or its last line not ended) vouches for fewer of them, so
    the resume finds a file missing and runs the chunk again, into the same store."""
    vary = {"springs.0.stiffness": [60.0, 90.0, 120.0, 150.0], "bodies.hoop.mass": [1.0, 2.0]}
    out = tmp_path / "m.zarr"
    first = sweep(system, vary, 0.5, chunk=4, out=out).load()
    marker = out / ".rollspring-done" / "1"
    assert "first_liftoff_time\n" in marker.read_text()
    assert not list((out / "first_liftoff_time").glob("c.*"))  # nothing lifts off: no file
    marker.write_text(cut)
    seen = []
    again = sweep(system, vary, 0.5, chunk=4, out=out, progress=seen.append).load()
    assert seen[0].chunks_skipped == 1 and seen[0].chunks_to_run == 1
    same(first, again)
    assert "first_liftoff_time\n" in marker.read_text()


def test_a_resumed_chunk_that_is_now_fill_removes_an_earlier_file(system, tmp_path):
    """A chunk rerun on resume whose variable is its fill value throughout writes no file and
    removes one an earlier attempt left (as Zarr deletes the key of a chunk it leaves out), so
    the store reads as a fresh one (found by a review)."""
    vary = {"springs.0.stiffness": [60.0, 90.0, 120.0, 150.0], "bodies.hoop.mass": [1.0, 2.0]}
    out = tmp_path / "s.zarr"
    fresh = sweep(system, vary, 0.5, chunk=4, out=out).load()
    assert "first_liftoff_time\n" in (out / ".rollspring-done" / "1").read_text()
    stale = out / "first_liftoff_time" / "c.1.0"
    stale.write_bytes((out / "cm_amplitude" / "c.0.0").read_bytes())  # not the fill value
    (out / ".rollspring-done" / "1").unlink()
    again = sweep(system, vary, 0.5, chunk=4, out=out).load()
    assert not stale.exists()
    same(fresh, again)
