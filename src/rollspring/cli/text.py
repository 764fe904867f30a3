"""Text for the terminal: what a user wrote is shown as text, and every line stays one line.

A system's name and description, ids, paths and values come from the user: Rich would read
``[/bold]`` in them as markup (and fail), a terminal would obey an ANSI escape (ESC ``[2J``
clears the screen) and a 50 MB id would print a 50 MB line. :func:`plain` escapes control
characters, :func:`markup` also Rich's markup, :func:`say` prints one bounded line on stderr.
"""

from __future__ import annotations

import re

import typer

__all__ = ["MAX_LINE", "markup", "one_line", "plain", "say"]

#: The longest line :func:`say` prints (characters); a longer one is cut, the cut marked.
MAX_LINE = 2000

#: C0 and C1 control characters, DEL and the bidirectional overrides: what a terminal obeys
#: rather than shows.
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def _escaped(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def plain(text: object) -> str:
    """``text`` with every control character written out (``\\x1b``): safe for a terminal."""
    return _CONTROL.sub(_escaped, str(text))


def markup(text: object) -> str:
    """``text`` safe to embed in a Rich markup string: control characters written out and
    ``[`` escaped, so it prints as it reads."""
    from rich.markup import escape

    return escape(plain(text))


def one_line(text: object, limit: int = MAX_LINE) -> str:
    """``text`` on one line (runs of white space, line breaks included, become one space),
    safe for a terminal and at most ``limit`` characters (a longer one cut, the cut marked)."""
    line = plain(" ".join(str(text).split()))
    if len(line) > limit:
        line = f"{line[: limit - 40]}… (cut: the line had {len(line)} characters)"
    return line


def say(line: object) -> None:
    """One line on stderr (errors, warnings, notes), never mixed into stdout."""
    typer.echo(one_line(line), err=True)
