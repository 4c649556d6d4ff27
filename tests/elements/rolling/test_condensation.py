"""Generic batched inner Newton and static condensation (seed 001 eqs 20-26)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.elements.rolling.condensation import (
    InnerNewton,
    LocalProblem,
    cholesky_solve,
    condense,
)
from rotorsim.errors import ModelError


def _spd(rng: np.random.Generator, m: int, n: int) -> np.ndarray:
    """``n`` random symmetric positive definite ``m x m`` matrices, layout (m, m, n)."""
    a = rng.normal(size=(n, m, m))
    return np.moveaxis(a @ np.swapaxes(a, 1, 2) + 0.1 * np.eye(m), 0, -1)


@pytest.mark.parametrize("m", [1, 2, 4, 6])
def test_cholesky_solve_matches_dense_solve(m):
    rng = np.random.default_rng(m)
    a = _spd(rng, m, 50)
    b = rng.normal(size=(m, 3, 50))
    x = cholesky_solve(a, b, np.full(m, 1e-12))
    ref = np.linalg.solve(np.moveaxis(a, -1, 0), np.moveaxis(b, -1, 0))
    assert np.allclose(np.moveaxis(x, -1, 0), ref, rtol=1e-10, atol=1e-12)


def test_cholesky_floor_replaces_singular_and_negative_pivots():
    # a zero matrix and a negative diagonal: the pivots become the floor, x = b / floor
    a = np.zeros((2, 2, 2))
    a[:, :, 1] = np.diag([-5.0, -1.0])
    b = np.ones((2, 1, 2))
    x = cholesky_solve(a, b, np.array([2.0, 4.0]))
    assert np.allclose(x[:, 0, :], [[0.5, 0.5], [0.25, 0.25]])


def _quadratic(h: np.ndarray, b: np.ndarray):
    """``Pi = 1/2 q.H.q - b.q`` for each system; ``q = (y, z)``; returns an evaluator at
    fixed ``z`` (stored in the last rows of ``q``)."""

    def make(z: np.ndarray, m: int):
        def evaluate(y, index):
            q = np.concatenate([y, z[:, index]])
            hh = h[..., index]
            g = np.einsum("ijM,jM->iM", hh, q) - b[:, index]
            e = 0.5 * np.einsum("iM,ijM,jM->M", q, hh, q) - np.einsum("iM,iM->M", b[:, index], q)
            return LocalProblem(e, g, np.array(hh), np.ones(q.shape[1]),
                                np.zeros((0, q.shape[1])))
        return evaluate
    return make


def test_condensation_of_a_quadratic_is_the_schur_complement():
    """Exact reference: for ``Pi`` quadratic, ``Pi*(z) = min_y Pi`` has the Hessian
    ``H_zz - H_zy H_yy^-1 H_yz`` and the gradient ``H* z - (b_z - H_zy H_yy^-1 b_y)``."""
    rng = np.random.default_rng(3)
    m, e, n = 4, 2, 20
    h = _spd(rng, m + e, n)
    b = rng.normal(size=(m + e, n))
    z = rng.normal(size=(e, n))
    evaluate = _quadratic(h, b)(z, m)
    # start away from the minimum: condense corrects the residual to second order (exact
    # for a quadratic, eq 25)
    local = evaluate(rng.normal(size=(m, n)), np.arange(n))
    g_star, h_star = condense(local, m, np.full(m, 1e-12))
    for k in range(n):
        hk, bk = h[..., k], b[:, k]
        schur = hk[m:, m:] - hk[m:, :m] @ np.linalg.solve(hk[:m, :m], hk[:m, m:])
        b_star = bk[m:] - hk[m:, :m] @ np.linalg.solve(hk[:m, :m], bk[:m])
        assert np.allclose(h_star[..., k], schur, rtol=1e-10, atol=1e-12)
        assert np.allclose(g_star[:, k], schur @ z[:, k] - b_star, rtol=1e-10, atol=1e-12)


def _quartic_evaluate(c: np.ndarray, z: np.ndarray):
    """Nonlinear convex test potential with one external DOF per system:
    ``Pi = sum_i c_i (y_i - z)^4 / 4 + |y|^2 / 2`` (y (2, M), z (M,))."""

    def evaluate(y, index):
        cc, zz = c[:, index], z[index]
        d = y - zz
        e = (cc * d**4).sum(0) / 4 + 0.5 * (y * y).sum(0)
        gy = cc * d**3 + y
        g = np.concatenate([gy, -(cc * d**3).sum(0)[None]])
        h = np.zeros((3, 3, y.shape[1]))
        h[0, 0], h[1, 1] = 3 * cc[0] * d[0] ** 2 + 1, 3 * cc[1] * d[1] ** 2 + 1
        h[0, 2] = h[2, 0] = -3 * cc[0] * d[0] ** 2
        h[1, 2] = h[2, 1] = -3 * cc[1] * d[1] ** 2
        h[2, 2] = (3 * cc * d**2).sum(0)
        return LocalProblem(e, g, h, np.abs(gy).sum(0) + 1.0, np.zeros((0, y.shape[1])))
    return evaluate


def test_newton_and_condensed_gradient_and_hessian_against_finite_differences():
    rng = np.random.default_rng(5)
    n = 12
    c = rng.uniform(1.0, 50.0, size=(2, n))
    z = rng.uniform(-2.0, 2.0, size=n)
    newton = InnerNewton(tol=1e-13)

    def condensed(zv):
        sol = newton.solve(_quartic_evaluate(c, zv), np.zeros((2, n)), 3, np.ones(2),
                           np.full(2, 10.0), np.full(2, 1e-9), 1.0)
        assert sol.stats.failures == 0 and sol.converged.all()
        g, h = condense(sol.local, 2, np.full(2, 1e-9))
        return sol, g[0], h[0, 0]

    sol, g, h = condensed(z)
    assert np.abs(sol.local.grad[:2]).max() <= 1e-12 * np.abs(sol.local.grad[2]).max()
    step = 1e-6
    energy = [condensed(z + s)[0].local.energy for s in (step, -step)]
    assert np.allclose(g, (energy[0] - energy[1]) / (2 * step), rtol=1e-7, atol=1e-9)
    grads = [condensed(z + s)[1] for s in (step, -step)]
    assert np.allclose(h, (grads[0] - grads[1]) / (2 * step), rtol=1e-6, atol=1e-8)


def test_line_search_backtracks_where_the_newton_step_overshoots():
    """``Pi = sqrt(1 + y^2)``: plain Newton from |y| > 1 diverges (y -> -y^3); the
    Armijo line search converges to 0."""

    def evaluate(y, index):
        r = np.sqrt(1 + y[0] ** 2)
        return LocalProblem(r, (y[0] / r)[None], (1 / r**3)[None, None],
                            np.ones(y.shape[1]), np.zeros((0, y.shape[1])))

    sol = InnerNewton(tol=1e-12).solve(evaluate, np.array([[1.5, -3.0, 0.5]]), 3, np.ones(1),
                                       np.full(1, 100.0), np.full(1, 1e-12), 1.0)
    assert sol.stats.failures == 0 and np.abs(sol.y).max() < 1e-10
    assert sol.stats.backtracks > 0


def test_failures_are_counted_not_hidden():
    rng = np.random.default_rng(2)
    c = rng.uniform(1.0, 50.0, size=(2, 6))
    z = np.full(6, 3.0)
    sol = InnerNewton(tol=1e-13, max_iter=1).solve(
        _quartic_evaluate(c, z), np.zeros((2, 6)), 3, np.ones(2), np.full(2, 10.0),
        np.full(2, 1e-9), 1.0)
    assert sol.stats.failures == 6 and not sol.converged.any()
    assert np.all(sol.residual > 1e-13)


@pytest.mark.parametrize("options", [dict(tol=0.0), dict(tol=0.5), dict(max_iter=0),
                                     dict(max_backtracks=1.5)])
def test_bad_options_raise_model_error(options):
    with pytest.raises(ModelError):
        InnerNewton(**options)
