"""The lab's endpoints (docs/web-api.md) on ``rollspring serve`` started from its command line on
loopback (the budget test in-process, where the pool's one worker can be stopped):
``POST /api/lab/data``
reads a measured table sent as text as :mod:`rollspring.lab.data` does, ``POST /api/fit`` gives
what :func:`rollspring.fit` gives on the same file and start, and every refusal — a bad file, a
PATH that is no number of the system, fewer points than fitted parameters — is a 422 with the
reader's or the fit's one-line message, located at the field it is about."""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

import rollspring
from rollspring.errors import DataError, FitError
from rollspring.lab.data import match_bodies, parse_data
from rollspring.lab.synthetic import exact_motion
from rollspring.model import load_system, system_from_dict, system_to_json
from rollspring.model.files import system_from_text
from rollspring.web import create_app
from tests.serving import Server

#: The truth the data are made from: the paper's hoop and cylinder, its spring damped.
STIFFNESS = 100.0
DAMPING = 0.5
FPS = 60
SECONDS = 10.0
NOISE = 1e-3  # m


def truth() -> dict[str, Any]:
    system = system_to_json(load_system("hoop-cylinder"))
    system["springs"][0]["stiffness"] = STIFFNESS
    system["springs"][0]["damping"] = DAMPING
    return system


def rough_start() -> dict[str, Any]:
    """The start a user gives: the stiffness 30% off, no damping."""
    system = truth()
    system["springs"][0]["stiffness"] = 0.7 * STIFFNESS
    system["springs"][0]["damping"] = 0.0
    return system


def recording(seed: int = 7) -> tuple[np.ndarray, np.ndarray]:
    """Times and noisy centre positions (N, 2) of the exact motion of :func:`truth`."""
    t = np.arange(int(SECONDS * FPS)) / FPS
    motion = exact_motion(system_from_dict(truth()), t)
    return t, motion.x + np.random.default_rng(seed).normal(0.0, NOISE, motion.x.shape)


def csv_text(t: np.ndarray, x: np.ndarray) -> str:
    rows = [f"{float(a)!r},{float(b)!r},{float(c)!r}" for a, (b, c) in zip(t, x, strict=True)]
    return "\n".join(["t,x_hoop,x_cylinder", *rows]) + "\n"


@pytest.fixture(scope="module")
def client() -> Iterator[Server]:
    """``rollspring serve`` started from its command line on loopback, one worker."""
    running = Server("--workers", "1", "--budget", "600")
    try:
        yield running
    finally:
        running.stop()


def refusal(answer: Any) -> tuple[list[Any], str]:
    assert answer.status_code == 422, answer.text
    body = answer.json()
    assert body["detail"][0]["msg"] == body["message"]
    return body["detail"][0]["loc"], body["message"]


def test_the_data_endpoint_reads_the_table_as_the_reader_does(client: Server) -> None:
    t, x = recording()
    text = csv_text(t, x)
    answer = client.post(
        "/api/lab/data", json={"system": rough_start(), "data": text, "filename": "run.csv"}
    )
    assert answer.status_code == 200, answer.text
    body = answer.json()
    read = parse_data(text, "run.csv")
    assert body["source"] == "run.csv"
    assert body["t"] == (read.t - read.t[0]).tolist()
    assert body["bodies"]["hoop"]["x"] == read.x[:, 0].tolist()
    assert body["bodies"]["cylinder"]["x"] == x[:, 1].tolist()
    assert body["points"] == 2 * t.size
    assert body["free"] == ["springs.0.stiffness", "springs.0.damping"]


def test_the_fit_endpoint_gives_what_rollspring_fit_gives(client: Server, tmp_path: Path) -> None:
    t, x = recording()
    text = csv_text(t, x)
    answer = client.post(
        "/api/fit", json={"system": rough_start(), "data": text, "filename": "run.csv"}
    )
    assert answer.status_code == 200, answer.text
    body = answer.json()
    fit = body["fit"]
    stiffness = fit["parameters"]["springs.0.stiffness"]
    damping = fit["parameters"]["springs.0.damping"]
    # the truth recovered: k to 1% and within 3 standard errors, the damping within 3 too
    assert abs(stiffness["value"] - STIFFNESS) < 0.01 * STIFFNESS
    assert abs(stiffness["value"] - STIFFNESS) < 3 * stiffness["stderr"]
    assert abs(damping["value"] - DAMPING) < 3 * damping["stderr"]
    # the same as rollspring.fit on the same file and start
    path = tmp_path / "run.csv"
    path.write_text(text)
    direct = rollspring.fit(
        str(path), system_from_dict(rough_start()), ["springs.0.stiffness", "springs.0.damping"]
    )
    for name, parameter in direct.parameters.items():
        assert fit["parameters"][name]["value"] == pytest.approx(
            parameter.value, rel=1e-7, abs=1e-12
        )
    assert set(fit["residual_rms"]) == {"hoop", "cylinder"}
    for body_id, rms in direct.residual_rms.items():
        assert fit["residual_rms"][body_id] == pytest.approx(rms, rel=1e-7)
        assert rms == pytest.approx(NOISE, rel=0.15)  # the noise the data were made with
    for claim in ("cm_peak_to_peak", "stationary_peak_to_peak"):
        assert fit["claims"][claim]["value"] == pytest.approx(
            direct.claims[claim]["value"], rel=1e-6, abs=1e-12
        )
        assert fit["claims"][claim]["stderr"] > 0
    # the fitted system, as JSON and TOML, is the fit's
    fitted = system_from_dict(body["system"])
    assert fitted.springs[0].stiffness == stiffness["value"]
    assert system_from_text(body["toml"], format="toml") == fitted
    # the table drawn in the fitted system's frame: t from t0, the x origin unchanged
    assert body["data"]["t"] == (t - fit["parameters"]["t0"]["value"]).tolist()
    assert body["data"]["bodies"]["hoop"]["x"] == x[:, 0].tolist()


def test_a_bad_file_is_a_422_with_the_readers_one_line_message(client: Server) -> None:
    for text in ("x,y\n1,2\n", "t,x_hoop\n0,0\n0,1\n", "t,x_wheel\n0,0\n1,1\n", ""):
        with pytest.raises(DataError) as raised:
            match_bodies(parse_data(text, "bad.csv"), load_system("hoop-cylinder"))
        expected = " ".join(str(raised.value).split())
        for endpoint in ("/api/lab/data", "/api/fit"):
            answer = client.post(
                endpoint,
                json={"system": rough_start(), "data": text, "filename": "bad.csv"},
            )
            loc, message = refusal(answer)
            assert loc == ["body", "data"]
            assert message == expected
            assert message.startswith("bad.csv: ")


def test_an_unknown_path_is_a_422_naming_it(client: Server) -> None:
    t, x = recording()
    answer = client.post(
        "/api/fit",
        json={
            "system": rough_start(),
            "data": csv_text(t, x),
            "filename": "run.csv",
            "free": ["springs.0.stiffness", "bodies.hoop.colour"],
        },
    )
    loc, message = refusal(answer)
    assert loc == ["body", "free", 1]
    assert message.startswith("free bodies.hoop.colour: ")
    from rollspring.lab.parameters import check_paths

    with pytest.raises(FitError) as raised:
        check_paths(load_system("hoop-cylinder"), ["bodies.hoop.colour"])
    assert message == str(raised.value).replace("--free ", "free ", 1)


def test_too_few_points_is_a_422_naming_the_file(client: Server) -> None:
    t, x = recording()
    text = csv_text(t[:3], x[:3])  # 6 positions, 6 fitted parameters (k, c, 2 x0, 2 v0)
    answer = client.post(
        "/api/fit", json={"system": rough_start(), "data": text, "filename": "short.csv"}
    )
    loc, message = refusal(answer)
    assert loc == ["body", "data"]
    assert message.startswith("short.csv: 6 measured positions, not more than the 6 fitted")


def test_the_request_is_checked_before_any_work(client: Server) -> None:
    t, x = recording()
    system = rough_start()
    system["bodies"][0]["mass"] = -1.0
    loc, message = refusal(client.post("/api/fit", json={"system": system, "data": csv_text(t, x)}))
    assert message.startswith("system.bodies[0].mass: ")
    assert loc[:3] == ["body", "system", "bodies"]
    loc, _ = refusal(
        client.post(
            "/api/fit",
            json={"system": rough_start(), "data": csv_text(t, x), "fix_initial": "yes"},
        )
    )
    assert loc == ["body", "fix_initial"]


def test_a_tracker_file_is_read_and_its_tracks_mapped_to_the_bodies(client: Server) -> None:
    t, x = recording()
    lines = ["#multi:", "\tmass A\t\tmass B\t", "t\tx\ty\tx\ty"]
    lines += [
        f"{float(a)!r}\t{float(b)!r}\t0.1\t{float(c)!r}\t0.1"
        for a, (b, c) in zip(t, x, strict=True)
    ]
    text = "\n".join(lines) + "\n"
    mapping = {"mass A": "hoop", "mass B": "cylinder"}
    request = {"system": rough_start(), "data": text, "filename": "tracker.txt"}
    loc, message = refusal(client.post("/api/lab/data", json=request))
    assert loc == ["body", "data"]
    assert message.startswith("tracker.txt: track 'mass A': no body 'mass A' in the system")
    answer = client.post("/api/lab/data", json={**request, "mapping": mapping})
    assert answer.status_code == 200, answer.text
    assert answer.json()["bodies"]["cylinder"]["x"] == x[:, 1].tolist()
    loc, message = refusal(client.post("/api/fit", json={**request, "mapping": {"mass C": "hoop"}}))
    assert loc == ["body", "mapping"]
    assert message.startswith("mapping mass C=hoop: tracker.txt has no track 'mass C'")


def test_a_fit_past_the_time_budget_is_a_503() -> None:
    """Deterministic: the only worker is stopped (SIGSTOP), so the fit cannot be answered
    within the budget at all; the pool abandons it with 503 (and replaces the worker)."""
    before = set(multiprocessing.active_children())
    t, x = recording()
    with TestClient(create_app(budget=1.0, workers=1)) as budgeted:
        workers = [
            p
            for p in multiprocessing.active_children()
            if p.name == "rollspring-worker" and p not in before
        ]
        assert len(workers) == 1 and workers[0].pid is not None
        os.kill(workers[0].pid, signal.SIGSTOP)
        stuck = budgeted.post("/api/fit", json={"system": rough_start(), "data": csv_text(t, x)})
        assert stuck.status_code == 503
        assert "time budget of 1 s" in stuck.json()["detail"]


def test_a_track_mapped_to_null_or_unmatched_is_left_out(client: Server) -> None:
    t, x = recording()
    lines = ["#multi:", "\tmass A\t\tmass B\t", "t\tx\ty\tx\ty"]
    lines += [
        f"{float(a)!r}\t{float(b)!r}\t0.1\t{float(c)!r}\t0.1"
        for a, (b, c) in zip(t, x, strict=True)
    ]
    request = {"system": rough_start(), "data": "\n".join(lines) + "\n", "filename": "tr.txt"}
    # "omit": the tracks named as no body left out, and said so
    answer = client.post("/api/lab/data", json={**request, "unmatched": "omit"})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["tracks"] == ["mass A", "mass B"]
    assert body["mapping"] == {"mass A": None, "mass B": None}
    assert body["bodies"] == {} and body["points"] == 0
    # one track matched, the other mapped to null
    mapping = {"mass A": None, "mass B": "cylinder"}
    answer = client.post("/api/lab/data", json={**request, "mapping": mapping})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["mapping"] == mapping
    assert list(body["bodies"]) == ["cylinder"]
    assert body["bodies"]["cylinder"]["x"] == x[:, 1].tolist()
    assert body["points"] == t.size
    # two tracks on one body: the reader's one line
    twice = {"mass A": "hoop", "mass B": "hoop"}
    loc, message = refusal(client.post("/api/lab/data", json={**request, "mapping": twice}))
    assert loc == ["body", "data"]
    with pytest.raises(DataError) as raised:
        match_bodies(parse_data(request["data"], "tr.txt"), load_system("hoop-cylinder"), twice)
    assert message == " ".join(str(raised.value).split())


def test_the_fit_endpoint_samples_the_posterior_when_asked(client: Server) -> None:
    """``"posterior": true`` (= rollspring fit --posterior): each fitted spring number's median
    and 95 % credible interval, the interval about as wide as 2 x 1.96 standard errors and
    holding the fitted value; without it there is none."""
    t, x = recording()
    request = {"system": rough_start(), "data": csv_text(t, x), "filename": "run.csv"}
    plain = client.post("/api/fit", json=request)
    assert plain.status_code == 200, plain.text
    assert "posterior" not in plain.json()["fit"]
    answer = client.post("/api/fit", json={**request, "posterior": True})
    assert answer.status_code == 200, answer.text
    fit = answer.json()["fit"]
    intervals = fit["posterior"]["credible_intervals"]
    for name in ("springs.0.stiffness", "springs.0.damping"):
        parameter, interval = fit["parameters"][name], intervals[name]
        assert interval["low"] < parameter["value"] < interval["high"]
        width = interval["high"] - interval["low"]
        assert width == pytest.approx(2 * 1.96 * parameter["stderr"], rel=0.35)
    assert 0.2 < fit["posterior"]["acceptance"] < 0.9
    refused = client.post("/api/fit", json={**request, "posterior": "yes"})
    assert refused.status_code == 422
