"""rs.periodic: harmonic balance branches of rotors on rolling bearings -- excitation and
fundamental, the speed derivative of the residual, condensation, restart, result accessors,
input checks, Floquet methods and convergence in H and N.

The Jeffcott rotor of these tests (and of ``test_periodic_validation.py``): a 0.3 m, 40 mm
steel shaft (two Timoshenko elements) with a 200 mm disk at mid-span, on two 6205-like deep
groove ball bearings (9 balls, 10 um diametral clearance, Hertz point contact, cage fixed so
that an unbalance response is exactly periodic) in parallel with viscous dampers of
5000 N s/m, axially located at the disk, under gravity and an unbalance of 3e-5 kg m.
Its unbalance response softens through the clearance: folds at 1244 and 1257 rad/s.
"""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.linear.frequency_response import unbalance_response
from rotorsim.analyses.periodic.excitation import (
    HarmonicBase,
    fundamental_order,
    plan_excitation,
)
from rotorsim.analyses.periodic.periodic import periodic
from rotorsim.analyses.periodic.problem import build_problem
from rotorsim.analyses.periodic.stability import stability_model
from rotorsim.assembly.system import assemble
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.floquet import hill
from rotorsim.harmonic_balance.monodromy import hsu
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers.continuation import Continuation
from rotorsim.solvers.stats import Stats

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
UNBALANCE = [(1, 3e-5, 0.0)]
FAST = {"harmonics": 6, "nodes": [1]}


def fast(**continuation):
    """The FAST keywords with the continuation options ``continuation`` (tol 1e-8)."""
    return {**FAST, "continuation": rs.ContinuationOptions(tol=1e-8, **continuation)}


def ball(cage: str = "fixed", clearance: float = 10e-6) -> BallBearing:
    return BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9,
                       f_i=0.52, f_o=0.52, diametral_clearance=clearance, cage=cage)


def jeffcott(cage: str = "fixed", damping: float = 5000.0) -> rs.Rotor:
    """The Jeffcott rotor of the module docstring."""
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=damping) for n in (0, 2)]
    bearings = [RollingBearing(ball(cage), n=n, tag=f"B{n}") for n in (0, 2)]
    return rs.Rotor(shaft, [disk], dampers, nonlinear_elements=bearings, fixed=[(1, "uz")])


def linear_rotor() -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(6)]
    disk = rs.DiskElement.from_geometry(n=3, material=STEEL, width=0.03, i_d=0.04, o_d=0.2)
    bearings = [rs.BearingElement(n=n, kxx=2e7, kyy=3e7, cxx=2e3, cyy=2e3) for n in (0, 6)]
    return rs.Rotor(shaft, [disk], bearings)


@pytest.fixture(scope="module")
def branch():
    """Unbalance branch of the Jeffcott rotor through both folds (Floquet by Hsu)."""
    return periodic(jeffcott(), start=1220.0, stop=1280.0, unbalance=UNBALANCE,
                    **fast(max_step=0.1))


# ----------------------------------------------------------------------------- physics
@pytest.mark.verification
def test_linear_rotor_branch_is_the_unbalance_response_plus_the_static_sag():
    """Exact reference: with linear bearings HB is exact with one harmonic; harmonic 1
    equals rs.unbalance_response and harmonic 0 equals rs.static (to round-off)."""
    rotor = linear_rotor()
    unb = [(3, 1e-4, 0.3)]
    res = periodic(rotor, start=200.0, stop=900.0, harmonics=2, unbalance=unb,
                   continuation=rs.ContinuationOptions(max_step=2.0, tol=1e-13), stability=None)
    ref = unbalance_response(rotor, res.parameter, unb)
    for dof in ("ux", "uy"):
        got, exact = res.harmonic(3, dof, 1), ref.complex(3, dof)
        np.testing.assert_allclose(got, exact, rtol=1e-8, atol=1e-10 * np.abs(exact).max())
        assert np.abs(res.harmonic(3, dof, 2)).max() < 1e-12 * np.abs(exact).max()
    sag = rs.static(rotor).displacement[6 * 3 + 1]   # node 3, uy
    np.testing.assert_allclose(res.amplitude(3, "uy", "mean"), sag, rtol=1e-9)
    assert res.approximation == "" and res.order == 1.0 and len(res) > 5


def test_branch_passes_both_folds_and_finds_them(branch):
    assert branch.status == rs.Status.OK and branch.reason.startswith("lam_max")
    folds = branch.events("fold")
    assert len(folds) == 2 and all(f.located for f in folds)
    assert sorted(round(f.parameter) for f in folds) == [1244, 1257]
    # the middle branch between the folds is unstable, the outer branches are stable
    i, j = sorted(f.index for f in folds)
    assert not branch.stable[i + 1:j + 1].any()
    assert branch.stable[:i - 1].all() and branch.stable[j + 2:].all()
    # at a fold a real Floquet multiplier sits at +1 (Hsu's method, non-smooth contacts)
    assert all(abs(f.multiplier - 1.0) < 0.02 for f in folds)


def test_fundamental_order_and_vc_treatment():
    z_kappa = 9 * ball("rotating").kappa
    elements = [RollingBearing(ball("rotating"), n=0)]
    vc = plan_excitation(elements, unbalance=False, base=None, varying_compliance=None,
                         fundamental=None, frequency_parameter=False)
    assert vc.order == pytest.approx(z_kappa) and vc.moving_elements and not vc.approximation
    both = plan_excitation(elements, unbalance=True, base=None, varying_compliance=None,
                           fundamental=None, frequency_parameter=False)
    assert both.order == 1.0 and not both.moving_elements
    assert "quasi-periodic" in both.approximation and "frozen" in both.approximation
    with pytest.raises(ModelError, match="quasi-periodic"):
        plan_excitation(elements, unbalance=True, base=None, varying_compliance=True,
                        fundamental=None, frequency_parameter=False)
    seed = plan_excitation(elements, unbalance=False, base=HarmonicBase(1e-4, 2 * z_kappa),
                           varying_compliance=None, fundamental=None, frequency_parameter=False)
    assert seed.order == pytest.approx(z_kappa) and seed.base_harmonic == 2
    half = plan_excitation([], unbalance=True, base=None, varying_compliance=None,
                           fundamental=0.5, frequency_parameter=False)
    assert half.unbalance_harmonic == 2                 # a period-2 branch
    with pytest.raises(ModelError, match="not an integer multiple"):
        plan_excitation([], unbalance=True, base=None, varying_compliance=None,
                        fundamental=0.3, frequency_parameter=False)
    assert fundamental_order([2.5, 5.0, 7.5]) == 2.5 and fundamental_order([1.0, np.pi]) is None


@pytest.mark.parametrize("cage, unbalance", [("fixed", UNBALANCE), ("rotating", [])])
def test_speed_derivative_of_the_residual(cage, unbalance):
    """dR/domega (analytic linear part and gyroscopics, central differences of the unbalance
    ~ W^2) equals a central difference of the whole residual in omega (step 1e-5 omega: the
    condensed residual curves strongly in omega, its truncation error is 4e-7 there)."""
    system = assemble(jeffcott(cage))
    plan = plan_excitation(system.nonlinear.elements, unbalance=bool(unbalance), base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False)
    rp = build_problem(system, plan, speed0=1000.0, fixed_speed=None, phi0=0.0,
                       unbalance=unbalance, gravity=9.81, direction=(0, -1, 0), loads=[],
                       base=None, stats=Stats())
    res = make_residual(rp.problem, 4)
    w = plan.order * 1000.0
    x = solve_point(res, w, res.restrict(np.vstack([rp.static[rp.active],
                                                    np.zeros((8, rp.problem.n))])),
                    x_scale=1e-6).x
    fun = continuation_function(res, "omega")
    _, _, r_w = fun(x, w)
    h = 1e-5 * w
    fd = (fun(x, w + h)[0] - fun(x, w - h)[0]) / (2 * h)
    assert np.abs(r_w - fd).max() < 1e-6 * np.abs(fd).max()
    assert np.abs(fd).max() > 0


def test_condensed_and_full_harmonic_balance_give_the_same_point():
    kw = {"unbalance": UNBALANCE, "continuation": rs.ContinuationOptions(max_points=2, tol=1e-11),
          "stability": rs.StabilityOptions(None, bifurcations=False)}
    cond = periodic(jeffcott(), start=1100.0, stop=1110.0, harmonics=4, **kw)
    full = periodic(jeffcott(), start=1100.0, stop=1110.0,
                    harmonics=rs.Harmonics(4, condense=False), **kw)
    np.testing.assert_allclose(full.coefficients[0], cond.coefficients[0], rtol=0,
                               atol=1e-7 * np.abs(cond.coefficients[0]).max())


def test_resume_after_an_interruption_equals_the_uninterrupted_branch(tmp_path, monkeypatch):
    import rotorsim.analyses.periodic.branch as pb

    kw = {"unbalance": UNBALANCE, "stability": rs.StabilityOptions(None, bifurcations=False),
          **fast(max_points=9)}
    whole = periodic(jeffcott(), start=1200.0, stop=1300.0, **kw)
    original = pb.continue_branch

    class Interrupted(Exception):
        pass

    def stop_at(state):
        if state.point == 6:
            raise Interrupted

    monkeypatch.setattr(pb, "continue_branch",
                        lambda *a, **k: original(*a, **k, monitor=stop_at))
    path = tmp_path / "branch.h5"
    with pytest.raises(Interrupted):
        periodic(jeffcott(), start=1200.0, stop=1300.0, checkpoint=rs.Checkpointing(path, every=3),
                 **kw)
    monkeypatch.setattr(pb, "continue_branch", original)
    resumed = periodic(jeffcott(), start=1200.0, stop=1300.0,
                       checkpoint=rs.Checkpointing(resume=path), **kw)
    np.testing.assert_array_equal(resumed.parameter, whole.parameter)
    np.testing.assert_array_equal(resumed.coefficients, whole.coefficients)


# ----------------------------------------------------------------------------- results
def test_result_accessors(branch):
    j = branch.column(1, "uy")
    ptp = branch.amplitude(1, "uy", "peak_to_peak")
    assert np.all(branch.amplitude(1, "uy", "max") >= 0.5 * ptp)
    np.testing.assert_allclose(branch.amplitude(1, "uy", "half_peak_to_peak"), 0.5 * ptp)
    X1 = branch.harmonic(1, "uy", 1)
    np.testing.assert_array_equal(X1, branch.coefficients[:, 1, j]
                                  - 1j * branch.coefficients[:, 2, j])
    k = len(branch) // 2
    t, q = branch.time_response(k, 512)
    assert t[-1] < 2 * np.pi / branch.fundamental[k]
    assert np.ptp(q[:, j]) == pytest.approx(ptp[k], rel=1e-4)
    x, y = branch.orbit(k, 1, 512)
    np.testing.assert_array_equal(y, q[:, j])
    np.testing.assert_array_equal(x, q[:, branch.column(1, "ux")])
    q0, v0 = branch.state(k)
    assert q0.shape == (branch.dof_map.ndof,) and q0[6 + 1] == pytest.approx(q[0, j])
    dt = 1e-7
    q_plus = branch.state(k, branch.fundamental[k] * dt)[0]
    q_minus = branch.state(k, -branch.fundamental[k] * dt)[0]
    assert v0[7] == pytest.approx((q_plus[7] - q_minus[7]) / (2 * dt), rel=1e-6)
    amps = branch.harmonic_amplitudes(k, 1, "uy")
    assert amps.shape == (branch.harmonics + 1,) and amps[1] == pytest.approx(abs(X1[k]))
    assert branch.nearest(branch.parameter[3]) == 3
    with pytest.raises(ModelError, match="not kept"):
        branch.column(1, "uz")                     # fixed: axially located at the disk
    assert branch.held_dofs.size >= 1 and branch.stats["points"] == len(branch)


def test_stability_is_refused_when_not_computed():
    res = periodic(jeffcott(), start=1000.0, stop=1010.0, unbalance=UNBALANCE,
                   stability=None, **fast(max_points=2))
    assert not res.has_stability and res.stability_method == "none"
    with pytest.raises(ModelError, match="no stability"):
        _ = res.stable


@pytest.mark.parametrize("kwargs, error, match", [
    ({"parameter": "clearance"}, TypeError, "unknown parameter"),
    ({"start": -1.0}, ModelError, "positive"),
    ({"stop": 1000.0}, ModelError, "equal"),
    ({"parameter": "frequency"}, ModelError, "fixed speed"),
    ({"speed": 100.0}, ModelError, "continuation parameter"),
    ({"stability": "lyapunov"}, TypeError, "unknown stability"),
    (lambda: {"stability": rs.StabilityOptions(modes=-3)}, ModelError,
     "stability_modes|integer"),
    ({"nodes": [99]}, ModelError, "outside"),
    ({"varying_compliance": True}, ModelError, "quasi-periodic"),
    # issue 12: H = 0 has no unbalance response; H must be a positive integer that carries
    # every forcing (unbalance at harmonic 2 of a period-2 fundamental needs H >= 2)
    ({"harmonics": 0}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": -1}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": 2.5}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": True}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": None}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": float("inf")}, ModelError, "periodic.harmonics: must be a positive"),
    ({"harmonics": "4"}, ModelError, "periodic.harmonics: must be a positive integer"),
    ({"harmonics": rs.Harmonics(1, fundamental=0.5), "varying_compliance": False}, ModelError,
     "1 harmonics drop the unbalance, which is harmonic 2"),
    # option groups are checked when built (lambda: inside pytest.raises)
    (lambda: {"harmonics": rs.Harmonics(2, samples=3)}, ModelError,
     r"Harmonics.samples: must be an integer >= 2 H"),
    (lambda: {"harmonics": rs.Harmonics(samples=float("nan"))}, ModelError, "Harmonics.samples"),
    ({"continuation": Continuation()}, ModelError,
     r"periodic\.continuation: expected rs\.ContinuationOptions or None, got Continuation \(a "
     r"solver Continuation goes into rs\.ContinuationOptions\(solver=\.\.\.\)\)"),
    ({"output": rs.Output(every=2)}, ModelError, r"periodic\.output\.every: not an option"),
    ({"nodes": [1], "output": rs.Output(nodes=[2])}, ModelError, r"periodic\.nodes: given twice"),
])
def test_bad_input_is_rejected_before_the_branch(kwargs, error, match):
    rotor = jeffcott("rotating")
    with pytest.raises(error, match=match):
        args = {"start": 1000.0, "stop": 1100.0, "unbalance": UNBALANCE,
                **(kwargs() if callable(kwargs) else kwargs)}
        periodic(rotor, **args)


def test_frequency_continuation_of_a_housing_excitation_at_fixed_speed():
    res = periodic(jeffcott(), parameter="frequency", speed=500.0, start=900.0, stop=1000.0,
                   excitation=rs.Excitation(base=HarmonicBase(2e-6)),
                   stability=None, **fast(max_points=4))
    assert res.parameter_name == "frequency" and res.order == 0.0
    np.testing.assert_array_equal(res.fundamental, res.parameter)
    assert np.all(res.speed == 500.0) and res.approximation == ""
    assert np.all(np.abs(res.harmonic(1, "uy", 1)) > 1e-7)   # the base drives the disk


# ----------------------------------------------------------------------------- numerics
@pytest.mark.verification
def test_hill_and_hsu_give_the_same_multipliers_on_a_rotor_point(branch):
    """Two independent Floquet methods (Hill's spectral method and Hsu's transition matrix
    with 512 steps, seed 002 eq 3.38): the critical multipliers agree to the accuracy Hsu
    reaches on a non-smooth (Hertz with clearance) tangent, 1 % (observed order 2 before
    the contact kinks dominate)."""
    system = assemble(jeffcott())
    plan = plan_excitation(system.nonlinear.elements, unbalance=True, base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False)
    rp = build_problem(system, plan, speed0=1250.0, fixed_speed=None, phi0=0.0,
                       unbalance=UNBALANCE, gravity=9.80665, direction=(0, -1, 0), loads=[],
                       base=None, stats=Stats())
    res = make_residual(rp.problem, 6)
    middle = [i for i in range(len(branch)) if not branch.stable[i]][2]
    w = branch.fundamental[middle]
    X = np.zeros((res.aft.rows, rp.problem.n))
    columns = np.searchsorted(rp.active, system.dof_map.full_to_free[branch.dofs])
    assert columns.size == rp.problem.n          # every active DOF is kept
    X[:, columns] = branch.coefficients[middle]
    x = solve_point(res, w, res.restrict(X), x_scale=1e-6).x
    sm = stability_model(res, "hsu", modes=None, omega_max=w)
    mu_hill = hill(sm.residual, x, w).critical
    mu_hsu = hsu(sm.residual, x, w, samples=512).critical
    assert mu_hill.real > 1.01 and abs(mu_hill.imag) < 1e-9       # a saddle: real mu > 1
    assert abs(mu_hsu - mu_hill) < 0.01 * abs(mu_hill)
    assert abs(branch.multipliers[middle, 0] - mu_hill) < 0.02 * abs(mu_hill)


@pytest.mark.verification
def test_response_converges_in_harmonics_and_samples():
    """Peak-to-peak response at 1200 rad/s against H = 24, N = 512: the error falls with H
    (1.2 % at H = 1, < 2e-4 at H = 8; the contact opening on part of the orbit makes the
    series converge algebraically) and with N at H = 6 against N = 512 (the AFT aliasing
    error is < 2e-5 from N = 64 on)."""
    def ptp(H, N=None):
        r = periodic(jeffcott(), start=1200.0, stop=1210.0, unbalance=UNBALANCE,
                     harmonics=rs.Harmonics(H, samples=N),
                     continuation=rs.ContinuationOptions(max_points=2, tol=1e-10),
                     stability=rs.StabilityOptions(None, bifurcations=False),
                     nodes=[1])
        return float(r.amplitude(1, "uy", "peak_to_peak")[0])

    reference = ptp(24, 512)
    by_h = np.array([abs(ptp(H) / reference - 1) for H in (1, 2, 4, 8)])
    assert np.all(np.diff(by_h) < 0) and by_h[0] > 5e-3 and by_h[-1] < 2e-4
    at_h6 = ptp(6, 512)
    by_n = np.array([abs(ptp(6, N) / at_h6 - 1) for N in (16, 64, 256)])
    assert by_n[0] > by_n[1] and by_n[1] < 2e-5 and by_n[2] < 2e-5


# ----------------------------------------------------------------------------- figures
def test_figures_draw_the_branch_its_stability_and_a_point(branch, tmp_path):
    import matplotlib.pyplot as plt

    from rotorsim.plotting import plot
    from rotorsim.plotting.periodic_figures import (
        frequency_response_figure,
        harmonics_figure,
    )

    fig = plot(branch)
    assert len(fig.axes) == 4
    fig.savefig(tmp_path / "periodic.png")
    assert (tmp_path / "periodic.png").stat().st_size > 20000
    ax = fig.axes[0]
    dashed = [line for line in ax.lines if line.get_linestyle() == "--" and line.get_xdata().size]
    assert dashed                                   # the unstable middle branch
    folds = [line for line in ax.lines if line.get_marker() == "o"
             and line.get_linestyle() == "None"]
    assert len(folds) == 2                          # both folds marked
    plt.close(fig)
    for figure in (frequency_response_figure(branch, node=1, measure="max", units="rpm"),
                   harmonics_figure(branch, node=1, dof="ux")):
        assert figure.axes and figure.axes[0].lines
        plt.close(figure)


def test_parameter_branch_resumes_from_its_checkpoint(tmp_path):
    from rotorsim.analyses.periodic.parameter import periodic_parameter

    def vary(c):
        return [RollingBearing(ball("fixed", clearance=c), n=n, tag=f"B{n}") for n in (0, 2)]

    kw = dict(speed=1250.0, start=10e-6, stop=8e-6, unbalance=UNBALANCE, harmonics=4,
              continuation=rs.ContinuationOptions(max_points=12), stability=None)
    path = tmp_path / "clearance.h5"
    full = periodic_parameter(jeffcott().linear_part(), vary,
                              checkpoint=rs.Checkpointing(path, every=4), **kw)
    again = periodic_parameter(jeffcott().linear_part(), vary,
                               checkpoint=rs.Checkpointing(resume=path), **kw)
    np.testing.assert_array_equal(again.parameter, full.parameter)
    np.testing.assert_array_equal(again.coefficients, full.coefficients)


# ----------------------------------------------------------------------------- issue 12
def test_harmonics_beyond_the_memory_limit_are_refused_with_the_figure(monkeypatch):
    """H = 10000 used to raise MemoryError after asking numpy for 429 GiB (the dense
    Jacobian of (2H + 1) k unknowns). The estimate comes first and names the figure and
    the limit; the limit is pinned here so that the test does not depend on the machine."""
    import rotorsim.harmonic_balance.memory as memory

    monkeypatch.setattr(memory, "memory_limit", lambda: 8 * memory.GIB)
    system = assemble(jeffcott())
    k = int(system.nonlinear.dofs.size)
    need = memory.estimate_bytes(10000, 131072, k, system.n_free)
    assert need >= 8 * (20001 * k) ** 2             # at least one dense Jacobian
    with pytest.raises(ModelError, match=r"periodic.harmonics: H = 10000 harmonics .* need "
                                         r"about .* GiB .* above the limit of 8 GiB"):
        periodic(jeffcott(), start=1000.0, stop=1100.0, unbalance=UNBALANCE, harmonics=10000)
    # an ordinary H is far below any limit
    assert memory.estimate_bytes(10, 128, k, system.n_free) < 2**27


def test_a_branch_short_of_its_end_is_not_ok_and_says_where_it_stopped(branch):
    assert branch.status == rs.Status.OK and branch.parameter[-1] == 1280.0
    short = periodic(jeffcott(), start=1220.0, stop=1280.0, unbalance=UNBALANCE,
                     stability=rs.StabilityOptions(None, bifurcations=False),
                     **fast(max_points=4))
    assert len(short) == 4 and short.parameter[-1] < 1280.0
    assert short.status == rs.Status.NOT_CONVERGED
    assert short.reason.startswith(f"incomplete: the branch ended at speed "
                                   f"{short.parameter[-1]:.6g} rad/s, short of its end speed "
                                   "1280 rad/s (max_points reached)")
    assert "Raise ContinuationOptions(max_points=...)" in short.reason   # what to change


def test_a_tolerance_below_round_off_is_met_at_the_round_off_floor():
    """tol = 1e-17 is below what floating point can reach: with tol = 1e-15 this branch
    used to stop at 1104.9 rad/s ("line search failed to reduce the residual"). Judged
    against the round-off floor of the residual's terms it reaches its end, and the
    residuals stay at round-off level (measured 3e-15), not at a loosened tolerance."""
    res = periodic(jeffcott(), start=1100.0, stop=1150.0, unbalance=UNBALANCE, harmonics=4,
                   continuation=rs.ContinuationOptions(tol=1e-17, max_step=0.1),
                   stability=rs.StabilityOptions(None, bifurcations=False), nodes=[1])
    assert res.status == rs.Status.OK and res.parameter[-1] == 1150.0
    assert np.max(res.residuals) < 1e-13


def test_resume_of_a_finished_run_returns_its_result_also_from_the_results_file(tmp_path):
    """As for transients, resuming a finished run computes nothing more. Saving the result
    under the checkpoint's name replaces the checkpoint; resuming from that results file
    returns the stored result when the run is the same, and names what differs if not."""
    from rotorsim.time_integration.checkpoint import CheckpointError

    kw = {"unbalance": UNBALANCE, "stability": rs.StabilityOptions(None, bifurcations=False),
          **fast()}
    path = tmp_path / "branch.h5"
    done = periodic(jeffcott(), start=1200.0, stop=1210.0, checkpoint=path, **kw)
    assert done.status == rs.Status.OK
    again = periodic(jeffcott(), start=1200.0, stop=1210.0,
                     checkpoint=rs.Checkpointing(resume=path), **kw)
    np.testing.assert_array_equal(again.coefficients, done.coefficients)  # same machine
    rs.save(done, path)
    stored = periodic(jeffcott(), start=1200.0, stop=1210.0,
                      checkpoint=rs.Checkpointing(resume=path), **kw)
    np.testing.assert_array_equal(stored.coefficients, done.coefficients)
    assert stored.status == done.status and stored.options == done.options
    with pytest.raises(CheckpointError, match=r"different run .*stop: checkpoint 1210\.0, "
                                              r"this run 1220\.0"):
        periodic(jeffcott(), start=1200.0, stop=1220.0, checkpoint=rs.Checkpointing(resume=path),
                 **kw)
    rs.save(rs.static(linear_rotor()), path)
    with pytest.raises(CheckpointError, match="StaticResult, not a periodic branch"):
        periodic(jeffcott(), start=1200.0, stop=1210.0, checkpoint=rs.Checkpointing(resume=path),
                 **kw)


@pytest.mark.parametrize("harmonics", [0, 2.5, 10000])
def test_parameter_branches_check_harmonics_before_any_solve(harmonics, monkeypatch):
    import rotorsim.harmonic_balance.memory as memory
    from rotorsim.analyses.periodic.parameter import periodic_parameter

    monkeypatch.setattr(memory, "memory_limit", lambda: 8 * memory.GIB)
    with pytest.raises(ModelError, match=r"periodic_parameter\.harmonics: (must be a positive "
                                         r"integer|H = 10000 harmonics)"):
        periodic_parameter(jeffcott(), "forcing", speed=1250.0, start=0.0, stop=1.0,
                           unbalance=UNBALANCE, harmonics=harmonics)


def test_a_short_parameter_branch_is_not_ok():
    from rotorsim.analyses.periodic.parameter import periodic_parameter

    res = periodic_parameter(jeffcott(), "forcing", speed=1100.0, start=0.2, stop=1.0,
                             unbalance=UNBALANCE, harmonics=4,
                             continuation=rs.ContinuationOptions(max_points=3),
                             stability=rs.StabilityOptions(None, bifurcations=False))
    assert len(res) == 3 and res.status == rs.Status.NOT_CONVERGED
    assert res.reason.startswith("incomplete: the branch ended at parameter ")
    assert "short of its end parameter 1 (max_points reached)" in res.reason


def test_hill_on_a_pencil_too_large_for_the_memory_is_refused(monkeypatch):
    import rotorsim.harmonic_balance.memory as memory

    monkeypatch.setattr(memory, "memory_limit", lambda: memory.GIB // 1024)   # 1 MiB
    system = assemble(jeffcott())
    res = make_residual(build_problem(
        system, plan_excitation(system.nonlinear.elements, unbalance=True, base=None,
                                varying_compliance=None, fundamental=None,
                                frequency_parameter=False),
        speed0=1000.0, fixed_speed=None, phi0=0.0, unbalance=UNBALANCE, gravity=None,
        direction=(0, -1, 0), loads=[], base=None, stats=Stats()).problem, 6)
    with pytest.raises(ModelError, match=r"periodic\.stability: Hill's method with a pencil "
                                         r"of \d+ rows needs about .* GiB"):
        stability_model(res, "hill", modes=None, omega_max=1000.0)
    assert stability_model(res, "hsu", modes=None, omega_max=1000.0).method == "hsu"
