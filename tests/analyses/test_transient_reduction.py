"""Craig-Bampton reduction of rotor transients, nonlinear DOFs kept physical."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.nonlinear_static import nominal_tangent
from rotorsim.assembly.reduction import accuracy, craig_bampton
from rotorsim.errors import ModelError

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.fixture(scope="module")
def default_rotor():
    model = rs.load_model(MODELS / "default.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings), list(model.loads.unbalance)


def test_all_interior_modes_reproduce_the_full_system(default_rotor):
    rotor, _ = default_rotor
    system = rs.assemble(rotor)
    b = system.nonlinear.dofs
    full = craig_bampton(system, b, system.n_free - b.size)
    check = accuracy(system, full, nominal_tangent(system), n_check=10)
    assert check["max_relative_error"] < 1e-9
    few = accuracy(system, craig_bampton(system, b, 8), nominal_tangent(system), n_check=6)
    more = accuracy(system, craig_bampton(system, b, 16), nominal_tangent(system), n_check=6)
    assert more["max_relative_error"] < few["max_relative_error"] < 1e-2


@pytest.mark.validation
def test_reduced_transient_matches_the_full_one(default_rotor):
    rotor, unbalance = default_rotor
    kw = dict(speed=300.0, unbalance=unbalance, nodes=[8, 16])
    full = rs.transient(rotor, 0.03, 1e-4, **kw)
    red = rs.transient(rotor, 0.03, 1e-4, reduction=16, **kw)
    report = red.options["reduction"]
    assert report["size"] < full.dof_map.n_free / 4 and report["max_relative_error"] < 1e-4
    np.testing.assert_allclose(red.q[0], full.q[0], rtol=0, atol=1e-12)  # static start exact
    for node in (8, 16):
        y, y_ref = red.displacement(node, "uy"), full.displacement(node, "uy")
        assert np.abs(y - y_ref).max() < 1e-3 * np.ptp(y_ref)
    np.testing.assert_allclose(red.bearing_loads, full.bearing_loads, rtol=0,
                               atol=1e-3 * np.abs(full.bearing_loads).max())


def test_reduction_needs_nonlinear_dofs_and_a_valid_mode_count(default_rotor):
    rotor, _ = default_rotor
    with pytest.raises(ModelError, match="nonlinear"):
        rs.transient(rotor.linear_part().with_bearings(
            [rs.BearingElement(n=0, kxx=1e8), rs.BearingElement(n=24, kxx=1e8)]),
            0.001, 1e-4, reduction=4, gravity=None, initial="zero")
    with pytest.raises(ModelError, match="n_modes"):
        rs.transient(rotor, 0.001, 1e-4, reduction=10_000)
