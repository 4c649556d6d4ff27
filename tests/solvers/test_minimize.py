"""Energy minimisation: local trust-region wrapper, batched trust region, global search."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.global_search import GlobalSearch, trust_region_batch
from rotorsim.solvers.minimize import minimize_energy
from rotorsim.solvers.stats import Stats

# Himmelblau's function: four minima with f = 0, one maximum and four saddles
HIMMELBLAU_MINIMA = np.array([[3.0, 2.0], [-2.805118, 3.131312], [-3.779310, -3.283186],
                              [3.584428, -1.848126]])
HIMMELBLAU_MAX = np.array([-0.270845, -0.923039])


def himmelblau(x):
    x = np.atleast_2d(x)
    a, b = x[:, 0], x[:, 1]
    u, v = a * a + b - 11.0, a + b * b - 7.0
    e = u * u + v * v
    g = np.stack([4 * a * u + 2 * v, 2 * u + 4 * b * v], axis=1)
    h = np.empty((x.shape[0], 2, 2))
    h[:, 0, 0] = 12 * a * a + 4 * b - 42
    h[:, 1, 1] = 12 * b * b + 4 * a - 26
    h[:, 0, 1] = h[:, 1, 0] = 4 * (a + b)
    return e, g, h


def rosenbrock(x):
    e = 100 * (x[1] - x[0] ** 2) ** 2 + (1 - x[0]) ** 2
    g = np.array([-400 * x[0] * (x[1] - x[0] ** 2) - 2 * (1 - x[0]), 200 * (x[1] - x[0] ** 2)])
    h = np.array([[1200 * x[0] ** 2 - 400 * x[1] + 2, -400 * x[0]], [-400 * x[0], 200.0]])
    return float(e), g, h


@pytest.mark.parametrize("method", ["trust-exact", "trust-ncg", "trust-constr", "Newton-CG"])
def test_local_minimum_of_rosenbrock(method):
    stats = Stats()
    found = minimize_energy(rosenbrock, [-1.2, 1.0], method=method, tol=1e-10, stats=stats)
    assert np.allclose(found.x, [1.0, 1.0], atol=1e-9)
    assert np.max(np.abs(found.gradient)) <= 1e-10 and found.positive_definite
    assert stats.residual_evaluations >= found.iterations > 5


def test_scales_are_honoured():
    """Same minimum with unknowns of size 1e-6 and energies of size 1e-9."""
    def fun(y):
        e, g, h = rosenbrock(y / 1e-6)
        return 1e-9 * e, 1e-9 * g / 1e-6, 1e-9 * h / 1e-12

    found = minimize_energy(fun, [-1.2e-6, 1e-6], x_scale=1e-6, energy_scale=1e-9)
    assert np.allclose(found.x, [1e-6, 1e-6], rtol=0, atol=1e-15)


def test_local_errors():
    with pytest.raises(TypeError, match="trust-exact"):
        minimize_energy(rosenbrock, [0.0, 0.0], method="BFGS")
    with pytest.raises(ConvergenceError):
        minimize_energy(rosenbrock, [-1.2, 1.0], max_iter=2)
    with pytest.raises(ModelError):
        minimize_energy(rosenbrock, [0.0, 0.0], x_scale=[-1.0, 1.0])


def test_global_search_finds_all_four_himmelblau_minima():
    stats = Stats()
    found = GlobalSearch(n_starts=32, seed=3).run(himmelblau, [-5.0, -5.0], [5.0, 5.0],
                                                  stats=stats)
    assert len(found.minima) == 4
    got = np.array(sorted(m.x.tolist() for m in found.minima))
    ref = np.array(sorted(HIMMELBLAU_MINIMA.tolist()))
    assert np.allclose(got, ref, atol=1e-6)  # reference printed to 6 decimals
    assert all(m.positive_definite and abs(m.energy) < 1e-18 for m in found.minima)
    assert sum(m.hits for m in found.minima) == found.n_converged
    assert found.n_converged + found.n_saddles + found.n_escaped + found.n_failed == 32
    assert stats.residual_evaluations == stats.iterations + 1  # one batched call each


def test_batch_leaves_the_maximum_and_saddles():
    """A start exactly on the maximum (zero gradient, negative Hessian) must move off."""
    starts = np.vstack([HIMMELBLAU_MAX, [0.0, 0.0], [3.5, -1.8]])
    out = trust_region_batch(himmelblau, starts, tol=1e-10, max_iter=100)
    assert np.all(out.status == 0)
    for x in out.x:
        assert np.min(np.abs(HIMMELBLAU_MINIMA - x).max(axis=1)) < 1e-6
    assert np.all(np.linalg.eigvalsh(out.hessian)[:, 0] > 0)


def test_batch_agrees_with_scipy_from_the_same_start():
    starts = np.array([[0.5, 0.5], [-1.0, 2.0], [4.0, -4.0]])
    out = trust_region_batch(himmelblau, starts, tol=1e-11)

    def single(x):
        e, g, h = himmelblau(x)
        return float(e[0]), g[0], h[0]

    for start, x in zip(starts, out.x, strict=True):
        ref = minimize_energy(single, start, tol=1e-11)
        if np.max(np.abs(ref.x - x)) < 1e-3:  # same basin: same point to the tolerance
            assert np.allclose(ref.x, x, atol=1e-9)
        else:  # different basins are allowed, both must be minima
            assert np.min(np.abs(HIMMELBLAU_MINIMA - ref.x).max(axis=1)) < 1e-6


def test_escaped_starts_are_counted():
    """E = -x^2/2 has no minimum: every start runs downhill out of the box."""
    def fun(x):
        return -0.5 * (x**2).sum(1), -x, -np.repeat(np.eye(1)[None], x.shape[0], 0)

    found = GlobalSearch(n_starts=8).run(fun, [-1.0], [1.0])
    assert found.minima == () and found.n_escaped + found.n_saddles == 8


def test_global_bad_input():
    with pytest.raises(ModelError):
        GlobalSearch().run(himmelblau, [1.0, 0.0], [0.0, 1.0])
    with pytest.raises(ModelError):
        GlobalSearch(n_starts=0).run(himmelblau, [0.0, 0.0], [1.0, 1.0])
