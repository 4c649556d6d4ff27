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
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.base import FloatArray, IntArray
from rotorsim.time_integration.problem import SecondOrderProblem, combine

DENSE_LIMIT = 400
"""Up to this size the shifted matrices are factorised densely (the problem's matrices are
dense there too: see ``transient.DENSE_STEPPING``)."""


@dataclass(frozen=True, eq=False)
class ShiftedFactors:
    """``S0(mu) = mu^2 M + mu (C + s G) + K`` factorised, with ``Z = S0^-1 P`` on ``dofs``."""

    mu: complex
    lu: Factorization
    dofs: IntArray
    Z: Any
    Zd: Any

    @classmethod
    def build(cls, problem: SecondOrderProblem, mu: complex, spin: float, dofs: IntArray,
              where: str) -> ShiftedFactors:
        """Factorise ``S0(mu)`` at the schedule value ``spin``."""
        n = problem.n
        real = mu.imag == 0.0
        m = mu.real if real else mu
        terms = [(1.0, problem.mass), (1.0, problem.damping), (spin, problem.gyroscopic)]
        D = combine(terms[1:], n) if any(A is not None for _, A in terms[1:]) else None
        if sp.issparse(problem.mass) or n > DENSE_LIMIT:
            S0: Any = m * m * sp.csr_matrix(problem.mass) + sp.csr_matrix(problem.stiffness)
            if D is not None:
                S0 = S0 + m * sp.csr_matrix(D)
            if n <= DENSE_THRESHOLD:
                S0 = S0.toarray()
        else:
            S0 = (m * m) * np.asarray(problem.mass) + np.asarray(problem.stiffness)
            if D is not None:
                S0 = S0 + m * (D.toarray() if sp.issparse(D) else D)
        lu = _factor(S0, where, dense=not sp.issparse(S0))
        P = np.zeros((n, dofs.size), dtype=S0.dtype)
        P[dofs, np.arange(dofs.size)] = 1.0
        Z = np.asarray(lu.solve(P)).reshape(n, dofs.size) if dofs.size else P
        return cls(complex(mu), lu, dofs, Z, Z[dofs])


def _factor(A: Any, where: str, dense: bool) -> Factorization:
    """LU of a real or complex matrix (``factorize`` handles the real dense case)."""
    if not np.iscomplexobj(A.data if sp.issparse(A) else A):
        return factorize(A, where=where, dense_threshold=max(DENSE_LIMIT, A.shape[0])
                         if dense else DENSE_THRESHOLD)
    if dense:
        lu, piv = sl.lu_factor(A, check_finite=False)
        d = np.abs(np.diag(lu))
        if not np.all(np.isfinite(d)) or d.min() <= 1e-15 * d.max():
            raise ConvergenceError("shifted iteration matrix is singular", where)
        return Factorization(A.shape[0], _dense=(lu, piv), _complex=True)
    return factorize(sp.csc_matrix(A), where=where)


@dataclass(frozen=True, eq=False)
class ShiftedSolve:
    """Solves with ``S(mu) = S0(mu) + P (mu C_b + K_b) P^T`` (frozen bearing tangents) and
    the condensed right-hand side (module docstring)."""

    base: ShiftedFactors
    block: Any
    capacitance: Any

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
            return cls(base, None, None)
        mu = base.mu if base.mu.imag != 0.0 else base.mu.real
        block = (np.zeros((k, k)) if kb is None else kb) + \
            (0.0 if cb is None else mu * cb)
        cap = np.eye(k) + block @ base.Zd
        lu, piv = sl.lu_factor(cap, check_finite=False)
        d = np.abs(np.diag(lu))
        if not np.all(np.isfinite(d)) or d.min() <= 1e-14 * max(d.max(), 1.0):
            raise ConvergenceError(f"iteration matrix is singular ({where})", where)
        return cls(base, block, (lu, piv))

    def solve(self, b: Any) -> Any:
        """``S(mu)^-1 b`` for ``b`` (n,) or (n, m)."""
        y = np.asarray(self.base.lu.solve(b))
        if self.block is None:
            return y
        w = sl.lu_solve(self.capacitance, self.block @ y[self.base.dofs],
                        check_finite=False)
        return y - self.base.Z @ w
