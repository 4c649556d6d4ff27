"""Observed order of accuracy equals the declared order, for every Newmark-family method
(STYLE practice 9: one test over all methods).

Two smooth problems with step halving: a forced damped oscillator with its closed-form
solution, and a forced damped pendulum (nonlinear, exercising the Newton path and the
force-weighted alpha terms) against scipy DOP853 at rtol 1e-12. The observed order
``log2(e(h) / e(h/2))`` must lie within 0.1 of the declared one; at these step sizes the
higher error terms shift it by at most 0.06 (generalised-alpha with rho_inf = 0 on the
pendulum, coarsest pair; below 0.01 for most pairs).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorsim.time_integration.adams import Adams
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem

METHODS = {
    "average_acceleration": Newmark.average_acceleration(),
    "linear_acceleration": Newmark.linear_acceleration(),
    "hht": Newmark.hht(alpha=-0.1),
    "hht_max_damping": Newmark.hht(alpha=-1.0 / 3.0),
    "generalized_alpha": Newmark.generalized_alpha(rho_inf=0.8),
    "generalized_alpha_0": Newmark.generalized_alpha(rho_inf=0.0),
}
DECLARED = {name: 2 for name in METHODS}  # issue 6: Newmark 2, HHT 2, generalised-alpha 2
METHODS["adams4"] = Adams()  # seed 002 Appendix F with RK4 start-up (issue 6: Adams 4)
DECLARED["adams4"] = 4

W, ZETA, OMEGA, FORCE = 1.3, 0.05, 2.0, 1.0
T_END = 4.0


def forced_oscillator_exact(t):
    """x'' + 2 zeta omega x' + omega^2 x = F cos(W t), x(0) = 1, x'(0) = 0."""
    H = FORCE / (OMEGA**2 - W**2 + 2j * ZETA * OMEGA * W)
    wd = OMEGA * np.sqrt(1 - ZETA**2)
    A = 1 - H.real
    B = (-(1j * W * H).real + ZETA * OMEGA * A) / wd
    decay = np.exp(-ZETA * OMEGA * t)
    x = (H * np.exp(1j * W * t)).real + decay * (A * np.cos(wd * t) + B * np.sin(wd * t))
    v = ((1j * W * H * np.exp(1j * W * t)).real
         + decay * ((B * wd - ZETA * OMEGA * A) * np.cos(wd * t)
                    - (A * wd + ZETA * OMEGA * B) * np.sin(wd * t)))
    return x, v


def pendulum(q, v, t):
    return 4.0 * np.sin(q), np.array([[4.0 * np.cos(q[0])]]), None


def pendulum_reference():
    sol = solve_ivp(lambda t, y: [y[1], 0.5 * np.cos(1.5 * t) - 0.1 * y[1] - 4 * np.sin(y[0])],
                    (0.0, T_END), [1.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14)
    return sol.y[0, -1], sol.y[1, -1]


PROBLEMS = {
    "forced_oscillator": (SecondOrderProblem(
        np.eye(1), np.array([[OMEGA**2]]), np.array([[2 * ZETA * OMEGA]]),
        load=lambda t: np.array([FORCE * np.cos(W * t)])), forced_oscillator_exact(T_END)),
    "pendulum": (SecondOrderProblem(
        np.eye(1), np.zeros((1, 1)), np.array([[0.1]]), restoring=pendulum,
        load=lambda t: np.array([0.5 * np.cos(1.5 * t)])), pendulum_reference()),
}


@pytest.mark.parametrize("problem_name", list(PROBLEMS))
@pytest.mark.parametrize("name", list(METHODS))
def test_observed_order_matches_declared_order(name, problem_name):
    method, (problem, (x_ref, v_ref)) = METHODS[name], PROBLEMS[problem_name]
    assert method.order == DECLARED[name]
    errors = []
    for steps in (100, 200, 400):
        res = integrate(problem, method, (0.0, T_END), [1.0], [0.0], dt=T_END / steps)
        errors.append(max(abs(res.q[-1, 0] - x_ref), abs(res.v[-1, 0] - v_ref)))
    observed = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(observed - DECLARED[name]) < 0.1), (errors, observed)

