"""Run control of rotor transients: stop when steady (against the closed-form Jeffcott
response), reducers from ``rs.Output`` (against the recorded samples), velocities only on
request."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.transient.speed_profile import LinearSpeed
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model

M, K, ZETA = 2.5, 4.0e6, 0.02  # kg, N/m, damping ratio
WN = math.sqrt(K / M)
ME = 1e-4  # kg m


def jeffcott() -> rs.Rotor:
    """A point mass on an isotropic damped support: the Jeffcott rotor."""
    c = 2 * ZETA * math.sqrt(K * M)
    return rs.Rotor([], point_mass_elements=[rs.PointMass(n=0, m=M)],
                    bearing_elements=[rs.BearingElement(n=0, kxx=K, cxx=c)])


def jeffcott_response(t: np.ndarray, W: float) -> np.ndarray:
    """Exact ``x + i y`` of the Jeffcott rotor started at rest under the unbalance force
    ``me W^2 e^{i W t}``: steady orbit ``Z e^{iWt}`` plus free vibration decaying as
    ``exp(-zeta wn t)`` (roots ``s = -zeta wn +- i wd``)."""
    c = 2 * ZETA * math.sqrt(K * M)
    Z = ME * W**2 / (K - M * W**2 + 1j * c * W)
    wd = WN * math.sqrt(1 - ZETA**2)
    s1, s2 = -ZETA * WN + 1j * wd, -ZETA * WN - 1j * wd
    # z(0) = 0 and z'(0) = 0: C1 + C2 = -Z, s1 C1 + s2 C2 = -i W Z
    C1, C2 = np.linalg.solve(np.array([[1, 1], [s1, s2]]), np.array([-Z, -1j * W * Z]))
    return Z * np.exp(1j * W * t) + C1 * np.exp(s1 * t) + C2 * np.exp(s2 * t)


def stop_revolution(t, x, W, rtol, revolutions):
    """The criterion of rs.SteadyStop written out on samples: the revolution at whose end
    the peak-to-peak per revolution has changed by <= rtol of the largest for
    ``revolutions`` consecutive revolutions."""
    rev = np.floor(W * t / (2 * np.pi)).astype(int)
    closed = np.unique(rev)[:-1]  # the last revolution is still open
    p = np.array([np.ptp(x[rev == k], axis=0) for k in closed])
    settled = np.max(np.abs(np.diff(p, axis=0)), axis=1) <= rtol * p[1:].max(axis=1)
    streak = 0
    for k, ok in zip(closed[1:], settled, strict=True):
        streak = streak + 1 if ok else 0
        if streak >= revolutions:
            return int(k)
    return None


@pytest.mark.validation
def test_jeffcott_stops_when_its_free_vibration_has_decayed():
    """Issue 14: the stop revolution equals that of the same criterion applied to the
    closed-form response, and lies where the decay exp(-zeta wn t) predicts."""
    W, rtol, revs = 0.6 * WN, 1e-3, 3
    period = 2 * np.pi / W
    res = rs.transient(jeffcott(), 80 * period, period / 400, speed=W,
                       unbalance=[(0, ME, 0.0)], excitation=rs.Excitation(gravity=None),
                       initial="zero", steady=rs.SteadyStop(rtol=rtol, revolutions=revs))
    assert res.status == rs.Status.OK and res.stopped is not None
    stop = res.stopped["revolution"]
    # same criterion on the exact response at the same samples: the Newmark phase error
    # of the free vibration ((wd dt)^2 / 12 relative, 0.02 rad after 30 revolutions) may
    # move the stop by one revolution
    z = jeffcott_response(res.t, W)
    exact = stop_revolution(res.t, np.column_stack([z.real, z.imag]), W, rtol, revs)
    assert exact is not None and abs(stop - exact) <= 1
    assert res.t[-1] == pytest.approx((stop + 1) * period, abs=period / 400)
    # closed-form bracket: the peak-to-peak of a revolution changes by at most 4 A(t),
    # A = |C1| exp(-zeta wn t) the free vibration, against 2 |Z| of the orbit: settled for
    # sure once 4 A <= rtol 2 |Z|, plus the revolutions to confirm and the one in progress
    Z = abs(jeffcott_response(np.array([1e3]), W)[0])  # free vibration gone at t = 1000 s
    A0 = abs(jeffcott_response(np.array([0.0]), W)[0] - Z)  # = |C1 + C2| >= |C1|, |C2|
    t_sure = math.log(4 * 2 * A0 / (rtol * 2 * Z)) / (ZETA * WN) + (revs + 2) * period
    t_half = math.log(2 * A0 / (rtol * 2 * Z)) / (ZETA * WN) / 2
    assert t_half < res.t[-1] <= t_sure


def test_rolling_bearing_rotor_stops_when_steady_and_stays_so():
    """A rigid rotor on a ball bearing with clearance: its steady response is
    quasi-periodic (ball pass order 8 kappa = 3.2 beside the unbalance), so the peak-to-peak
    per revolution keeps wandering by ~1-2 %; the criterion stops once the start-up
    transient (20 % changes) is gone, and the response stays within a few rtol."""
    disk = rs.DiskElement(n=0, m=1.0, Id=2.5e-4, Ip=4.5e-4)
    ball = rs.BallBearing(n_balls=8, pitch_diameter=0.0385, ball_diameter=0.00794, f_i=0.52,
                          f_o=0.52, Kn=9.3e9, radial_clearance=10e-6, tag="B")
    damper = rs.BearingElement(n=0, kxx=0.0, cxx=1e3)
    rotor = rs.Rotor([], [disk], [damper], fixed=tuple((0, d) for d in ("uz", "rx", "ry",
                                                                         "rz"))
                     ).with_nonlinear([rs.RollingBearing(ball, n=0, tag="B")])
    W, rtol = 1000.0, 0.03
    period = 2 * np.pi / W
    kw = dict(speed=W, unbalance=[(0, 5e-4, 0.0)], output=rs.Output(
        every=50, reducers=("peak_to_peak",)))
    res = rs.transient(rotor, 40 * period, period / 100, **kw,
                       steady=rs.SteadyStop(rtol=rtol, revolutions=3))
    assert res.stopped is not None and res.stopped["revolution"] >= 3
    assert res.t[-1] == pytest.approx((res.stopped["revolution"] + 1) * period, rel=1e-9)
    # the reducer sees the same per-revolution peak-to-peak as the criterion
    p = res.reduced["peak_to_peak"]
    change = np.abs(np.diff(p[-4:], axis=0)).max(axis=1) / p[-3:].max(axis=1)
    assert np.all(change <= rtol) and res.stopped["relative_change"] <= rtol
    # and it stays steady: 20 more revolutions stay within a few rtol of the last one
    more = rs.transient(rotor, res.t[-1] + 20 * period, period / 100, initial=res, **kw)
    q = more.reduced["peak_to_peak"]
    assert q.shape[0] == 20 and np.abs(q - p[-1]).max() <= 3 * rtol * p[-1].max()


def test_steady_stop_checks_its_nodes():
    with pytest.raises(ModelError, match=r"transient\.steady\.nodes: node 3 outside"):
        rs.transient(jeffcott(), 0.01, 1e-4, speed=100.0, initial="zero",
                     excitation=rs.Excitation(gravity=None), steady=rs.SteadyStop(nodes=[3]))


@pytest.fixture(scope="module")
def rolling_rotor() -> rs.Rotor:
    model = load_model("models/rolling_ball.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings)


def _expected_reductions(res, after):
    sel = res.t >= after
    t, q = res.t[sel], res.q[sel]
    rev = np.floor(res.angle[sel] / (2 * np.pi))
    revs = np.unique(rev)
    if np.count_nonzero(rev == revs[-1]) == 1:  # the run ended on the first step of one
        revs = revs[:-1]
    nodes = res.amplitude_nodes
    amp = np.hypot(*(q[:, [res.column(n, d) for n in nodes]] for d in ("ux", "uy")))
    rms = np.sqrt(np.trapezoid(q**2, t, axis=0) / (t[-1] - t[0]))
    ptp = np.array([np.ptp(q[rev == k], axis=0) for k in revs])
    return {"max_abs": np.abs(q).max(axis=0), "rms": rms, "max_amplitude": amp.max(axis=0),
            "peak_to_peak": ptp, "peak_to_peak_revolution": revs}


@pytest.mark.parametrize("reduction", [None, 8])
def test_reducers_equal_the_reductions_of_the_samples(rolling_rotor, reduction):
    after = 0.001
    kw = dict(speed=LinearSpeed(0.0, 3000.0, 0.0, 0.004), nodes=[5], unbalance=[(5, 1e-5, 0)],
              reduction=reduction)
    out = rs.Output(reducers=("max_abs", "peak_to_peak", "max_amplitude", "rms"), after=after)
    every_step = rs.transient(rolling_rotor, 0.004, 2e-5, output=out, **kw)
    expected = _expected_reductions(every_step, after)
    assert list(every_step.reduced) == ["max_abs", "peak_to_peak", "peak_to_peak_revolution",
                                        "max_amplitude", "rms"]
    for key, value in expected.items():
        # the same numbers reduced in another order (trapezoid sums): round-off; after a
        # reduction the reducers see T x per step and the samples x T^T (other sums), so
        # DOFs near zero differ by round-off of the largest terms
        np.testing.assert_allclose(every_step.reduced[key], value, rtol=1e-12,
                                   atol=1e-13 * np.abs(value).max(), err_msg=key)
    assert every_step.amplitude_nodes.tolist() == [0, 5, 10]  # node 5 and the bearings
    sparse = rs.transient(rolling_rotor, 0.004, 2e-5, output=rs.Output(
        every=10**6, reducers=out.reducers, after=after), **kw)
    assert sparse.t.size == 2  # the first and last states only, the reducers see all steps
    for key in expected:
        np.testing.assert_array_equal(sparse.reduced[key], every_step.reduced[key])


def test_velocities_only_on_request_and_bearing_loads_unchanged(rolling_rotor):
    kw = dict(speed=300.0, nodes=[5], unbalance=[(5, 1e-5, 0.0)])
    plain = rs.transient(rolling_rotor, 0.002, 2e-5, **kw)
    with_v = rs.transient(rolling_rotor, 0.002, 2e-5, output=rs.Output(velocities=True), **kw)
    assert plain.v is None and with_v.v.shape == with_v.q.shape
    np.testing.assert_array_equal(plain.bearing_loads, with_v.bearing_loads)
    np.testing.assert_array_equal(plain.q, with_v.q)
    with pytest.raises(ModelError, match=r"Output\(velocities=True\)"):
        plain.velocity(5, "uy")
    assert with_v.velocity(5, "uy").shape == plain.t.shape


def test_reduced_run_keeps_physical_velocities_on_request(rolling_rotor):
    kw = dict(speed=300.0, nodes=[5], unbalance=[(5, 1e-5, 0.0)], reduction=8)
    with_v = rs.transient(rolling_rotor, 0.002, 2e-5, output=rs.Output(velocities=True), **kw)
    plain = rs.transient(rolling_rotor, 0.002, 2e-5, **kw)
    assert with_v.v.shape == with_v.q.shape and plain.v is None
    np.testing.assert_array_equal(plain.bearing_loads, with_v.bearing_loads)
    # the velocity is the derivative of the displacement: central differences of the
    # samples agree to O(dt^2) (a few 1e-3 of the velocity amplitude here)
    y, v = with_v.displacement(5, "uy"), with_v.velocity(5, "uy")
    dy = (y[2:] - y[:-2]) / (with_v.t[2:] - with_v.t[:-2])
    assert np.abs(dy - v[1:-1]).max() < 2e-2 * np.abs(v).max()


def test_reducer_options_are_checked():
    with pytest.raises(ModelError, match=r"Output\.reducers: expected distinct names"):
        rs.Output(reducers=("rms", "p2p"))
    with pytest.raises(TypeError, match=r"'velocities' moved to output=rs\.Output"):
        rs.transient(jeffcott(), 0.01, 1e-4, velocities=True)
    with pytest.raises(ModelError, match=r"periodic\.output\.reducers: not an option"):
        rs.periodic(jeffcott(), start=10.0, stop=20.0, output=rs.Output(reducers=("rms",)))


def test_bearing_loads_are_evaluated_in_chunks(rolling_rotor, monkeypatch):
    """Rigid-ring ball bearings evaluate each sample alone: chunks change nothing."""
    from rotorsim.analyses.transient import run_control

    kw = dict(speed=300.0, nodes=[5], unbalance=[(5, 1e-5, 0.0)])
    whole = rs.transient(rolling_rotor, 0.001, 2e-5, **kw)
    monkeypatch.setattr(run_control, "LOAD_CHUNK", 7)
    chunked = rs.transient(rolling_rotor, 0.001, 2e-5, **kw)
    np.testing.assert_array_equal(chunked.bearing_loads, whole.bearing_loads)
