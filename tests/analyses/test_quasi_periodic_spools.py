"""Two spools: the unbalances of the reference line and of a spool at ``r W`` force a torus
of their two 1X frequencies (issue 17 item 3), computed by the same two-frequency harmonic
balance.

- Two rigid disks on isotropic springs, one per line (LP at the reference speed, HP
  counter-rotating at ``r = -1.3``), joined by a 1e-3 N/m link: each disk responds at its
  own spool's speed with the closed form ``me (r W)^2 / |k - m (r W)^2 + i c |r| W|``
  (as ``tests/validation/test_multi_shaft.py`` checks for ``rs.unbalance_response``),
  the HP disk whirling backwards.
- The same machine with the LP disk on a 9-ball bearing with 10 um clearance (cages held,
  gravity) and a 2e5 N/m inter-shaft link: the torus against ``rs.transient`` started on
  it (rtol 1e-6) over 0.06 s (18 HP revolutions), which stays on it. The LP journal's
  vertical motion (1 um peak-to-peak in the Hertz contact) is the slowest to converge in
  the box: its deviation is 0.32, 0.093, 0.014 and 0.0051 of the peak-to-peak at
  ``H = 3, 6, 8, 10`` (``scripts/spool_torus_convergence.py``), so the test uses
  ``H = 10`` and 1e-2. The bearing mixes the two spools into combination tones;
  ``rs.periodic`` returns the branch of tori, with a box ``(H, H)``.
"""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.errors import ModelError
from rotorsim.model.lines import ShaftLine
from rotorsim.results.quasi_periodic import QuasiPeriodicResult

M, K, C, ME, R = 10.0, 1e6, 200.0, 1e-4, -1.3
UNBALANCE = [(0, ME, 0.0), (1, ME, 0.0)]


def machine(rolling: bool = False, link: float = 1e-3) -> rs.Rotor:
    lines = [ShaftLine("LP", []), ShaftLine("HP", [], z0=0.5, speed_ratio=R)]
    disks = [rs.DiskElement(n=0, m=M, Id=0.05, Ip=0.02, tag="lp"),
             rs.DiskElement(n=1, m=M, Id=0.05, Ip=0.02, tag="hp")]
    bearings = [rs.BearingElement(n=n, kxx=0.0 if rolling and n == 0 else K, cxx=C, kzz=K,
                                  krr=1e5, czz=C, crr=2.0, tag=f"b{n}") for n in (0, 1)]
    weak = rs.BearingElement(n=0, n_link=1, kxx=link, tag="link")
    nonlinear = ()
    if rolling:
        ball = BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9,
                           f_i=0.52, f_o=0.52, diametral_clearance=10e-6, cage="fixed")
        nonlinear = (RollingBearing(ball, n=0, tag="lp"),)
    return rs.Rotor([], disks, [*bearings, weak], lines=lines, nonlinear_elements=nonlinear)


def test_each_disk_responds_at_its_spool_speed_and_whirl() -> None:
    speed = 240.0
    point = rs.quasi_periodic_point(machine(), speed, unbalance=UNBALANCE, harmonics=(2, 2),
                                    truncation="box",
                                    excitation=rs.Excitation(gravity=None))
    assert point.vc_frequency == pytest.approx(abs(R) * speed, rel=1e-15)
    for node, (k1, k2), ratio in ((0, (1, 0), 1.0), (1, (0, 1), R)):
        w = abs(ratio) * speed
        closed = ME * w**2 / abs(K - M * w**2 + 1j * C * w)
        # the 1e-3 N/m link perturbs the response by ~1e-9 relative
        assert point.amplitude(node, "ux", k1, k2) == pytest.approx(closed, rel=1e-7)
        t = np.linspace(0.0, 2 * np.pi / w, 64, endpoint=False)
        x, y = point.response(t, node, "ux"), point.response(t, node, "uy")
        turn = np.sign(np.mean(x * np.gradient(y, t) - y * np.gradient(x, t)))
        assert turn == np.sign(ratio)           # the HP disk whirls backwards


def test_a_torus_of_two_spools_on_a_rolling_bearing_is_the_response() -> None:
    rotor, speed = machine(rolling=True, link=2e5), 300.0
    point = rs.quasi_periodic_point(rotor, speed, unbalance=UNBALANCE, harmonics=(10, 10),
                                    truncation="box")
    assert point.rotor_problem.plan is not None and point.rotor_problem.plan.second == "spool"
    T = 0.06
    q0, v0 = point.state(0.0)
    run = rs.transient(rotor, T, speed=speed, unbalance=UNBALANCE, initial=(q0, v0),
                       rtol=1e-6, output=rs.Output(times=np.linspace(0.0, T, 1201)))
    # measured 1.2e-3 / 5.1e-3 (LP journal) and 4e-6 (HP disk): the box's truncation
    for node, dof, tol in ((0, "ux", 1e-2), (0, "uy", 1e-2), (1, "ux", 1e-4), (1, "uy", 1e-4)):
        got = run.displacement(node, dof)
        torus = point.response(run.t, node, dof)
        deviation = np.abs(got - torus).max() / np.ptp(torus)
        print(f"node {node} {dof}: deviation {deviation:.2e} of the peak-to-peak")
        assert deviation < tol
    # the bearing mixes the two spools: combination tones appear at the LP disk
    assert point.amplitude(0, "ux", 1, 1) > 1e-4 * point.amplitude(0, "ux", 1, 0)


def test_periodic_returns_the_tori_of_two_spools() -> None:
    res = rs.periodic(machine(rolling=True, link=2e5), start=290.0, stop=310.0, harmonics=4,
                      unbalance=UNBALANCE, continuation=rs.ContinuationOptions(max_points=30))
    assert isinstance(res, QuasiPeriodicResult) and res.second == "spool"
    assert res.approximation == "" and res.vc_order == pytest.approx(1.3, rel=1e-15)
    assert res.options["box"] == [4, 4]           # both spools force the bearing
    assert res.speed[-1] == pytest.approx(310.0, rel=1e-12)
    with pytest.raises(ModelError, match="reference line"):
        rs.quasi_periodic_point(machine(), 240.0, unbalance=[(1, ME, 0.0)])
