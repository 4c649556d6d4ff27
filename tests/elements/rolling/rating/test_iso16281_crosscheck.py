"""ISO/TS 16281 of a deep-groove ball bearing against the reference values of an independent
open-source implementation (GitHub minzhun/ISO16281, ``Test_BallBearing.py``: 7 balls of
11.5 mm on a 43.5 mm pitch, f_i = 0.52, f_o = 0.53, E = 210 GPa, nu = 0.3, C = 23.4 kN;
its axial displacement is named after MASTA, the likely source of the values).

Only the printed numbers are used. Its ISO/TS 16281 spring constant is the Hertz constant
with the complete elliptic integrals, so rotorsim's exact Hertz must give the same
displacements; its raceway capacities use the nominal contact angle, rotorsim's the loaded
angle of each ball (docs/bearing_life.md), so the lives agree when rotorsim is given the
nominal angle and differ by the stated convention otherwise."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing

# (diametral clearance [m], load [Fx, Fy, Fz, Mx, My], reference (radial, axial) um, L10r)
CASES = [
    (0.0, [1000.0, 0, 0, 0, 0], (15.1101, None), 13163.019),
    (0.0, [0, 0, 1000.0, 0, 0], (None, 133.5381), 2222.7318),
    (10e-6, [1000.0, 0, 0, 0, 0], (21.223, None), 10795.7948),
    (10e-6, [0, 0, 1000.0, 0, 0], (None, 149.1717), 3115.8781),
    (10e-6, [1000.0, 0, 1000.0, 0, 0], (19.5923, 146.4603), 1630.5367),
]


def _bearing(clearance: float) -> rs.BallBearing:
    return rs.BallBearing.from_geometry(
        n_balls=7, pitch_diameter=43.5e-3, ball_diameter=11.5e-3, f_i=0.52, f_o=0.53,
        E_ball=210e9, nu_ball=0.3, E_ring=210e9, nu_ring=0.3, diametral_clearance=clearance,
        groove_center_radius="pitch")


@pytest.mark.parametrize(("clearance", "load", "deflection", "l10r"), CASES)
def test_displacements_and_lives_match_the_independent_implementation(clearance, load,
                                                                       deflection, l10r):
    b = _bearing(clearance)
    eq = rs.bearing_equilibrium(b, load)
    got = (eq.displacement[0] * 1e6, eq.displacement[2] * 1e6)
    for g, ref in zip(got, deflection, strict=True):
        if ref is not None:  # printed to 4-6 digits
            assert g == pytest.approx(ref, rel=5e-5)
    rated = RatedBearing(b, rs.RatingOptions(C=23400.0))
    nominal = rated.reference.life(eq.element_load[None], np.zeros((1, 7)))
    # +0.1 % in every case: the common capacity factor, calibrated here on C (ISO 281
    # reference case), against the printed constants of the standard there
    assert nominal.L10r[0] == pytest.approx(l10r * 1.001, rel=3e-4)
    loaded = rated.life(eq.displacement[None], eq.element_angles[None])
    if load[2] == 0.0:  # pure radial: the loaded angles are the nominal one
        assert loaded.L10r[0] == pytest.approx(nominal.L10r[0], rel=1e-9)
    else:  # axial load: the capacities at the loaded angles (20-30 deg) give 2-6 % more
        assert 1.02 < loaded.L10r[0] / l10r < 1.06
