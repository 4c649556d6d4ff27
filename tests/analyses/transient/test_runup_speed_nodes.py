"""Run-ups without a factorisation per step (issue 14, part 3) and linear bearings whose
coefficients follow the speed in transients (part 4): the same steps as refactorising at
every speed, a frozen-speed run equal to the constant-speed one, an independent integration
of the run-up, resume, and the checks made before a run."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from transient_interrupt import resumed_run

import rotorsim as rs
from rotorsim.analyses.linear.frequency_response import unbalance_response
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.loads import unbalance_amplitudes
from rotorsim.assembly.system import assemble
from rotorsim.cli.main import main
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
TABLE = dict(frequency=[0.0, 500.0, 1500.0], kxx=[1e7, 2e7, 3e7], kyy=[2e7, 3e7, 4e7],
             cxx=[3e4, 2e4, 1e4], cyy=[4e4, 3e4, 2e4], kxy=[0.0, 2e6, 4e6],
             kyx=[0.0, -2e6, -4e6])
NO_GRAVITY = rs.Excitation(gravity=None)


def _rotor(tabulated: bool = True, **extra) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(6)]
    disk = rs.DiskElement.from_geometry(n=3, material=STEEL, width=0.03, i_d=0.04, o_d=0.25)
    coefficients = TABLE if tabulated else dict(kxx=2e7, kyy=3e7, cxx=2e3, cyy=3e3)
    bearings = [rs.BearingElement(n=n, tag=f"B{n}", **coefficients, **extra) for n in (0, 6)]
    return rs.Rotor(shaft, [disk], bearings)


def _rolling_rotor() -> rs.Rotor:
    model = load_model("models/rolling_ball.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings)


def _refactorised() -> rs.Newmark:
    return rs.Newmark(max_contraction=0.0)


def _scale(run) -> float:
    return float(np.max(np.ptp(run.q, axis=0)))


def _rolling_rotor_with_seal() -> rs.Rotor:
    """The rolling-bearing rotor with a seal tabulated over speed at mid-span: rolling
    tangents and speed terms in one low-rank update."""
    rotor = _rolling_rotor()
    seal = rs.BearingElement(n=5, tag="seal", **TABLE)
    return rotor.with_bearings([*rotor.bearing_elements, seal])


@pytest.mark.parametrize(("case", "agreement"), [
    # the Newton tolerance, 1e-10 of the largest |q| (here the gravity sag) per step, carried
    # over 500 steps through the contacts: measured 7.3e-8 of the motion
    ("rolling", 1e-6), ("rolling_seal", 1e-6),
    # an affine step is solved to theta^2 of its correction: measured 1.7e-12 and 1.1e-12
    ("linear", 1e-9), ("tabulated", 1e-9)])
def test_runup_reuses_factorisations_and_takes_the_same_steps(case, agreement):
    """The frozen-speed iteration converges to the same step equation: the samples differ
    from factorising at every speed only by the Newton tolerance, while the run factorises
    at a few speed nodes (21 and 49 instead of 501 and 1001)."""
    if case.startswith("rolling"):
        rotor = _rolling_rotor() if case == "rolling" else _rolling_rotor_with_seal()
        t_end, dt, unb = 0.01, 2e-5, [(5, 1e-5, 0.0)]
        kw = dict(nodes=[5])
    else:
        rotor, t_end, dt, unb = _rotor(case == "tabulated"), 0.05, 5e-5, [(3, 2e-4, 0.0)]
        kw = dict(nodes=[3], excitation=NO_GRAVITY, initial="zero")
    speed = rs.LinearSpeed(100.0, 600.0, 0.0, t_end)  # 1 rad/s per step or less
    nodes = transient(rotor, t_end, dt, speed=speed, unbalance=unb, **kw)
    every = transient(rotor, t_end, dt, speed=speed, unbalance=unb, method=_refactorised(),
                      **kw)
    steps = int(nodes.stats["steps"])
    assert every.stats["factorizations"] >= steps
    assert nodes.stats["factorizations"] <= 0.1 * steps
    np.testing.assert_allclose(nodes.q, every.q, rtol=0, atol=agreement * _scale(every))


def test_tabulated_bearings_at_a_frozen_speed_equal_the_constant_speed_run():
    """A 'ramp' from W to W takes the speed-dependent path (bearing forces from the tables at
    every step, low-rank update); a constant speed folds the bearings into the matrices once.
    Same equation, so the same samples up to round-off (measured 7e-15 of the motion)."""
    rotor, W, unb = _rotor(), 800.0, [(3, 2e-4, 0.3)]
    kw = dict(unbalance=unb, excitation=NO_GRAVITY, initial="zero", nodes=[3])
    frozen = transient(rotor, 0.03, 5e-5, speed=rs.LinearSpeed(W, W, 0.0, 0.03), **kw)
    constant = transient(rotor, 0.03, 5e-5, speed=W, **kw)
    assert frozen.stats["factorizations"] == constant.stats["factorizations"] == 2
    np.testing.assert_allclose(frozen.q, constant.q, rtol=0, atol=1e-8 * _scale(constant))


@pytest.mark.verification
def test_frozen_speed_steady_state_matches_the_frequency_domain_response():
    """At a frozen speed the 1X steady state of the speed-dependent path matches the
    unbalance response with the tables interpolated at that speed (an independent solve):
    0.5 % in amplitude and phase, the period error of the trapezoidal rule at 200 steps per
    revolution being 1e-4."""
    rotor, W, unb = _rotor(), 700.0, [(3, 2e-4, 0.7)]
    period = 2 * np.pi / W
    t_end = 60 * period
    res = transient(rotor, t_end, period / 200, speed=rs.LinearSpeed(W, W, 0.0, t_end),
                    unbalance=unb, excitation=NO_GRAVITY, initial="zero", nodes=[3],
                    output=rs.Output(times=np.linspace(t_end - 10 * period, t_end, 2001)))
    ref = unbalance_response(rotor, [W], unb)
    for dof in ("ux", "uy"):
        x = res.displacement(3, dof)
        basis = np.column_stack([np.cos(W * res.t), -np.sin(W * res.t), np.ones_like(res.t)])
        a, b, _ = np.linalg.lstsq(basis, x, rcond=None)[0]
        X, X_ref = complex(a, b), ref.response[0, ref.dof_map.index(3, dof), 0]
        assert abs(abs(X) / abs(X_ref) - 1) < 5e-3
        assert abs(np.angle(X / X_ref)) < 5e-3


def _smooth_runup(w0: float, w1: float, T: float) -> rs.SpeedFunction:
    """``W(t) = w0 + (w1 - w0) s(t / T)``, ``s(x) = 3 x^2 - 2 x^3``: no jump of ``W'`` at the
    start (a jump in the unbalance load would cost the trapezoidal rule its order)."""
    def speed(t: float) -> float:
        x = min(max(t / T, 0.0), 1.0)
        return w0 + (w1 - w0) * x * x * (3.0 - 2.0 * x)

    def derivative(t: float) -> float:
        x = min(max(t / T, 0.0), 1.0)
        return (w1 - w0) * 6.0 * x * (1.0 - x) / T

    return rs.SpeedFunction(speed, derivative)


def _reference_runup(rotor: rs.Rotor, speed: rs.SpeedFunction, unb, t_end: float, dof: int,
                     times: np.ndarray) -> np.ndarray:
    """The run-up integrated independently: first-order form with the global matrices
    assembled by the linear analyses' path at the table speeds and interpolated linearly
    between them (the tables' documented rule), scipy's Radau at rtol 1e-9 with its exact
    Jacobian (atol 1e-15 m and 1e-12 m/s: 1e-10 of the motion, 20 um and 0.03 m/s)."""
    system = assemble(rotor)
    bound = speed.bind(0.0, t_end)
    U = unbalance_amplitudes(system, unb)
    n = system.n_free
    Minv = np.linalg.inv(system.matrices(0.0).M.toarray())
    grid = np.asarray(TABLE["frequency"])
    tables = [system.matrices(float(w)) for w in grid]
    G = tables[0].G.toarray()

    def matrices(t):
        W = bound.speed(t)
        i = min(int(np.searchsorted(grid, W, side="right")) - 1, grid.size - 2)
        u = min(max((W - grid[i]) / (grid[i + 1] - grid[i]), 0.0), 1.0)
        K = (1 - u) * tables[i].K.toarray() + u * tables[i + 1].K.toarray()
        C = (1 - u) * tables[i].C.toarray() + u * tables[i + 1].C.toarray()
        return K, C + W * G

    def rhs(t, y):
        W, A, phi = bound.speed(t), bound.acceleration(t), bound.angle(t)
        K, D = matrices(t)
        f = (U * (W * W - 1j * A) * np.exp(1j * phi)).real
        return np.concatenate([y[n:], Minv @ (f - K @ y[:n] - D @ y[n:])])

    def jac(t, y):
        K, D = matrices(t)
        return np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ D]])

    sol = solve_ivp(rhs, (0.0, t_end), np.zeros(2 * n), method="Radau", jac=jac, rtol=1e-9,
                    atol=np.r_[np.full(n, 1e-15), np.full(n, 1e-12)], t_eval=times)
    assert sol.success
    return sol.y[dof]


@pytest.mark.verification
def test_runup_on_tabulated_bearings_matches_an_independent_integration():
    """Second-order convergence to the independent run-up: the error falls about 4x per
    halving of the step (measured 3.995 and 3.999), and is 9.2e-5 of the motion at 25 us
    (asserted below 2e-4); the automatic path is within the rtol it is given."""
    rotor, unb, t_end = _rotor(), [(3, 2e-4, 0.0)], 0.02
    speed = _smooth_runup(300.0, 1300.0, t_end)
    system = assemble(rotor)
    dof = int(system.dofs_of(3, ("uy",))[0])
    times = np.linspace(0.0, t_end, 101)[1:]
    reference = _reference_runup(rotor, speed, unb, t_end, dof, times)
    errors = []
    for dt in (1e-4, 5e-5, 2.5e-5):
        run = transient(rotor, t_end, dt, speed=speed, unbalance=unb, excitation=NO_GRAVITY,
                        initial="zero", output=rs.Output(times=times, nodes=[3]))
        x = run.displacement(3, "uy")[-times.size:]  # the samples at `times`
        errors.append(np.max(np.abs(x - reference)) / np.ptp(reference))
    assert 3.5 < errors[0] / errors[1] < 4.5 and 3.5 < errors[1] / errors[2] < 4.5
    assert errors[2] < 2e-4
    # the automatic path (Radau IIA with the tables in its stage forces and tangents) meets
    # the accuracy it is asked for: measured 4.9e-7 and 1.3e-9 at rtol 1e-3 and 1e-5
    for rtol in (1e-3, 1e-5):
        run = transient(rotor, t_end, rtol=rtol, speed=speed, unbalance=unb,
                        excitation=NO_GRAVITY, initial="zero",
                        output=rs.Output(times=times, nodes=[3]))
        x = run.displacement(3, "uy")[-times.size:]
        assert np.max(np.abs(x - reference)) / np.ptp(reference) < rtol


def test_resume_of_a_runup_on_tabulated_bearings_equals_the_uninterrupted_run(tmp_path,
                                                                             monkeypatch):
    """A checkpoint stores the speed node of the factors and its contraction estimate, so the
    resumed run takes the same decisions: bit-identical samples."""
    rotor = _rotor()
    kw = dict(speed=rs.LinearSpeed(200.0, 1400.0, 0.0, 0.02), unbalance=[(3, 2e-4, 0.0)],
              excitation=NO_GRAVITY, initial="zero", nodes=[3])
    full = transient(rotor, 0.02, 5e-5, **kw)
    resumed = resumed_run(monkeypatch, tmp_path / "run.h5", 230, 75, rotor, 0.02, 5e-5, **kw)
    np.testing.assert_array_equal(resumed.q, full.q)


def test_added_mass_tabulated_over_speed_is_refused_at_varying_speed():
    rotor = _rotor(mxx=[0.0, 1.0, 2.0])
    with pytest.raises(ModelError, match="added mass tabulated over speed"):
        transient(rotor, 0.01, 1e-4, speed=rs.LinearSpeed(0.0, 500.0, 0.0, 0.01),
                  excitation=NO_GRAVITY, initial="zero")
    transient(rotor, 0.01, 1e-4, speed=400.0, excitation=NO_GRAVITY, initial="zero")


def test_info_and_run_check_the_speed_tables_before_any_analysis(tmp_path, capsys):
    text = open("models/compressor_tilting_pad.toml").read()
    wide = text.replace('speed_stop = "11000 rpm"', 'speed_stop = "13000 rpm"')
    path = tmp_path / "wide.toml"
    path.write_text(wide)
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "note: runup: BearingElement 'DE': coefficients tabulated over" in out
    assert "above 1256.64 rad/s" in out
    bad = re.sub(r"(?m)^(cyy = .*)$", r'\1\nmxx = { values = [0, 1, 2, 3, 4], unit = "kg" }',
                 wide, count=1)
    assert "mxx" in bad
    path.write_text(bad)
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--no-plots"])
    err = capsys.readouterr()
    assert code != 0 and "added mass tabulated over speed" in err.err
    assert "analysis 'runup'" in err.err
    assert "campbell" not in err.out  # refused before the first analysis ran


def test_torque_driven_runup_on_tabulated_bearings_reports_the_spin_feedback():
    """A torque drive on a rotor with tabulated bearings: the bearings follow the computed
    speed, and the spin-feedback report is computed even when only other nodes are kept
    (the unbalance node is kept for it)."""
    model = load_model("models/compressor_tilting_pad.toml")
    drive = rs.TorqueDrive(rs.ConstantTorque(400.0), drive_node=0,
                           loads=[(24, rs.QuadraticTorque(2e-4))], initial_speed=300.0)
    run = transient(model.rotor, 0.01, 5e-5, speed=drive, unbalance=[(8, 7.6e-5, 0.0)],
                    nodes=[15])
    assert run.speed[-1] > run.speed[0] + 1.0
    feedback = run.options["spin_feedback"]
    assert feedback["questionable"] is False and 0.0 < feedback["ratio"] < 1e-3


def test_a_runup_on_tabulated_bearings_continues_at_constant_speed():
    """Run up, then continue at the top speed (the bearings folded into the matrices): the
    same as one run whose ramp ends halfway, to round-off and the Newton tolerance (the
    model identity digests the tables, not the matrices at one speed)."""
    rotor = _rotor()
    kw = dict(unbalance=[(3, 2e-4, 0.0)], excitation=NO_GRAVITY, nodes=[3])
    ramp = rs.LinearSpeed(200.0, 400.0, 0.0, 0.01)
    whole = transient(rotor, 0.02, 5e-5, speed=ramp, initial="zero", **kw)
    first = transient(rotor, 0.01, 5e-5, speed=ramp, initial="zero", **kw)
    second = transient(rotor, 0.02, 5e-5, speed=400.0, initial=first, **kw)
    np.testing.assert_allclose(second.q[-1], whole.q[-1], rtol=0, atol=1e-9 * _scale(whole))
    changed = rotor.with_bearings(  # another table: refused
        [rs.BearingElement(n=0, tag="B0", **{**TABLE, "kxx": [1e7, 2e7, 5e7]}),
         rotor.bearing_elements[1]])
    with pytest.raises(ModelError, match="model differs"):
        transient(changed, 0.02, 5e-5, speed=400.0, initial=first, **kw)
