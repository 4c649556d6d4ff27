"""Bordered linear algebra of continuation: determinants, fill-in, and a large branch."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp

from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_core import bordered, signed_log_det
from rotorsim.solvers.linear import factorize


@pytest.mark.parametrize("n", [7, 150])  # dense LAPACK and SuperLU paths
def test_signed_log_det_matches_numpy(n):
    rng = np.random.default_rng(3)
    for _ in range(3):
        A = rng.standard_normal((n, n)) + np.diag(rng.standard_normal(n))
        fact = factorize(sp.csc_matrix(A) if n > 120 else A)
        sign, log_det = signed_log_det(fact)
        ref_sign, ref_log = np.linalg.slogdet(A)
        assert sign == ref_sign and log_det == pytest.approx(ref_log, rel=1e-10)


def test_sparse_bordered_matrix_factors_without_fill():
    """A dense border row would be chosen as pivot by partial pivoting and fill the LU
    factors (O(m^2)); the weighted border keeps them O(m). The Jacobian rows are solved to
    round-off, the border row to ~eps / BORDER_WEIGHT = 2e-8 (see its docstring)."""
    m = 1000
    jh = sp.diags([-0.5, 1.0, -0.5], [-1, 0, 1], shape=(m, m)).tocsr()
    rng = np.random.default_rng(0)
    jlh, border = rng.random(m), rng.random(m + 1)
    border /= np.linalg.norm(border)
    matrix, weight = bordered(jh, jlh, border)
    fact = factorize(matrix)
    assert fact._sparse.L.nnz + fact._sparse.U.nnz <= 10 * m
    rhs = rng.standard_normal(m + 1)
    z = fact.solve(np.concatenate([rhs[:-1], [weight * rhs[-1]]]))
    assert np.allclose(jh @ z[:-1] + jlh * z[-1], rhs[:-1], atol=1e-12)
    assert border @ z == pytest.approx(rhs[-1], abs=1e-7)


def test_large_sparse_branch_cost():
    """300 points of a 1000-unknown Bratu branch (tridiagonal Jacobian) cost at most two
    factorisations per point here: one corrector iteration and one tangent solve."""
    n = 1000
    lap = (sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)) * (n + 1) ** 2).tocsr()

    def bratu(u, lam):
        e = np.exp(u)
        return lap @ u - lam * e, (lap - sp.diags(lam * e)).tocsr(), -e

    opts = Continuation(initial_step=0.05, max_step=0.05, max_points=300,
                        x_scale=math.sqrt(n), r_scale="auto")
    b = continue_branch(bratu, np.zeros(n), 0.0, opts, progress=True)
    assert len(b) == 300 and b.reason == "max_points reached"
    assert b.stats["factorizations"] <= 2 * len(b) and b.stats["rejected_steps"] == 0
    assert np.count_nonzero(np.diff(np.sign(b.tangents[:, -1]))) == 1  # passed the fold
    assert b.stats["wall_time"] < 60.0  # ~2 s on one core when this test was written


# ---------------------------------------------------------------- round-off floor (issue 12)
BIG = 1e10   # constant terms of R that cancel: R carries an error of ~eps * BIG = 2e-6


def _cancelling(x, lam):
    """``R = (x + BIG) - BIG - lam`` (root ``x = lam``), evaluated as written: round-off of
    ~2e-6, far above tol = 1e-10, wherever ``x`` is."""
    return np.array([(x[0] + BIG) - BIG - lam]), np.eye(1), -np.ones(1)


def _cancelling_with_terms(x, lam):
    r, jac, jlam = _cancelling(x, lam)
    return r, jac, jlam, np.array([abs(x[0]) + 2 * BIG + abs(lam)])


OPTS_FLOOR = Continuation(initial_step=0.1, max_step=0.2, lam_min=0.0, lam_max=1.0,
                          tol=1e-10)


def test_convergence_is_judged_against_the_reachable_round_off_floor():
    """With the size of the terms given (4th item), a residual at round-off level counts
    as converged: the branch reaches its bound. The accepted points solve the problem to
    the floor ROUNDOFF * eps * 2e10 = 2.8e-4 (the residual itself, not a tolerance choice)."""
    from rotorsim.solvers.continuation_core import ROUNDOFF

    b = continue_branch(_cancelling_with_terms, [0.0], 0.0, OPTS_FLOOR)
    assert b.status.name == "OK" and b.reason == "lam_max = 1 reached"
    floor = ROUNDOFF * np.finfo(float).eps * (2 * BIG + 2.0)
    assert np.all(b.residuals <= floor)
    np.testing.assert_allclose(b.x[:, 0], b.lam, rtol=0, atol=floor)


def test_a_miss_above_tol_without_the_term_sizes_stops_and_says_why():
    """Without the term sizes the floor is estimated from |dR/dx| |x| + |dR/dlam| |lam|,
    which does not see the cancelling constants: the branch stops, not OK, and the
    message gives the residual, the tolerance and the floor."""
    b = continue_branch(_cancelling, [0.0], 0.0, OPTS_FLOOR)
    assert b.status.name == "NOT_CONVERGED" and b.lam[-1] < 0.5   # far from lam_max = 1
    assert "against tol 1e-10, round-off floor" in b.reason
