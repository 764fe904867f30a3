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


#: Two systems a random seed of the property tests found (the developers' Hypothesis profile,
#: test_physics.py::test_modes_do_not_depend_on_the_order_of_the_bodies): free chains with an
#: off-centre spring and a force of 1e-10 / 1e-9 N along their zero mode, so no exact
#: equilibrium within reach.
NO_EXACT_EQUILIBRIUM = [
    make_system(
        [
            body(
                "b0",
                mass=4.974141329603432,
                radius=0.10422551806542213,
                x=0.0,
                track_height=-0.13323760755792635,
            ),
            body(
                "b1",
                "shell",
                mass=1.9,
                radius=0.11116167303783393,
                x=0.8,
                track_height=-0.03456711381086469,
            ),
        ],
        [
            spring(
                "b0",
                "b1",
                stiffness=90.0,
                rest_length=0.6358304332605174,
                at=[{"radius": 0.050048415875308006, "angle": 0.001}, {}],
            ),
        ],
        forces=[{"body": "b0", "fx": 1e-10, "fy": 3.0975903330693285e-131}],
    ),
    make_system(
        [
            body(
                "b0", mass=0.5, radius=0.2852497426235727, x=0.0, track_height=0.13926376794792727
            ),
            body("b1", "shell", mass=3.0, radius=0.2, x=0.8, track_height=0.07366093548503233),
            body(
                "b2",
                "cylinder",
                mass=2.148978362850682,
                radius=0.05545606348883701,
                x=1.6,
                track_height=-6.450410616923357e-171,
            ),
        ],
        [
            spring("b0", "b1", stiffness=90.0, rest_length=0.99999),
            spring(
                "b1",
                "b2",
                stiffness=91.78369777053396,
                rest_length=0.5229820757523322,
                at=[
                    {"radius": 0.0459907883326543, "angle": 126.27300832359833},
                    {"radius": 0.0505187173118037, "angle": 113.30778659122751},
                ],
            ),
        ],
        forces=[
            {
                "body": "b0",
                "at": {"radius": 6.103515625e-05, "angle": -155.8807253672466},
                "fx": 1e-09,
                "fy": 4e-16,
            }
        ],
    ),
]


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """Debian's Chromium, headless, driven by Playwright (one per test module)."""
    from tests.serving import launch_chromium

    with launch_chromium() as launched:
        yield launched


# -- the page: one real server per test module, pages opened in its Chromium ----------------------


@pytest.fixture(scope="module")
def server() -> Iterator[str]:
    """``rollspring serve`` on a free port of 127.0.0.1 (one per test module); its base URL (no
    trailing slash)."""
    from tests.serving import Server

    running = Server("--budget", "600")  # about answers, not speed: never reached
    try:
        yield running.url.rstrip("/")
    finally:
        running.stop()


def _opened(browser: Any, server: str, viewport: dict[str, int]) -> Iterator[Any]:
    """The page at ``viewport``, ready; after the test: no console error, no foreign request."""
    from tests.test_web_page import open_page

    seen = open_page(browser, server, viewport=viewport)
    yield seen
    seen.check_clean()
    seen.page.close()


@pytest.fixture()
def opened(browser: Any, server: str) -> Iterator[Any]:
    """The page on the laptop's screen."""
    from tests.serving import LAPTOP

    yield from _opened(browser, server, LAPTOP)


@pytest.fixture()
def laptop(browser: Any, server: str) -> Iterator[Any]:
    """The page on the laptop's screen (beside ``sized`` and ``phone``)."""
    from tests.serving import LAPTOP

    yield from _opened(browser, server, LAPTOP)


@pytest.fixture()
def phone(browser: Any, server: str) -> Iterator[Any]:
    """The page on the phone's screen."""
    from tests.serving import PHONE

    yield from _opened(browser, server, PHONE)


@pytest.fixture(params=["laptop-1280x800", "phone-390x844"])
def sized(request: pytest.FixtureRequest, browser: Any, server: str) -> Iterator[Any]:
    """The page on each screen in turn."""
    from tests.serving import SIZES

    yield from _opened(browser, server, dict(SIZES)[request.param])


def moving_hoop_cylinder() -> System:
    """The paper's hoop and cylinder set rolling (hoop 0.3 m/s, cylinder -0.4 m/s): both bodies
    move, as a video of them shows them."""
    from rollspring.model import load_system, system_to_json

    data = system_to_json(load_system("hoop-cylinder"))
    data["bodies"][0]["v"], data["bodies"][1]["v"] = 0.3, -0.4
    return system_from_dict(data)
