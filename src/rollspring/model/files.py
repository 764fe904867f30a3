"""System files (TOML or JSON, the same structure), presets, and one-line validation errors."""

from __future__ import annotations

import json
import math
import os
import re
import stat
import sys
import tomllib
from pathlib import Path
from typing import Any

from pydantic import ValidationError
from pydantic_core import ErrorDetails

from rollspring.errors import ModelError
from rollspring.model.catalog import DEFAULT_PRESET, preset_names, preset_path
from rollspring.model.schema import System

__all__ = [
    "DEFAULT_PRESET",
    "MAX_FILE_BYTES",
    "as_system",
    "load_system",
    "not_regular",
    "preset_names",
    "preset_path",
    "system_from_dict",
    "system_from_text",
    "system_json_schema",
    "system_to_json",
    "system_to_toml",
    "validation_errors",
]


#: The largest system file read (bytes): ``rollspring chain``'s largest (20 000 bodies, 7.8 MB
#: as JSON with every field) and the model's limits (docs/system-files.md) fit; a bigger file
#: is refused before it is read.
MAX_FILE_BYTES = 16 * 1024 * 1024

#: The most characters of a path or a value a message shows (then "…"): a message stays a line.
_SHOWN_CHARACTERS = 120


def load_system(source: str | os.PathLike[str]) -> System:
    """Load a system from a ``.toml`` or ``.json`` file, or by preset name.

    Raises :class:`~rollspring.errors.ModelError` with a one-line message naming the file, the
    field and the reason for a missing file, a syntax error or an invalid value. Only a regular
    file of at most :data:`MAX_FILE_BYTES` is read (not a folder, a device, a FIFO or a socket;
    checked before it is opened, and opened without blocking).

    Parameters
    ----------
    source
        A ``.toml`` or ``.json`` file path, or a preset name (:func:`preset_names`).

    Returns
    -------
    System
        The validated system (SI units).
    """
    if not isinstance(source, str | os.PathLike):
        raise ModelError(
            f"system: must be a file path or a preset name (got {type(source).__name__})"
        )
    if not os.fspath(source):
        raise ModelError(
            f"system: must not be empty (a file or a preset name: {', '.join(preset_names())})"
        )
    try:
        path = Path(source)
        exists = os.path.lexists(path)
    except (TypeError, ValueError) as exc:  # a NUL character; a path that is not text
        raise ModelError(f"{_shown(source)}: not a valid path ({_oneline(exc)})") from None
    if not exists:
        if isinstance(source, str) and source in preset_names():
            path = preset_path(source)
        elif isinstance(source, str) and not path.suffix and "/" not in source:
            raise ModelError(
                f"'{_shown(source)}' is neither a file nor a preset "
                f"(presets: {', '.join(preset_names())})"
            )
        else:
            raise ModelError(f"{_shown(source)}: file not found")
    text = _read_text(path)
    try:
        data = _parse(text, path)
    except RecursionError:
        raise ModelError(f"{_shown(path)}: nested too deeply to be a system file") from None
    except ValueError as exc:  # e.g. an integer with more digits than Python converts
        if isinstance(exc, ModelError):
            raise
        raise _too_many_digits(_shown(path)) from None
    return system_from_dict(data, source=_shown(path))


_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def not_regular(mode: int) -> str | None:
    """What a file of ``mode`` is when it is not a regular file (None for a regular file)."""
    if stat.S_ISREG(mode):
        return None
    return next((kind for test, kind in _KINDS if test(mode)), "not a regular file")


def _read_text(path: Path) -> str:
    """The text of the regular file ``path``, at most :data:`MAX_FILE_BYTES`: checked with
    ``stat`` before opening, opened non-blocking (a FIFO swapped in meanwhile never hangs), the
    open file checked again, and no more than the cap read."""
    shown = _shown(path)
    try:
        info = os.stat(path)
    except OSError as exc:
        raise ModelError(f"{shown}: cannot read ({exc.strerror or exc})") from None
    kind = not_regular(info.st_mode)
    if kind == "a folder":
        raise ModelError(f"{shown}: is a folder, not a system file")
    if kind is not None:
        raise ModelError(f"{shown}: is {kind}, not a system file (give a regular file)")
    if info.st_size > MAX_FILE_BYTES:
        raise ModelError(_too_large(shown, info.st_size))
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        descriptor = os.open(path, flags)
    except OSError as exc:
        raise ModelError(f"{shown}: cannot read ({exc.strerror or exc})") from None
    try:
        kind = not_regular(os.fstat(descriptor).st_mode)
        if kind is not None:  # replaced between the two looks
            raise ModelError(f"{shown}: is {kind}, not a system file (give a regular file)")
        chunks, size = [], 0
        while size <= MAX_FILE_BYTES:
            chunk = os.read(descriptor, MAX_FILE_BYTES + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise ModelError(f"{shown}: cannot read ({exc.strerror or exc})") from None
    finally:
        os.close(descriptor)
    if size > MAX_FILE_BYTES:
        raise ModelError(_too_large(shown, size, grew=True))
    try:
        return b"".join(chunks).decode("utf-8-sig")  # a leading byte-order mark is allowed
    except UnicodeDecodeError:
        raise ModelError(f"{shown}: not a text file (not valid UTF-8)") from None


def _too_large(shown: str, size: int, *, grew: bool = False) -> str:
    what = "more than" if grew else f"{size} bytes,"
    return f"{shown}: too large to be a system file ({what} the limit of {MAX_FILE_BYTES} bytes)"


def as_system(value: Any, name: str = "system") -> System:
    """``value`` as a validated :class:`System`: a System itself, its JSON form (a dict), or a
    file path or preset name (str or path); anything else is a one-line
    :class:`~rollspring.errors.ModelError` naming ``name`` (what the CLI says for the same
    mistake, never an ``AttributeError`` from deep inside)."""
    if isinstance(value, System):
        return value
    if isinstance(value, dict):
        return system_from_dict(value, source=name)
    if isinstance(value, str | os.PathLike):
        return load_system(value)
    raise ModelError(
        f"{name}: must be a System, its JSON form (a dict), a file path or a preset name "
        f"(got {type(value).__name__})"
    )


#: Characters a terminal would obey rather than show: C0 and C1 controls (ESC starts ANSI
#: escape sequences), DEL, and the bidirectional overrides that reorder a line.
_UNPRINTABLE = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def _escape(match: re.Match[str]) -> str:
    char = match.group()
    named = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}
    if char in named:
        return named[char]
    code = ord(char)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def _oneline(value: object) -> str:
    """Text on one line and safe for a terminal: line breaks shown as \\n, every other control
    character escaped (\\x1b), runs of spaces kept."""
    return _UNPRINTABLE.sub(_escape, str(value))


def _shortened(text: str, limit: int = _SHOWN_CHARACTERS) -> str:
    """``text`` cut to ``limit`` characters, the cut marked with its length."""
    if len(text) <= limit:
        return text
    return f"{text[: limit - 30]}… ({len(text)} characters)"


def _quoted(text: str, limit: int = _SHOWN_CHARACTERS) -> str:
    """``repr(text)``, safe for a terminal, of at most ``limit`` characters of ``text`` (a longer
    one cut, with its length)."""
    if len(text) <= limit:
        return _oneline(repr(text))
    return f"{_oneline(repr(text[: limit - 30]))}… ({len(text)} characters)"


def _shown(path: Path | str | os.PathLike[str]) -> str:
    try:
        text = os.fspath(path)
    except TypeError:
        text = str(path)
    if isinstance(text, bytes):
        text = text.decode("utf-8", "backslashreplace")
    return _shortened(_oneline(text))


def _parse(text: str, path: Path, *, shown: str | None = None) -> dict[str, Any]:
    suffix = path.suffix.lower()
    name = _shown(path) if shown is None else shown
    if suffix == ".json":
        try:
            data = json.loads(
                text, parse_constant=_json_constant, object_pairs_hook=_no_duplicate_keys
            )
        except ModelError as exc:  # a duplicate key
            raise ModelError(f"{name}: {exc}") from None
        except RecursionError:
            raise ModelError(f"{name}: nested too deeply to be a system file") from None
        except json.JSONDecodeError as exc:
            raise ModelError(
                f"{name}: JSON syntax error: {exc.msg} (line {exc.lineno}, column {exc.colno})"
            ) from None
        if not isinstance(data, dict):
            raise ModelError(f"{name}: the top level must be a JSON object")
        return data
    if suffix in (".toml", ""):
        try:
            return tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise ModelError(f"{name}: TOML syntax error: {_oneline(exc)}") from None
    raise ModelError(f"{name}: unknown file type {_quoted(suffix)} (use .toml or .json)")


def _no_duplicate_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise ModelError(f"duplicate key {_quoted(key)} in a JSON object")
        out[key] = value
    return out


def _json_constant(name: str) -> float:
    # JSON has no NaN or infinity; Python's parser accepts them, and so do we, so that
    # ``mu_static: Infinity`` works and NaN is rejected by validation with a clear message.
    return {"Infinity": math.inf, "-Infinity": -math.inf, "NaN": math.nan}[name]


def system_from_dict(data: dict[str, Any], *, source: str = "system") -> System:
    """Validate a dictionary (the parsed file) into a :class:`System`."""
    try:
        return System.model_validate(data)
    except ValidationError as exc:
        raise ModelError(f"{source}: {_oneline(_one_line(exc))}") from None


def system_from_text(
    text: str,
    *,
    format: str = "toml",  # noqa: A002 - toml | json
    source: str = "toml",
) -> System:
    """Parse and validate the text of a system file (``format`` ``"toml"`` or ``"json"``);
    errors are one-line :class:`~rollspring.errors.ModelError` messages starting with
    ``source``, as for files."""
    try:
        data = _parse(text, Path(f"{source}.{format}"), shown=source)
    except RecursionError:
        raise ModelError(f"{source}: nested too deeply to be a system file") from None
    except ValueError as exc:
        if isinstance(exc, ModelError):
            raise
        raise _too_many_digits(source) from None
    return system_from_dict(data, source=source)


def validation_errors(
    errors: list[dict[str, Any]], data: Any, *, json: bool = False
) -> list[tuple[tuple[Any, ...], str, str]]:
    """pydantic's validation errors (``ValidationError.errors()``, locations relative to
    ``data``) as ``(loc, message, type)``: ``message`` the one-line words the CLI prints
    (with ``json``, in JSON's words: "object" and "array" for TOML's "table" and "list")."""
    out = []
    for error in errors:
        loc = tuple(
            p for p in error["loc"] if not (isinstance(p, str) and p.startswith("function-"))
        )
        out.append((loc, _oneline(_describe(error, json=json)), str(error["type"])))
    return out


def _json_number(value: float) -> float | str:
    return value if math.isfinite(value) else ("inf" if value > 0 else "-inf")


def system_to_json(system: System) -> dict[str, Any]:
    """The JSON form of a system: the structure of a system file, unset options left out,
    an infinite ``mu_static`` written as ``"inf"`` (JSON has no infinity)."""
    data = system.model_dump(mode="python", exclude_none=True)
    for body in data["bodies"]:
        body["mu_static"] = _json_number(body["mu_static"])
    return data


def system_to_toml(system: System) -> str:
    """The system as the text of a TOML system file (tomli-w); loading it gives the same
    system."""
    import tomli_w

    data = system.model_dump(mode="python", exclude_none=True)
    for key in ("anchors", "springs", "forces"):
        if not data[key]:
            del data[key]
    return tomli_w.dumps(data)


def _one_line(exc: ValidationError) -> str:
    errors = exc.errors(include_url=False)
    first = errors[0]
    message = _describe(first)
    if len(errors) > 1:
        message += f" (and {len(errors) - 1} more problem{'s' if len(errors) > 2 else ''})"
    return message


#: What a value must be, in a TOML file's words and in JSON's (the web API's).
_TYPE_WORDS = {
    "float": ("a number", "a number"),
    "int": ("a whole number", "a whole number"),
    "string": ("a string", "a string"),
    "bool": ("a bool", "true or false"),
    "list": ("a list", "an array"),
    "tuple": ("a tuple", "an array"),
    "dict": ("a table", "an object"),
    "model": ("a table", "an object"),
    "model_attributes": ("a table", "an object"),
}


def _describe(error: ErrorDetails | dict[str, Any], *, json: bool = False) -> str:
    loc = [p for p in error["loc"] if not (isinstance(p, str) and p.startswith("function-"))]
    kind = error["type"]
    msg: str = error["msg"]
    if msg.startswith("Value error, "):
        msg = msg.removeprefix("Value error, ")
    if kind == "extra_forbidden":
        key = loc[-1] if loc else "?"
        where = _path(loc[:-1])
        return f"{where + ': ' if where else ''}unknown key {_quoted(str(key))}"
    if kind == "missing":
        return f"{_path(loc)}: missing (required)"
    if kind in ("finite_number",):
        msg = "must be a finite number (no NaN or infinity)"
    elif kind in ("greater_than", "greater_than_equal", "less_than_equal", "less_than"):
        bound = error.get("ctx", {})
        op = {
            "greater_than": ">",
            "greater_than_equal": ">=",
            "less_than": "<",
            "less_than_equal": "<=",
        }[kind]
        limit = next(iter(bound.values()), "?")
        msg = (
            f"must be {op} {limit:g}"
            if isinstance(limit, (int, float))
            else f"must be {op} {limit}"
        )
    elif kind == "literal_error":
        expected = error.get("ctx", {}).get("expected", "")
        msg = f"unknown value {_show(error.get('input'))} (expected one of {expected})"
    elif kind in (
        "float_type",
        "int_type",
        "string_type",
        "bool_type",
        "list_type",
        "tuple_type",
        "dict_type",
        "model_type",
        "model_attributes_type",
    ):
        msg = f"must be {_TYPE_WORDS[kind.removesuffix('_type')][1 if json else 0]}"
    elif kind == "string_pattern_mismatch":
        msg = "must start with a letter or '_' and hold only letters, digits, '_' or '-'"
    elif kind in ("too_short", "too_long") and loc and loc[-1] in ("ends", "at"):
        msg = "must name exactly two ends" if loc[-1] == "ends" else "needs one entry per end (two)"
    elif kind == "too_short" and loc and loc[-1] == "bodies":
        msg = "at least one body is needed"
    elif kind == "string_too_short":
        msg = "must not be empty"
    value = error.get("input")
    if kind not in ("literal_error", "missing") and _is_scalar(value) and loc:
        msg += f" (got {_show(value)})"
    where = _path(loc)
    return f"{where}: {msg}" if where else msg


def _is_scalar(value: Any) -> bool:
    return isinstance(value, (int, float, str, bool)) and not isinstance(value, dict)


def _show(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int) and abs(value) >= 10**20:
        return f"an integer of {_digits(value)} digits"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else str(value)
    if isinstance(value, str):
        return _quoted(value)
    return _shortened(_oneline(repr(value)))


def _too_many_digits(source: str) -> ModelError:
    """The error for an integer longer than Python converts (its own message advises a
    function call, which a file's author cannot act on)."""
    return ModelError(
        f"{source}: a number has too many digits (at most {sys.get_int_max_str_digits()} are read)"
    )


def _digits(value: int) -> str:
    """How many decimal digits ``value`` has, "about" that many beyond what Python converts to
    text (4300 digits by default: ``str`` would raise)."""
    try:
        return str(len(str(abs(value))))
    except ValueError:
        return f"about {int(abs(value).bit_length() * math.log10(2)) + 1}"


def _path(loc: list[Any]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def system_json_schema() -> dict[str, Any]:
    """The JSON Schema of a system file (TOML files have the same structure)."""
    schema = System.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "rollspring system"
    return schema
