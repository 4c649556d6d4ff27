"""Adaptive step size: the error estimate, rejections, step growth and failures."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.adaptive import Adaptive
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem

OMEGA, ZETA, W, FORCE = 2.0, 0.05, 1.3, 1.0


def oscillator(zeta=ZETA, omega=OMEGA, load=None):
    return SecondOrderProblem(np.eye(1), np.array([[omega**2]]),
                              np.array([[2 * zeta * omega]]), load=load)


def exact_from(t0, q0, v0, t):
    """Solution of x'' + 2 zeta omega x' + omega^2 x = F cos(W t) through (t0, q0, v0)."""
    H = FORCE / (OMEGA**2 - W**2 + 2j * ZETA * OMEGA * W)
    xp = lambda s: (H * np.exp(1j * W * s)).real  # noqa: E731
    vp = lambda s: (1j * W * H * np.exp(1j * W * s)).real  # noqa: E731
    wd = OMEGA * np.sqrt(1 - ZETA**2)
    A = q0 - xp(t0)
    B = (v0 - vp(t0) + ZETA * OMEGA * A) / wd
    tau = t - t0
    return xp(t) + np.exp(-ZETA * OMEGA * tau) * (A * np.cos(wd * tau) + B * np.sin(wd * tau))


@pytest.mark.validation
@pytest.mark.parametrize("method", [Newmark.average_acceleration(), Newmark.hht(-0.1),
                                    Newmark.hht(-0.3), Newmark.generalized_alpha(0.8),
                                    Newmark.generalized_alpha(0.0)],
                         ids=["average", "hht-0.1", "hht-0.3", "galpha0.8", "galpha0"])
def test_error_estimate_tracks_the_true_local_error(method):
    problem = oscillator(load=lambda t: np.array([FORCE * np.cos(W * t)]))
    states = [method.init(problem, 0.0, [1.0], [0.0], dt=0.01)]
    for _ in range(400):
        states.append(method.step(problem, states[-1]))
    old, new = states[100:-1], states[101:]  # after the start-up of the alpha methods
    t0, q0, v0 = (np.array([getattr(s, f) if f == "t" else getattr(s, f)[0] for s in old])
                  for f in ("t", "q", "v"))
    t1, q1 = np.array([s.t for s in new]), np.array([s.q[0] for s in new])
    true = q1 - exact_from(t0, q0, v0, t1)
    estimate = np.array([method.local_error(a, b)[0] for a, b in zip(old, new, strict=True)])
    # leading-term analysis (Zienkiewicz & Xie 1991; alpha shift of Arnold & Bruls 2007):
    # the estimate is exact up to O(h^4) terms, i.e. O(omega h) = 2 % of the error size
    assert np.max(np.abs(estimate - true)) < 0.05 * np.max(np.abs(true))


@pytest.mark.validation
def test_global_error_follows_the_tolerance():
    problem = oscillator()
    wd = OMEGA * np.sqrt(1 - ZETA**2)
    exact = lambda t: np.exp(-ZETA * OMEGA * t) * (  # noqa: E731
        np.cos(wd * t) + ZETA * OMEGA / wd * np.sin(wd * t))
    errors = []
    for rtol in (1e-4, 1e-6):
        res = integrate(problem, Adaptive(rtol=rtol, atol=0.0), (0.0, 10.0), [1.0], [0.0],
                        dt=0.1)
        errors.append(np.max(np.abs(res.q[:, 0] - exact(res.t))))
    # local error ~ tol, steps ~ tol^(-1/3): global error ~ tol^(2/3), ratio 100^(2/3) = 21.5
    assert 21.5 / 2 < errors[0] / errors[1] < 21.5 * 2


def test_rejected_steps_are_recorded_and_counted():
    problem = oscillator(zeta=0.0, omega=2 * np.pi)
    res = integrate(problem, Adaptive(rtol=1e-5), (0.0, 3.0), [1.0], [0.0], dt=1.0)
    stats = res.stats
    assert stats["rejected_steps"] >= 2  # a first trial of one period cannot pass
    assert stats["newton_failures"] == 0
    # linear problem: one solve per attempt plus the initial acceleration
    assert stats["solves"] == 1 + stats["steps"] + stats["rejected_steps"]
    assert stats["factorizations"] < stats["steps"] / 2  # the hold band reuses most LUs


def test_step_grows_as_a_vibration_decays():
    zeta, omega = 0.05, 2 * np.pi
    res = integrate(oscillator(zeta, omega), Adaptive(rtol=1e-5), (0.0, 20.0), [1.0], [0.0],
                    dt=1e-3)
    h = np.diff(res.t)
    early, late = h[res.t[1:] < 2.0].mean(), h[res.t[1:] > 18.0].mean()
    # error ~ amplitude h^3 at a fixed absolute scale: h ~ amplitude^(-1/3), i.e.
    # exp(zeta omega 16 / 3) = 5.3 between the two windows; hold bands quantise the ratio
    assert 5.3 / 1.5 < late / early < 5.3 * 1.5


def test_step_shrinks_at_a_load_ramp_and_grows_after_it():
    ramp = lambda t: np.array([np.tanh((t - 2.0) / 0.005) + 1.0])  # noqa: E731
    log = []
    res = integrate(oscillator(zeta=0.3, load=ramp), Adaptive(rtol=1e-5, dt_max=0.02),
                    (0.0, 6.0), [0.0], [0.0], dt=0.01,
                    callback=lambda s: log.append((s.t, s.counters.rejected_steps)))
    t, rejected = np.array(log).T
    h = np.diff(res.t)
    assert abs(res.t[1:][np.argmin(h)] - 2.0) < 0.02 and h.min() < 0.002
    first_rejection = t[np.argmax(rejected > 0)]
    assert 1.9 < first_rejection < 2.05
    assert h[-20:].min() > 10 * h.min()  # smooth again: the step has grown back


def test_failed_newton_solve_is_retried_with_a_smaller_step():
    def hardening(q, v, t):
        return 50.0 * q**3, np.array([[150.0 * q[0] ** 2]]), None

    problem = SecondOrderProblem(np.eye(1), np.eye(1), restoring=hardening)
    stepper = Adaptive(Newmark(max_iter=4), rtol=1e-4)
    res = integrate(problem, stepper, (0.0, 2.0), [2.0], [0.0], dt=0.5)
    assert res.stats["newton_failures"] >= 1
    assert res.stats["rejected_steps"] >= res.stats["newton_failures"]
    assert res.t[1] <= 0.5 / 4 and res.t[-1] == 2.0 and np.all(np.isfinite(res.q))


def test_step_size_underflow_raises():
    load = lambda t: np.array([np.nan if t > 0.5 else 0.0])  # noqa: E731
    with pytest.raises(ConvergenceError, match=r"fell below the minimum|consecutive"):
        integrate(oscillator(load=load), Adaptive(), (0.0, 1.0), [1.0], [0.0], dt=0.01)


def test_invalid_adaptive_options_are_rejected():
    with pytest.raises(ModelError, match="vanishes"):
        Adaptive(Newmark.linear_acceleration())
    with pytest.raises(ModelError, match="safety"):
        Adaptive(safety=1.5)
    with pytest.raises(ModelError, match="hold"):
        Adaptive(hold=(1.1, 1.3))
