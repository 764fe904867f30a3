"""The report's style sheet and animation player, read from their front-end files and inlined.

The files are package data: ``assets/report.css`` (the style sheet, print layout included) and
``assets/player.js`` (the player, an ES module: see its opening comment), which draws bodies and
springs with ``outputs/js/geometry.js`` (one drawing of zigzag springs for the report and the web
page, which is served the module; Node's tests import both). The report is one
file that fetches nothing, so :func:`player_script` joins the two modules into one classic
script: their ``export`` keywords and the player's import of geometry.js are removed, the rest
is kept as written, wrapped in a function that calls ``startPlayer(document, window)``.
"""

from __future__ import annotations

import functools
import re
from importlib.resources import files

__all__ = ["GEOMETRY_JS", "player_script", "style_sheet"]

_ASSETS = files("rollspring.outputs.report") / "assets"
#: The drawing of the scene, shared by the player and the web page (package data of this layer).
GEOMETRY_JS = files("rollspring.outputs") / "js" / "geometry.js"
#: The one import the player may have: geometry.js's names, on one line.
_IMPORT = re.compile(r'^import \{[\w, ]+\} from "\.\./\.\./js/geometry\.js";\n', re.M)
_EXPORT = re.compile(r"^export (?=(?:async )?function |const |let |class )", re.M)


def _inline(source: str, name: str) -> str:
    """``source`` of the ES module ``name`` as part of a classic script: without its export
    keywords and its import of geometry.js; refused if anything else of a module remains."""
    text = _EXPORT.sub("", _IMPORT.sub("", source))
    left = re.search(r"^(?:import|export)\b.*$", text, re.M)
    if left is not None:
        raise ValueError(f"{name}: cannot inline {left.group(0)!r}")
    if re.search(r"</script|<!--", text, re.I):
        raise ValueError(f"{name}: '</script' or '<!--' would end the inline script")
    return text


@functools.cache
def style_sheet() -> str:
    """The report's CSS (``assets/report.css``), for its ``<style>`` element."""
    return (_ASSETS / "report.css").read_text(encoding="utf-8")


@functools.cache
def player_script() -> str:
    """The player as one classic script for the report's ``<script>`` element: geometry.js and
    ``assets/player.js`` inlined in a function that starts the player."""
    geometry = _inline(GEOMETRY_JS.read_text(encoding="utf-8"), "geometry.js")
    player = _inline((_ASSETS / "player.js").read_text(encoding="utf-8"), "player.js")
    return (
        '\n(function () {\n  "use strict";\n'
        + geometry
        + "\n"
        + player
        + "\n  startPlayer(document, window);\n})();\n"
    )
