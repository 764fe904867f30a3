"""A fast command line: each command loads only what it needs (issue 12, point 3), and a
command that needs a missing optional extra says which one to install.

What is loaded is checked, not how long it takes (no test depends on wall-clock speed; the
times are measured by bench/bench_startup.py).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import rollspring
from rollspring import errors
from rollspring.cli import app

ROLLSPRING = str(Path(sys.executable).with_name("rollspring"))
HEAVY = (
    "numpy",
    "scipy",
    "numba",
    "pydantic",
    "sympy",
    "matplotlib",
    "pandas",
    "fastapi",
    "dask",
    "distributed",
    "xarray",
    "zarr",
    "uvicorn",
    "PIL",
    "IPython",
)

#: how a subprocess reports the heavy top-level modules it ended with
REPORT = (
    "import atexit, sys, json; atexit.register(lambda: sys.stderr.write('LOADED ' + "
    f"json.dumps(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r})))))"
)


def loaded(code: str) -> list[str]:
    done = subprocess.run(
        [sys.executable, "-c", f"{REPORT}\n{code}"], capture_output=True, text=True, check=False
    )
    line = [x for x in done.stderr.splitlines() if x.startswith("LOADED ")]
    assert line, done.stderr
    return json.loads(line[-1].removeprefix("LOADED "))


def command(*args: str) -> str:
    return (
        "import sys\nfrom rollspring.cli import main\n"
        f"sys.argv = ['rollspring', *{list(args)!r}]\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
    )


def test_import_rollspring_loads_no_heavy_library() -> None:
    assert loaded("import rollspring") == []


def test_help_loads_no_heavy_library() -> None:
    assert loaded(command("--help")) == []


def test_analyze_needs_numpy_pydantic_but_not_scipy_or_the_compiled_kernels() -> None:
    """The paper's system: NumPy's eigh (diagonal M), the one-step equilibrium of level centre
    springs and the friction ratio's closed form need no SciPy."""
    assert loaded(command("analyze", "hoop-cylinder", "--json")) == ["numpy", "pydantic"]


def test_analyze_loads_scipy_only_for_what_needs_it() -> None:
    """Three bodies, a tilted spring off the centres (one frequency group, a varying normal
    force), and several frequencies with a varying normal force (the friction ratio's maximum
    over the torus of phases: the root of a convex function, docs/physics.md (M20)) need no
    SciPy; a long chain (its sparse matrices and banded eigensolvers) does."""
    assert "scipy" not in loaded(command("analyze", "three-bodies", "--json"))
    assert "scipy" not in loaded(command("analyze", "frictionless", "--json"))
    tilted_chain = (
        "from rollspring import analyze\n"
        "from rollspring.model import system_from_dict\n"
        "at = [{'radius': 0.05, 'angle': 30}, {'radius': 0.08, 'angle': -100}]\n"
        "bodies = [{'id': i, 'shape': 'hoop', 'mass': 1.0, 'radius': 0.1, 'x': 0.5 * k,\n"
        "           'v': 0.05 * k} for k, i in enumerate('abc')]\n"
        "springs = [{'ends': e, 'stiffness': 100.0, 'at': at} for e in (['a', 'b'], ['b', 'c'])]\n"
        "result = analyze(system_from_dict({'bodies': bodies, 'springs': springs}))\n"
        "assert len({round(m.omega, 6) for m in result.oscillating}) == 2\n"
        "assert result.required_mu is not None and all(result.required_mu >= 0)\n"
    )
    assert "scipy" not in loaded(tilted_chain)
    long_chain = (
        "from rollspring import analyze, chain\n"
        "assert hasattr(analyze(chain('hoop', 100, walls='both')).stiffness, 'tocoo')\n"
    )
    assert "scipy" in loaded(long_chain)


def test_simulate_loads_the_kernels_but_no_plotting_or_symbolic_library() -> None:
    assert loaded(command("simulate", "hoop-cylinder", "-T", "0.5", "--json")) == [
        "numba",
        "numpy",
        "pydantic",
        "scipy",
    ]


def test_simulate_of_the_paper_system_needs_no_scipy() -> None:
    """What of SciPy a run loads is Numba's own: ``import scipy`` (its version check) and
    scipy.linalg (numba.np.arraymath checks for BLAS when the CPU target starts). With SciPy
    made unimportable the paper's system still analyses and simulates: neither needs it;
    SciPy's optimizers and integrators load only for what needs them (slip, damping, events).
    """
    report = (
        "import atexit, sys\n"
        "atexit.register(lambda: sys.stderr.write('SCIPY ' + ' '.join(sorted({"
        "'.'.join(m.split('.')[:2]) for m in sys.modules if m.startswith('scipy.')}))))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", report + command("simulate", "hoop-cylinder", "-T", "1")],
        capture_output=True,
        text=True,
        check=False,
    )
    line = [x for x in done.stderr.splitlines() if x.startswith("SCIPY")]
    parts = set(line[-1].split()[1:])
    assert "scipy.linalg" in parts  # Numba's
    assert not parts & {"scipy.optimize", "scipy.integrate", "scipy.special", "scipy.sparse"}
    without_scipy = (
        "import sys\n"
        "sys.modules['scipy'] = None  # any import of SciPy fails\n"
        "import rollspring\n"
        "system = rollspring.load_system('hoop-cylinder')\n"
        "analysis = rollspring.analyze(system)\n"
        "run = rollspring.simulate(system, 10.0)\n"
        "assert run.status == 'finished' and analysis.required_mu is not None\n"
        "print('ok')\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", without_scipy], capture_output=True, text=True, check=False
    )
    assert done.stdout.strip() == "ok", done.stderr


def test_every_public_name_still_loads_and_the_version_comes_from_the_metadata() -> None:
    from importlib.metadata import version

    assert rollspring.__version__ == version("rollspring")
    for name in rollspring.__all__:
        assert getattr(rollspring, name) is not None, name
    assert callable(rollspring.simulate) and rollspring.simulate.run is not None
    assert set(rollspring.__all__) <= set(dir(rollspring))


#: What a command that computes no motion leaves out: Numba, SciPy and the compiled kernels.
MOTION = ("numba", "scipy", "rollspring.simulate.kernels")


@pytest.mark.parametrize(
    ("args", "written"),
    [
        (["chain", "--n", "3", "--pattern", "hoop", "--out", "c.toml"], ["c.toml"]),
        (["export", "hoop-cylinder", "--format", "mjcf", "-o", "x.xml"], ["x.xml"]),
        (["derive", "hoop-cylinder", "-o", "d.txt"], ["d.txt"]),
        (["worksheet", "--level", "4", "--seed", "3", "-o", "w.md"], ["w.md", "w-solutions.md"]),
        (["presets"], []),
    ],
    ids=["chain --out", "export", "derive -o", "worksheet", "presets"],
)
def test_a_command_that_computes_no_motion_loads_no_numba_scipy_or_kernels(
    args: list[str], written: list[str], tmp_path: Path
) -> None:
    """Writing a chain's file, a MuJoCo model, a derivation or a worksheet, or listing the
    presets, simulates nothing: none of Numba, SciPy or rollspring's compiled kernels is
    imported (issue 23: ``chain --out`` and ``export`` took 1.6-2.6 s, loading them to write a
    file)."""
    report = (
        "import atexit, sys, json; atexit.register(lambda: sys.stderr.write('LOADED ' + "
        f"json.dumps([m for m in {MOTION!r} if m in sys.modules])))"
    )
    done = subprocess.run(
        [sys.executable, "-c", f"{report}\n{command(*args)}"],
        capture_output=True,
        text=True,
        check=False,
        cwd=tmp_path,
    )
    line = [x for x in done.stderr.splitlines() if x.startswith("LOADED ")]
    assert line, done.stderr
    for name in written:  # the command did its work
        assert (tmp_path / name).stat().st_size > 0, done.stderr
    assert json.loads(line[-1].removeprefix("LOADED ")) == []


def test_a_trajectory_view_loads_the_outputs_layer_on_first_use() -> None:
    assert loaded(
        "import rollspring\n"
        "t = rollspring.simulate(rollspring.load_system('hoop-cylinder'), 0.1, "
        "n_output=3)\nassert list(t.to_pandas().index) == list(t.t)\n"
        "print('ok')"
    ) == ["numba", "numpy", "pandas", "pydantic", "scipy"]


@pytest.mark.parametrize(
    ("args", "extras"),
    [
        (["report", "hoop-cylinder"], ("report",)),
        (["derive", "hoop-cylinder"], ("report",)),
        (["paper-check"], ("report",)),
        (["worksheet"], ("report",)),
        (["animate", "hoop-cylinder", "-o", "x.gif"], ("plot",)),
        (["serve"], ("web",)),
        (["sweep", "hoop-cylinder", "--vary", "springs.0.stiffness=90:110:3"], ("sweep",)),
        (
            ["sweep-plot", "s.zarr", "--x", "a", "--y", "b", "-m", "status", "-o", "m.png"],
            ("sweep", "plot"),
        ),
    ],
)
def test_a_command_without_its_extra_says_which_to_install(monkeypatch, args, extras) -> None:
    """One line on stderr, exit code 2, before anything else (the extras' modules are made to
    look missing)."""
    for extra in extras:
        monkeypatch.setitem(errors.EXTRAS, extra, ("rollspring_no_such_module",))
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2, result.output
    names = " and ".join(f"'{extra}'" for extra in extras)
    plural = "s" if len(extras) > 1 else ""
    assert result.stderr == (
        f"error: rollspring {args[0]} needs the {names} extra{plural}: "
        f"pip install 'rollspring[{','.join(extras)}]'\n"
    )


def test_a_library_name_without_its_extra_says_which_to_install(monkeypatch) -> None:
    monkeypatch.setitem(errors.EXTRAS, "report", ("rollspring_no_such_module",))
    monkeypatch.delitem(vars(rollspring), "build_report", raising=False)
    with pytest.raises(
        errors.MissingExtraError,
        match=r"^rollspring.build_report needs the 'report' extra: "
        r"pip install 'rollspring\[report\]'$",
    ):
        rollspring.build_report  # noqa: B018 - the attribute access is the test
    assert isinstance(errors.MissingExtraError("x", ("plot",)), ImportError)


def test_a_missing_module_met_inside_a_guarded_block_names_its_extra() -> None:
    with (
        pytest.raises(errors.MissingExtraError, match=r"needs the 'plot' extra"),
        errors.require_extra("plot", "this"),
    ):
        raise ModuleNotFoundError("No module named 'matplotlib.pyplot'", name="matplotlib.pyplot")
    # a module of no extra is a bug, left as it is
    with pytest.raises(ModuleNotFoundError), errors.require_extra("plot", "this"):
        raise ModuleNotFoundError("No module named 'nothing'", name="nothing")


def test_the_console_script_starts_and_exits_cleanly() -> None:
    done = subprocess.run([ROLLSPRING, "--help"], capture_output=True, text=True, check=False)
    assert done.returncode == 0 and "analyze" in done.stdout


def test_a_warm_run_loads_its_kernels_without_starting_numbas_compiler() -> None:
    """With the kernels in Numba's cache a run loads their machine code alone: none of the
    implementations a compilation would install (typed containers, NumPy's random generators:
    0.1-0.2 s) is imported (rollspring.simulate._load_cached_kernels_lightly; the compiled
    setup of level systems, kernels.level_setup, once loaded with the whole compiler)."""
    probe = (
        "import atexit, sys\n"
        "atexit.register(lambda: sys.stderr.write('COMPILER ' + ' '.join(sorted(m for m in "
        "sys.modules if m.startswith(('numba.typed.', 'numba.np.random'))))))\n"
    )
    warm = command("simulate", "wall-hoop-cylinder", "-T", "1", "--json")
    subprocess.run([sys.executable, "-c", warm], capture_output=True, check=True)  # the cache
    done = subprocess.run(
        [sys.executable, "-c", probe + warm], capture_output=True, text=True, check=True
    )
    line = [x for x in done.stderr.splitlines() if x.startswith("COMPILER")]
    assert line == ["COMPILER "], done.stderr[-2000:]
