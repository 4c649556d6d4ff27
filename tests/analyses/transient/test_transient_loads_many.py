"""The loads of the stages of a Runge-Kutta step in one call equal the loads at each time."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.transient.loads import TransientLoads
from rotorsim.analyses.transient.speed_profile import ConstantSpeed

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


@pytest.mark.parametrize("profile", [ConstantSpeed(600.0),
                                     rs.LinearSpeed(100.0, 900.0, 0.001, 0.003)])
@pytest.mark.parametrize("ratio", [None, "spools"])
def test_loads_of_several_times_equal_those_of_each_time(profile, ratio):
    n = 12
    rng = np.random.default_rng(3)
    unbalance = rng.standard_normal(n) + 1j * rng.standard_normal(n)
    loads = TransientLoads(n, profile.bind(0.0, 0.004), rng.standard_normal(n),
                           unbalance=unbalance,
                           unbalance_ratio=None if ratio is None else
                           np.repeat([1.0, -1.7], n // 2))
    times = np.array([0.0, 0.0011, 0.0015, 0.0027, 0.0039])
    each = np.stack([loads(float(t)) for t in times])
    # the same formula vectorised: equal up to the round-off of exp and the products
    np.testing.assert_allclose(loads.many(times), each, rtol=0,
                               atol=1e-14 * np.max(np.abs(each)))
