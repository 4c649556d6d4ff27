"""The linear solves of the Radau IIA stepper, condensed onto the displacements.

Simplified Newton on the three-stage Radau IIA collocation equations of the first-order form
``y = (q, v)``, ``y' = (v, a)``, ``M a = -g(q, v, t)``, needs solves with ``mu I - J`` for
one real and one complex shift ``mu`` (the eigenvalues of the inverse Runge-Kutta matrix
over ``h``; Hairer & Wanner IV.8). With the Jacobian
``J = [[0, I], [-M^-1 K_t, -M^-1 D_t]]`` the solve of ``(mu I - J) (x_q, x_v) = (b_q, b_v)``
condenses onto the displacements:

    S(mu) x_q = M b_v + (mu M + D_t) b_q,    x_v = mu x_q - b_q,
    S(mu) = mu^2 M + mu D_t + K_t,

with ``D_t = C + s G + dr/dv`` and ``K_t = K + dr/dq``. No inverse of ``M`` is formed and
``M b_v`` is known from the net force (``M a = -g``). The nonlinear tangents live on a few
DOFs, so ``S(mu) = S0(mu) + P (mu C_b + K_b) P^T``: ``S0(mu)`` (mass, damping, gyroscopic and
linear stiffness) is factorised once per step size and speed and the bearing part is added
by the Woodbury identity of :mod:`~rotorsim.time_integration.local_tangent`, as in the
Newmark steps.

References
----------
E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., Springer 1996,
section IV.8 (eqs 8.15-8.20). The condensation is the block elimination of ``J``'s
second-order structure.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.time_integration.base import FloatArray, IntArray
from rotorsim.time_integration.problem import SecondOrderProblem, combine

DENSE_LIMIT = 400
"""Up to this size the shifted matrices are factorised densely (the problem's matrices are
dense there too: see ``equation.DENSE_STEPPING``)."""


@dataclass(frozen=True, eq=False)
class ShiftedFactors:
    """``S0(mu) = mu^2 M + mu D + K`` factorised (``D = C + s G``), with ``Z = S0^-1 P`` on
    ``dofs``; ``damping`` is ``D`` itself and ``coupling`` is ``mu M + D``, the matrix
    that takes ``b_q`` into the condensed right-hand side."""

    mu: complex
    lu: Any
    dofs: IntArray
    Z: Any
    Zd: Any
    damping: Any
    coupling: Any

    @classmethod
    def build(cls, problem: SecondOrderProblem, mu: complex, spin: float, dofs: IntArray,
              where: str) -> ShiftedFactors:
        """Factorise ``S0(mu)`` at the schedule value ``spin``."""
        n = problem.n
        m = mu.real if mu.imag == 0.0 else mu
        terms = [(1.0, problem.damping), (spin, problem.gyroscopic)]
        D = combine(terms, n) if any(A is not None for _, A in terms) else None
        sparse = sp.issparse(problem.mass) or n > DENSE_LIMIT
        if sparse:
            coupling: Any = m * sp.csr_matrix(problem.mass)
            S0: Any = m * coupling + sp.csr_matrix(problem.stiffness)
            if D is not None:
                D = sp.csr_matrix(D)
                S0 = S0 + m * D
                coupling = coupling + D
        else:
            coupling = m * np.asarray(problem.mass)
            S0 = m * coupling + np.asarray(problem.stiffness)
            if D is not None:
                D = D.toarray() if sp.issparse(D) else np.asarray(D)
                S0 = S0 + m * D
                coupling = coupling + D
        lu = _factor(S0, where, sparse)
        P = np.zeros((n, dofs.size), dtype=S0.dtype)
        P[dofs, np.arange(dofs.size)] = 1.0
        Z = lu.solve(P) if dofs.size else P
        return cls(complex(mu), lu, dofs, Z, Z[dofs], D, coupling)


class _DenseLU:
    """Dense ``S0^-1``: the shifted matrices of a small problem are well conditioned
    (``mu^2 M`` dominates) and only drive a simplified Newton iteration whose residual is
    exact, so one matrix-vector product replaces each pair of triangular solves. The
    inverse comes from the LU factors by LAPACK ``getri`` with its optimal workspace (about
    half the cost of solving for the identity at n = 150, real or complex)."""

    def __init__(self, A: Any, where: str) -> None:
        lu, piv = sl.lu_factor(A, check_finite=False)
        d = np.abs(np.diag(lu))
        if not np.all(np.isfinite(d)) or d.min() <= 1e-15 * d.max():
            raise ConvergenceError("shifted iteration matrix is singular", where)
        getri, query = sl.get_lapack_funcs(("getri", "getri_lwork"), (lu,))
        work, _ = query(lu.shape[0])  # the blocked inverse needs its optimal workspace
        inverse, info = getri(lu, piv, lwork=int(np.real(work)))
        if info != 0:
            raise ConvergenceError("shifted iteration matrix is singular", where)
        self.inverse = inverse

    def solve(self, b: Any) -> Any:
        return self.inverse @ b


class _SparseLU:
    """SuperLU of a sparse real or complex matrix."""

    def __init__(self, A: Any, where: str) -> None:
        self.lu: Factorization = factorize(sp.csc_matrix(A), where=where,
                                           dense_threshold=0)

    def solve(self, b: Any) -> Any:
        return self.lu.solve(b)


def _factor(A: Any, where: str, sparse: bool) -> Any:
    """LU of a real or complex, dense or sparse matrix."""
    return _SparseLU(A, where) if sparse else _DenseLU(A, where)


@dataclass(frozen=True, eq=False)
class ShiftedSolve:
    """Solves with ``S(mu) = S0(mu) + P B P^T``, ``B = mu C_b + K_b`` (frozen bearing
    tangents): ``S^-1 b = y - U y_d`` with ``y = S0^-1 b`` and ``U = Z (I + B Z_d)^-1 B``
    (the Woodbury identity, :mod:`~rotorsim.time_integration.local_tangent`)."""

    base: ShiftedFactors
    U: Any

    @classmethod
    def build(cls, base: ShiftedFactors, kb: FloatArray | None, cb: FloatArray | None,
              where: str) -> ShiftedSolve:
        """Add the bearing tangents ``K_b``, ``C_b`` (k, k) on ``base.dofs``.

        Raises
        ------
        ConvergenceError
            When the updated matrix is singular.
        """
        k = base.dofs.size
        if k == 0 or (kb is None and cb is None):
            return cls(base, None)
        mu = base.mu if base.mu.imag != 0.0 else base.mu.real
        block = (np.zeros((k, k)) if kb is None else kb) + \
            (0.0 if cb is None else mu * cb)
        cap = np.eye(k) + block @ base.Zd
        try:
            W = np.linalg.solve(cap, block)
        except np.linalg.LinAlgError:
            W = np.full_like(block, np.nan)
        if not np.all(np.isfinite(W)):
            raise ConvergenceError(f"iteration matrix is singular ({where})", where)
        return cls(base, base.Z @ W)

    def solve(self, b: Any) -> Any:
        """``S(mu)^-1 b`` for ``b`` (n,)."""
        y = self.base.lu.solve(b)
        if self.U is None:
            return y
        return y - self.U @ y[self.base.dofs]
