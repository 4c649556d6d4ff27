"""Disk-dominated rotors against closed forms: gyroscopic whirl split and Jeffcott rotor.

References
----------
- Rigid disk on a support with lateral stiffness k and tilting stiffness k_r: the
  translations give ``w = sqrt(k/m)``; the tilts obey ``Id w^2 -+ Ip W w - k_r = 0``, so
  ``w_F,B = (+-Ip W + sqrt((Ip W)^2 + 4 Id k_r)) / (2 Id)`` (Friswell et al. 2010,
  section 3.5; Genta, *Dynamics of Rotating Systems* 2005, ch. 4).
- Jeffcott rotor (reference README): critical speed ``sqrt(k/m)``; for a disk at mid-span
  of a massless simply supported shaft ``1/k = L^3/(48 E I) + L/(4 kappa G A)`` (bending
  plus shear deflection under a central load, Timoshenko & Gere).
"""

from __future__ import annotations

import numpy as np
import pytest
from beam_theory import cowper_solid
from modal_matching import relative_error

from rotorsim.analyses.linear.modal import modal
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

pytestmark = pytest.mark.validation

M, ID, IP = 20.0, 0.15, 0.28  # kg, kg m^2, kg m^2
K, KRR = 2e6, 4e5  # N/m, N m/rad
SPEEDS = (0.0, 500.0, 2000.0, 10000.0)  # rad/s; at 10000 the backward tilt drops below sqrt(k/m)

# The node carrying the disk needs a shaft element: a 10 mm long, 20 mm element of a
# near-massless material (3.1e-9 kg, 1.6e-10 of the disk mass; rotary inertia 1e-13 of Id).
# Its far node is free, so it adds no stiffness; its inertia shifts the frequencies by
# about half the mass ratio, ~1e-10 (measured 7.7e-11 on the translation pair, 6e-13 on
# the tilting pair). Tolerance 1e-8 covers this and the eigen-solver round-off.
GHOST = Material(name="ghost", E=1e9, nu=0.3, rho=1e-3)
RTOL = 1e-8


def disk_on_support() -> Rotor:
    shaft = [ShaftElement(L=0.01, idl=0.0, odl=0.02, material=GHOST)]
    disk = DiskElement(n=0, m=M, Id=ID, Ip=IP)
    support = BearingElement(n=0, kxx=K, krr=KRR)
    return Rotor(shaft, [disk], [support], tag="disk_on_support").without_axial_torsion()


def tilt_frequencies(speed: float) -> tuple[float, float]:
    """Backward and forward tilting frequencies [rad/s] from ``Id w^2 -+ Ip W w - k_r = 0``."""
    root = np.sqrt((IP * speed) ** 2 + 4.0 * ID * KRR)
    return (root - IP * speed) / (2.0 * ID), (root + IP * speed) / (2.0 * ID)


def split_modes(result) -> tuple[np.ndarray, np.ndarray, tuple[str, str]]:
    """Translation pair, tilting pair (sorted) and the tilting modes' whirl labels."""
    order = np.argsort(np.abs(result.wd - np.sqrt(K / M)))
    translation, tilt = order[:2], order[2:]
    tilt = tilt[np.argsort(result.wd[tilt])]
    whirl = (result.whirl[tilt[0]], result.whirl[tilt[1]])
    return result.wd[translation], result.wd[tilt], whirl


@pytest.mark.parametrize("speed", SPEEDS)
def test_translation_and_gyroscopic_tilt_split(speed):
    result = modal(disk_on_support(), speed, 4, sparse=False)
    assert result.rigid_body_modes == 0
    assert result.num_modes == 4
    np.testing.assert_allclose(result.log_dec, 0.0, atol=1e-8)
    translation, tilt, whirl = split_modes(result)
    np.testing.assert_allclose(translation, np.sqrt(K / M), rtol=RTOL)
    np.testing.assert_allclose(tilt, tilt_frequencies(speed), rtol=RTOL)
    # the split w_F - w_B = Ip W / Id (difference of the two roots)
    assert tilt[1] - tilt[0] == pytest.approx(IP * speed / ID, rel=RTOL, abs=1e-6)
    if speed > 0.0:  # at rest the tilting pair is degenerate and has no whirl direction
        assert whirl == ("backward", "forward")


def test_bearing_jeffcott_critical_speed():
    """Disk on a lateral spring: ``w = sqrt(k/m)`` at any speed; forward mode crosses 1X."""
    critical = np.sqrt(K / M)
    result = modal(disk_on_support(), critical, 4, sparse=False)
    near = np.abs(result.wd - critical) < 1e-6 * critical
    assert near.sum() == 2  # the translation pair, unaffected by gyroscopics


STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
SPAN, SHAFT_D, DISK_M = 0.8, 0.05, 30.0


def jeffcott_rotor(timoshenko: bool) -> Rotor:
    """Disk at mid-span of a near-massless, simply supported shaft (two elements)."""
    light = Material(name="light_steel", E=STEEL.E, G_s=STEEL.G_s, rho=1e-6)
    shaft = [ShaftElement(L=SPAN / 2, idl=0.0, odl=SHAFT_D, material=light,
                          shear_effects=timoshenko, rotary_inertia=timoshenko,
                          shear_coefficient=cowper_solid(STEEL.nu)) for _ in range(2)]
    disk = DiskElement(n=1, m=DISK_M, Id=0.2, Ip=0.35)
    pinned = [(n, d) for n in (0, 2) for d in ("ux", "uy")]
    return Rotor(shaft, [disk], fixed=pinned, tag="jeffcott").without_axial_torsion()


@pytest.mark.parametrize("timoshenko", [False, True], ids=["euler_bernoulli", "timoshenko"])
@pytest.mark.parametrize("speed", [0.0, 300.0])
def test_shaft_jeffcott_frequency(timoshenko, speed):
    area, inertia = np.pi * SHAFT_D**2 / 4, np.pi * SHAFT_D**4 / 64
    flexibility = SPAN**3 / (48.0 * STEEL.E * inertia)
    if timoshenko:
        flexibility += SPAN / (4.0 * cowper_solid(STEEL.nu) * STEEL.G_s * area)
    critical = np.sqrt(1.0 / (flexibility * DISK_M))
    result = modal(jeffcott_rotor(timoshenko), speed, 2, sparse=False)
    # the shaft element's static stiffness is exact (cubic/quadratic fields solve the
    # static beam equations); shaft mass 5e-11 of the disk mass; by symmetry the disk tilt
    # does not couple with its translation, so gyroscopics leave this pair unchanged.
    # The near-massless shaft ends make the mass matrix nearly singular: the dense solver
    # then uses its unscaled QZ companion form, with eigenvalues up to ~1e9 rad/s in the
    # same pencil; round-off measured up to 7.6e-9 here, hence 1e-7.
    assert np.all(relative_error(result.wd[:2], critical) < 1e-7)
