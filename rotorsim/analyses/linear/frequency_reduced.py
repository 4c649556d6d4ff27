"""Harmonic responses over many frequencies from a basis of a few direct solutions.

The responses ``X(w)`` of ``(K - w^2 M + i w (C + W G)) X = F`` over a frequency sweep vary
smoothly and lie, to working accuracy, in a subspace spanned by the responses at a few
frequencies (multi-point moment matching, Grimme, *Krylov projection methods for model
reduction*, PhD thesis, 1997; the greedy choice of points of reduced-basis methods, Hesthaven,
Rozza and Stamm, *Certified reduced basis methods for parametrized PDEs*, Springer 2016,
section 3.2). :func:`reduced_sweep`:

1. solves directly (one sparse LU each) at :data:`FIRST_POINTS` points spread evenly;
2. projects the dynamic stiffness on the real orthonormal basis of those solutions and
   solves the small dense systems at every point, all at once;
3. evaluates every point's residual with the full matrices, measured as the displacement
   ``P^-1 r`` that would balance it relative to the response (``P`` a real shifted
   stiffness, :func:`~rotorsim.solvers.projected_eigen.shift_inverted_residuals` uses the
   same norm), and solves directly at the worst points, which join the basis, until every
   point is below ``tol``.

Points solved directly keep their direct solution. Used only when no bearing coefficient
depends on speed (the projected matrices are then formed once).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.system import SystemMatrices
from rotorsim.solvers.eigen import default_shift
from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.solvers.projected_eigen import extend_basis
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

RESPONSE_TOL = 1e-9
"""Largest relative residual ``||P^-1 r|| / ||x||`` of a point of a reduced sweep [-]. Near a
resonance the error can exceed the residual by the dynamic amplification (``1 / (2 zeta)``);
measured against direct solves: 1e-9 relative to the peak or better (docs/benchmarks.md)."""
FIRST_POINTS = 5
"""Direct solves the basis starts from, evenly spread over the points."""
POINTS_PER_ROUND = 8
"""Direct solves added per refinement round (the worst points, apart from each other)."""
MAX_DIRECT_FRACTION = 0.25
"""When the direct solves would exceed this fraction of the points, the rest are solved
directly (the sweep is not smooth enough to gain from a basis)."""


def reduced_sweep(mats: SystemMatrices, w: FloatArray, spins: FloatArray,
                  loads: ComplexArray, direct: Callable[[int], ComplexArray], stats: Stats,
                  tol: float = RESPONSE_TOL) -> tuple[ComplexArray, dict[str, float]]:
    """Responses ``(F, n, p)`` at the frequencies ``w`` (spin speeds ``spins``) to ``loads``
    ``(F, n, p)`` on the free DOFs; ``direct(i)`` is the full solution at point ``i``.

    Returns the responses and counters (direct solves, basis size, largest residual).
    """
    n_pts, n, p = loads.shape
    out = np.zeros((n_pts, n, p), dtype=complex)
    done = np.zeros(n_pts, dtype=bool)
    zero = ~np.any(loads != 0, axis=(1, 2))
    done[zero] = True  # zero load: zero response, no solve
    shift = default_shift(mats.M, mats.K)
    lu = factorize(mats.K + shift * mats.C + shift**2 * mats.M, stats=stats,
                   where="frequency sweep norm")
    balanced = lu.solve(np.ascontiguousarray(loads.transpose(1, 0, 2).reshape(n, n_pts * p))
                        ).reshape(n, n_pts, p)
    V = np.zeros((n, 0))
    todo = np.flatnonzero(~done)
    first = sorted({int(todo[j]) for j in np.linspace(0, todo.size - 1, FIRST_POINTS)
                    .round().astype(int)}) if todo.size else []
    worst = 0.0
    pending = first
    direct_count = 0
    limit = max(3, int(MAX_DIRECT_FRACTION * n_pts))
    while pending:
        for i in pending:
            out[i] = direct(i)
            done[i] = True
            V = extend_basis(V, out[i])
        todo = np.flatnonzero(~done)
        if todo.size == 0:
            break
        X, err = _project_solve(mats, V, w[todo], spins[todo], loads[todo],
                                balanced[:, todo].reshape(n, -1), lu)
        bad = err > tol
        out[todo[~bad]] = X[~bad]
        worst = max([worst, *err[~bad].tolist()])
        done[todo[~bad]] = True
        if not np.any(bad):
            break
        direct_count += len(pending)
        if direct_count + POINTS_PER_ROUND > limit:
            for i in todo[bad]:  # not smooth enough to gain from a basis: solve directly
                out[i] = direct(int(i))
            direct_count += int(np.count_nonzero(bad))
            break
        pending = _worst_points(todo[bad], err[bad], POINTS_PER_ROUND)
    info = {"basis_size": float(V.shape[1]), "direct_solves": float(direct_count),
            "max_residual": worst}
    return out, info


def _worst_points(points: NDArray[np.int64], err: FloatArray, count: int) -> list[int]:
    """Up to ``count`` points of largest error, each the worst of its run of neighbours."""
    runs = np.split(np.arange(points.size), np.flatnonzero(np.diff(points) > 1) + 1)
    best = sorted(runs, key=lambda r: -err[r].max())[:count]
    return sorted(int(points[r[np.argmax(err[r])]]) for r in best)


def _project_solve(mats: SystemMatrices, V: FloatArray, w: FloatArray, spins: FloatArray,
                   loads: ComplexArray, balanced: ComplexArray, lu: Factorization
                   ) -> tuple[ComplexArray, FloatArray]:
    """Galerkin solutions ``(F, n, p)`` at all points and their relative residuals ``(F,)``.

    ``balanced`` is ``P^-1 loads`` ``(n, F p)``; the residual in the ``P^-1`` norm is then
    ``sum_k c_k(w) (P^-1 A_k V) y - P^-1 f`` over ``A_k = K, M, C, G``: one product with the
    ``n x 4m`` matrix of the ``P^-1 A_k V``, no solve per point.
    """
    n_pts, n, p = loads.shape
    m = V.shape[1]
    AV = [np.asarray(getattr(mats, k) @ V) for k in "KMCG"]
    reduced = [V.T @ a for a in AV]
    B = lu.solve(np.hstack(AV))  # (n, 4m)
    w_ = w[:, None, None]
    s_ = spins[:, None, None]
    Zr = reduced[0][None] - w_**2 * reduced[1][None] + 1j * w_ * (reduced[2][None]
                                                                  + s_ * reduced[3][None])
    Y = np.linalg.solve(Zr, V.T @ loads)  # (F, m, p)
    coef = np.stack([np.ones_like(w_), -w_**2, 1j * w_, 1j * w_ * s_])  # (4, F, 1, 1)
    Zc = (coef * Y[None]).transpose(0, 2, 1, 3).reshape(4 * m, n_pts * p)
    resid = (B @ Zc.real + 1j * (B @ Zc.imag)) - balanced
    num = np.linalg.norm(resid.reshape(n, n_pts, p), axis=(0, 2))
    X = (V @ Y.transpose(1, 0, 2).reshape(m, n_pts * p)).reshape(n, n_pts, p)
    den = np.maximum(np.linalg.norm(X, axis=(0, 2)), 1e-300)
    return X.transpose(1, 0, 2), num / den
