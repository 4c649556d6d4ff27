"""Rotor transients: linear steady state against the frequency response, loads, speed
profiles, nonlinear bearings, resume and faults."""

from __future__ import annotations

import numpy as np
import pytest
from transient_interrupt import resumed_run

import rotorsim as rs
from rotorsim.analyses.linear.frequency_response import unbalance_response
from rotorsim.analyses.transient.loads import BaseExcitation
from rotorsim.analyses.transient.speed_profile import LinearSpeed, SpeedFunction
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.system import assemble
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.io.model_file import load_model
from rotorsim.time_integration.newmark import Newmark

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _rotor(c: float = 2e3) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(6)]
    disk = rs.DiskElement.from_geometry(n=3, material=STEEL, width=0.03, i_d=0.04, o_d=0.2)
    bearings = [rs.BearingElement(n=0, kxx=2e7, kyy=3e7, cxx=c, cyy=c),
                rs.BearingElement(n=6, kxx=2e7, kyy=3e7, cxx=c, cyy=c)]
    return rs.Rotor(shaft, [disk], bearings)


def _rolling_model():
    return load_model("models/rolling_ball.toml")


@pytest.mark.verification
def test_linear_steady_state_matches_unbalance_response():
    """Issue 6: amplitude and phase within 0.5 % of the frequency-domain solution."""
    rotor, W, unb = _rotor(), 400.0, [(3, 2e-4, 0.7)]
    period = 2 * np.pi / W
    t_end = 60 * period
    res = transient(rotor, t_end, period / 200, speed=W, unbalance=unb,
                    excitation=rs.Excitation(gravity=None),
                    output=rs.Output(times=np.linspace(t_end - 10 * period, t_end, 2001)),
                    initial="zero", nodes=[3])
    ref = unbalance_response(rotor, [W], unb)
    for dof in ("ux", "uy"):
        x = res.displacement(3, dof)
        basis = np.column_stack([np.cos(W * res.t), -np.sin(W * res.t), np.ones_like(res.t)])
        a, b, _ = np.linalg.lstsq(basis, x, rcond=None)[0]
        X = complex(a, b)  # x = Re(X e^{i W t})
        X_ref = ref.response[0, ref.dof_map.index(3, dof), 0]
        assert abs(abs(X) / abs(X_ref) - 1) < 5e-3
        assert abs(np.angle(X / X_ref)) < 5e-3


def test_unbalance_angular_acceleration_term_is_the_reaction_of_the_eccentric_mass():
    """The force is -me d2/dt2 [cos, sin](phi + a), checked by finite differences of the
    position of the eccentric mass along a quadratic-in-time angle."""
    me, a, W0, alpha = 1e-3, 0.3, 50.0, 400.0
    system = assemble(_rotor())
    res_loads = _loads(system, LinearSpeed(W0, W0 + alpha, 0.0, 1.0), [(3, me, a)])
    phi = lambda t: W0 * t + 0.5 * alpha * t * t  # noqa: E731
    pos = lambda t: me * np.array([np.cos(phi(t) + a), np.sin(phi(t) + a)])  # noqa: E731
    ix, iy = system.dofs_of(3, ("ux", "uy"))
    for t in (0.1, 0.37, 0.8):
        h = 1e-5
        acc = (pos(t + h) - 2 * pos(t) + pos(t - h)) / h**2
        f = res_loads(t)
        # central difference: truncation h^2 W^2 / 12 ~ 1e-7 and round-off ~1e-6
        np.testing.assert_allclose([f[ix], f[iy]], -acc, rtol=1e-5)
        tangential = me * alpha  # the W' term, far above the tolerance
        assert tangential > 100 * 1e-5 * np.abs(acc).max()


def _loads(system, profile, unbalance):
    from rotorsim.analyses.transient.equation import rotor_problem as _problem

    bound = profile.bind(0.0, 1.0)
    _, loads = _problem(system, bound, 0.0, rs.Excitation(unbalance, gravity=None))
    return loads


def test_speed_profiles_angle_and_rejects_nan():
    ramp = LinearSpeed(10.0, 110.0, t_start=1.0, t_stop=3.0).bind(0.0, 5.0)
    assert ramp.angle(1.0) == pytest.approx(10.0)
    assert ramp.angle(3.0) == pytest.approx(10.0 + 2 * 60.0)
    assert ramp.acceleration(2.0) == pytest.approx(50.0)
    f = SpeedFunction(lambda t: 100.0 + 30.0 * np.sin(3.0 * t)).bind(0.0, 2.0, 64)
    exact = 100.0 * 1.37 + 10.0 * (1 - np.cos(3.0 * 1.37))
    assert f.angle(1.37) == pytest.approx(exact, rel=1e-12)
    assert f.acceleration(0.5) == pytest.approx(90.0 * np.cos(1.5), rel=1e-7)
    with pytest.raises(ModelError, match="SpeedFunction"):
        SpeedFunction(lambda t: np.nan if t > 0.5 else 1.0).bind(0.0, 1.0)


@pytest.mark.validation
def test_base_excitation_of_a_rigidly_mounted_rotor_is_a_rigid_motion():
    """A rotor on stiff supports follows its base: relative motion ~ w^2/wn^2 of the base
    amplitude (single-DOF transmissibility, below resonance)."""
    rotor, amp, w = _rotor(c=0.0), 1e-4, 30.0
    res = transient(rotor, 0.5, 2e-4,
                    excitation=rs.Excitation(base=BaseExcitation.harmonic(amp, w), gravity=None),
                    initial="zero", nodes=[3])
    rel = np.max(np.abs(res.displacement(3, "uy")))
    wn = rs.modal(rotor, speed=0.0, num_modes=4).wn
    wy = min(wn[wn > 0])
    assert 0 < rel < 3 * amp * (w / wy) ** 2


def test_local_tangents_give_the_dense_path_result():
    model = _rolling_model()
    kw = dict(speed=300.0, nodes=[5], unbalance=[(5, 1e-5, 0.0)])
    fast = transient(model.rotor.with_nonlinear(model.rolling_bearings), 0.004, 2e-5, **kw)
    system = assemble(model.rotor, model.rolling_bearings)
    from rotorsim.analyses.transient import loads as transient_loads

    original = transient_loads.RestoringForce.__call__

    def dense(self, q, v, t):
        r, K, C = original(self, q, v, t)
        return r, K.toarray(), C.toarray()

    transient_loads.RestoringForce.__call__ = dense
    try:
        slow = transient(system, 0.004, 2e-5, **kw)
    finally:
        transient_loads.RestoringForce.__call__ = original
    # two linear-algebra paths (low-rank update of a constant factorisation against a dense
    # factorisation per iteration): equal at the accuracy of the Newton iteration, whose
    # stopping test is max |dq| <= 1e-10 max |q| (Newmark default). Measured 4e-14 ... 3e-13
    # relative depending on the BLAS kernel.
    np.testing.assert_allclose(fast.q, slow.q, rtol=0, atol=1e-10 * np.abs(slow.q).max())
    assert fast.stats["factorizations"] == 2 and slow.stats["factorizations"] > 100


def test_balanced_rotor_on_ball_bearings_starts_in_equilibrium():
    model = _rolling_model()
    res = transient(model.rotor, 1e-3, 1e-5, nonlinear=model.rolling_bearings, speed=0.0,
                    nodes=[5])
    weight = 9.80665 * model.rotor.m
    total = res.bearing_loads[0, :, :2].sum(axis=0)
    np.testing.assert_allclose(total, [0.0, -weight], atol=1e-8 * weight)
    assert np.ptp(res.displacement(5, "uy")) < 1e-12
    # the static start (Newton on the whole system) equals rs.static's solution (Newton on
    # the linearised bearings with an energy line search)
    reference = rs.static(model.rotor.with_nonlinear(model.rolling_bearings)).displacement
    np.testing.assert_allclose(res.q[0], reference[res.dofs], rtol=0,
                               atol=1e-8 * np.abs(reference).max())


@pytest.mark.validation
def test_varying_compliance_frequency_in_the_spectrum():
    """Issue 6: a balanced rotor on ball bearings with clearance under gravity vibrates at
    the ball-pass frequency N_b kappa W and its harmonics."""
    model = _rolling_model()
    W = 400.0
    rb = model.rolling_bearings[0]
    f_vc = rb.bearing.n_elements * rb.bearing.kappa * W
    period = 2 * np.pi / f_vc
    res = transient(model.rotor, 40 * period, period / 64, nonlinear=model.rolling_bearings,
                    speed=W, nodes=[5], output=rs.Output(every=1))
    keep = res.t > 10 * period
    y = res.displacement(5, "uy")[keep]
    y = (y - y.mean()) * np.hanning(y.size)
    spec = np.abs(np.fft.rfft(y))
    freq = 2 * np.pi * np.fft.rfftfreq(y.size, res.t[1] - res.t[0])
    floor = np.median(spec)
    for harmonic in (1, 2):
        near = np.abs(freq - harmonic * f_vc) < 0.1 * f_vc
        peak = freq[near][np.argmax(spec[near])]
        assert peak == pytest.approx(harmonic * f_vc, rel=0.02)
        assert spec[near].max() > 30 * floor


def test_resume_equals_uninterrupted(tmp_path, monkeypatch):
    model = _rolling_model()
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    kw = dict(speed=LinearSpeed(0.0, 500.0, 0.0, 0.003), nodes=[5], unbalance=[(5, 1e-5, 0.0)])
    full = transient(rotor, 0.003, 2e-5, **kw)
    resumed = resumed_run(monkeypatch, tmp_path / "run.h5", 70, 25, rotor, 0.003, 2e-5, **kw)
    np.testing.assert_array_equal(resumed.q, full.q)
    np.testing.assert_array_equal(resumed.bearing_loads, full.bearing_loads)


@pytest.mark.parametrize("kwargs, match", [
    (dict(dt=0.0), "dt"),
    (dict(dt=-1e-4), "dt"),
    (dict(t_end=0.0), "t_end"),
    (dict(speed=lambda t: float("nan")), "SpeedFunction"),
    (dict(method="euler"), "method"),
    (dict(nodes=[99]), "node"),
    (dict(initial="hot"), "initial"),
])
def test_bad_input_is_rejected_up_front(kwargs, match):
    args = dict(t_end=0.01, dt=1e-4, excitation=rs.Excitation(gravity=None), initial="zero")
    args.update(kwargs)
    with pytest.raises(ModelError, match=match):
        transient(_rotor(), **args)


def test_diverging_run_reports_time_and_dof(tmp_path):
    model = _rolling_model()
    stepper = Newmark.average_acceleration(max_iter=2, newton_rtol=1e-14)
    path = tmp_path / "ck.h5"
    with pytest.raises(ConvergenceError, match=r"t = .* DOF"):
        transient(model.rotor, 0.01, 5e-4, nonlinear=model.rolling_bearings, speed=3000.0,
                  unbalance=[(5, 5e-3, 0.0)], method=stepper,
                  checkpoint=rs.Checkpointing(path, every=1))
    assert path.exists()


def test_linear_analyses_refuse_a_rotor_with_rolling_bearings():
    model = _rolling_model()
    rotor = rs.Rotor(model.rotor.shaft_elements, model.rotor.disk_elements,
                     [*model.rotor.bearing_elements, *model.rolling_bearings])
    assert len(rotor.nonlinear_elements) == 2 and not rotor.bearing_elements
    with pytest.raises(ModelError, match="linearize_rolling_bearings"):
        rs.modal(rotor, speed=0.0, num_modes=4)
    lin = rs.linearize_rolling_bearings(rotor)
    assert len(lin.rotor.bearing_elements) == 2 and not lin.rotor.nonlinear_elements
    assert rs.modal(lin.rotor, speed=0.0, num_modes=4).wn.size == 4


def test_memory_is_bounded_by_the_output_not_the_number_of_steps():
    """Issue 6: a long run keeping one node does not grow with the number of steps."""
    import tracemalloc

    peaks = []
    for steps in (1_000, 10_000):
        tracemalloc.start()
        transient(_rotor(), steps * 1e-5, 1e-5, speed=300.0, unbalance=[(3, 1e-4, 0.0)],
                  excitation=rs.Excitation(gravity=None), output=rs.Output(every=10**9),
                  initial="zero", nodes=[3])
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    assert peaks[1] < 1.2 * peaks[0] + 200_000


def test_rolling_element_histories_add_up_to_the_bearing_load():
    model = _rolling_model()
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    res = transient(rotor, 0.002, 2e-5, speed=300.0, nodes=[5],
                    output=rs.Output(rolling_elements=True))
    b = model.rolling_bearings[0].bearing
    psi = b.element_angles(res.angle)
    loads, alpha = res.element_loads["DE"], res.contact_angles["DE"]
    assert loads.shape == (res.t.size, b.n_elements) and np.all(loads >= 0)
    fx = (loads * np.cos(alpha) * np.cos(psi)).sum(axis=1)
    fy = (loads * np.cos(alpha) * np.sin(psi)).sum(axis=1)
    # at rest (first sample) the bearing force is the elastic one: the element loads add up
    np.testing.assert_allclose([fx[0], fy[0]], res.bearing_loads[0, 0, :2], rtol=0,
                               atol=1e-9 * abs(res.bearing_loads[0, 0, 1]))
