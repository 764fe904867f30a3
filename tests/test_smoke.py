"""The default system analyses and reproduces the paper's headline result."""

import pytest

from rollspring.analysis import analyze
from rollspring.model import DEFAULT_PRESET, load_system


def test_default_system_frequency_is_the_papers() -> None:
    result = analyze(load_system(DEFAULT_PRESET))
    k, m1, m2 = 100.0, 1.0, 1.0
    assert result.oscillating[0].eigenvalue == pytest.approx(k / (2 * m1) + 2 * k / (3 * m2),
                                                             rel=1e-12)  # paper eq. (QQQ1)
