"""rs.periodic against an independent reference: the steady state of rs.transient (Newmark
average acceleration, rotorsim.time_integration) on the same rotor.

Rotor: the Jeffcott rotor on ball bearings with clearance of ``test_periodic.py``
(unbalance response with two folds, 1244 and 1257 rad/s) and the same rotor balanced with
turning cages (varying compliance under gravity, fundamental ``Z kappa W``).

Tolerances: stable HB points and transient steady states agree within 0.5 % in
peak-to-peak amplitude (issue 7); the HB truncation error at H = 6-8 is < 2e-4
(``test_response_converges_in_harmonics_and_samples``) and Newmark with 64 steps per period
errs by ~(w dt)^2 / 12 = 8e-4 in phase, ~1e-4 in these amplitudes. Sweeps jump after they
pass a fold (a slow passage through a saddle-node lags behind it, more so the faster the
sweep): the lag must shrink when the rate is halved and stay below 0.5 % of the speed at
the rates used.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_periodic import UNBALANCE, jeffcott

import rotorsim as rs
from rotorsim.analyses.periodic.periodic import periodic
from rotorsim.analyses.transient.speed_profile import LinearSpeed
from rotorsim.analyses.transient.transient import transient

pytestmark = pytest.mark.verification
DISK = 1


@pytest.fixture(scope="module")
def hb():
    """The unbalance branch from 1190 to 1310 rad/s with all DOFs kept (transient starts)."""
    return periodic(jeffcott(), start=1190.0, stop=1310.0, unbalance=UNBALANCE, harmonics=6,
                    continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1))


def segments(res):
    """Indices of the lower, middle and upper branches (split at the two folds)."""
    i, j = sorted(f.index for f in res.events("fold"))
    idx = np.arange(len(res))
    return idx[: i + 1], idx[i + 1: j + 1], idx[j + 1:]


def run(rotor, speed, periods, steps, initial="static", unbalance=UNBALANCE):
    """Disk ``uy`` of a transient and the period [s] (``speed`` constant or a profile)."""
    w = speed if isinstance(speed, float) else max(speed.start, speed.stop)
    T = 2 * np.pi / w
    res = transient(rotor, periods * T, T / steps, speed=speed, unbalance=unbalance,
                    nodes=[DISK], initial=initial)
    return res, T


def last_ptp(res, T, periods=2):
    y = res.displacement(DISK, "uy")
    return float(np.ptp(y[res.t > res.t[-1] - periods * T]))


def branch_value(res, branch, speed):
    """HB peak-to-peak of the disk on one branch at ``speed`` (linear interpolation)."""
    p, a = res.parameter[branch], res.amplitude(DISK, "uy", "peak_to_peak")[branch]
    order = np.argsort(p)
    return float(np.interp(speed, p[order], a[order]))


def test_stable_points_agree_with_the_transient_steady_state(hb):
    """Below the folds, and on both stable branches where they coexist: transients started
    5 % off the HB orbit (velocity) settle on it. 96 steps per period: near the folds the
    response is steep in frequency and Newmark's period error (w dt)^2 / 12 = 3.6e-4 costs
    0.2 % of amplitude (0.9 % at 48 steps, second order)."""
    lower, middle, upper = segments(hb)
    assert hb.stable[lower].all() and hb.stable[upper].all() and not hb.stable[middle].any()
    ptp = hb.amplitude(DISK, "uy", "peak_to_peak")
    nearest = [lower[np.argmin(abs(hb.parameter[lower] - W))] for W in (1200.0, 1248.0)]
    nearest.append(upper[np.argmin(abs(hb.parameter[upper] - 1252.0))])
    rotor = jeffcott()
    for i in nearest:
        q0, v0 = hb.state(i)
        res, T = run(rotor, float(hb.parameter[i]), 40, 96, (q0, 1.05 * v0))
        settled = last_ptp(res, T) / float(np.ptp(res.displacement(DISK, "uy")[
            (res.t > res.t[-1] - 4 * T) & (res.t <= res.t[-1] - 2 * T)]))
        assert abs(settled - 1) < 1e-4
        assert last_ptp(res, T) == pytest.approx(ptp[i], rel=5e-3), hb.parameter[i]


def test_an_unstable_orbit_is_left_for_the_two_stable_ones(hb):
    """Floquet: the middle branch is a saddle (real multiplier > 1). Started on its orbit
    pushed 10 % of the way towards the lower or the upper orbit (states of the nearest
    branch points), the transient leaves it, once to the lower and once to the upper branch
    (within 0.5 %; 96 steps per period, as near the folds above)."""
    lower, middle, upper = segments(hb)
    i = middle[len(middle) // 2]
    W = float(hb.parameter[i])
    assert hb.max_multiplier[i] > 1.01
    q0, v0 = hb.state(i)
    ends = []
    for side in (lower, upper):
        q1, v1 = hb.state(int(side[np.argmin(abs(hb.parameter[side] - W))]))
        initial = (q0 + 0.1 * (q1 - q0), v0 + 0.1 * (v1 - v0))
        ends.append(last_ptp(*run(jeffcott(), W, 50, 96, initial)))
    ptp = hb.amplitude(DISK, "uy", "peak_to_peak")[i]
    assert abs(ends[0] / ptp - 1) > 0.1 and abs(ends[1] / ptp - 1) > 0.1
    assert ends[0] == pytest.approx(branch_value(hb, lower, W), rel=5e-3)
    assert ends[1] == pytest.approx(branch_value(hb, upper, W), rel=5e-3)


def jump_speed(res, level):
    """Mean speed of the first revolution whose peak-to-peak crosses ``level``."""
    y = res.displacement(DISK, "uy")
    rev = np.floor(res.angle / (2 * np.pi)).astype(int)
    revs = np.unique(rev)[1:-1]
    ptp = np.array([np.ptp(y[rev == k]) for k in revs])
    above = ptp > level
    k = int(np.flatnonzero(above != above[0])[0])
    return float(res.speed[rev == revs[k]].mean())


def test_jump_speeds_of_run_up_and_run_down_match_the_folds(hb):
    lower, _, upper = segments(hb)
    fold_down, fold_up = sorted(f.parameter for f in hb.events("fold"))
    level = 0.5 * (branch_value(hb, lower, fold_up) + branch_value(hb, upper, fold_up))
    rotor = jeffcott()
    # run-up on the lower branch (static start below the folds) at 25 rad/s^2
    up = LinearSpeed(1240.0, 1265.0, 0.02, 1.02)
    res, _ = run(rotor, up, 1.04 / (2 * np.pi / 1265.0), 32)
    W_up = jump_speed(res, level)
    assert fold_up <= W_up <= fold_up * 1.005
    # run-down on the upper branch (started on its orbit) at 40 and 20 rad/s^2
    i = upper[np.argmin(abs(hb.parameter[upper] - 1252.0))]
    lags = []
    for rate in (40.0, 20.0):
        W0 = float(hb.parameter[i])
        down = LinearSpeed(W0, 1232.0, 0.0, (W0 - 1232.0) / rate)
        res, _ = run(rotor, down, down.t_stop / (2 * np.pi / W0), 32, hb.state(i))
        lags.append(fold_down - jump_speed(res, level))
    assert 0 < lags[1] < lags[0] and lags[1] < 0.005 * fold_down


def test_varying_compliance_response_agrees_with_the_transient():
    """Balanced rotor, turning cages, gravity: the response is periodic at Z kappa W and
    HB's peak-to-peak VC vibration of the disk (tens of nm on a 10 um sag) matches the
    transient's steady state within 0.5 %."""
    rotor = jeffcott("rotating")
    res = periodic(rotor, start=1000.0, stop=1010.0, harmonics=8,
                   continuation=rs.ContinuationOptions(tol=1e-10, max_points=2),
                   nodes=[DISK])
    # ball-pass order of the inner ring: Z (1 - D / d_m) / 2 (9 balls, D = 7.94 mm,
    # d_m = 38.5 mm, contact angle 0)
    assert res.approximation == ""
    assert res.order == pytest.approx(9 / 2 * (1 - 0.00794 / 0.0385), rel=1e-12)
    T = 2 * np.pi / res.fundamental[0]
    tr = transient(rotor, 100 * T, T / 64, speed=1000.0, nodes=[DISK])
    assert last_ptp(tr, T) == pytest.approx(res.amplitude(DISK, "uy", "peak_to_peak")[0],
                                            rel=5e-3)
    assert np.mean(tr.displacement(DISK, "uy")[tr.t > 98 * T]) == pytest.approx(
        res.amplitude(DISK, "uy", "mean")[0], rel=1e-4)


def test_fold_map_matches_the_folds_of_a_branch_at_reduced_unbalance():
    """Folds continued in the forcing amplitude (extended system, seed 002 3.5.2.2) against
    the folds of an independent branch computed with 95 % of the unbalance."""
    mapped = periodic(jeffcott(), start=1190.0, stop=1310.0, unbalance=UNBALANCE, harmonics=6,
                      continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1), stability=None,
                      fold_map=True)
    curves = mapped.options["fold_map"]
    assert len(curves) == 2
    predicted = []
    for c in curves:
        f, p = np.array(c["forcing"]), np.array(c["parameter"])
        assert f[0] == 1.0 and f.min() < 0.95
        assert p[0] == pytest.approx(
            min((b.parameter for b in mapped.events("fold")), key=lambda v: abs(v - p[0])),
            rel=1e-9)
        predicted.append(float(np.interp(0.95, f[::-1], p[::-1])))
    reduced = [(n, 0.95 * me, a) for n, me, a in UNBALANCE]
    direct = periodic(jeffcott(), start=1190.0, stop=1330.0, unbalance=reduced, harmonics=6,
                      continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1), stability=None)
    folds = sorted(b.parameter for b in direct.events("fold"))
    np.testing.assert_allclose(sorted(predicted), folds, rtol=1e-4)


def test_clearance_branch_matches_speed_branches_at_fixed_clearances(hb):
    """rs.periodic_parameter: continuation in the bearing clearance at 1250 rad/s (inside
    the hysteresis of the 10 um branch) against independent rs.periodic solutions at fixed
    clearances 9 and 8 um; the clearance branch turns at a fold (coexistence ends)."""
    from test_periodic import ball

    from rotorsim.analyses.periodic.parameter import periodic_parameter
    from rotorsim.elements.rolling.element import RollingBearing

    def vary(c):
        return [RollingBearing(ball("fixed", clearance=c), n=n, tag=f"B{n}") for n in (0, 2)]

    W, base = 1250.0, jeffcott().linear_part()
    res = periodic_parameter(base, vary, speed=W, start=10e-6, stop=2e-6, unbalance=UNBALANCE,
                             harmonics=6, name="diametral clearance [m]",
                             continuation=rs.ContinuationOptions(max_points=80))
    folds = res.events("fold")
    assert len(folds) == 1 and 6e-6 < folds[0].parameter < 9e-6
    leg = slice(0, folds[0].index + 1)
    p, a = res.parameter[leg], res.amplitude(DISK, "uy", "peak_to_peak")[leg]
    for c in (9e-6, 8e-6):
        direct = periodic(base.with_nonlinear(vary(c)), start=W, stop=W + 0.5,
                          unbalance=UNBALANCE, harmonics=6,
                          continuation=rs.ContinuationOptions(max_points=2),
                          stability=rs.StabilityOptions(None, bifurcations=False))
        # linear interpolation between branch points: 1e-3
        assert np.interp(c, p[::-1], a[::-1]) == pytest.approx(
            direct.amplitude(DISK, "uy", "peak_to_peak")[0], rel=1e-3)
    # stability: the lower leg is stable; back at 10 um after the fold the branch is the
    # unstable middle response of the 10 um speed branch at 1250 rad/s
    assert res.stable[: folds[0].index].all() and not res.stable[-1]
    assert res.parameter[-1] == pytest.approx(10e-6)
    _, middle, _ = segments(hb)
    speeds = hb.speed[middle]
    amp = hb.amplitude(DISK, "uy", "peak_to_peak")[middle]
    order = np.argsort(speeds)
    assert res.amplitude(DISK, "uy", "peak_to_peak")[-1] == pytest.approx(
        np.interp(W, speeds[order], amp[order]), rel=2e-3)


def test_folds_tracked_in_the_clearance_match_a_branch_at_that_clearance():
    """A clearance-speed jump map (fold_map=ParameterMap): the folds of the 10 um branch
    continued in the clearance; where a curve reaches 9 um its speed matches the fold of an
    independent speed branch computed with 9 um bearings."""
    from test_periodic import ball

    from rotorsim.analyses.periodic.folds import ParameterMap
    from rotorsim.elements.rolling.element import RollingBearing

    def vary(c):
        return [RollingBearing(ball("fixed", clearance=c), n=n, tag=f"B{n}") for n in (0, 2)]

    mapped = periodic(jeffcott(), start=1190.0, stop=1310.0, unbalance=UNBALANCE, harmonics=6,
                      continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1), stability=None,
                      fold_map=ParameterMap(vary, 10e-6, 8.5e-6, "diametral clearance"))
    curves = mapped.options["fold_map"]["curves"]
    assert len(curves) == 2
    starts = sorted(c["parameter"][0] for c in curves)
    np.testing.assert_allclose(starts, sorted(f.parameter for f in mapped.events("fold")),
                               rtol=1e-9)
    direct = periodic(jeffcott().linear_part().with_nonlinear(vary(9e-6)), start=1150.0,
                      stop=1310.0, unbalance=UNBALANCE, harmonics=6,
                      continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1),
                      stability=None)
    folds = [f.parameter for f in direct.events("fold")]
    reached = [c for c in curves if min(c["mu"]) <= 9e-6]
    assert reached  # the upper fold's curve crosses 9 um (the lower one moves slowly)
    for c in reached:
        mu, p = np.array(c["mu"]), np.array(c["parameter"])
        speed = float(np.interp(9e-6, mu[::-1], p[::-1]))
        assert min(abs(speed - f) for f in folds) < 1e-4 * speed


def test_forcing_branch_matches_speed_branches_at_reduced_unbalance():
    """rs.periodic_parameter(rotor, "forcing"): the load (unbalance) amplitude as the
    continuation parameter at 1250 rad/s, against rs.periodic with 90 % and 60 % of it."""
    from rotorsim.analyses.periodic.parameter import periodic_parameter

    W = 1250.0
    res = periodic_parameter(jeffcott(), "forcing", speed=W, start=1.0, stop=0.3,
                             unbalance=UNBALANCE, harmonics=6, name="forcing fraction",
                             continuation=rs.ContinuationOptions(max_points=80))
    assert res.parameter[0] == pytest.approx(1.0) and res.parameter[-1] == pytest.approx(0.3)
    a = res.amplitude(DISK, "uy", "peak_to_peak")
    for frac in (0.9, 0.6):
        reduced = [(n, frac * me, ph) for n, me, ph in UNBALANCE]
        direct = periodic(jeffcott(), start=W, stop=W + 0.5, unbalance=reduced, harmonics=6,
                          continuation=rs.ContinuationOptions(max_points=2),
                          stability=rs.StabilityOptions(None, bifurcations=False))
        assert np.interp(frac, res.parameter[::-1], a[::-1]) == pytest.approx(
            direct.amplitude(DISK, "uy", "peak_to_peak")[0], rel=1e-3)
