"""When the automatic path integrates by exponential collocation, and its fallback to
Radau IIA when the eigenbasis is refused."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
import rotorsim.time_integration.exponential_modes as modes
from rotorsim.analyses.transient.auto_exponential import harmonic_load
from rotorsim.analyses.transient.equation import rotor_problem
from rotorsim.analyses.transient.speed_profile import ConstantSpeed
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.system import assemble
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
UNBALANCE = [(2, 1e-5, 0.3)]


def rotor_on_balls():
    shaft = [rs.ShaftElement(L=0.05, idl=0.0, odl=0.03, material=STEEL) for _ in range(4)]
    disk = rs.DiskElement.from_geometry(n=2, material=STEEL, width=0.02, i_d=0.03, o_d=0.1)
    ball = BallBearing(n_balls=8, pitch_diameter=0.035, ball_diameter=0.007, Kn=8e9,
                       diametral_clearance=10e-6, f_i=0.52, f_o=0.52)
    bearings = [RollingBearing(ball, n=n, tag=t, contact_damping="proportional",
                               damping_factor=2e-5) for n, t in ((0, "A"), (4, "B"))]
    return rs.Rotor(shaft, [disk]), bearings


def test_constant_speed_takes_exponential_collocation_a_run_up_radau():
    rotor, bearings = rotor_on_balls()
    steady = transient(rotor, 1e-3, nonlinear=bearings, speed=800.0, unbalance=UNBALANCE,
                       rtol=1e-3, nodes=[2])
    ramp = rs.LinearSpeed(700.0, 800.0, t_start=0.0, t_stop=1e-3)
    run_up = transient(rotor, 1e-3, nonlinear=bearings, speed=ramp, unbalance=UNBALANCE,
                       rtol=1e-3, nodes=[2])
    assert steady.method == "exponential" and run_up.method == "radau5"


def test_the_harmonic_form_is_checked_against_the_loads():
    rotor, bearings = rotor_on_balls()
    system = assemble(rotor, bearings)
    profile = ConstantSpeed(800.0).bind(0.0, 1e-3)
    problem, loads = rotor_problem(system, profile, 0.0, rs.Excitation(unbalance=UNBALANCE))
    load = harmonic_load(problem, loads, profile, (0.0, 1e-3))
    assert load is not None
    for t in (0.0, 3.3e-4, 1e-3):  # the same force at any time, to round-off
        assert np.allclose(load(t), loads(t), rtol=0, atol=1e-12 * np.max(np.abs(loads(t))))
    ramp = rs.LinearSpeed(700.0, 800.0, t_start=0.0, t_stop=1e-3).bind(0.0, 1e-3)
    problem, loads = rotor_problem(system, ramp, 0.0, rs.Excitation(unbalance=UNBALANCE))
    assert harmonic_load(problem, loads, ramp, (0.0, 1e-3)) is None


def test_a_refused_eigenbasis_falls_back_to_radau(monkeypatch):
    def refuse(*args, **kwargs):
        raise modes.IllConditionedModes("eigenbasis of the linear part is ill-conditioned",
                                        "test")

    monkeypatch.setattr(modes.LinearModes, "build", refuse)
    rotor, bearings = rotor_on_balls()
    res = transient(rotor, 5e-4, nonlinear=bearings, speed=800.0, unbalance=UNBALANCE,
                    rtol=1e-3, nodes=[2])
    assert res.method == "radau5"
    with pytest.raises(modes.IllConditionedModes):  # no fallback outside the automatic path
        modes.LinearModes.build()
