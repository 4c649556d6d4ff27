"""Periodic responses of machines of several lines (issue 15): one spool's unbalance turns
at its own speed ``r W``; two spools' unbalances together give a torus of their two 1X
frequencies, with the inter-shaft bearing's rolling elements frozen (their varying
compliance would be a third frequency) and the result saying so."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.model.lines import ShaftLine

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
HP_DISK = 7
UNBALANCE = [(HP_DISK, 2e-5, 0.0)]


def _machine(r_lp: float, r_hp: float) -> rs.Rotor:
    """An LP shaft on two supports and an HP rigid disk riding on it through a 9-ball
    inter-shaft bearing with 2 um clearance."""
    ball = rs.BallBearing(n_balls=9, pitch_diameter=0.05, ball_diameter=0.01, Kn=8e9,
                          f_i=0.52, f_o=0.52, radial_clearance=2e-6)
    lp = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL)] * 6
    lines = [ShaftLine("LP", lp, speed_ratio=r_lp), ShaftLine("HP", [], z0=0.3,
                                                             speed_ratio=r_hp)]
    disks = [rs.DiskElement(n=3, m=8.0, Id=0.04, Ip=0.07, tag="lp"),
             rs.DiskElement(n=HP_DISK, m=4.0, Id=0.02, Ip=0.035, tag="hp")]
    supports = [rs.BearingElement(n=0, kxx=3e7, kzz=1e8, cxx=300.0, tag="a"),
                rs.BearingElement(n=6, kxx=3e7, cxx=300.0, tag="b"),
                rs.BearingElement(n=HP_DISK, kzz=1e8, krr=1e6, cxx=100.0, tag="thrust")]
    inter = rs.RollingBearing(ball, n=HP_DISK, n_link=3, tag="inter",
                              contact_damping="proportional", damping_factor=2e-5)
    return rs.Rotor([], disks, supports, lines=lines, nonlinear_elements=[inter])


def _branch(rotor: rs.Rotor, start: float, stop: float,
            direction: tuple[float, float, float] = (0.0, -1.0, 0.0)) -> rs.PeriodicResult:
    return rs.periodic(rotor, start=start, stop=stop, unbalance=UNBALANCE, harmonics=2,
                       varying_compliance=False,
                       excitation=rs.Excitation(gravity=9.81, direction=direction),
                       continuation=rs.ContinuationOptions(max_points=40))


@pytest.mark.verification
def test_a_spool_unbalance_equals_the_same_machine_referenced_to_that_spool() -> None:
    """The HP unbalance of the machine at ratios (1, 1.45) over W is the HP unbalance of
    the same machine at ratios (1/1.45, 1) over 1.45 W: the same physical motion."""
    ahead = _branch(_machine(1.0, 1.45), 220.0, 235.0)
    again = _branch(_machine(1.0 / 1.45, 1.0), 220.0 * 1.45, 235.0 * 1.45)
    assert ahead.status == again.status == rs.Status.OK
    for W in (222.0, 228.0, 233.0):
        a = np.interp(W, ahead.parameter, ahead.amplitude(HP_DISK, "ux"))
        b = np.interp(1.45 * W, again.parameter, again.amplitude(HP_DISK, "ux"))
        # both branches converge to the corrector tolerance; the interpolation between
        # points differs (other steps), so compare at 1e-6 of the amplitude
        assert a == pytest.approx(b, rel=1e-6)


@pytest.mark.validation
@pytest.mark.parametrize("ratio", [1.45, -1.3])
def test_the_periodic_unbalance_force_turns_with_its_spool(ratio: float) -> None:
    """The harmonic-balance load of an unbalance ``me`` at angle ``a`` on a spool at ratio
    ``r``, sampled over one period of ``|r| W``, is ``me (r W)^2 [cos(r W t + a),
    sin(r W t + a)]`` (closed form; backwards in the fixed frame for ``r < 0``)."""
    from rotorsim.analyses.periodic.excitation import plan_excitation
    from rotorsim.analyses.periodic.problem import PeriodicLoads

    me, a, W, phi0 = 2e-5, 0.4, 230.0, 0.3
    plan = plan_excitation((), unbalance=True, base=None, varying_compliance=None,
                           fundamental=None, frequency_parameter=False,
                           unbalance_ratio=ratio)
    assert plan.order == pytest.approx(abs(ratio)) and plan.unbalance_harmonic == 1
    amp = np.array([me * np.exp(1j * a), -1j * me * np.exp(1j * a)])
    loads = PeriodicLoads(np.zeros(2), amp, None, None, plan, phi0)
    coefficients = loads(plan.order * W, 0.0)   # omega = order W
    t = np.linspace(0.0, 2 * np.pi / (abs(ratio) * W), 7)
    tau = abs(ratio) * W * t
    fx = coefficients[1, 0] * np.cos(tau) + coefficients[2, 0] * np.sin(tau)
    fy = coefficients[1, 1] * np.cos(tau) + coefficients[2, 1] * np.sin(tau)
    angle = ratio * (W * t + phi0) + a
    force = me * (ratio * W) ** 2
    np.testing.assert_allclose(fx, force * np.cos(angle), atol=1e-12 * force)
    np.testing.assert_allclose(fy, force * np.sin(angle), atol=1e-12 * force)


def test_two_spools_unbalances_give_a_torus_with_the_rolling_elements_frozen() -> None:
    res = rs.periodic(_machine(1.0, 1.45), start=220.0, stop=230.0,
                      unbalance=[*UNBALANCE, (3, 1e-5, 0.0)], harmonics=2,
                      continuation=rs.ContinuationOptions(max_points=6))
    assert isinstance(res, rs.QuasiPeriodicResult) and res.second == "spool"
    assert res.vc_order == pytest.approx(1.45, rel=1e-15)
    assert "frozen" in res.approximation and "third frequency" in res.approximation
    assert res.speed[-1] == pytest.approx(230.0, rel=1e-12)
    # each spool's own 1X dominates at its disk
    hp, lp = res.tone(HP_DISK, "ux", 0, 1), res.tone(3, "ux", 1, 0)
    assert np.all(np.abs(hp) > np.abs(res.tone(HP_DISK, "ux", 1, 0)))
    assert np.all(np.abs(lp) > 0.0)
