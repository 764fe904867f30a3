"""The web API's computations, as they run inside a worker process (:mod:`.workers`).

Each job takes the validated request (a :class:`~rollspring.model.System` and plain options)
and returns the finished response body as bytes, so that only bytes cross the pipe back. The
work itself is the orchestration layer's (:mod:`rollspring.service`); this module only encodes.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import orjson

from rollspring.errors import CostTooHigh, RollspringError
from rollspring.model import load_system
from rollspring.service import runs

__all__ = ["JOBS", "execute", "warm_up"]

_JSON_OPTIONS = orjson.OPT_SERIALIZE_NUMPY


def _json(value: Any) -> bytes:
    return orjson.dumps(value, option=_JSON_OPTIONS)


def analyze(request: dict[str, Any]) -> bytes:
    """``POST /api/analyze``: the ``analyze --json`` object."""
    payload, _ = runs.analysis_payload(request["system"])
    return _json(payload)


def _run(request: dict[str, Any]) -> runs.SimulationRun:
    start = request.get("start")
    return runs.run_simulation(
        request["system"],
        request["duration"],
        rtol=request["rtol"],
        outputs=request["outputs"],
        on_slip=request["on_slip"],
        start=None if start is None else runs.ModeStart(start["mode"], start["amplitude"]),
        linear=request.get("linear", False),
    )


def simulate(request: dict[str, Any]) -> bytes:
    """``POST /api/simulate``: the summary and every output array."""
    return _json(runs.simulation_payload(_run(request)))


def simulate_csv(request: dict[str, Any]) -> bytes:
    """``POST /api/simulate.csv``: ``trajectory.csv`` as ``simulate --out`` writes it."""
    from rollspring.outputs import trajectory_csv

    return trajectory_csv(_run(request).trajectory).encode()


def derive(request: dict[str, Any]) -> bytes:
    """``POST /api/derive``: the derivation by the requested methods, with MathML."""
    from rollspring.service import documents  # SymPy: loaded on first use

    method = request["method"]  # "all", one method, or several separated by commas
    methods = [part.strip() for part in method.split(",")] if "," in method else method
    return _json(documents.derivation_payload(request["system"], methods))


def report(request: dict[str, Any]) -> bytes:
    """``POST /api/report``: the self-contained HTML report."""
    from rollspring.service import documents  # SymPy and Matplotlib: loaded on first use

    built = documents.build_report(request["system"], duration=request.get("duration"))
    return built.html.encode()


def _lab_refusal(message: str, request: dict[str, Any]) -> tuple[str, list[str | int]]:
    """A lab error's one line in the API's words and its location: a PATH of ``free`` when the
    message names one, ``mapping`` for a track matched by ``--map``, else ``data``."""
    for index, path in enumerate(request.get("free") or ()):
        if message.startswith((f"--free {path}:", f"free {path}:")):
            return message.replace("--free ", "free ", 1), ["body", "free", index]
    if message.startswith(("--free", "free")):
        return message.replace("--free", "free", 1), ["body", "free"]
    if message.startswith("--map"):
        return message.replace("--map", "mapping", 1), ["body", "mapping"]
    return message, ["body", "data"]


def lab_data(request: dict[str, Any]) -> bytes:
    """``POST /api/lab/data``: the measured table read and matched to the system's bodies."""
    from rollspring.service import lab_payloads

    payload = lab_payloads.data_payload(
        request["data"],
        request["filename"],
        request["system"],
        request.get("mapping"),
        unmatched=request.get("unmatched", "refuse"),
    )
    return _json(payload)


def fit(request: dict[str, Any]) -> bytes:
    """``POST /api/fit``: the fit of ``rollspring fit --json``, the fitted system and its TOML."""
    from rollspring.service import lab_payloads

    payload = lab_payloads.fit_payload(
        request["data"],
        request["filename"],
        request["system"],
        request.get("free"),
        request.get("mapping"),
        fix_initial=request.get("fix_initial", False),
        posterior=request.get("posterior", False),
        unmatched=request.get("unmatched", "refuse"),
        budget=request.get("budget"),
    )
    return _json(payload)


#: The jobs whose errors name the lab's fields (``data``, ``free``, ``mapping``).
_LAB_JOBS = frozenset({"lab_data", "fit"})
#: The jobs estimated against the server's time budget before they start (a refusal: 503).
_BUDGETED_JOBS = frozenset({"fit"})

JOBS: dict[str, Callable[[dict[str, Any]], bytes]] = {
    "analyze": analyze,
    "simulate": simulate,
    "simulate_csv": simulate_csv,
    "derive": derive,
    "report": report,
    "lab_data": lab_data,
    "fit": fit,
}

#: A message that starts with one of the request's fields names it (``duration: must be …``).
_FIELD = re.compile(
    r"^(system|toml|duration|rtol|outputs|on_slip|start(?:\.\w+)?|method|"
    r"linear)\b"
)


def execute(job: str, request: dict[str, Any]) -> tuple[str, Any]:
    """Run a job: ``("ok", bytes)``, or ``("error", (kind, message, loc))`` with kind
    ``"over_budget"`` for a fit estimated beyond the server's time budget before it started
    (HTTP 503), ``"invalid"`` for rollspring's own errors and numerical failures of the values
    asked for (HTTP 422) and ``"crash"`` for anything else (a bug: HTTP 500)."""
    try:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore", RuntimeWarning)
            return "ok", JOBS[job](request)
    except RollspringError as exc:
        message = " ".join(str(exc).split())
        if job in _BUDGETED_JOBS and isinstance(exc, CostTooHigh):
            return "error", ("over_budget", message, [])
        if job in _LAB_JOBS:
            return "error", ("invalid", *_lab_refusal(message, request))
        match = _FIELD.match(message)
        loc = ["body", *match.group(1).split(".")] if match else ["body"]
        return "error", ("invalid", message, loc)
    except (ArithmeticError, np.linalg.LinAlgError, ValueError) as exc:
        message = (
            f"the computation failed for these values ({type(exc).__name__}: "
            f"{' '.join(str(exc).split())[:300]})"
        )
        return "error", ("invalid", message, ["body", "system"])
    except Exception as exc:  # noqa: BLE001 - a bug: reported as HTTP 500 with its type
        return "error", ("crash", f"internal error: {type(exc).__name__}: {exc}"[:500], [])


def warm_up() -> None:
    """Load the compiled kernels (Numba's disk cache) before the first request."""
    system = load_system("hoop-cylinder")
    execute(
        "simulate",
        {
            "system": system,
            "duration": 0.05,
            "rtol": 1e-8,
            "outputs": 11,
            "on_slip": "stop",
            "linear": True,
        },
    )
