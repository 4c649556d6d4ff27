"""The average-acceleration flow with its sensitivities (the discrete monodromy matrix)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.sensitivity_flow import average_acceleration_flow


def _duffing(alpha: float = 4e3, force: float = 1.0, omega: float = 1.3) -> SecondOrderProblem:
    """Two masses on springs with a cubic spring to ground on the first and a harmonic
    force on it: ``M = I``, ``K = [[2, -1], [-1, 2]]``, light damping."""
    def restoring(q, v, t):
        k = np.array([[3.0 * alpha * q[0] ** 2]])
        return (np.array([alpha * q[0] ** 3, 0.0]), LocalMatrix(2, np.array([0]), k),
                LocalMatrix(2, np.array([0]), np.zeros((1, 1))))

    return SecondOrderProblem(mass=np.eye(2), stiffness=np.array([[2.0, -1.0], [-1.0, 2.0]]),
                              damping=0.02 * np.eye(2), restoring=restoring,
                              load=lambda t: np.array([force * np.cos(omega * t), 0.0]))


def test_the_monodromy_of_a_damped_oscillator_tends_to_the_exact_one_at_second_order():
    """``q'' + 2 zeta w q' + w^2 q = 0`` over ``T = 2 pi / w``: the exact multipliers are
    ``exp(lambda T)``, ``lambda = -zeta w +- i w sqrt(1 - zeta^2)``. The scheme's are off
    by ``O(h^2)``: halving the step divides the error by about 4 (3.5 to 4.5 accepted)."""
    w, zeta = 3.0, 0.05
    p = SecondOrderProblem(mass=np.eye(1), stiffness=np.array([[w * w]]),
                           damping=np.array([[2 * zeta * w]]))
    T = 2 * np.pi / w
    lam = -zeta * w + 1j * w * np.sqrt(1 - zeta ** 2)
    exact = np.exp(lam * T)
    errors = []
    for steps in (50, 100, 200):
        mu = np.linalg.eigvals(average_acceleration_flow(p, np.zeros(1), np.zeros(1), 0.0, T,
                                                         steps).monodromy)
        errors.append(np.min(np.abs(mu - exact)))
    assert errors[-1] < 1e-3
    for coarse, fine in itertools.pairwise(errors):
        assert 3.5 < coarse / fine < 4.5


def test_an_undamped_linear_oscillator_keeps_unit_multipliers():
    """Average acceleration conserves the energy of a linear undamped system: the moduli
    of its multipliers are 1 to round-off, whatever the step (no numerical damping)."""
    p = SecondOrderProblem(mass=np.diag([1.0, 2.0]), stiffness=np.array([[5.0, -1.0],
                                                                            [-1.0, 3.0]]))
    mu = np.linalg.eigvals(average_acceleration_flow(p, np.zeros(2), np.zeros(2), 0.0, 1.7,
                                                     23).monodromy)
    assert np.allclose(np.abs(mu), 1.0, atol=1e-12)


def test_the_sensitivities_are_the_derivatives_of_the_discrete_flow():
    """Against central differences of the flow itself on a forced cubic-spring chain:
    the propagated monodromy is the exact Jacobian of the discrete map (to the Newton
    tolerance), so the two agree to the differences' truncation, ~1e-7 of its norm."""
    p = _duffing()
    q0, v0 = np.array([0.02, -0.01]), np.array([0.05, 0.03])
    T = 2 * np.pi / 1.3
    phi = average_acceleration_flow(p, q0, v0, 0.0, T, 120).monodromy
    z0, h = np.concatenate([q0, v0]), 1e-6
    fd = np.empty((4, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = h
        plus = average_acceleration_flow(p, (z0 + e)[:2], (z0 + e)[2:], 0.0, T, 120,
                                         sensitivities=False)
        minus = average_acceleration_flow(p, (z0 - e)[:2], (z0 - e)[2:], 0.0, T, 120,
                                          sensitivities=False)
        fd[:, j] = (np.concatenate([plus.q, plus.v]) - np.concatenate([minus.q, minus.v])) / (2 * h)
    assert np.max(np.abs(phi - fd)) < 1e-6 * np.max(np.abs(phi))


def test_a_banded_system_gives_the_dense_result():
    """A 40-DOF chain (band storage) against the same chain with one long spring that
    couples its ends set to zero stiffness, i.e. the same matrix, factorised densely: the
    monodromy matrices agree to round-off (1e-9 of their size)."""
    n = 40
    K = 2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    banded = SecondOrderProblem(mass=np.eye(n), stiffness=K, damping=0.01 * K)
    wide = K.copy()
    wide[0, -1] = wide[-1, 0] = 1e-300       # a stored entry far off the band
    dense = SecondOrderProblem(mass=np.eye(n), stiffness=wide, damping=0.01 * K)
    q0 = np.sin(np.arange(n))
    a = average_acceleration_flow(banded, q0, np.zeros(n), 0.0, 3.0, 60)
    b = average_acceleration_flow(dense, q0, np.zeros(n), 0.0, 3.0, 60)
    assert np.max(np.abs(a.monodromy - b.monodromy)) < 1e-9 * np.max(np.abs(a.monodromy))
    assert np.allclose(a.q, b.q, rtol=0, atol=1e-12)


def test_bad_arguments_and_a_failing_step_are_named():
    p = _duffing()
    with pytest.raises(ModelError, match="steps"):
        average_acceleration_flow(p, np.zeros(2), np.zeros(2), 0.0, 1.0, 0)
    with pytest.raises(ModelError, match="duration"):
        average_acceleration_flow(p, np.zeros(2), np.zeros(2), 0.0, float("nan"), 10)
    with pytest.raises(ModelError, match=r"\(2,\)"):
        average_acceleration_flow(p, np.zeros(3), np.zeros(2), 0.0, 1.0, 10)
    # a stiffening spring started far out: Newton cannot follow within the iterations
    with pytest.raises(ConvergenceError, match="step"):
        average_acceleration_flow(_duffing(alpha=1e9), np.array([5.0, 0.0]), np.zeros(2),
                                  0.0, 5.0, 2, max_iterations=3)
