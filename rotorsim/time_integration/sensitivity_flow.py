"""The average-acceleration flow of a second-order problem with its exact sensitivities.

For ``M a + (C + s(t) G) v + K q + r(q, v, t) = f(t)`` (a
:class:`~rotorsim.time_integration.problem.SecondOrderProblem`), one step of the
non-dissipative Newmark scheme (``beta = 1/4``, ``gamma = 1/2``) from ``(q, v, a)`` at ``t``
to ``t + h`` is

    q1 = q + h v + h^2/4 (a + a1),   v1 = v + h/2 (a + a1),
    M a1 + D(t1) v1 + K q1 + r(q1, v1, t1) = f(t1),

solved for ``a1`` by Newton with the iteration matrix ``S = M + h/2 (D + dr/dv) +
h^2/4 (K + dr/dq)`` (seed 002 section 3.4; Geradin & Rixen, *Mechanical Vibrations*,
section 7.2). Differentiating the converged step with respect to the start state ``z0 =
(q0, v0)`` gives the sensitivities ``Q = dq/dz0``, ``V = dv/dz0``, ``A = da/dz0`` (each
``n x 2n``) step by step with the same ``S``:

    S A1 = -(K + dr/dq) (Q + h V + h^2/4 A) - (D + dr/dv) (V + h/2 A),
    Q1 = Q + h V + h^2/4 (A + A1),   V1 = V + h/2 (A + A1),

starting from ``Q = [I 0]``, ``V = [0 I]``, ``M A = -[K + dr/dq, D + dr/dv]``. After the
steps of one period ``[Q; V]`` is the monodromy matrix of the *discrete* period map,
exactly (to the Newton tolerance), so that Newton on ``P(z) - z = 0`` converges
quadratically (:mod:`rotorsim.verification.full_shooting`) and its eigenvalues are the
Floquet multipliers of the scheme's periodic orbit. The scheme is second order and, for a
linear undamped system, conserves ``|mu| = 1`` exactly: the moduli of lightly damped modes
carry no numerical damping.

Cost per step: one LU of the dense ``n x n`` matrix ``S`` per Newton iteration and one solve
with ``2n`` right-hand sides with the last one, ``O(n^3)``; meant for the few hundred DOFs
of a beam rotor.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.banded_lu import BandLayout
from rotorsim.time_integration.problem import SecondOrderProblem

FloatArray = NDArray[np.float64]
WHERE = "average_acceleration_flow"
LARGEST = 2000
"""Most unknowns of a problem integrated with dense sensitivities."""
DENSE = 48
"""Up to this many unknowns the matrices are dense (scipy.sparse's call overhead exceeds
the products)."""


@dataclass(frozen=True, eq=False)
class DiscreteFlow:
    """The state after the steps and its sensitivities.

    Attributes
    ----------
    q, v : arrays (n,)
        Displacements and velocities at the end [m, rad, m/s, rad/s].
    monodromy : array (2n, 2n) or None
        ``d(q, v)_end / d(q, v)_start`` (None when not asked for).
    iterations : int
        Newton iterations of all steps together.
    """

    q: FloatArray
    v: FloatArray
    monodromy: FloatArray | None
    iterations: int


def _dense(A: object, n: int) -> FloatArray:
    if A is None:
        return np.zeros((n, n))
    return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)  # type: ignore[attr-defined]


def _sparse(A: object, n: int) -> sp.csr_matrix:
    if A is None:
        return sp.csr_matrix((n, n))
    return sp.csr_matrix(A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float))  # type: ignore[attr-defined]


class _Stepper:
    """The matrices of the scheme: ``M``, ``K``, ``C``, ``G`` as sparse rows, and the
    iteration matrix ``S`` factorised in band storage when the band is narrow (the nodes
    of a beam rotor are numbered along the shaft), densely otherwise."""

    def __init__(self, problem: SecondOrderProblem, c1: float, c2: float) -> None:
        n = problem.n
        if n > LARGEST:
            raise ModelError(f"{n} unknowns: dense sensitivities are meant for at most "
                             f"{LARGEST} (reduce the model first)", WHERE)
        if problem.speed_terms is not None:
            raise ModelError("speed-dependent bearing terms are not supported here: give "
                             "the matrices at the constant speed", WHERE)
        self.problem, self.n, self.c1, self.c2 = problem, n, c1, c2
        self.dense = n <= DENSE
        kind = _dense if self.dense else _sparse
        self.M, self.K, self.C = (kind(getattr(problem, name), n)
                                  for name in ("mass", "stiffness", "damping"))
        self.G = None if problem.gyroscopic is None else kind(problem.gyroscopic, n)
        self.dense_base = np.zeros(0)
        self.spin = math.nan
        self.D = self.C
        self.base: sp.csc_matrix | None = None
        self.dofs = np.zeros(0, dtype=np.int64)
        self.layout: BandLayout | None = None
        self.block_at = np.zeros(0, dtype=np.int64)
        self.mask = np.zeros((0, 0), dtype=bool)
        self.block_ij = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))

    def at(self, t: float, dofs: NDArray[np.int64], kt: FloatArray | None,
           ct: FloatArray | None) -> None:
        """``D = C + s(t) G`` and the pattern of ``S``: the linear part's and the nonzero
        entries of the tangent blocks on ``dofs`` seen so far (two bearings' blocks do
        not couple, so the band stays narrow)."""
        s = self.problem.spin(t) if self.G is not None else 0.0
        if self.dense:
            if s != self.spin or not self.dense_base.size:
                self.spin, self.dofs = s, dofs
                self.D = self.C if self.G is None else self.C + s * self.G
                self.dense_base = self.M + self.c1 * self.D + self.c2 * self.K
            self.dofs = dofs
            return
        if not np.array_equal(dofs, self.dofs):
            self.dofs, self.base = dofs, None
            self.mask = np.zeros((dofs.size, dofs.size), dtype=bool)
        if kt is not None and ct is not None:
            seen = (kt != 0.0) | (ct != 0.0)
            if np.any(seen & ~self.mask):
                self.mask, self.base = self.mask | seen, None
        if s != self.spin or self.base is None:
            self.spin = s
            self.D = self.C if self.G is None else sp.csr_matrix(self.C + s * self.G)
            base = sp.coo_matrix(self.M + self.c1 * self.D + self.c2 * self.K)
            i, j = np.nonzero(self.mask)
            base = sp.coo_matrix((np.concatenate([base.data, np.zeros(i.size)]),
                                  (np.concatenate([base.row, dofs[i]]),
                                   np.concatenate([base.col, dofs[j]]))), shape=base.shape)
            base = base.tocsc()   # sums duplicates, keeps the explicit zeros
            base.sort_indices()
            self.base = base
            self.layout = BandLayout.of(base, widest=max(4, self.n // 4))
            self.block_at = _positions(base, dofs[i], dofs[j])
            self.block_ij = (i, j)

    def factorize(self, kt: FloatArray | None, ct: FloatArray | None) -> Any:
        """LU of ``S`` with the tangent blocks ``kt``, ``ct`` on ``self.dofs``."""
        if self.dense:
            S = self.dense_base.copy()
            if kt is not None and ct is not None:
                S[np.ix_(self.dofs, self.dofs)] += self.c1 * ct + self.c2 * kt
            return _DenseLU.of(S)
        assert self.base is not None
        data = self.base.data.copy()
        if kt is not None and ct is not None:
            i, j = self.block_ij
            data[self.block_at] += self.c1 * ct[i, j] + self.c2 * kt[i, j]
        if self.layout is not None:
            return self.layout.factorize(data, WHERE)
        dense = sp.csc_matrix((data, self.base.indices, self.base.indptr),
                              shape=self.base.shape).toarray()
        return _DenseLU.of(dense)

    def times(self, A: sp.csr_matrix, block: FloatArray | None, x: FloatArray) -> FloatArray:
        """``(A + block on dofs) @ x`` for ``x`` of shape (n,) or (n, k)."""
        out = np.asarray(A @ x)
        if block is not None:
            out[self.dofs] += block @ x[self.dofs]
        return out


_GETRF, _GETRS = sla.get_lapack_funcs(("getrf", "getrs"), (np.zeros((1, 1)),))


@dataclass(frozen=True, eq=False)
class _DenseLU:
    """LAPACK ``getrf`` factors (called directly: the wrappers' checks cost more than the
    factorisation of a small matrix)."""

    lu: FloatArray
    piv: NDArray[np.int32]

    @classmethod
    def of(cls, S: FloatArray) -> _DenseLU:
        lu, piv, info = _GETRF(S)
        if info > 0:
            raise ConvergenceError(f"the iteration matrix is singular (column {info})", WHERE)
        return cls(lu, piv)

    def solve(self, b: FloatArray) -> FloatArray:
        x, _ = _GETRS(self.lu, self.piv, b)
        return np.asarray(x)


def _positions(A: sp.csc_matrix, rows: NDArray[np.int64], cols: NDArray[np.int64]
               ) -> NDArray[np.int64]:
    """Position in ``A.data`` (sorted CSC) of each stored entry ``(rows[k], cols[k])``."""
    starts = A.indptr[cols]
    out = np.empty(rows.size, dtype=np.int64)
    for k, (r, c, s0) in enumerate(zip(rows, cols, starts, strict=True)):
        out[k] = s0 + np.searchsorted(A.indices[s0:A.indptr[c + 1]], r)
    return out


def _tangents(problem: SecondOrderProblem, q: FloatArray, v: FloatArray, t: float
              ) -> tuple[FloatArray, FloatArray | None, FloatArray | None, NDArray[np.int64]]:
    """Restoring force (n,) and its tangent blocks on their DOFs."""
    n = problem.n
    if problem.restoring is None:
        return np.zeros(n), None, None, np.zeros(0, dtype=np.int64)
    out = problem.restoring(q, v, t)
    if out is None:
        return np.zeros(n), None, None, np.zeros(0, dtype=np.int64)
    r, kt, ct = out
    if kt is None or ct is None or not np.array_equal(kt.dofs, ct.dofs):
        raise ModelError("the restoring force must give both tangents on the same DOFs",
                         WHERE)
    return np.asarray(r, dtype=float).reshape(-1), kt.block, ct.block, kt.dofs


def average_acceleration_flow(problem: SecondOrderProblem, q0: FloatArray, v0: FloatArray,
                              t0: float, duration: float, steps: int, *,
                              sensitivities: bool = True, tolerance: float = 1e-12,
                              max_iterations: int = 30) -> DiscreteFlow:
    """Integrate ``steps`` equal steps of the average-acceleration scheme (module
    docstring) from ``(q0, v0)`` at ``t0`` over ``duration``.

    Parameters
    ----------
    problem : SecondOrderProblem
        The equation of motion (at most :data:`LARGEST` unknowns; no speed terms).
    q0, v0 : arrays (n,)
        Start state [m, rad, m/s, rad/s].
    t0, duration : float
        Start time and length of the run [s].
    steps : int
        Number of equal steps.
    sensitivities : bool
        Also propagate the monodromy matrix.
    tolerance : float
        Newton stops when the correction of ``h^2/4 a1`` (the displacement) is below
        ``tolerance`` times the largest ``|q|`` of the step (and 1e-30 m).
    max_iterations : int
        Newton iterations per step.

    Returns
    -------
    DiscreteFlow

    Raises
    ------
    ConvergenceError
        Newton fails in a step (the step, its time and residual are named).
    ModelError
        A problem that is too large or has speed terms, bad arguments.

    Examples
    --------
    >>> p = SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1))
    >>> out = average_acceleration_flow(p, np.ones(1), np.zeros(1), 0.0, 2 * np.pi, 64)
    >>> bool(np.allclose(np.abs(np.linalg.eigvals(out.monodromy)), 1.0))
    True
    """
    if not (isinstance(steps, int | np.integer) and steps >= 1):
        raise ModelError(f"must be an integer >= 1, got {steps!r}", f"{WHERE}.steps")
    if not (math.isfinite(duration) and duration > 0):
        raise ModelError(f"must be finite and > 0, got {duration!r}", f"{WHERE}.duration")
    n = problem.n
    q, v = (np.array(x, dtype=float).reshape(-1) for x in (q0, v0))
    if q.shape != (n,) or v.shape != (n,):
        raise ModelError(f"expected ({n},) start displacements and velocities, got "
                         f"{q.shape} and {v.shape}", WHERE)
    h = duration / int(steps)
    c1, c2 = 0.5 * h, 0.25 * h * h
    st = _Stepper(problem, c1, c2)
    r, kt, ct, dofs = _tangents(problem, q, v, t0)
    st.at(t0, dofs, kt, ct)
    M = st.M if isinstance(st.M, np.ndarray) else st.M.toarray()
    a = np.linalg.solve(M, problem.external(t0) - st.D @ v - st.K @ q - r)
    Q = V = A = np.zeros(0)
    if sensitivities:
        Q = np.hstack([np.eye(n), np.zeros((n, n))])
        V = np.hstack([np.zeros((n, n)), np.eye(n)])
        A = -np.linalg.solve(M, np.hstack([st.times(st.K, kt, np.eye(n)),
                                           st.times(st.D, ct, np.eye(n))]))
    total = 0
    previous = a
    for step in range(1, int(steps) + 1):
        t1 = t0 + step * h
        f1 = problem.external(t1)
        qp, vp = q + h * v + c2 * a, v + c1 * a
        a1 = 2.0 * a - previous          # linear extrapolation of the acceleration
        scale = max(float(np.max(np.abs(qp))), 1e-30)
        for iteration in range(1, max_iterations + 2):
            q1, v1 = qp + c2 * a1, vp + c1 * a1
            r, kt, ct, dofs = _tangents(problem, q1, v1, t1)
            st.at(t1, dofs, kt, ct)
            residual = st.M @ a1 + st.D @ v1 + st.K @ q1 + r - f1
            lu = st.factorize(kt, ct)
            da = -lu.solve(residual)
            if not np.all(np.isfinite(da)):
                raise ConvergenceError("the Newton correction is not finite", WHERE,
                                       step=step, iteration=iteration,
                                       residual=float(np.linalg.norm(residual)))
            if iteration > max_iterations:
                raise ConvergenceError(
                    f"Newton did not converge in {max_iterations} iterations at "
                    f"t = {t1:.6g} s", WHERE, step=step, iteration=iteration,
                    residual=float(np.linalg.norm(residual)))
            a1 += da
            total += 1
            if c2 * float(np.max(np.abs(da))) <= tolerance * scale:
                break
        q1, v1 = qp + c2 * a1, vp + c1 * a1
        if sensitivities:
            # the iteration matrix of the last iterate: the state moved by at most
            # ``tolerance`` since, which changes the tangents by as little
            Qp, Vp = Q + h * V + c2 * A, V + c1 * A
            A = -lu.solve(st.times(st.K, kt, Qp) + st.times(st.D, ct, Vp))
            Q, V = Qp + c2 * A, Vp + c1 * A
        previous = a
        q, v, a = q1, v1, a1
    return DiscreteFlow(q, v, np.vstack([Q, V]) if sensitivities else None, total)
