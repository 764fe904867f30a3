"""Shared helpers: build systems from small dictionaries, strict numerics."""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from hypothesis import settings

from rollspring.model import System, system_from_dict

# Hypothesis: CI runs a fixed, derandomised profile (the same examples every run, no example
# database); developers get random examples (HYPOTHESIS_PROFILE=dev, or any run outside CI).
# No deadline: tests are never timed (a loaded machine must not fail an example for its speed).
settings.register_profile("ci", derandomize=True, database=None, print_blob=True, deadline=None)
settings.register_profile("dev", print_blob=True, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))


@pytest.fixture(autouse=True)
def strict_numerics() -> Iterator[None]:
    """Every test runs with floating-point errors raised, not silently turned into NaN/inf."""
    with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
        yield


def body(
    id: str,  # noqa: A002 - the schema's field name
    shape: str = "hoop",
    *,
    mass: float = 1.0,
    radius: float = 0.1,
    x: float = 0.0,
    **extra: Any,
) -> dict[str, Any]:
    """A body entry of a system file."""
    return {"id": id, "shape": shape, "mass": mass, "radius": radius, "x": x, **extra}


def spring(a: str, b: str, *, stiffness: float = 100.0, **extra: Any) -> dict[str, Any]:
    """A spring entry of a system file."""
    return {"ends": [a, b], "stiffness": stiffness, **extra}


def make_system(
    bodies: list[dict[str, Any]], springs: list[dict[str, Any]] | None = None, **extra: Any
) -> System:
    """Validate a system from entries."""
    return system_from_dict({"bodies": bodies, "springs": springs or [], **extra})


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """Debian's Chromium, headless, driven by Playwright (one per test module)."""
    from tests.serving import launch_chromium

    with launch_chromium() as launched:
        yield launched
