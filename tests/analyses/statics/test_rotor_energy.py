"""The rotor's total potential energy: its gradient is the static residual, and its minimum
is the Newton equilibrium."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

import rotorsim as rs
from rotorsim.analyses.rigid_motions import free_rigid_motions, held_dofs
from rotorsim.analyses.statics.nonlinear_static import nominal_tangent
from rotorsim.analyses.statics.rotor_energy import RotorEnergy, energy_equilibrium
from rotorsim.analyses.statics.static import _applied_load
from rotorsim.assembly.loads import unit_direction
from rotorsim.errors import ModelError

MODELS = Path(__file__).resolve().parents[3] / "models"
FILES = ("rolling_ball", "rolling_tapered", "default")


def _rotor(name):
    model = rs.load_model(MODELS / f"{name}.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings)


def _energy(rotor):
    system = rs.assemble(rotor)
    f, _ = _applied_load(system, rotor.linear_part(), 9.80665, unit_direction((0, -1, 0)), ())
    K = system.matrices().K
    held = held_dofs(free_rigid_motions(system, sp.csr_matrix(K + nominal_tangent(system))))
    return system, f, held


@pytest.mark.parametrize("name", FILES)
def test_energy_gradient_is_the_static_residual(name):
    """Central differences of Pi against K q + r - f at a loaded state."""
    system, f, held = _energy(_rotor(name))
    keep = np.setdiff1d(np.arange(system.n_free), held)
    energy = RotorEnergy(system, f, 0.0, 0.0, keep)
    x = energy_equilibrium(system, f, held=held).q[keep] * 1.3  # off the minimum
    grad, _ = energy.gradient_and_tangent(x)
    nl_positions = np.flatnonzero(np.isin(keep, system.nonlinear.dofs))
    for j in nl_positions[:: max(1, nl_positions.size // 6)]:
        step = 1e-9 if keep[j] % 6 < 3 else 1e-8
        e = np.zeros_like(x)
        e[j] = step
        fd = (energy.value(x + e) - energy.value(x - e)) / (2 * step)
        assert fd == pytest.approx(grad[j], rel=1e-5, abs=1e-6 * np.abs(grad).max())


@pytest.mark.verification
@pytest.mark.parametrize("name", FILES)
def test_energy_minimum_is_the_newton_equilibrium(name):
    """Two independent formulations of the static problem: Newton with an energy line search
    on linearised bearings (rs.static default) and the minimum of the total potential
    energy (seed 000 for the whole rotor)."""
    rotor = _rotor(name)
    newton = rs.static(rotor)
    energy = rs.static(rotor, method="energy")
    scale = np.abs(newton.displacement).max()
    np.testing.assert_allclose(energy.displacement, newton.displacement, rtol=0,
                               atol=1e-9 * scale)
    np.testing.assert_allclose(energy.bearing_forces, newton.bearing_forces, rtol=0,
                               atol=1e-7 * np.abs(newton.bearing_forces).max())
    assert energy.options["method"] == "energy" and energy.options["hessian_min"] > 0


def test_unknown_static_method_is_refused():
    with pytest.raises(ModelError, match="method"):
        rs.static(_rotor("rolling_ball"), method="simplex")


def test_static_result_lists_the_rolling_element_loads():
    rotor = _rotor("rolling_ball")
    for method in ("newton", "energy"):
        res = rs.static(rotor, method=method)
        assert set(res.element_loads) == {"DE", "NDE"}
        for tag, loads in res.element_loads.items():
            b = next(el for el in rotor.nonlinear_elements if el.tag == tag).bearing
            psi, alpha = b.element_angles(0.0), res.contact_angles[tag]
            fy = float(np.sum(loads * np.cos(alpha) * np.sin(psi)))
            # the element loads add up to the load the bearing carries (half the weight)
            assert fy == pytest.approx(-9.80665 * rotor.m / 2, rel=1e-6)
