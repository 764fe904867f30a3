"""Images compared with their baselines in ``tests/baselines/`` (the figures' and the page's
screenshots alike): a match is an RMS difference of the pixels (0-255 scale, Matplotlib's
``compare_images``) below :data:`TOLERANCE`, so a font-rendering change of a pixel here and
there passes while a moved body fails. ``ROLLSPRING_UPDATE_BASELINES=1`` writes the baselines
instead of comparing (then review them: they are what the tests hold the code to)."""

from __future__ import annotations

import os
from pathlib import Path

from matplotlib.testing.compare import compare_images

BASELINES = Path(__file__).parent / "baselines"
TOLERANCE = 2.0
UPDATE = os.environ.get("ROLLSPRING_UPDATE_BASELINES") == "1"


def check_against_baseline(actual: Path, name: str, test_file: str) -> None:
    """``actual`` (a PNG) against ``tests/baselines/<name>.png`` (written there when updating);
    ``test_file`` is named in the message of a missing baseline (the test that makes it)."""
    expected = BASELINES / f"{name}.png"
    if UPDATE:
        BASELINES.mkdir(exist_ok=True)
        expected.write_bytes(actual.read_bytes())
    assert expected.exists(), (
        f"no baseline {expected.name}; create it with ROLLSPRING_UPDATE_BASELINES=1 "
        f".venv/bin/python -m pytest {Path(test_file).name}"
    )
    result = compare_images(str(expected), str(actual), tol=TOLERANCE)
    assert result is None, f"{name}: {result} (see {actual.parent})"
