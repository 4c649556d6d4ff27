"""Local (bearing-DOF) tangents: the low-rank solve equals the dense one."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.local_tangent import (
    BaseFactors,
    LocalMatrix,
    LowRankSolve,
    embed,
)
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem


def test_woodbury_solve_equals_the_dense_solve():
    rng = np.random.default_rng(1)
    n, dofs = 12, np.array([2, 5, 9])
    S0 = rng.normal(size=(n, n)) + n * np.eye(n)
    B = rng.normal(size=(3, 3))
    full = S0.copy()
    full[np.ix_(dofs, dofs)] += B
    b = rng.normal(size=n)
    solve = LowRankSolve.build(BaseFactors.build(factorize(S0), dofs), B, "test")
    np.testing.assert_allclose(solve.solve(b), np.linalg.solve(full, b), rtol=1e-12)


def test_local_matrix_products_and_embedding():
    A = LocalMatrix(5, np.array([4, 1]), np.array([[1.0, 2.0], [3.0, 4.0]]))
    B = LocalMatrix(5, np.array([1, 2]), np.eye(2))
    x = np.arange(5.0)
    np.testing.assert_allclose(A @ x, A.toarray() @ x)
    np.testing.assert_allclose(A.tocsr().toarray(), A.toarray())
    dofs, block = embed([(2.0, A), (3.0, B)])
    full = np.zeros((5, 5))
    full[np.ix_(dofs, dofs)] = block
    np.testing.assert_allclose(full, 2 * A.toarray() + 3 * B.toarray())
    with pytest.raises(ModelError):
        LocalMatrix(3, np.array([0, 0]), np.eye(2))


def _chain(local: bool) -> SecondOrderProblem:
    """Spring chain with a cubic spring and a cubic damper on DOFs 3 and 4."""
    n = 8
    K = 2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    dofs = np.array([3, 4])

    def restoring(q, v, t):
        d, w = q[4] - q[3], v[4] - v[3]
        f = 50.0 * d**3 + 0.5 * w**3
        r = np.zeros(n)
        r[dofs] = [-f, f]
        e = np.array([[1.0, -1.0], [-1.0, 1.0]])
        kb, cb = 150.0 * d**2 * e, 1.5 * w**2 * e
        if local:
            return r, LocalMatrix(n, dofs, kb), LocalMatrix(n, dofs, cb)
        K_full, C_full = np.zeros((n, n)), np.zeros((n, n))
        K_full[np.ix_(dofs, dofs)], C_full[np.ix_(dofs, dofs)] = kb, cb
        return r, K_full, C_full

    return SecondOrderProblem(mass=np.eye(n), stiffness=K, damping=0.01 * K,
                              restoring=restoring, load=lambda t: np.sin(3 * t) * np.eye(n)[0])


@pytest.mark.parametrize("method", [Newmark.average_acceleration(), Newmark.hht(-0.1)])
def test_newmark_with_local_tangents_matches_dense_and_factorises_once(method):
    q0 = np.linspace(0.0, 0.3, 8)
    runs = [integrate(_chain(local), method, (0.0, 5.0), q0, np.zeros(8), dt=0.01)
            for local in (True, False)]
    np.testing.assert_allclose(runs[0].q, runs[1].q, rtol=0, atol=1e-11)
    assert runs[0].stats["factorizations"] == 2  # M, then the constant part once
    assert runs[1].stats["factorizations"] > 400
