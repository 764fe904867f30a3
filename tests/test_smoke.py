"""The default system analyses and reproduces the paper's headline result."""

import pytest

from rollspring.analysis import analyze
from rollspring.model import DEFAULT_PRESET, load_system


def test_default_system_frequency_is_the_papers() -> None:
    result = analyze(load_system(DEFAULT_PRESET))
    k, m1, m2 = 100.0, 1.0, 1.0
    assert result.oscillating[0].eigenvalue == pytest.approx(
        k / (2 * m1) + 2 * k / (3 * m2), rel=1e-12
    )  # paper eq. (QQQ1)


def test_import_stays_light_and_the_symbolic_and_picture_parts_load_on_use():
    import subprocess
    import sys

    code = (
        "import sys, rollspring; heavy = [m for m in ('sympy', 'matplotlib', 'pandas') "
        "if m in sys.modules]; assert not heavy, heavy; "
        "assert callable(rollspring.derive) and 'sympy' in sys.modules; "
        # build_report imports the renderer when it runs; the renderer itself loads Matplotlib
        "assert callable(rollspring.build_report) and 'matplotlib' not in sys.modules; "
        "assert callable(rollspring.write_report) and 'matplotlib' in sys.modules; "
        "assert set(rollspring.__all__) <= set(dir(rollspring))"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
