"""Linearly tapered shaft elements against independent references.

(a) A hollow truncated-cone cantilever against a shooting solution of the beam differential
    equations with variable ``E I(z)``, ``rho A(z)``, ``rho I(z)``, ``kappa G A(z)``
    (:mod:`beam_theory`; the solver itself is checked against Blevins' table and the
    simply supported Timoshenko closed form in the other validation files).
(b) The tapered rotor of ``examples/textbook_rotors.py`` against ROSS 3.1.0 on the
    identical model (:mod:`reference_ross`).
"""

from __future__ import annotations

import numpy as np
import pytest
from beam_theory import CANTILEVER_BETA_L_BLEVINS, VariableBeam, cowper_hollow, shooting_frequencies
from modal_matching import match_eigenvalues, relative_error
from reference_ross import ROSS
from scipy.integrate import quad

from examples.textbook_rotors import tapered_rotor
from rotorsim.analyses.linear.modal import modal
from rotorsim.elements.shaft import ShaftElement
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

pytestmark = pytest.mark.validation

STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
L, D0, D1, BORE = 1.0, 0.10, 0.05, 0.03  # cone frustum, clamped at the large end
N_MODES = 3
CLAMP = [(0, d) for d in ("ux", "uy", "uz", "rx", "ry", "rz")]


def cone_cantilever(n_elements: int, timoshenko: bool) -> Rotor:
    z = np.linspace(0.0, L, n_elements + 1)
    outer = D0 + (D1 - D0) * z / L
    shaft = [ShaftElement(L=L / n_elements, idl=BORE, odl=float(outer[i]), idr=BORE,
                          odr=float(outer[i + 1]), material=STEEL, shear_effects=timoshenko,
                          rotary_inertia=timoshenko, gyroscopic=False)
             for i in range(n_elements)]
    # bending in the x-z plane only (uy, rx fixed): the planes of a circular section are
    # identical, and the planar model keeps the dense eigen-solves small
    planar = [(n, d) for n in range(1, n_elements + 1) for d in ("uy", "rx")]
    return Rotor(shaft, fixed=CLAMP + planar, tag="cone_cantilever").without_axial_torsion()


def fe_errors(n_elements: int, timoshenko: bool, reference: np.ndarray) -> np.ndarray:
    result = modal(cone_cantilever(n_elements, timoshenko), 0.0, N_MODES, sparse=False)
    assert result.rigid_body_modes == 0
    return (result.wd - reference) / reference


def ode_reference(timoshenko: bool) -> np.ndarray:
    beam = VariableBeam(L=L, d0=D0, d1=D1, di0=BORE, di1=BORE, E=STEEL.E, G=STEEL.G_s,
                        rho=STEEL.rho, shear=timoshenko, rotary=timoshenko)
    return shooting_frequencies(beam, ("clamped", "free"), N_MODES, omega_max=9.0e3, n_scan=60)


def test_shooting_reproduces_the_uniform_cantilever():
    """The reference solver on a uniform beam gives Blevins' beta L (8 digits)."""
    d = 0.05
    beam = VariableBeam(L=1.0, d0=d, d1=d, E=STEEL.E, G=STEEL.G_s, rho=STEEL.rho,
                        shear=False, rotary=False)
    omega = shooting_frequencies(beam, ("clamped", "free"), 3, omega_max=5.0e3, n_scan=40)
    scale = np.sqrt(STEEL.E * (np.pi * d**4 / 64) / (STEEL.rho * np.pi * d**2 / 4))
    np.testing.assert_allclose(np.sqrt(omega / scale), CANTILEVER_BETA_L_BLEVINS[:3],
                               rtol=1e-8)


def test_euler_bernoulli_cone_converges_to_the_ode_at_fourth_order():
    """Exact static stiffness of the cone element (flexibility integrals) with the cubic
    Hermite consistent mass: O(h^4) (the mass interpolation error, Strang & Fix 1973).

    The stiffness and mass no longer come from one interpolation, so the FE values are not
    Rayleigh-Ritz upper bounds (modes 1-2 converge from below). Measured |errors| at 32
    elements 3.8e-8 / 1.0e-7 / 1.3e-6 (modes 1-3); order 4.0 / 4.1 / 3.9 between 16 and 32.
    """
    ref = ode_reference(timoshenko=False)
    errors = np.abs(np.array([fe_errors(n, False, ref) for n in (8, 16, 32)]))
    assert np.all(np.diff(errors, axis=0) < 0)
    order = np.log2(errors[1] / errors[2])
    assert np.all(order > 3.8), order
    assert np.all(errors[2] < 2e-6)


def test_timoshenko_cone_converges_to_the_ode():
    """Shear and rotary inertia on: monotone, asymptotic order 2 (the constant shear strain
    of the interpolation, as for the uniform element in test_timoshenko_beam).

    With the exact tapered stiffness the error constant is that of a uniform element:
    mode 1 is 2.5e-5 at 8 elements (it was 2.1e-3 with the earlier element-average shear
    parameter, and is 1.5e-5 for a uniform cantilever of the mean diameter). Measured
    |errors| at 64 elements 3.0e-7 / 5.8e-6 / 4.8e-5, order 2.0 between 32 and 64.
    """
    ref = ode_reference(timoshenko=True)
    errors = np.abs(np.array([fe_errors(n, True, ref) for n in (8, 16, 32, 64)]))
    assert np.all(np.diff(errors, axis=0) < 0)
    order = np.log2(errors[2] / errors[3])
    assert np.all(order > 1.8), order
    assert errors[0, 0] < 1e-4


def shear_flexibility_ratio(length: float, d_left: float, d_right: float) -> float:
    """Tip shear compliance of one clamped element over the exact ``int dz / (kappa G A)``.

    The element's shear compliance is its Timoshenko tip compliance minus its
    Euler-Bernoulli one (same cubic bending fields), loaded by a unit tip force.
    """
    compliance = []
    for shear in (False, True):
        el = ShaftElement(L=length, idl=BORE, odl=d_left, idr=BORE, odr=d_right,
                          material=STEEL, shear_effects=shear)
        tip = np.ix_([6, 10], [6, 10])  # ux, ry of the right node
        compliance.append(np.linalg.solve(el.matrices().K[tip], [1.0, 0.0])[0])

    def shear_compliance_density(z: float) -> float:
        outer = d_left + (d_right - d_left) * z / length
        area = np.pi / 4 * (outer**2 - BORE**2)
        return float(1.0 / (cowper_hollow(STEEL.nu, BORE / outer) * STEEL.G_s * area))

    exact = quad(shear_compliance_density, 0.0, length, epsabs=0.0, epsrel=1e-12)[0]
    return float((compliance[1] - compliance[0]) / exact)


def test_single_element_shear_flexibility():
    """One element, uniform or tapered, carries the exact shear compliance
    ``int dz / (kappa G A)`` of its frustum (its stiffness is the inverse of the exact
    cantilever flexibility; the earlier interpolation-based element captured only
    0.992 / 0.945 / 0.714 of it for 6 / 12.5 / 25 % diameter change)."""
    assert shear_flexibility_ratio(0.25, 0.075, 0.075) == pytest.approx(1.0, rel=1e-10)
    for length in (0.5, 0.25, 0.125):
        ratio = shear_flexibility_ratio(length, 0.1, 0.1 - 0.05 * length)
        assert ratio == pytest.approx(1.0, rel=1e-10)


# (b) ROSS 3.1.0 on the identical tapered rotor (with shear, 8 and 64 elements). ROSS's
# tapered element interpolates with a mid-element shear parameter and converges more
# slowly; both codes must approach the same limit, and rotorsim with 8 elements must be
# closer to ROSS's own 64-element solution than ROSS with 8 elements is.
def _ross(case: str, speed_rpm: float) -> dict:
    return ROSS[case][speed_rpm]


def _lateral(n_elements: int, speed_rpm: float) -> np.ndarray:
    # uz and rz do not couple with bending: fixing them leaves the lateral modes unchanged
    rotor = tapered_rotor(n_elements=n_elements).without_axial_torsion()
    return modal(rotor, speed_rpm * np.pi / 30.0, 14, sparse=False).eigenvalues


def _gap(computed: np.ndarray, reference: np.ndarray) -> np.ndarray:
    i, j = match_eigenvalues(reference, computed)
    order = np.argsort(i)
    return relative_error(computed[j[order]], reference[i[order]])


@pytest.mark.parametrize("speed_rpm", [0.0, 4000.0])
def test_tapered_rotor_converges_faster_than_ross(speed_rpm):
    ross64 = np.asarray(_ross("tapered_64", speed_rpm)["eigenvalues"])
    ross8 = np.asarray(_ross("tapered_8", speed_rpm)["eigenvalues"])
    ours8 = _lateral(8, speed_rpm)
    ours64 = _lateral(64, speed_rpm)
    ross_error_8 = _gap(ross8, ross64)  # ROSS's own 8-element error, measured 4e-4 .. 1e-2
    assert np.all(_gap(ours8, ross64) < ross_error_8)
    # same limit: the 64-element gap (measured <= 8e-5) is well inside ROSS's convergence
    assert np.all(_gap(ours64, ross64) < ross_error_8 / 10)


def test_tapered_rotor_whirl_agrees_with_ross():
    ref = _ross("tapered_64", 4000.0)
    result = modal(tapered_rotor(n_elements=64).without_axial_torsion(), 4000 * np.pi / 30,
                   14, sparse=False)
    i, j = match_eigenvalues(np.asarray(ref["eigenvalues"]), result.eigenvalues)
    assert [result.whirl[k] for k in j] == [ref["whirl"][k] for k in i]
