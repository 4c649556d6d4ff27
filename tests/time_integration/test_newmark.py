"""Newmark family: analytic SDOF and Jeffcott solutions, energy, spectral radius, Duffing,
Newton convergence, factorisation reuse, output spec and failures.

Exact identities used as references: average acceleration is the trapezoidal rule on the
first-order form ``y' = A y + b f`` (``v_{n+1} = v_n + h (a_n + a_{n+1}) / 2`` and
``q_{n+1} = q_n + h (v_n + v_{n+1}) / 2``), so each eigenvalue ``s`` of the free system is
mapped exactly to ``R(s h) = (1 + s h / 2) / (1 - s h / 2)`` and a harmonic load of frequency
``W`` sees the transfer function at the warped frequency ``(2 / h) tan(W h / 2)`` (bilinear
transform; Hughes, *The Finite Element Method*, 2000, sections 9.1-9.3).
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.integrate import solve_ivp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.output import OutputSpec, Reducer
from rotorsim.time_integration.problem import SecondOrderProblem

EPS = np.finfo(float).eps


def sdof(m=1.0, c=0.0, k=1.0, load=None, restoring=None):
    return SecondOrderProblem(np.array([[m]]), np.array([[k]]), np.array([[c]]),
                              restoring=restoring, load=load)


def trapezoidal_map(s, h):
    return (1 + s * h / 2) / (1 - s * h / 2)


# --- linear SDOF against closed forms -------------------------------------------------

@pytest.mark.validation
@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_free_vibration_is_the_exact_solution_with_mapped_eigenvalues(zeta):
    w, h, q0, v0 = 2 * np.pi, 0.01, 1.0, 0.5
    res = integrate(sdof(c=2 * zeta * w, k=w * w), Newmark(), (0.0, 10.0), [q0], [v0], dt=h)
    n = np.arange(len(res.t))
    s = -zeta * w + 1j * w * np.sqrt(1 - zeta**2) * np.array([1, -1])
    # y0 = c1 (1, s1) + c2 (1, s2)
    c = np.linalg.solve(np.array([[1, 1], s]), np.array([q0, v0], dtype=complex))
    discrete = (c[None, :] * trapezoidal_map(s, h)[None, :] ** n[:, None]).sum(axis=1).real
    exact = (c[None, :] * np.exp(s[None, :] * res.t[:, None])).sum(axis=1).real
    # identity to round-off (1000 steps x a few eps on a unit amplitude)
    assert np.max(np.abs(res.q[:, 0] - discrete)) < 1e-11
    # difference to the exact solution: mean-value bound with the eigenvalue error
    s_tilde = np.log(trapezoidal_map(s, h)) / h
    bound = np.sum(np.abs(c)) * np.abs(s_tilde - s).max() * res.t
    assert np.all(np.abs(res.q[:, 0] - exact) <= 1.0001 * bound + 1e-11)
    assert np.abs(res.q[:, 0] - exact).max() > 0.5 * bound.max() * np.exp(-zeta * w * 10)
    if zeta == 0:  # period elongation only: amplitude conserved exactly
        amplitude = np.hypot(res.q[:, 0], res.v[:, 0] / w)
        assert np.ptp(amplitude) < 1e-12


@pytest.mark.validation
def test_forced_steady_state_matches_closed_form():
    m, c, k, F, W = 1.0, 0.2, 1.0, 1.0, 0.8
    period = 2 * np.pi / W
    h = period / 100
    load = lambda t: np.array([F * np.cos(W * t)])  # noqa: E731
    res = integrate(sdof(m, c, k, load), Newmark(), (0.0, 50 * period), [0.0], [0.0], dt=h,
                    output=OutputSpec(every=1, velocities=False))
    tail = res.t > res.t[-1] - 2 * period  # transient ~ exp(-0.1 t) < 1e-14 by then
    basis = np.column_stack([np.cos(W * res.t[tail]), -np.sin(W * res.t[tail])])
    coef, *_ = np.linalg.lstsq(basis, res.q[tail, 0], rcond=None)
    X = coef[0] + 1j * coef[1]  # q = Re(X e^{iWt})
    closed = F / (k - m * W**2 + 1j * c * W)
    Ww = 2 / h * np.tan(W * h / 2)  # bilinear-transform frequency
    warped = F / (k - m * Ww**2 + 1j * c * Ww)
    assert abs(X - warped) < 1e-10 * abs(closed)
    assert abs(X - closed) < 2e-3 * abs(closed)  # size of the warping at 100 steps/period


@pytest.mark.validation
def test_average_acceleration_conserves_energy_of_linear_undamped_system():
    k = np.array([1.0, 40.0, 900.0])  # a chain with a stiff spring: omega h up to ~3
    K = np.diag(k + np.r_[k[1:], 0.0]) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
    M = np.diag([1.0, 0.5, 0.2])
    res = integrate(SecondOrderProblem(M, K), Newmark(), (0.0, 40.0), [1.0, -0.5, 0.3],
                    [0.0, 2.0, -1.0], dt=0.02)
    energy = 0.5 * (np.einsum("ti,ij,tj->t", res.v, M, res.v)
                    + np.einsum("ti,ij,tj->t", res.q, K, res.q))
    drift = np.abs(energy / energy[0] - 1)
    # exact conservation (Hughes 2000, sec 9.1.3); round-off of ~4 eps per step at most
    assert drift.max() < 4 * EPS * res.stats["steps"]
    hht = integrate(SecondOrderProblem(M, K), Newmark.hht(-0.1), (0.0, 40.0),
                    [1.0, -0.5, 0.3], [0.0, 2.0, -1.0], dt=0.02)
    e_hht = 0.5 * (hht.v[-1] @ M @ hht.v[-1] + hht.q[-1] @ K @ hht.q[-1])
    assert e_hht < 0.99 * energy[0]  # HHT removes the stiff mode's energy


# --- numerical dissipation -----------------------------------------------------------

def chung_hulbert_amplification(method, omega_h):
    """Amplification matrix of (q, v h, a h^2) for x'' + omega^2 x = 0, from the scheme's
    three equations written out independently (Chung & Hulbert 1993, eqs 6-8)."""
    b, g, am, af = method.beta, method.gamma, method.alpha_m, method.alpha_f
    w2 = omega_h**2
    left = np.array([[1, 0, -b], [0, 1, -g], [(1 - af) * w2, 0, 1 - am]])
    right = np.array([[1, 1, 0.5 - b], [0, 1, 1 - g], [-af * w2, 0, -am]])
    return np.linalg.solve(left, right)


def measured_amplification(method, omega_h):
    """One step of the stepper from three unit states (h = 1)."""
    problem = sdof(k=omega_h**2)
    columns = []
    for e in np.eye(3):
        state = method.init(problem, 0.0, e[:1], e[1:2], dt=1.0, a0=e[2:])
        new = method.step(problem, state)
        columns.append([new.q[0], new.v[0], new.a[0]])
    return np.array(columns).T


@pytest.mark.validation
@pytest.mark.parametrize("method, rho_inf", [
    (Newmark.average_acceleration(), 1.0),
    (Newmark.hht(-0.3), 0.7 / 1.3),              # (1 + alpha) / (1 - alpha), HHT 1977
    (Newmark.generalized_alpha(0.8), 0.8),
    (Newmark.generalized_alpha(0.3), 0.3),
    (Newmark.generalized_alpha(0.0), 0.0),
], ids=["average", "hht-0.3", "galpha0.8", "galpha0.3", "galpha0"])
def test_high_frequency_dissipation_matches_spectral_radius(method, rho_inf):
    for omega_h in (1e2, 1e4, 1e6):
        theory = chung_hulbert_amplification(method, omega_h)
        measured = measured_amplification(method, omega_h)
        assert np.max(np.abs(measured - theory)) < 1e-12 * np.max(np.abs(theory))
    rho = max(abs(np.linalg.eigvals(measured)))
    # the triple root -rho_inf at infinity splits like (omega h)^(-2/3) (= 1e-4 at 1e6)
    assert abs(rho - rho_inf) < 2e-4
    # a stiff mode (omega h = 1e4) beside a soft one (omega h = 0.01), 60 steps of h = 0.01:
    # each mode follows y_n = A^n y_0 with y = (q, v h, a h^2) and the theory matrix A
    h, steps, omegas = 0.01, 60, np.array([1.0, 1e6])
    problem = SecondOrderProblem(np.eye(2), np.diag(omegas**2))
    res = integrate(problem, method, (0.0, steps * h), [1.0, 1.0], [0.0, 0.0], dt=h)
    for mode, omega in enumerate(omegas):
        amplification = chung_hulbert_amplification(method, omega * h)
        y = np.linalg.matrix_power(amplification, steps) @ [1.0, 0.0, -(omega * h) ** 2]
        # round-off: a few eps per step, amplified by the size omega h of a h^2
        assert res.q[-1, mode] == pytest.approx(y[0], abs=10 * steps * max(1.0, omega * h) * EPS)
    if rho_inf <= 0.5:
        assert abs(res.q[-1, 1]) < 1e-6  # the stiff mode is gone (~ 60^2 0.5^60)
    # the soft mode keeps second-order accuracy (error constants: test_order.py)
    assert abs(res.q[-1, 0] - np.cos(steps * h)) < 0.5 * h**2


# --- gyroscopic 2-DOF rotor -----------------------------------------------------------

@pytest.mark.validation
def test_jeffcott_free_whirl_matches_complex_eigensolution():
    m, k, c, g_spin = 2.0, 800.0, 0.4, 6.0  # g_spin = polar-inertia coupling x speed
    G = np.array([[0.0, g_spin], [-g_spin, 0.0]])  # skew: in the damping slot
    problem = SecondOrderProblem(m * np.eye(2), k * np.eye(2), c * np.eye(2) + G)
    z0, dz0, h = 1e-3 + 0.5e-3j, 0.02 - 0.01j, 2e-3
    res = integrate(problem, Newmark(), (0.0, 2.0), [z0.real, z0.imag],
                    [dz0.real, dz0.imag], dt=h)
    # z = x + i y obeys m z'' + (c - i g) z' + k z = 0: roots of m s^2 + (c - i g) s + k
    s = np.roots([m, c - 1j * g_spin, k])
    coef = np.linalg.solve(np.array([[1, 1], s]), np.array([z0, dz0]))
    n = np.arange(len(res.t))
    exact = (coef * np.exp(np.outer(res.t, s))).sum(axis=1)
    discrete = (coef * trapezoidal_map(s, h) ** n[:, None]).sum(axis=1)
    z = res.q[:, 0] + 1j * res.q[:, 1]
    assert np.max(np.abs(z - discrete)) < 1e-12
    s_tilde = np.log(trapezoidal_map(s, h)) / h
    bound = np.sum(np.abs(coef)) * np.abs(s_tilde - s).max() * res.t
    assert np.all(np.abs(z - exact) <= 1.0001 * bound + 1e-14)
    assert abs(s[0].imag) != pytest.approx(abs(s[1].imag), rel=0.05)  # split whirls


def test_variable_speed_gyroscopic_term_equals_the_same_term_as_restoring_force():
    G = np.array([[0.0, 3.0], [-3.0, 0.0]])
    speed = lambda t: 1.0 + 4.0 * t  # noqa: E731

    def as_force(q, v, t):
        return speed(t) * (G @ v), None, speed(t) * G

    base = dict(mass=np.eye(2), stiffness=np.diag([100.0, 120.0]),
                load=lambda t: np.array([np.cos(9 * t), 0.0]))
    a = integrate(SecondOrderProblem(**base, gyroscopic=G, speed=speed), Newmark.hht(-0.1),
                  (0.0, 1.0), [0.0, 0.0], [0.0, 0.0], dt=0.01)
    b = integrate(SecondOrderProblem(**base, restoring=as_force), Newmark.hht(-0.1),
                  (0.0, 1.0), [0.0, 0.0], [0.0, 0.0], dt=0.01)
    assert np.max(np.abs(a.q - b.q)) < 1e-12 * np.max(np.abs(a.q))
    assert a.stats["factorizations"] == 1 + 100  # the iteration matrix changes every step


# --- nonlinear: Duffing ---------------------------------------------------------------

DUFFING = dict(c=0.05, k=1.0, k3=0.1, P=0.18, W=1.2)  # shared/reference/README.md


def duffing_problem(log=None, exact_tangent=True):
    c, k, k3, P, W = (DUFFING[key] for key in ("c", "k", "k3", "P", "W"))

    def restoring(q, v, t):
        if log is not None:
            log.append((t, q[0]))
        tangent = np.array([[3 * k3 * q[0] ** 2]]) if exact_tangent else None
        return k3 * q**3, tangent, None

    return sdof(1.0, c, k, lambda t: np.array([P * np.cos(W * t)]), restoring)


@pytest.mark.validation
def test_duffing_steady_amplitude_matches_dop853_at_second_order():
    c, k, k3, P, W = (DUFFING[key] for key in ("c", "k", "k3", "P", "W"))
    period, x0 = 2 * np.pi / W, 2.5  # start near the resonant (upper) branch
    t_end = 80 * period
    sample = np.linspace(t_end - 2 * period, t_end, 801)
    ref = solve_ivp(lambda t, y: [y[1], P * np.cos(W * t) - c * y[1] - k * y[0] - k3 * y[0]**3],
                    (0.0, t_end), [x0, 0.0], method="DOP853", rtol=1e-10, atol=1e-12,
                    dense_output=True).sol(sample)[0]
    amp_ref = np.ptp(ref) / 2
    amps = {}
    for steps_per_period in (50, 100):
        res = integrate(duffing_problem(), Newmark(), (0.0, t_end), [x0], [0.0],
                        dt=period / steps_per_period, output=OutputSpec(times=sample))
        amps[steps_per_period] = np.ptp(res.q[:, 0]) / 2
        assert res.stats["iterations_per_step"] <= 3.0 and res.stats["max_iterations"] <= 4
    assert 2.3 < amp_ref < 2.84162  # upper branch, below the single-harmonic peak
    # second order: Richardson estimate of the error at 100 steps/period, 50 % margin
    richardson = abs(amps[50] - amps[100]) / 3
    assert abs(amps[100] - amp_ref) <= 1.5 * richardson
    assert abs(amps[50] - amp_ref) / abs(amps[100] - amp_ref) == pytest.approx(4.0, rel=0.1)


def test_exact_tangent_gives_quadratic_newton_convergence():
    log: list[tuple[float, float]] = []
    period = 2 * np.pi / DUFFING["W"]
    res = integrate(duffing_problem(log), Newmark(newton_rtol=1e-14), (0.0, 10 * period),
                    [2.5], [0.0], dt=period / 20)
    t, q = np.array(log).T
    constants = []
    for ti in np.unique(t)[1:]:
        dq = np.abs(np.diff(q[t == ti]))
        pairs = [(a, b) for a, b in itertools.pairwise(dq) if b > 1e-14]
        constants += [b / a**2 for a, b in pairs]
    # dq_{k+1} <= C dq_k^2 with C = |r''| beta h^2 / (2 S) <= 6 k3 |q| beta h^2 / 2 ~ 0.015
    assert constants and max(constants) < 0.03
    frozen = integrate(duffing_problem(exact_tangent=False), Newmark(newton_rtol=1e-14),
                       (0.0, 10 * period), [2.5], [0.0], dt=period / 20)
    assert res.stats["iterations_per_step"] < 3.5 < frozen.stats["iterations_per_step"]
    assert res.stats["residual_evaluations"] == res.stats["iterations"] + 1  # + initial


# --- factorisation reuse, output and failures -----------------------------------------

def chain(n, speed=None):
    K = sp.diags([2e6 * np.ones(n), -1e6 * np.ones(n - 1), -1e6 * np.ones(n - 1)],
                 [0, 1, -1], format="csr")
    f = np.zeros(n)
    f[-1] = 1.0
    return SecondOrderProblem(sp.identity(n, format="csr"), K, 1e-4 * K,
                              load=lambda t: f * np.sin(50 * t))


def test_linear_run_factorises_once_and_keeps_only_the_output_spec():
    n = 600
    spec = OutputSpec(every=100, dofs=[0, 300, 599], velocities=False,
                      reducers=(Reducer("max_abs", dofs=(599,)), Reducer("max", name="top")))
    res = integrate(chain(n), Newmark(), (0.0, 0.1), np.zeros(n), np.zeros(n), dt=1e-4,
                    output=spec)
    assert res.stats["factorizations"] == 2  # M for a0, then S for all 1000 steps
    assert res.stats["solves"] == 1 + res.stats["steps"] == 1001
    assert res.q.shape == (11, 3) and res.v is None and res.reduced["top"].shape == (n,)
    assert res.reduced["max_abs_q"][0] >= np.abs(res.q[:, 2]).max() > 0


def test_unchanged_nonlinear_tangent_reuses_the_factorisation():
    def gap_contact(q, v, t):  # a stop 1 mm away that the motion never reaches
        pen = np.maximum(q - 1e-3, 0.0)
        return 1e9 * pen**1.5, (sp.diags(1.5e9 * np.sqrt(pen)) if pen.any() else None), None

    n = 200
    problem = dataclasses.replace(chain(n), restoring=gap_contact)
    res = integrate(problem, Newmark(), (0.0, 0.05), np.zeros(n), np.zeros(n), dt=1e-4,
                    output=OutputSpec(every=50, dofs=[n - 1]))
    assert np.abs(res.state.q).max() < 1e-3  # never in contact
    assert res.stats["factorizations"] == 2 and res.stats["iterations"] == 2 * 500


def test_sparse_and_dense_tangents_give_the_same_answer():
    n = 150  # above the dense threshold of solvers.linear: sparse iteration matrix

    def cubic(q, v, t, sparse):
        tangent = 3e12 * q**2
        return 1e12 * q**3, (sp.diags(tangent) if sparse else np.diag(tangent)), None

    runs = [integrate(dataclasses.replace(chain(n), restoring=lambda q, v, t, s=s:
                                          cubic(q, v, t, s)), Newmark.generalized_alpha(0.9),
                      (0.0, 0.02), np.zeros(n), np.full(n, 1e-3), dt=1e-4,
                      output=OutputSpec(every=20)) for s in (True, False)]
    scale = np.abs(runs[0].q).max()
    assert np.max(np.abs(runs[0].q - runs[1].q)) < 1e-9 * scale
    assert runs[0].stats["max_iterations"] <= 4


def test_progress_bar_reports_simulated_time(capsys):
    integrate(sdof(), Newmark(), (0.0, 1.0), [1.0], [0.0], dt=0.01, progress=True)
    err = capsys.readouterr().err
    assert "average_acceleration" in err and "100%" in err and "t = 1/1 s" in err


def test_time_samples_are_hermite_interpolants_of_the_steps():
    w = 3.0
    times = np.linspace(0.0, 2.0, 37)  # not on the step grid
    problem = sdof(k=w * w)
    dense = integrate(problem, Newmark(), (0.0, 2.0), [1.0], [0.0], dt=1e-3,
                      output=OutputSpec(times=times))
    steps = integrate(problem, Newmark(), (0.0, 2.0), [1.0], [0.0], dt=1e-3)
    assert np.array_equal(dense.t, times)
    # interpolation error O(h^4 w^4) << method error O(h^2 w^3 t) ~ 4e-6
    assert np.max(np.abs(dense.q[:, 0] - np.cos(w * times))) < 5e-6
    on_grid = np.isin(steps.t, times)
    assert np.array_equal(steps.q[on_grid, 0], dense.q[np.isin(times, steps.t), 0])


def test_newton_failure_raises_convergence_error_with_location():
    with pytest.raises(ConvergenceError) as info:
        integrate(duffing_problem(), Newmark(max_iter=2, newton_rtol=1e-14), (0.0, 10.0),
                  [2.5], [0.0], dt=0.5)
    err = info.value
    assert err.step == 1 and err.iteration == 2 and err.residual > 0
    assert "t = 0.5 s" in str(err) and "DOF 0" in str(err)


def test_nan_is_detected_at_the_step_where_it_appears():
    load = lambda t: np.array([np.nan if t > 0.305 else 1.0, 0.0])  # noqa: E731
    problem = SecondOrderProblem(np.eye(2), np.eye(2), load=load)
    with pytest.raises(ConvergenceError, match=r"not finite at t = 0\.31 s \(DOF 0\)") as info:
        integrate(problem, Newmark(), (0.0, 1.0), [0.0, 0.0], [0.0, 0.0], dt=0.01)
    assert info.value.step == 31


def test_non_finite_tangent_is_reported_with_its_dof():
    def bad(q, v, t):
        tangent = np.zeros((2, 2))
        tangent[1, 0] = np.inf if t > 0.205 else 0.0
        return np.zeros(2), sp.csr_matrix(tangent), None

    problem = SecondOrderProblem(np.eye(2), np.eye(2), restoring=bad)
    with pytest.raises(ConvergenceError, match=r"tangent dr/dq is not finite at t = 0\.21 s "
                                               r"\(DOF 1\)") as info:
        integrate(problem, Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 0.0], dt=0.01)
    assert info.value.step == 21


@pytest.mark.parametrize("kwargs, match", [
    (dict(dt=0.0), "dt must be positive"),
    (dict(dt=np.nan), "dt must be positive"),
    (dict(dt=0.1, t_span=(1.0, 1.0)), "t_end > t0"),
    (dict(dt=0.1, q0=[0.0, 1.0]), "q0"),
    (dict(dt=0.1, output=OutputSpec(dofs=[3])), "indices"),
    (dict(dt=0.1, output=OutputSpec(times=[0.5, 2.0])), "times must lie"),
])
def test_bad_inputs_are_rejected_up_front(kwargs, match):
    args = dict(t_span=(0.0, 1.0), q0=[0.0], v0=[0.0])
    args.update(kwargs)
    t_span, q0, v0 = args.pop("t_span"), args.pop("q0"), args.pop("v0")
    with pytest.raises(ModelError, match=match):
        integrate(sdof(), Newmark(), t_span, q0, v0, **args)


def test_bad_schedule_and_options_are_rejected():
    G = np.array([[0.0, 1.0], [-1.0, 0.0]])
    problem = SecondOrderProblem(np.eye(2), np.eye(2), gyroscopic=G, speed=lambda t: np.nan)
    with pytest.raises(ModelError, match="speed"):
        integrate(problem, Newmark(), (0.0, 1.0), [0.0, 0.0], [0.0, 0.0], dt=0.1)
    with pytest.raises(ModelError, match="both"):
        SecondOrderProblem(np.eye(2), np.eye(2), gyroscopic=G)
    with pytest.raises(ModelError, match="stiffness"):
        SecondOrderProblem(np.eye(2), np.eye(3))
    with pytest.raises(TypeError, match="average_acceleration, linear_acceleration"):
        Newmark.from_name("wilson_theta")
    with pytest.raises(ModelError, match="alpha"):
        Newmark.hht(-0.5)
    with pytest.raises(ModelError, match="rho_inf"):
        Newmark.generalized_alpha(1.5)
    assert Newmark.from_name("hht", alpha=-0.2) == Newmark.hht(-0.2)
