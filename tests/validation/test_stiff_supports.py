"""Pinned supports modelled as very stiff springs (1e20 and 1e30 N/m, usual practice).

Reference: the exact frequency equation of the simply supported Timoshenko beam (Han,
Benaroya & Wei, J. Sound Vib. 225 (1999) 935-988), :func:`beam_theory.simply_supported_frequency`.
Before issue 12 such supports made ``modal`` report bending modes as rigid-body modes (the
rigid tolerance scaled with the stiffest spring), fail with "matrix is singular to working
precision" on the sparse path, and report spurious negatively damped modes at 1e30 N/m.
"""

from __future__ import annotations

import numpy as np
import pytest
from beam_theory import cowper_solid, simply_supported_frequency

import rotorsim as rs

pytestmark = pytest.mark.validation

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
L, D, N_EL = 1.0, 0.05, 24
KAPPA = cowper_solid(STEEL.nu)
FE_TOLERANCE = (1e-5, 1e-4, 5e-4)
"""Relative discretisation error allowed for bending modes 1-3 with 24 cubic Timoshenko
elements. The error falls as h^2 under mesh halving (measured 8.2e-6, 1.3e-4, 6.3e-4 at 16
elements and 1.9e-6, 2.9e-5, 1.4e-4 at 32), so these bounds hold with a margin of about 2-3
while a lost or shifted mode fails by orders of magnitude."""


def _shaft() -> list[rs.ShaftElement]:
    return [rs.ShaftElement(L=L / N_EL, idl=0.0, odl=D, material=STEEL,
                            shear_coefficient=KAPPA) for _ in range(N_EL)]


def _exact(count: int) -> np.ndarray:
    area, inertia = np.pi * D**2 / 4, np.pi * D**4 / 64
    return np.array([simply_supported_frequency(j, L, STEEL.E, STEEL.G_s, STEEL.rho, area,
                                                inertia, KAPPA) for j in range(1, count + 1)])


@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("k_support", [1e20, 1e30])
def test_stiff_pinned_supports_give_the_simply_supported_frequencies(k_support, sparse):
    bearings = [rs.BearingElement(n=0, kxx=k_support), rs.BearingElement(n=N_EL, kxx=k_support)]
    result = rs.modal(rs.Rotor(_shaft(), [], bearings), 0.0, 6, sparse=sparse)
    # only the free axial translation and the free rotation about z are rigid
    assert result.rigid_body_modes == 2
    assert set(result.kind) == {"lateral"}
    # x/y pairs of the first three bending modes, each against the exact Timoshenko value
    error = result.wn.reshape(3, 2) / _exact(3)[:, None] - 1.0
    assert np.all(np.abs(error) < np.array(FE_TOLERANCE)[:, None]), error
    # undamped model: no damping at all, in particular no false instability
    # (eigen-solver accuracy ~1e-11 on lam; observed |zeta| <= 7e-13)
    assert np.abs(result.damping_ratio).max() < 1e-9
    assert result.notes == ()


@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("k_support", [1e20, 1e30])
def test_stiff_supports_agree_with_exact_constraints(k_support, sparse):
    """Penalty springs against the same shaft with ux, uy fixed: they differ by the penalty
    error ``~ k_shaft / k_support <= 1e-11``; the tolerance 5e-9 is the eigen-solver
    accuracy (ARPACK tol 1e-11 on ``mu``, amplified by the non-normal first-order operator:
    observed up to 7.2e-12)."""
    bearings = [rs.BearingElement(n=0, kxx=k_support), rs.BearingElement(n=N_EL, kxx=k_support)]
    springs = rs.modal(rs.Rotor(_shaft(), [], bearings), 300.0, 8, sparse=sparse)
    fixed = [(n, d) for n in (0, N_EL) for d in ("ux", "uy")]
    exact = rs.modal(rs.Rotor(_shaft(), fixed=fixed), 300.0, 8, sparse=sparse)
    np.testing.assert_allclose(springs.wn, exact.wn, rtol=5e-9)
    assert springs.whirl == exact.whirl
    assert springs.rigid_body_modes == exact.rigid_body_modes == 2


@pytest.mark.parametrize("k_support", [1e20, 1e30])
def test_four_element_cone_keeps_its_first_bending_pair(k_support):
    """The reported case: a 4-element cone on 1e20 N/m supports lost its lowest bending pair
    to the rigid-body modes (4 rigid instead of 2). Exact constraints give the reference."""
    od = np.linspace(0.08, 0.04, 5)
    shaft = [rs.ShaftElement(L=0.25, idl=0.02, odl=od[i], idr=0.02, odr=od[i + 1],
                             material=STEEL) for i in range(4)]
    springs = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=k_support),
                                   rs.BearingElement(n=4, kxx=k_support)])
    fixed = rs.Rotor(shaft, fixed=[(n, d) for n in (0, 4) for d in ("ux", "uy")])
    for sparse in (False, True):
        got, ref = rs.modal(springs, 0.0, 4, sparse=sparse), rs.modal(fixed, 0.0, 4)
        assert got.rigid_body_modes == 2
        np.testing.assert_allclose(got.wn, ref.wn, rtol=5e-9)  # reason as above


def test_campbell_on_penalty_supports_shows_no_false_instability():
    """The reported symptom at 1e30 N/m: a mode with zeta = -0.59. Undamped model: every
    log dec must be zero to solver accuracy (observed 3e-11), and at rest the tracks
    start on the exact simply supported frequencies (tolerance as FE_TOLERANCE)."""
    bearings = [rs.BearingElement(n=0, kxx=1e30), rs.BearingElement(n=N_EL, kxx=1e30)]
    result = rs.campbell(rs.Rotor(_shaft(), [], bearings), [0.0, 500.0, 1000.0], num_modes=6)
    assert np.abs(result.log_dec).max() < 1e-7
    error = np.sort(result.wd[0]).reshape(3, 2) / _exact(3)[:, None] - 1.0
    assert np.all(np.abs(error) < np.array(FE_TOLERANCE)[:, None]), error
