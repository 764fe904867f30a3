"""The sweep's ``stationary_amplitude`` is half the range of X̂ (docs/sweeps.md) on every path:
the batch measured it on (M11)'s weights (1 + gamma) m whatever the system, 2000 times X̂'s
for the paper's Fig. 3 system (springs at the percussion points, X̂ on (M14)'s weights 1/2,
1/2) and a number for a system between walls, which has no X̂; ``--on-slip continue`` (each run
alone through simulate) measured X̂. Both now agree, and agree with simulate's own X̂."""

from __future__ import annotations

import numpy as np
import pytest

import rollspring
from rollspring import simulate_batch
from rollspring.service.sweeps import sweep

VARY = {"springs.0.stiffness": [100.0, 120.0]}


def _simulated(system: str, stiffness: float) -> float:
    """Half the range of simulate's X̂ (M14), its uniform motion removed."""
    from rollspring.model import system_from_dict, system_to_json

    data = system_to_json(rollspring.load_system(system))
    data["springs"][0]["stiffness"] = stiffness
    model = system_from_dict(data)
    run = rollspring.simulate(model, 2.0, rtol=1e-10)
    weights = rollspring.analyze(model).stationary_weights
    v0 = np.array([b.v for b in model.bodies])
    stationary = run.stationary_x - float(weights @ v0) * run.t
    return 0.5 * float(np.ptp(stationary))


@pytest.mark.parametrize("system", ["frictionless", "hoop-cylinder"])
def test_stationary_amplitude_is_x_hat_s_on_both_paths(system):
    stop = sweep(system, VARY, 2.0)
    go_on = sweep(system, VARY, 2.0, on_slip="continue")
    for j, k in enumerate(VARY["springs.0.stiffness"]):
        truth = _simulated(system, k)
        assert float(stop["stationary_amplitude"][j]) == pytest.approx(truth, rel=2e-3, abs=1e-9)
        assert float(go_on["stationary_amplitude"][j]) == pytest.approx(truth, rel=2e-3, abs=1e-9)
    if system == "frictionless":  # X-hat's weights are (M14)'s, not (1 + gamma) m
        assert np.allclose(stop["stationary_weight"].values, 0.5)
        assert np.all(stop["stationary_amplitude"].values < 1e-5)


def test_a_system_between_walls_has_no_stationary_amplitude():
    for on_slip in ("stop", "continue"):
        result = sweep("wall-hoop-cylinder", VARY, 2.0, on_slip=on_slip)
        assert np.all(np.isnan(result["stationary_weight"].values)), on_slip
        assert np.all(np.isnan(result["stationary_amplitude"].values)), on_slip


def test_simulate_batch_measures_x_hat_on_the_weights_given():
    system = rollspring.load_system("frictionless")
    k = np.array([90.0, 100.0, 110.0])
    weights = np.array([[0.5, 0.5], [0.3, 0.7], [np.nan, np.nan]])
    same = {"keep_trajectories": True, "n_output": 2001, "metric_every": 1}
    result = simulate_batch(
        system, {"springs.0.stiffness": k}, 1.0, stationary_weights=weights, **same
    )
    v0 = np.array([b.v for b in system.bodies])
    for run in range(2):
        w = weights[run]
        stationary = result.x[run] @ w - float(w @ v0) * result.t
        assert result.stationary_amplitude[run] == pytest.approx(
            0.5 * float(np.ptp(stationary)), rel=1e-3
        )
    assert np.isnan(result.stationary_amplitude[2])
    plain = simulate_batch(
        system,
        {"springs.0.stiffness": k},
        1.0,
        step=result.step,
        integrator=result.integrator,
        **same,
    )
    assert np.all(plain.stationary_amplitude > 100 * result.stationary_amplitude[0])
    assert np.array_equal(plain.cm_amplitude, result.cm_amplitude)  # only X-hat changed


@pytest.mark.parametrize("weights", [[True, False], ["a", "b"], [[0.5, 0.5, 0.5]], [0.5]])
def test_simulate_batch_refuses_weights_that_are_not_one_per_body(weights):
    from rollspring.errors import ModelError

    with pytest.raises(ModelError, match="stationary_weights: expected numbers of shape"):
        simulate_batch(
            "frictionless", {"springs.0.stiffness": [90.0, 100.0]}, 0.1, stationary_weights=weights
        )
