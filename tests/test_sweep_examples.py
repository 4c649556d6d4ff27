"""The sweep examples run in fast mode and their numbers agree with independent checks."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import monte_carlo_critical_speeds as monte_carlo  # noqa: E402
from examples import stability_map  # noqa: E402
from rotorsim.analyses.sweep.sweep import min_log_dec  # noqa: E402
from rotorsim.errors import Status  # noqa: E402


@pytest.fixture(scope="module")
def stability(tmp_path_factory):
    out = tmp_path_factory.mktemp("stability")
    return out, stability_map.main(fast=True, out=out)


def test_stability_map_is_stable_at_rest_and_unstable_above_an_onset_speed(stability):
    _, run = stability
    result = run["result"]
    assert result.status == Status.OK and run["figure"].stat().st_size > 20000
    log_dec = result.reshape("log_dec_min")          # (stiffness, speed)
    assert np.all(log_dec[:, 0] > 0)                 # no cross-coupling at rest
    assert np.all(log_dec[:, -1] < 0)                # unstable at the top speed, every k
    for row in log_dec:                              # one boundary: stable below, unstable above
        unstable = np.flatnonzero(row < 0)
        assert unstable.tolist() == list(range(unstable[0], row.size))
    # the onset rises with the support stiffness (higher first forward frequency)
    assert np.all(np.diff(run["onset_energy"]) > 0)


def test_stability_boundary_matches_the_energy_balance(stability):
    _, run = stability
    result = run["result"]
    step = float(np.diff(result.axis("speed"))[0])
    # the map's zero crossing is interpolated linearly between grid speeds: it can be off
    # by less than one grid step from the exact onset
    assert np.all(np.abs(run["onset_map"] - run["onset_energy"]) < step)
    # sharper: just below/above the energy-balance onset the modal log dec changes sign
    evaluate = min_log_dec("speed", 6, sparse=False)
    for k, onset in zip(result.axis("bearing_k")[::2], run["onset_energy"][::2], strict=True):
        rotor = stability_map.seal_rotor(stiffness=k)
        below = evaluate(rotor, {"speed": onset * (1 - 1e-4)})["log_dec_min"]
        above = evaluate(rotor, {"speed": onset * (1 + 1e-4)})["log_dec_min"]
        assert below > 0 > above, (k, onset, below, above)


def test_weaker_cross_coupling_moves_the_onset_up(tmp_path, stability):
    # swirl 0.1 instead of 0.5: onset where 0.1 W = w_f(W), about five times higher
    weak = stability_map.stability_sweep(tmp_path, fast=True, swirl=0.1)
    log_dec, speed = weak.reshape("log_dec_min"), weak.axis("speed")
    onset = np.array([stability_map.energy_balance_onset(k, swirl=0.1)
                      for k in weak.axis("bearing_k")])
    # the softest support (w_f about 40 rad/s) goes unstable near 400 rad/s, the others
    # not below the top speed of the map (600 rad/s)
    assert 350 < onset[0] < 450 and np.all(np.isnan(onset[1:]))
    assert np.all(log_dec[1:] > 0)
    np.testing.assert_array_equal(log_dec[0] < 0, speed > onset[0])
    assert onset[0] > 4 * stability[1]["onset_energy"][0]


def test_monte_carlo_mean_spread_and_sensitivity(tmp_path):
    run = monte_carlo.main(fast=True, out=tmp_path)
    assert run["result"].status == Status.OK and run["figure"].stat().st_size > 20000
    n, mean, se = int(run["n"]), run["mean"], run["std_error"]
    assert n == 200
    # sample mean vs the second-order prediction: within 4 standard errors (CLT)
    assert np.all(np.abs(mean - run["second_order_mean"]) < 4 * se)
    # and vs the nominal critical speeds: sampling error plus the small second-order bias
    bias = np.abs(run["second_order_mean"] - run["nominal"])
    assert np.all(np.abs(mean - run["nominal"]) < 4 * se + bias)
    # relative difference: 4 SE (0.2 % at n = 200) plus the 0.04 % bias stay below 0.3 %
    assert np.all(np.abs(mean / run["nominal"] - 1) < 3e-3)
    # spread vs the first-order (delta-method) prediction: within 4 standard errors of a
    # sample standard deviation, std / sqrt(2 (n - 1))
    std = run["std"]
    assert np.all(np.abs(std - run["linear_std"]) < 4 * std / np.sqrt(2 * (n - 1)))
    # stiffer bearings -> higher critical speeds
    assert np.all(run["correlation"] > 0)
