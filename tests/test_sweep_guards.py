"""The sweep's guards that a hostile session found missing: ``--out`` checked before any work
(``--overwrite`` replaced a device, a FIFO or any folder with a store; a file in the path or
``.`` failed after the computation with an internal error), ``--rtol`` and ``--step`` held to
what every run takes (they made a store of runs all "invalid", exit 0), and the Python API's
values numbers only."""

from __future__ import annotations

import os
import socket
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rollspring.cli.app import app
from rollspring.errors import SweepError
from rollspring.service.sweeps import sweep

GRID = ["hoop-cylinder", "--vary", "bodies.cylinder.v=0,0.1", "-T", "0.5"]


def _sweep(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(app, ["sweep", *GRID, *args])
    return result.exit_code, result.output


def _special(kind: str, path: Path) -> Path:
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "socket":
        server = socket.socket(socket.AF_UNIX)
        server.bind(str(path))
        server.close()
    elif kind == "folder":
        path.mkdir()
        (path / "thesis.tex").write_text("months of work")
    return path


@pytest.mark.parametrize(
    ("kind", "words"),
    [
        ("fifo", "is a FIFO (named pipe), not a folder"),
        ("socket", "is a socket, not a folder"),
        ("folder", "a folder that is not a sweep's store (it holds thesis.tex)"),
    ],
)
def test_overwrite_replaces_only_a_store(tmp_path: Path, kind: str, words: str) -> None:
    place = _special(kind, tmp_path / "x.zarr")
    before = sorted(p.name for p in tmp_path.rglob("*"))
    code, output = _sweep("-o", str(place), "--overwrite")
    assert code == 2 and output == f"error: --out {place}: {words}" + output.split(words)[1]
    assert output.count("\n") == 1
    assert sorted(p.name for p in tmp_path.rglob("*")) == before  # nothing touched


def test_a_device_is_never_a_store(tmp_path: Path) -> None:
    for overwrite in ([], ["--overwrite"]):
        code, output = _sweep("-o", "/dev/null", *overwrite)
        assert code == 2 and output.startswith("error: --out /dev/null: is a character device")
    assert Path("/dev/null").is_char_device()


def test_overwrite_still_replaces_a_store_an_empty_folder_and_a_file(tmp_path: Path) -> None:
    store = tmp_path / "s.zarr"
    assert _sweep("-o", str(store))[0] == 0
    assert _sweep("-T", "0.25", "-o", str(store), "--overwrite")[0] == 0
    (tmp_path / "empty.zarr").mkdir()
    assert _sweep("-o", str(tmp_path / "empty.zarr"), "--overwrite")[0] == 0
    (tmp_path / "file.zarr").write_text("x")
    code, output = _sweep("-o", str(tmp_path / "file.zarr"))
    assert code == 2 and "use --overwrite to replace it" in output
    assert _sweep("-o", str(tmp_path / "file.zarr"), "--overwrite")[0] == 0
    assert (tmp_path / "file.zarr" / "zarr.json").is_file()


@pytest.mark.parametrize(
    ("place", "words"),
    [
        ("{tmp}/file/x.zarr", "cannot write there"),
        (".", "give the store's own folder name"),
        ("", "give the store's own folder name"),
        ("..", "give the store's own folder name"),
    ],
)
def test_a_place_no_store_can_have_is_refused_before_the_work(
    tmp_path: Path, place: str, words: str
) -> None:
    (tmp_path / "file").write_text("x")
    code, output = _sweep("-o", place.format(tmp=tmp_path), "--overwrite")
    assert code == 2 and words in output and output.count("\n") == 1, output
    assert output.startswith("error: --out")


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--rtol", "0.9"], "--rtol: must be between 1e-14 and 0.1"),
        (["--rtol", "1e-300", "--step", "0.001"], "--rtol: must be between"),
        (["--step", "1e-9"], "--step: 1e-09 s takes about 5e+08 steps over 0.5 s"),
        (["--step", "1e-320"], "--step: "),
    ],
)
def test_rtol_and_step_beyond_a_run_s_are_refused(
    tmp_path: Path, args: list[str], words: str
) -> None:
    code, output = _sweep(*args, "-o", str(tmp_path / "s.zarr"))
    assert code == 2 and output.startswith(f"error: {words}"), output
    assert not (tmp_path / "s.zarr").exists()


@pytest.mark.parametrize(
    ("values", "words"),
    [
        ([True, False], "the values must be numbers, got bool True"),
        (["0.1"], "the values must be numbers, got str '0.1'"),
        ([0, 10**400], "an integer of more than 20 digits is too large for a float"),
        (np.array([True, False]), "the values must be numbers, got an array of bool"),
    ],
)
def test_the_api_takes_numbers_only(values: object, words: str) -> None:
    with pytest.raises(SweepError) as caught:
        sweep("hoop-cylinder", {"bodies.cylinder.v": values}, 0.5)
    assert str(caught.value) == f"--vary bodies.cylinder.v: {words}"


def test_the_api_takes_numpy_numbers_and_refuses_a_place_that_is_no_path() -> None:
    result = sweep("hoop-cylinder", {"bodies.cylinder.v": [np.float32(0.5), np.int64(0)]}, 0.5)
    assert result["bodies.cylinder.v"].values.tolist() == [0.5, 0.0]
    with pytest.raises(SweepError, match="--out: expected a folder's path, got int"):
        sweep("hoop-cylinder", {"bodies.cylinder.v": [0.0]}, 0.5, out=123)


def test_one_sweep_at_a_time_writes_a_store(tmp_path: Path) -> None:
    """Two sweeps on one store (the second with --overwrite) left chunks of the first under
    the attributes of the second, both exit 0: the second is now refused while the first
    holds the store, in this process or another, and the lock's file goes with the sweep."""
    from rollspring.service.sweeps.store import store_lock

    store = tmp_path / "s.zarr"
    with store_lock(store):
        with pytest.raises(SweepError, match="another sweep is writing this store"):
            sweep("hoop-cylinder", {"bodies.cylinder.v": [0.0]}, 0.5, out=store, overwrite=True)
        code, output = _sweep("-o", str(store), "--overwrite")
        assert code == 2 and "another sweep is writing this store" in output
        assert not store.exists()
    sweep("hoop-cylinder", {"bodies.cylinder.v": [0.0]}, 0.5, out=store)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.zarr"]


def test_a_grid_whose_friction_pairs_are_all_invalid_is_refused(tmp_path: Path) -> None:
    """mu_static 0.1, 0.2 against mu_kinetic 0.5, 0.6: each value valid alone, no run valid
    (mu_kinetic <= mu_static); it was a store of runs all invalid, exit 0."""
    code, output = _sweep(
        "--vary",
        "bodies.hoop.mu_static=0.1,0.2",
        "--vary",
        "bodies.hoop.mu_kinetic=0.5,0.6",
        "-o",
        str(tmp_path / "s.zarr"),
    )
    assert code == 2 and "no run of the grid is a valid system" in output, output
    assert not (tmp_path / "s.zarr").exists()
    with pytest.raises(SweepError, match="no run of the grid is a valid system: every"):
        sweep(
            "hoop-cylinder",
            {"bodies.hoop.mu_static": [0.1, 0.2], "bodies.hoop.mu_kinetic": [0.5, 0.6]},
            0.5,
        )
    mixed = sweep(
        "hoop-cylinder",
        {"bodies.hoop.mu_static": [0.1, 0.6], "bodies.hoop.mu_kinetic": [0.5]},
        0.5,
    )
    assert mixed["status"].values.ravel().tolist()[1] != mixed["status"].values.ravel()[0]


def test_overwrite_leaves_another_zarr_dataset_and_a_link_shares_the_lock(tmp_path: Path) -> None:
    """A Zarr dataset that is not a sweep's (no grid fingerprint, no done markers) was replaced
    by --overwrite; a store reached through a link took a second lock beside the first."""
    import xarray as xr

    from rollspring.service.sweeps.store import store_lock

    precious = tmp_path / "data.zarr"
    xr.Dataset({"precious": ("x", np.arange(3.0))}).to_zarr(precious, consolidated=False)
    with pytest.raises(SweepError, match="a folder that is not a sweep's store"):
        sweep("hoop-cylinder", {"bodies.cylinder.v": [0.0]}, 0.5, out=precious, overwrite=True)
    assert xr.open_zarr(precious, consolidated=False)["precious"].values.tolist() == [0.0, 1.0, 2.0]
    real = tmp_path / "real.zarr"
    real.mkdir()
    (tmp_path / "link.zarr").symlink_to(real)
    with (
        store_lock(real),
        pytest.raises(SweepError, match="another sweep is writing"),
        store_lock(tmp_path / "link.zarr"),
    ):
        pass
