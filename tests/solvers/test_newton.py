"""Damped Newton solver: convergence order, line search, scaling, counters and failures."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.newton import Newton, ResidualProblem
from rotorsim.solvers.stats import Stats


def _counted(fun):
    calls = {"n": 0}

    def wrapped(x):
        calls["n"] += 1
        return fun(x)

    return wrapped, calls


def _circle_line(x):
    """r = (x0^2 + x1^2 - 4, x0 - x1): roots (+-sqrt 2, +-sqrt 2)."""
    r = np.array([x[0] ** 2 + x[1] ** 2 - 4.0, x[0] - x[1]])
    return r, np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])


def test_quadratic_convergence_and_counters():
    fun, calls = _counted(_circle_line)
    problem = ResidualProblem.scaled(fun, 2)
    solver = Newton(tol=1e-14)
    stats = Stats()
    state = solver.init(problem, [3.0, 1.0], stats)
    history = [state.residual]
    while state.residual > 1e-14:
        state = solver.step(problem, state, stats)
        history.append(state.residual)
    assert np.allclose(state.x, [math.sqrt(2), math.sqrt(2)], rtol=0, atol=1e-14)
    # quadratic: r_{k+1} <= C r_k^2 once in the basin (C ~ |J^-1| |r''| / 2 < 1 here)
    tail = [(b, a) for a, b in itertools.pairwise(history) if a < 0.1 and b > 0]
    assert tail and all(b <= 1.0 * a * a for b, a in tail)
    assert stats.residual_evaluations == calls["n"] == len(history)
    assert stats.iterations == len(history) - 1 and stats.rejected_steps == 0
    assert stats.factorizations == stats.iterations


def test_line_search_rescues_newton_on_arctan():
    """Plain Newton on atan(x) = 0 diverges from |x0| > 1.39; the damped one converges."""
    def fun(x):
        return np.array([math.atan(x[0])]), np.array([[1.0 / (1.0 + x[0] ** 2)]])

    x = 3.0
    for _ in range(4):  # undamped iterates blow up
        x -= math.atan(x) * (1.0 + x * x)
    assert abs(x) > 1e3
    stats = Stats()
    state = Newton(tol=1e-13).solve(ResidualProblem.scaled(fun, 1), [3.0], stats)
    assert abs(state.x[0]) < 1e-13 and stats.rejected_steps > 0


def test_scaling_makes_badly_scaled_system_converge_to_same_root():
    """Unknowns of size 1e-5 (m) and 1e-3 (rad), residuals 1e3 N and 1 N m."""
    def fun(x):
        a, b = x[0] / 1e-5, x[1] / 1e-3
        r = np.array([1e3 * (a**3 + a - 2.0 + 0.1 * b), 1.0 * (b**3 + b - 2.0 + 0.1 * a)])
        j = np.array([[1e3 * (3 * a**2 + 1) / 1e-5, 1e3 * 0.1 / 1e-3],
                      [0.1 / 1e-5, (3 * b**2 + 1) / 1e-3]])
        return r, j

    problem = ResidualProblem.scaled(fun, 2, x_scale=[1e-5, 1e-3], r_scale=[1e3, 1.0])
    state = Newton(tol=1e-12).solve(problem, [0.0, 0.0])
    a, b = state.x / [1e-5, 1e-3]
    assert a == pytest.approx(b, abs=1e-12)  # symmetric in the scaled variables
    assert a**3 + a - 2.0 + 0.1 * b == pytest.approx(0.0, abs=1e-11)


def test_max_step_caps_the_first_step():
    fun = lambda x: (np.array([x[0] - 100.0]), np.array([[1.0]]))  # noqa: E731
    solver = Newton(max_step=10.0)
    problem = ResidualProblem.scaled(fun, 1)
    state = solver.step(problem, solver.init(problem, [0.0]))
    assert state.x[0] == pytest.approx(10.0) and state.step_length == pytest.approx(10.0)


def test_singular_jacobian_uses_regularised_step():
    """r = (x0^2 - 1, x0 + x1 - 2): J is singular at x0 = 0 but not zero."""
    def fun(x):
        return (np.array([x[0] ** 2 - 1.0, x[0] + x[1] - 2.0]),
                np.array([[2 * x[0], 0.0], [1.0, 1.0]]))

    state = Newton(tol=1e-12).solve(ResidualProblem.scaled(fun, 2), [0.0, 0.5])
    assert abs(abs(state.x[0]) - 1.0) < 1e-12 and state.x.sum() == pytest.approx(2.0)


def test_failures_raise_convergence_error_with_context():
    zero = lambda x: (np.array([1.0 + 0 * x[0]]), np.array([[0.0]]))  # noqa: E731
    with pytest.raises(ConvergenceError, match="Jacobian is zero") as err:
        Newton(where="bearing B1").solve(ResidualProblem.scaled(zero, 1), [0.0])
    assert err.value.where == "bearing B1" and err.value.iteration == 0
    assert err.value.residual == pytest.approx(1.0)
    slow = lambda x: (np.array([math.exp(x[0]) + 1.0]), np.array([[math.exp(x[0])]]))  # noqa: E731
    with pytest.raises(ConvergenceError) as err:  # no root: exp(x) + 1 > 0
        Newton(max_iter=5).solve(ResidualProblem.scaled(slow, 1), [0.0])
    assert err.value.iteration is not None and err.value.residual is not None


def test_bad_input():
    fun = lambda x: (x, np.eye(1))  # noqa: E731
    with pytest.raises(ModelError, match="x0"):
        Newton().solve(ResidualProblem.scaled(fun, 1), [1.0, 2.0])
    with pytest.raises(ModelError, match="x0"):
        Newton().solve(ResidualProblem.scaled(fun, 1), [math.nan])
    with pytest.raises(ModelError, match="x_scale"):
        ResidualProblem.scaled(fun, 1, x_scale=[0.0])
    with pytest.raises(ModelError):
        Newton(tol=-1.0)
    nan_fun = lambda x: (np.array([math.nan]), np.eye(1))  # noqa: E731
    with pytest.raises(ConvergenceError, match="not finite"):
        Newton().solve(ResidualProblem.scaled(nan_fun, 1), [1.0])
