"""Branch switching on harmonic-balance branches, confirmed by time integration.

* Period doubling: the preloaded Duffing oscillator
  ``x'' + 0.02 x' + x + x^3 = 0.265625 + 0.5 cos(omega t)`` (static position 0.25: a
  quadratic term ``0.75 x^2`` about it) has its period-1 response near twice its natural
  frequency (``omega_0 = 1.09``) doubled between ``omega = 2.100`` and ``2.275``
  (principal parametric resonance of the response's own stiffness modulation). The
  period-2 branch from the first doubling is supercritical and stable.
* Branch point: ``x'' + c x' + x + g x^3 + b x y^2 = F cos(omega t)``,
  ``y'' + c y' + w2^2 y + g y^3 + b x^2 y = 0`` keeps ``y = 0`` invariant; the response
  ``x`` modulates ``y``'s stiffness at ``2 omega`` and ``y = 0`` loses stability in a
  pitchfork (multiplier +1, a branch point of the continuation) near ``omega = w2``.

The references are scipy's ``solve_ivp`` (DOP853, rtol 1e-11) started on the HB orbit
and run for tens of periods: a steady orbit of the true equations stays on itself.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.bifurcation import BifurcationOptions, detect_bifurcations
from rotorsim.harmonic_balance.branch_switching import (
    period_doubling_point,
    spread_harmonics,
    subharmonic_problem,
    switch_branch_point,
    switch_period_doubling,
)
from rotorsim.harmonic_balance.floquet import hill
from rotorsim.harmonic_balance.fourier import AFT
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers.continuation import Continuation, continue_branch

DAMPING, PRELOAD, FORCE = 0.02, 0.265625, 0.5
C2, W2, BETA, GAMMA, F2 = 0.02, 1.5, 1.0, 0.1, 0.5


def cubic(q, v, tau, w, p):
    return q**3, 3 * q[:, :, None] ** 2, None


def preloaded_duffing(harmonics=6):
    pb = HBProblem(np.eye(1), np.eye(1), damping=DAMPING * np.eye(1), nl_dofs=[0],
                   force=cubic, excitation=[[PRELOAD], [FORCE], [0.0]])
    return make_residual(pb, harmonics, condense=False)


def coupled(q, v, tau, w, p):
    x, y = q[:, 0], q[:, 1]
    f = np.stack([GAMMA * x**3 + BETA * x * y**2, GAMMA * y**3 + BETA * x**2 * y], axis=1)
    K = np.empty((q.shape[0], 2, 2))
    K[:, 0, 0], K[:, 1, 1] = 3 * GAMMA * x**2 + BETA * y**2, 3 * GAMMA * y**2 + BETA * x**2
    K[:, 0, 1] = K[:, 1, 0] = 2 * BETA * x * y
    return f, K, None


def autoparametric(harmonics=5):
    pb = HBProblem(np.eye(2), np.diag([1.0, W2**2]), damping=C2 * np.eye(2),
                   nl_dofs=[0, 1], force=coupled, excitation=[[0, 0], [F2, 0], [0, 0]])
    return make_residual(pb, harmonics)


def integrate(rhs, X, omega, periods, n):
    """solve_ivp from the HB orbit (coefficients X (2H+1, n), fundamental omega) over
    ``periods`` periods 2 pi / omega; returns the HB and the integrated displacement over
    the last period, sampled at 64 phases."""
    aft = AFT((X.shape[0] - 1) // 2)
    tau = 2 * np.pi * np.arange(64) / 64
    from rotorsim.harmonic_balance.fourier import derivative
    z0 = np.concatenate([aft.basis([0.0]) @ X, omega * aft.basis([0.0]) @ derivative(X)],
                        axis=1).ravel()
    T = 2 * np.pi / omega
    t_eval = (periods - 1) * T + tau / omega
    sol = solve_ivp(rhs, (0.0, periods * T), z0, method="DOP853", rtol=1e-11, atol=1e-13,
                    t_eval=t_eval)
    assert sol.success
    return aft.basis(tau) @ X, sol.y[:n].T


@pytest.fixture(scope="module")
def doubling():
    res = preloaded_duffing()
    fun = continuation_function(res)
    start = solve_point(res, 2.0, np.r_[0.3, np.zeros(res.size - 1)])
    branch = continue_branch(fun, start.x, 2.0, Continuation(lam_max=2.4, max_step=0.1))
    events = detect_bifurcations(fun, branch,
                                 multipliers=lambda x, w: hill(res, x, w).multipliers)
    return res, [e for e in events if e.kind == "period_doubling"]


def test_subharmonic_problem_keeps_the_period_one_solutions():
    res = preloaded_duffing(3)
    sol = solve_point(res, 1.5, np.r_[0.3, np.zeros(res.size - 1)])
    doubled = make_residual(subharmonic_problem(res.problem), 6, condense=False)
    x2 = spread_harmonics(sol.x.reshape(7, 1), 2, 6).ravel()
    r = doubled.evaluate(x2, 0.75, jacobian=False).r
    # the same sums on twice the samples: zero to the round-off of the period-1 solve
    assert np.abs(r).max() < 1e-12
    with pytest.raises(ModelError, match="factor"):
        subharmonic_problem(res.problem, 1)


@pytest.mark.validation
def test_period_two_branch_from_a_doubling_is_confirmed_by_time_integration(doubling):
    res, events = doubling
    assert [round(e.lam, 3) for e in events] == [2.100, 2.275]
    pd_event = events[0]
    assert abs(pd_event.multipliers[np.argmin(np.abs(pd_event.multipliers + 1))] + 1) < 1e-4
    opts = Continuation(lam_max=1.1, max_step=0.05)
    branch, pd, _ = switch_period_doubling(res, pd_event.x, pd_event.lam, opts,
                                              step=1e-3)
    # the odd block is singular at the refined point, its second singular value is not
    assert pd.singular_values[1] < 1e-12 < 0.1 < pd.singular_values[0]
    # Hill (harmonics -H..H of omega) and the odd block (odd harmonics of omega / 2) place
    # the doubling alike up to the truncation error of H = 6 (measured 1.2e-11)
    assert abs(2 * pd.omega - pd_event.lam) < 1e-8
    # the branches meet there: a jump of 1e-3 in the odd harmonics moves omega by
    # O(1e-6) (pitchfork: omega - omega_PD ~ a_odd^2) and the even harmonics by as little
    X = branch.x.reshape(len(branch), -1)
    odd = np.abs(X[:, 1::4]).max(axis=1) + np.abs(X[:, 2::4]).max(axis=1)
    assert abs(2 * branch.lam[0] - 2 * pd.omega) < 1e-5
    assert np.abs(X[0, 0::4] - pd.x[0::4]).max() < 1e-5
    assert 1e-4 < odd[0] < 2e-3 and odd[-1] > 0.3
    assert branch.status.name == "OK" and branch.lam[-1] == 1.1
    # supercritical: the period-2 branch exists above the doubling, and is stable
    assert np.all(2 * branch.lam >= 2 * pd.omega - 1e-9)
    # a point next to the doubling, omega = 2.12, integrated over 60 periods of 2 T
    i = int(np.argmin(np.abs(2 * branch.lam - 2.12)))
    sol = solve_point(pd.residual, 1.06, branch.x[i])
    mu = hill(pd.residual, sol.x, 1.06).multipliers
    assert np.abs(mu).max() < 0.99
    hb, ode = integrate(lambda t, z: [z[1], PRELOAD + FORCE * np.cos(2.12 * t) - DAMPING * z[1]
                                      - z[0] - z[0] ** 3], sol.coefficients, 1.06, 60, 1)
    amplitude = np.ptp(hb)
    error = np.abs(hb - ode).max()
    # HB with 12 harmonics of omega / 2 against the true orbit: truncation error (measured
    # 1.8e-11 of the motion, at the ODE tolerance)
    assert error < 1e-9 * amplitude
    # the orbit has period 2 T, not T: its half-period shift differs by the odd harmonics
    assert np.abs(ode - np.roll(ode, 32, axis=0)).max() > 0.2 * amplitude


def test_period_doubling_direction_lies_in_the_odd_harmonics(doubling):
    res, events = doubling
    pd = period_doubling_point(res, events[1].x, events[1].lam, refine=False)
    phi = pd.direction.reshape(-1, 1)
    assert np.abs(phi[0::4]).max() == 0.0 and np.abs(phi[3::4]).max() == 0.0
    assert np.linalg.norm(phi) == pytest.approx(1.0)


@pytest.mark.validation
def test_second_branch_through_a_pitchfork_is_confirmed_by_time_integration():
    res = autoparametric()
    fun = continuation_function(res)
    branch = continue_branch(fun, np.zeros(res.size), 1.35,
                             Continuation(lam_min=1.35, lam_max=1.8, max_step=0.1))
    events = detect_bifurcations(fun, branch, options=BifurcationOptions(
        kinds=("fold", "branch_point")))
    assert [e.kind for e in events] == ["branch_point", "branch_point"]
    e = events[0]
    along = np.append(branch.x[e.index + 1] - branch.x[e.index],
                      branch.lam[e.index + 1] - branch.lam[e.index])
    second, _ = switch_branch_point(res, e.x, e.lam, along,
                                       Continuation(lam_min=1.35, lam_max=1.8,
                                                    max_step=0.1), step=0.01)
    Y = second.x.reshape(len(second), -1, 2)[:, :, 1]
    assert np.abs(branch.x.reshape(len(branch), -1, 2)[:, :, 1]).max() == 0.0  # y = 0
    assert np.abs(Y[1:]).max(axis=1).min() > 0.01                # the new branch: y != 0
    assert abs(second.lam[0] - e.lam) < 1e-4
    # next to the branch point, omega = 1.525, y = 0 is unstable and the new branch stable
    w = 1.525
    trivial = solve_point(res, w, branch.x[np.argmin(np.abs(branch.lam - w))])
    assert np.abs(hill(res, trivial.x, w).multipliers).max() > 1.005   # 1.0075: a real one
    i = int(np.argmin(np.abs(second.lam - w)))
    sol = solve_point(res, w, second.x[i])
    assert np.abs(hill(res, sol.x, w).multipliers).max() < 0.99

    def rhs(t, z):
        x, y, vx, vy = z
        return [vx, vy, F2 * np.cos(w * t) - C2 * vx - x - GAMMA * x**3 - BETA * x * y**2,
                -C2 * vy - W2**2 * y - GAMMA * y**3 - BETA * x**2 * y]

    hb, ode = integrate(rhs, sol.coefficients, w, 60, 2)
    amplitude = np.ptp(hb, axis=0)
    assert amplitude[1] > 0.3
    # 5 harmonics of a weakly nonlinear orbit: truncation error (measured 1.1e-8 of it)
    assert np.all(np.abs(hb - ode).max(axis=0) < 1e-7 * amplitude.max())
