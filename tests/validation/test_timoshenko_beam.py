"""Simply supported uniform beam: rotorsim shaft elements against the exact frequencies.

Reference: the exact frequency equation of the simply supported Timoshenko beam (Han,
Benaroya & Wei, J. Sound Vib. 225 (1999) 935-988), implemented in
:func:`beam_theory.simply_supported_frequency` and itself checked here against an
independent shooting solution of the beam differential equations.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from beam_theory import VariableBeam, cowper_solid, shooting_frequencies, simply_supported_frequency
from modal_matching import relative_error

from rotorsim.analyses.linear.modal import modal
from rotorsim.elements.shaft import ShaftElement
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
L, D = 1.0, 0.1  # stocky: L/d = 10, shear lowers mode 5 by 20 %
AREA, INERTIA = np.pi * D**2 / 4, np.pi * D**4 / 64
KAPPA = cowper_solid(STEEL.nu)
N_MODES = 5


def pinned_beam(n_elements: int, shear: bool = True, rotary: bool = True,
                planar: bool = True, d: float = D) -> Rotor:
    """Beam with ``ux = uy = 0`` at both ends (rotations free), no axial/torsional DOFs.

    ``planar`` also fixes ``uy, rx`` everywhere: bending in the x-z plane only, which
    halves the model for the convergence studies (the planes are checked equal below).
    """
    shaft = [ShaftElement(L=L / n_elements, idl=0.0, odl=d, material=STEEL,
                          shear_effects=shear, rotary_inertia=rotary, gyroscopic=False,
                          shear_coefficient=KAPPA) for _ in range(n_elements)]
    fixed = [(n, d) for n in (0, n_elements) for d in ("ux", "uy")]
    if planar:
        fixed += [(n, d) for n in range(n_elements + 1) for d in ("uy", "rx")]
    return Rotor(shaft, fixed=sorted(set(fixed)), tag="pinned_beam").without_axial_torsion()


@cache
def fe_frequencies(n_elements: int, shear: bool = True, rotary: bool = True,
                   d: float = D) -> np.ndarray:
    """First ``N_MODES`` bending frequencies [rad/s] in the x-z plane."""
    result = modal(pinned_beam(n_elements, shear, rotary, d=d), 0.0, N_MODES, sparse=False)
    assert result.rigid_body_modes == 0
    assert set(result.kind) == {"lateral"}
    return result.wd


def exact(shear: bool = True, rotary: bool = True, d: float = D) -> np.ndarray:
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    return np.array([simply_supported_frequency(n, L, STEEL.E, STEEL.G_s, STEEL.rho, area,
                                                inertia, KAPPA, shear, rotary)
                     for n in range(1, N_MODES + 1)])


def observed_order(errors_coarse: np.ndarray, errors_fine: np.ndarray) -> np.ndarray:
    """``log2(e_h / e_{h/2})`` for a mesh halving."""
    return np.log2(errors_coarse / errors_fine)


@pytest.mark.verification
def test_x_and_y_planes_agree():
    """The full lateral model gives each frequency twice (x-z and y-z planes)."""
    result = modal(pinned_beam(20, planar=False), 0.0, 2 * N_MODES, sparse=False)
    planes = result.wd.reshape(N_MODES, 2)
    np.testing.assert_allclose(planes[:, 0], planes[:, 1], rtol=1e-7)  # solver round-off
    np.testing.assert_allclose(planes[:, 0], fe_frequencies(20), rtol=1e-7)


@pytest.mark.validation
def test_frequency_equation_matches_the_differential_equation():
    """The closed form (derived for sin modes) equals a shooting solution of the ODEs."""
    beam = VariableBeam(L=L, d0=D, d1=D, E=STEEL.E, G=STEEL.G_s, rho=STEEL.rho)
    shot = shooting_frequencies(beam, ("pinned", "pinned"), N_MODES, omega_max=3.0e4,
                                n_scan=60)
    # both are exact: agreement to the root-finder tolerance (1e-10 relative)
    np.testing.assert_allclose(shot, exact(), rtol=1e-9)
    # and the Euler-Bernoulli limit is (n pi / L)^2 sqrt(E I / (rho A))
    eb = (np.arange(1, N_MODES + 1) * np.pi / L) ** 2 * np.sqrt(
        STEEL.E * INERTIA / (STEEL.rho * AREA))
    np.testing.assert_allclose(exact(shear=False, rotary=False), eb, rtol=1e-14)


@pytest.mark.validation
def test_timoshenko_20_elements_within_0p1_percent_at_l_over_d_50():
    """Issue requirement (first 5 frequencies within 0.1 % with 20 elements) on a beam of
    L/d = 50, where shear and rotary inertia still lower mode 5 by 1.19 %, i.e. more
    than 10 times the tolerance, so the check does test the Timoshenko terms.

    The requirement does not hold for stocky beams with this element class (constant shear
    strain per element, order-2 convergence with shear; see the next tests and
    docs/validation.md, case 1).
    """
    d = L / 50
    ref = exact(d=d)
    errors = relative_error(fe_frequencies(20, d=d), ref)
    assert np.all(errors < 1e-3), errors
    timoshenko_effect = 1.0 - ref[-1] / exact(shear=False, rotary=False, d=d)[-1]
    assert timoshenko_effect > 10 * 1e-3


@pytest.mark.validation
def test_stocky_beam_needs_54_elements_for_0p1_percent():
    """At L/d = 10 (shear lowers mode 5 by 20 %) the 0.1 % accuracy of the first 5 modes
    needs 54 elements (measured; 48 elements give 0.123 % on mode 5)."""
    errors_54 = relative_error(fe_frequencies(54), exact())
    errors_48 = relative_error(fe_frequencies(48), exact())
    assert np.all(errors_54 < 1e-3), errors_54
    assert errors_48[-1] > 1e-3


@pytest.mark.validation
def test_timoshenko_converges_from_above_at_second_order():
    """4, 8, 16, 32 elements: Rayleigh-Ritz upper bounds, observed order -> 2.

    The element interpolates a constant shear strain, so the shear energy (and the
    eigenvalue) error is O(h^2) (Strang & Fix, *An Analysis of the Finite Element Method*,
    1973, ch. 6: eigenvalue error ~ energy-norm error squared). Measured 2.02-2.04 between
    16 and 32 elements; 1.8 allows for the pre-asymptotic terms.
    """
    ref = exact()
    errors = np.array([(fe_frequencies(n) - ref) / ref for n in (4, 8, 16, 32)])
    assert np.all(errors > 0)
    assert np.all(np.diff(errors, axis=0) < 0)
    order = observed_order(errors[2], errors[3])
    assert np.all(order > 1.8), order


@pytest.mark.validation
@pytest.mark.parametrize("rotary", [False, True], ids=["euler_bernoulli", "rayleigh"])
def test_without_shear_converges_at_fourth_order(rotary):
    """Shear off: cubic Hermite bending with consistent mass, eigenvalue error O(h^4).

    Strang & Fix (1973): O(h^(2(k+1-m))) with k = 3, m = 2. Measured order 3.97-4.00
    between 16 and 32 elements for modes 1-3 (higher modes are pre-asymptotic at 16).
    """
    ref = exact(shear=False, rotary=rotary)
    errors = np.array([(fe_frequencies(n, False, rotary) - ref) / ref for n in (8, 16, 32)])
    assert np.all(errors > 0)
    order = observed_order(errors[1, :3], errors[2, :3])
    assert np.all(order > 3.8), order
    # the 20-element accuracy requirement holds for all five modes without shear
    assert np.all(relative_error(fe_frequencies(20, False, rotary), ref) < 1e-3)
