"""The web app: the interactive page and the JSON API it uses (docs/web-api.md).

Endpoints that compute are plain ``def`` (FastAPI runs them in its thread pool, never on the
event loop) and hand the work to a :class:`~rollspring.web.workers.ComputePool` of worker
processes, which abandons a computation that runs past its budget (HTTP 503). Requests are
validated before any work starts: the system against its schema, then the bounds (at most
``MAX_BODIES`` bodies, ``MAX_DURATION`` s, ``MAX_OUTPUTS`` outputs, ``MAX_REQUEST_BYTES`` of
request body), each problem a 422 naming the field with the CLI's one-line message. The API
reads no file on a client's behalf: systems arrive in the request, presets by name.
"""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Callable
from pathlib import Path
from typing import Any, Literal

from fastapi import FastAPI, Request
from fastapi.exception_handlers import http_exception_handler
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, ConfigDict, Field, model_validator
from starlette.exceptions import HTTPException as StarletteHTTPException

from rollspring.errors import RollspringError
from rollspring.model import System, system_to_json, validation_errors
from rollspring.model.files import system_json_schema
from rollspring.service.systems import preset_catalogue, resolve_system, system_forms
from rollspring.simulate.arguments import MIN_DURATION
from rollspring.web.workers import ComputePool, JobFailed, OverBudget, Overloaded, check_pool

__all__ = ["MAX_BODIES", "MAX_DURATION", "MAX_OUTPUTS", "MAX_REQUEST_BYTES", "create_app"]

MAX_BODIES = 50
MAX_DURATION = 600.0
MAX_OUTPUTS = 20_000
MAX_REQUEST_BYTES = 256 * 1024
#: The most PATHs one fit frees.
MAX_FREE = 40
#: Default time budget of one computation (s).
DEFAULT_BUDGET = 10.0

STATIC = Path(__file__).resolve().parent / "static"
UPLOT = STATIC / "node_modules" / "uplot" / "dist"
#: The drawing of the scene, the outputs layer's (its report player inlines the same module),
#: served to the page as /static/js/geometry.js (a path: importing rollspring.outputs would load
#: NumPy into the server's start-up)
GEOMETRY_JS = Path(__file__).resolve().parents[1] / "outputs" / "js" / "geometry.js"


# ---------------------------------------------------------------- request and response models


class SystemRequest(BaseModel):
    """A system: its JSON form (``system``) or the text of a TOML system file (``toml``)."""

    model_config = ConfigDict(extra="forbid")

    system: System | None = Field(default=None, description="The system in its JSON form.")
    toml: str | None = Field(default=None, description="The text of a TOML system file.")

    @model_validator(mode="after")
    def _exactly_one(self) -> SystemRequest:
        if (self.system is None) == (self.toml is None):
            raise ValueError("give exactly one of 'system' and 'toml'")
        return self


class ModeStartRequest(BaseModel):
    """Start at rest in the equilibrium displaced along one normal mode."""

    model_config = ConfigDict(extra="forbid")

    mode: int = Field(ge=0, le=MAX_BODIES, strict=True, description="Index into analyze's `modes`.")
    amplitude: float = Field(
        allow_inf_nan=False,
        ge=-1.0,
        le=1.0,
        strict=True,  # a number: true is not 1.0
        description="Largest centre displacement (m).",
    )


class SimulateRequest(SystemRequest):
    """What to simulate and how."""

    duration: float = Field(
        ge=MIN_DURATION,
        le=MAX_DURATION,
        allow_inf_nan=False,
        strict=True,
        description="Simulated time (s).",
    )
    rtol: float = Field(
        default=1e-8,
        gt=0,
        le=0.1,
        allow_inf_nan=False,
        strict=True,
        description="Relative accuracy of the motion over the run.",
    )
    outputs: int = Field(
        default=601, ge=2, le=MAX_OUTPUTS, strict=True, description="Output times."
    )
    on_slip: Literal["stop", "continue"] = Field(
        default="stop", description="stop at the first slip, or continue (stick-slip)."
    )
    start: ModeStartRequest | None = None
    linear: bool = Field(
        default=False, strict=True, description="Also return the linear modal solution."
    )


class DeriveRequest(SystemRequest):
    """Which derivations."""

    method: str = Field(
        default="all",
        max_length=200,
        description="all, or comma-separated methods: newton, conservation, "
        "lagrange, natural-frequencies, hamilton.",
    )


class ReportRequest(SystemRequest):
    """The report's simulated time (default: four periods of the slowest mode)."""

    duration: float | None = Field(
        default=None, ge=MIN_DURATION, le=MAX_DURATION, allow_inf_nan=False, strict=True
    )


class LabDataRequest(SystemRequest):
    """A measured table, sent as text, for the system's bodies."""

    data: str = Field(
        max_length=MAX_REQUEST_BYTES,
        description="The text of the table: a track CSV or a plain CSV (t, x_<id>, phi_<id>), "
        "or a Tracker data file.",
    )
    filename: str = Field(
        default="data",
        min_length=1,
        max_length=200,
        description="The file's name, as messages name it.",
    )
    mapping: dict[str, str | None] = Field(
        default_factory=dict,
        max_length=MAX_BODIES,
        description="Tracks matched to bodies, {track: body id}, null for a track left out "
        "(default: by name).",
    )
    unmatched: Literal["refuse", "omit"] = Field(
        default="refuse",
        description="A track that names no body and is not in mapping: refused (as the CLI), or "
        "left out.",
    )


class FitRequest(LabDataRequest):
    """What to fit (= rollspring fit DATA --system SYSTEM --free PATH ...)."""

    free: list[str] | None = Field(
        default=None,
        max_length=MAX_FREE,
        description="PATHs of the system to fit (springs.0.stiffness, bodies.<id>.mass, ...); "
        "default: every spring's stiffness and damping.",
    )
    fix_initial: bool = Field(
        default=False,
        strict=True,
        description="Hold the system's initial state and fit the data's time t0 at which it "
        "holds (default: each body's initial x and v are fitted).",
    )
    posterior: bool = Field(
        default=False,
        strict=True,
        description="Also sample the posterior by MCMC (emcee, = rollspring fit --posterior): "
        "each fitted parameter's median and 95 % credible interval, in fit.posterior.",
    )


class Problem(BaseModel):
    """One problem of a request."""

    loc: list[str | int]
    msg: str
    type: str


class InvalidRequest(BaseModel):
    """HTTP 422: every problem, and ``message``, the one line the CLI prints for the first."""

    detail: list[Problem]
    message: str


class Unavailable(BaseModel):
    """HTTP 503: over the time budget, or at capacity."""

    detail: str


class Preset(BaseModel):
    name: str
    title: str
    system: dict[str, Any]


class SystemForms(BaseModel):
    system: dict[str, Any]
    toml: str


class StartSystem(BaseModel):
    """The system the server was started with."""

    preset: str | None
    system: dict[str, Any]


Series = list[float | None]


class BodySeries(BaseModel):
    x: Series
    phi: Series
    v: Series
    omega: Series
    friction: Series
    normal: Series
    friction_ratio: Series = Field(description="|f|/(mu_s N); null where infinite (N <= 0).")
    slipping: list[bool]


class SpringSeries(BaseModel):
    length: Series
    tension: Series


class EnergySeries(BaseModel):
    kinetic: Series
    potential: Series
    total: Series
    translational: Series = Field(description="The kinetic energy of the centres' motion.")
    rotational: Series = Field(description="The kinetic energy of the rotations.")


class SimulateResponse(BaseModel):
    summary: dict[str, Any]
    t: Series
    bodies: dict[str, BodySeries]
    springs: list[SpringSeries]
    energy: EnergySeries
    cm_x: Series
    cm_a: Series = Field(description="The CM's acceleration; null where a body slips.")
    friction_x: Series = Field(description="The sum of the frictions (N).")
    other_external_x: Series = Field(
        description="The other horizontal external forces (walls, external forces), N; null "
        "where a body slips."
    )
    total_mass: float
    stationary_x: Series | None
    initial: dict[str, dict[str, float]]
    linear: dict[str, Series] | None


#: A JSON object answer, documented as one (its fields: docs/web-api.md and the README).
_OBJECT: dict[int | str, dict[str, Any]] = {
    200: {"content": {"application/json": {"schema": {"type": "object"}}}}
}

_ERRORS: dict[int | str, dict[str, Any]] = {
    422: {"model": InvalidRequest, "description": "An invalid request."},
    503: {"model": Unavailable, "description": "Over the time budget, or at capacity."},
}


class JSONBytes(JSONResponse):
    """A JSON body already encoded (by a worker, with orjson). A JSONResponse to FastAPI, so
    the documented 200 schema is the model's alone (a plain Response class makes FastAPI add
    ``"type": "string"`` beside the model's ``$ref``, which no JSON object satisfies)."""

    media_type = "application/json"

    def render(self, content: Any) -> bytes:
        return content if isinstance(content, bytes) else super().render(content)


# ------------------------------------------------------------------------------------ the app


def create_app(
    system: System | None = None,
    *,
    preset: str | None = None,
    budget: float = DEFAULT_BUDGET,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> FastAPI:
    """The ASGI app: the page at ``/`` (opening on ``system``, default the default preset),
    the JSON API under ``/api``, with ``workers`` worker processes (default: one per core)
    and ``budget`` seconds for each computation.

    Parameters
    ----------
    system, preset
        The system the page opens on (default: the preset ``preset``, or the default preset).
    budget
        Seconds each computation may take before it is answered with 503 (at most a day).
    workers
        Worker processes (default: one per core; at most four per core).
    progress
        Called ``progress(ready, workers)`` as each worker becomes ready while the app starts
        (it answers once every one is).

    Returns
    -------
    fastapi.FastAPI
        The app, for ``uvicorn.run(app)`` (``rollspring serve`` does that).
    """
    from rollspring.model import DEFAULT_PRESET, load_system

    workers, budget = check_pool(workers, budget)  # before anything starts
    if system is None:
        preset = preset or DEFAULT_PRESET
        system = load_system(preset)
    start = {"preset": preset, "system": system_to_json(system)}
    holder: dict[str, ComputePool] = {}

    @contextlib.asynccontextmanager
    async def lifespan(_: FastAPI) -> AsyncIterator[None]:
        holder["pool"] = ComputePool(workers, budget, progress=progress)
        try:
            yield
        finally:
            holder.pop("pool").close()

    app = FastAPI(
        title="rollspring",
        version=_version(),
        lifespan=lifespan,
        description="Coupled rolling oscillators: the interactive page's API. "
        "SI units throughout; see docs/web-api.md.",
        # FastAPI's /docs and /redoc pages load Swagger UI, ReDoc and fonts from CDNs: no
        # request leaves this server's pages (the schema stays at /openapi.json)
        docs_url=None,
        redoc_url=None,
    )
    app.add_middleware(_BodyLimit, limit=MAX_REQUEST_BYTES)

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return _invalid_response(exc.errors(), getattr(exc, "body", None))

    @app.exception_handler(StarletteHTTPException)
    async def unreadable(request: Request, exc: StarletteHTTPException) -> Response:
        if exc.status_code == 400:  # a body FastAPI cannot even decode (not UTF-8, not JSON)
            return _problem(
                ["body"], f"body: cannot be read as JSON ({exc.detail})", "json_invalid"
            )
        return await http_exception_handler(request, exc)

    def compute(
        job: str, request: dict[str, Any], media: type[Response] = JSONBytes, **kwargs: Any
    ) -> Response:
        try:
            return media(holder["pool"].run(job, request), **kwargs)
        except (OverBudget, Overloaded) as exc:
            return JSONResponse({"detail": str(exc)}, status_code=503)
        except JobFailed as exc:
            if exc.kind == "over_budget":  # estimated beyond the budget: refused, not started
                return JSONResponse({"detail": exc.message}, status_code=503)
            if exc.kind == "invalid":
                return _problem(list(exc.loc) or ["body"], exc.message, "value_error")
            return JSONResponse({"detail": exc.message}, status_code=500)

    @app.get("/", include_in_schema=False)
    def page() -> Response:
        index = STATIC / "index.html"
        if not index.is_file():
            return JSONResponse({"detail": "the page is not installed"}, status_code=404)
        return FileResponse(index, media_type="text/html")

    @app.get("/static/js/geometry.js", include_in_schema=False)
    def geometry() -> Response:
        return FileResponse(GEOMETRY_JS, media_type="text/javascript")

    @app.get("/api/presets", response_model=list[Preset], summary="The built-in systems")
    def presets() -> Any:
        return preset_catalogue()

    @app.get("/api/schema", summary="The JSON Schema of a system file")
    def schema() -> dict[str, Any]:
        return system_json_schema()

    @app.get(
        "/api/start", response_model=StartSystem, summary="The system the server was started with"
    )
    def start_system() -> Any:
        return start

    @app.post(
        "/api/system",
        response_model=SystemForms,
        responses=_ERRORS,
        summary="Validate a system; its JSON form and TOML text",
    )
    def system_endpoint(request: SystemRequest) -> Any:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return system_forms(resolved)

    @app.post(
        "/api/analyze",
        response_class=JSONBytes,
        responses={**_OBJECT, **_ERRORS},
        summary="Linear analysis (= rollspring analyze --json)",
    )
    def analyze(request: SystemRequest) -> Response:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return compute("analyze", {"system": resolved})

    def simulation(request: SimulateRequest) -> dict[str, Any] | Response:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return {
            "system": resolved,
            "duration": request.duration,
            "rtol": request.rtol,
            "outputs": request.outputs,
            "on_slip": request.on_slip,
            "start": None if request.start is None else request.start.model_dump(),
            "linear": request.linear,
        }

    @app.post(
        "/api/simulate",
        response_class=JSONBytes,
        responses={200: {"model": SimulateResponse}, **_ERRORS},
        summary="The exact nonlinear motion (summary = rollspring simulate --json)",
    )
    def simulate(request: SimulateRequest) -> Response:
        job = simulation(request)
        return job if isinstance(job, Response) else compute("simulate", job)

    @app.post(
        "/api/simulate.csv",
        response_class=Response,
        responses={200: {"content": {"text/csv": {}}}, **_ERRORS},
        summary="The trajectory as CSV (= trajectory.csv of simulate --out)",
    )
    def simulate_csv(request: SimulateRequest) -> Response:
        job = simulation(request)
        if isinstance(job, Response):
            return job
        return compute(
            "simulate_csv",
            job,
            Response,
            media_type="text/csv",
            headers={"Content-Disposition": 'attachment; filename="trajectory.csv"'},
        )

    @app.post(
        "/api/derive",
        response_class=JSONBytes,
        responses={**_OBJECT, **_ERRORS},
        summary="The derivation by the paper's five methods, as MathML and LaTeX",
    )
    def derive(request: DeriveRequest) -> Response:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return compute("derive", {"system": resolved, "method": request.method})

    @app.post(
        "/api/report",
        response_class=Response,
        responses={200: {"content": {"text/html": {}}}, **_ERRORS},
        summary="The self-contained HTML report",
    )
    def report(request: ReportRequest) -> Response:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return compute(
            "report",
            {"system": resolved, "duration": request.duration},
            Response,
            media_type="text/html",
        )

    def lab_job(request: LabDataRequest) -> dict[str, Any] | Response:
        resolved = _resolve(request)
        if isinstance(resolved, Response):
            return resolved
        return {
            "system": resolved,
            "data": request.data,
            "filename": request.filename,
            "mapping": dict(request.mapping),
            "unmatched": request.unmatched,
        }

    @app.post(
        "/api/lab/data",
        response_class=JSONBytes,
        responses={**_OBJECT, **_ERRORS},
        summary="A measured table read and matched to the system's bodies",
    )
    def lab_data(request: LabDataRequest) -> Response:
        job = lab_job(request)
        return job if isinstance(job, Response) else compute("lab_data", job)

    @app.post(
        "/api/fit",
        response_class=JSONBytes,
        responses={**_OBJECT, **_ERRORS},
        summary="Fit the system to a measured table (fit = rollspring fit --json)",
    )
    def fit(request: FitRequest) -> Response:
        job = lab_job(request)
        if isinstance(job, Response):
            return job
        job["free"] = None if request.free is None else list(request.free)
        job["fix_initial"] = request.fix_initial
        job["posterior"] = request.posterior
        job["budget"] = holder["pool"].budget  # a fit estimated beyond it is refused (503)
        return compute("fit", job)

    @app.get("/static/node_modules/{rest:path}", include_in_schema=False)
    def not_served(rest: str) -> Response:
        # the front-end packages' folder: the page's uPlot is served as /vendor/uplot, and the
        # rest (axe-core, for the tests) is not the page's
        return JSONResponse({"detail": "Not Found"}, status_code=404)

    if STATIC.is_dir():
        app.mount("/static", StaticFiles(directory=STATIC), name="static")
    app.mount("/vendor/uplot", StaticFiles(directory=UPLOT, check_dir=False), name="uplot")
    return app


# ---------------------------------------------------------------------------------- helpers


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("rollspring")
    except PackageNotFoundError:
        return "0"


def _resolve(request: SystemRequest) -> System | Response:
    """The request's system, validated (TOML parsed) and within the bounds — or a 422."""
    field = "toml" if request.toml is not None else "system"
    try:
        system = resolve_system(request.system, toml=request.toml)
    except RollspringError as exc:
        return _problem(["body", field], " ".join(str(exc).split()), "value_error")
    if len(system.bodies) > MAX_BODIES:
        return _problem(
            ["body", field, "bodies"],
            f"{field}.bodies: at most {MAX_BODIES} bodies "
            f"in one request (got {len(system.bodies)})",
            "too_long",
        )
    return system


def _problem(loc: list[Any], message: str, kind: str) -> JSONResponse:
    return JSONResponse(
        {"detail": [{"loc": loc, "msg": message, "type": kind}], "message": message},
        status_code=422,
    )


def _invalid_response(errors: Any, body: Any) -> JSONResponse:
    """422 for pydantic's errors of a request body: each location with the CLI's one-line
    words, in JSON's terms ("object", "array"); a body that is not a JSON object, or not JSON
    at all, said so (a syntax error with its line and column)."""
    errors = list(errors)
    detail: list[dict[str, Any]] = []
    for error in errors:
        loc = list(error.get("loc", ()))
        relative = loc[1:] if loc[:1] == ["body"] else loc
        data = body if isinstance(body, dict) else {}
        kind = str(error.get("type", "invalid"))
        whole = _whole_body(error, body)
        if whole is not None:
            loc, message = ["body"], whole
        elif relative[:1] == ["system"] and isinstance(data.get("system"), dict):
            inner = validation_errors(
                [{**error, "loc": tuple(relative[1:])}], data["system"], json=True
            )
            message = f"system.{inner[0][1]}" if relative[1:] else f"system: {inner[0][1]}"
        else:
            message = validation_errors([{**error, "loc": tuple(relative)}], data, json=True)[0][1]
            if not relative:
                message = f"body: {message}"
        detail.append({"loc": loc, "msg": message, "type": kind})
    if not detail:
        detail = [{"loc": ["body"], "msg": "body: invalid request", "type": "invalid"}]
    first = detail[0]["msg"]
    more = len(detail) - 1
    message = first + (f" (and {more} more problem{'s' if more > 1 else ''})" if more else "")
    return JSONResponse({"detail": detail, "message": message}, status_code=422)


#: What a JSON value is, in JSON's words.
_JSON_KINDS = {list: "an array", str: "a string", int: "a number", float: "a number"}


def _whole_body(error: dict[str, Any], body: Any) -> str | None:
    """The message for a request body that is not a JSON object at all (not JSON, a JSON
    syntax error, another JSON value, or nothing), or None when the problem is inside it."""
    loc = list(error.get("loc", ()))
    kind = error.get("type")
    if kind == "json_invalid":
        reason = str((error.get("ctx") or {}).get("error") or "not valid JSON")
        where = ""
        if len(loc) > 1 and isinstance(loc[1], int) and isinstance(body, str | bytes):
            text = body.decode("utf-8", "replace") if isinstance(body, bytes) else body
            before = text[: loc[1]]
            line = before.count("\n") + 1
            column = loc[1] - (before.rfind("\n") + 1) + 1
            where = f" at line {line}, column {column}"
        return f"body: not valid JSON{where} ({reason[:1].lower()}{reason[1:]})"
    if loc != ["body"]:
        return None
    if kind == "missing" or body in (None, b""):
        return "body: expected a JSON object with 'system' or 'toml', got nothing (or null)"
    if kind in ("model_attributes_type", "dict_type", "model_type"):
        if isinstance(body, bytes | bytearray):
            return (
                "body: expected a JSON object (sent with Content-Type: application/json), got text"
            )
        if isinstance(body, bool):
            got = "true" if body else "false"
        else:
            got = next((w for t, w in _JSON_KINDS.items() if isinstance(body, t)), "a value")
        return f"body: expected a JSON object, got {got}"
    return None


class _BodyLimit:
    """ASGI middleware: a request body over ``limit`` bytes gets a 422 before it is read whole
    (by its Content-Length, or by counting a body sent without one)."""

    def __init__(self, app: Any, limit: int) -> None:
        self.app = app
        self.limit = limit

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = dict(scope.get("headers") or []).get(b"content-length")
        if declared is not None:
            if not declared.isdigit() or int(declared) > self.limit:
                await self._refuse(scope, receive, send)
                return
            await self.app(scope, receive, send)
            return
        # no Content-Length (chunked): read it here, at most `limit` bytes, then hand it on
        body = bytearray()
        more = True
        while more:
            message = await receive()
            if message["type"] != "http.request":
                return
            body += message.get("body", b"")
            more = message.get("more_body", False)
            if len(body) > self.limit:
                await self._refuse(scope, receive, send)
                return
        sent = False

        async def replay() -> dict[str, Any]:
            nonlocal sent
            if sent:
                return await receive()
            sent = True
            return {"type": "http.request", "body": bytes(body), "more_body": False}

        await self.app(scope, replay, send)

    async def _refuse(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        message = (
            f"body: the request is larger than {self.limit // 1024} kB (the largest a "
            "request may be)"
        )
        response = JSONResponse(
            {"detail": [{"loc": ["body"], "msg": message, "type": "too_long"}], "message": message},
            status_code=422,
        )
        await response(scope, receive, send)
