"""Bordered linear algebra of continuation: the matrix ``[[dR/dy], [b^T]]``, its
determinant sign and the branch tangent (seed 002 eq 3.39).

Used by :mod:`rotorsim.solvers.continuation_core` (which re-exports these names) on the
scaled evaluations of a :class:`~rotorsim.solvers.continuation_core.ScaledSystem`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.solvers.stats import Stats

if TYPE_CHECKING:
    from rotorsim.solvers.continuation_core import Evaluation

FloatArray = NDArray[np.float64]
Matrix = Any


DENSE_BORDERED = 2000
"""A bordered matrix stored dense (a dense Jacobian) is factorised by dense LU up to this
size: SuperLU on a full matrix is several times slower than LAPACK (measured on the
default model's torus branch: 15 ms against 4 ms at 651 rows)."""


def factor_bordered(matrix: Matrix, stats: Stats, where: str) -> Factorization:
    """LU of a bordered matrix from :func:`bordered` (dense LU for a dense one up to
    :data:`DENSE_BORDERED` rows)."""
    threshold = DENSE_BORDERED if isinstance(matrix, np.ndarray) else DENSE_THRESHOLD
    return factorize(matrix, stats=stats, where=where, dense_threshold=threshold)


BORDER_WEIGHT = 1e-8
"""Sparse bordered matrices carry the border row times ``w = BORDER_WEIGHT max|jh| /
max|border|``. Row scaling leaves the solution unchanged, but keeps SuperLU's partial
pivoting from choosing the dense border row as pivot (which fills the factors) unless the
Jacobian part is nearly singular there; the constraint is then resolved to about
``eps / BORDER_WEIGHT`` relative accuracy."""


def bordered(jh: Matrix, jlh: FloatArray, border: FloatArray) -> tuple[Matrix, float]:
    """``[[jh, jlh], [w border^T]]`` (m + 1, m + 1) and the row weight ``w``.

    Dense for a dense ``jh`` (``w = 1``), else sparse CSC (duplicate entries of a COO
    ``jh`` are summed) with ``w`` from :data:`BORDER_WEIGHT`. Multiply the last
    right-hand side entry by ``w``.
    """
    if not sp.issparse(jh):
        return np.block([[jh, jlh[:, None]], [border[None, :]]]), 1.0
    size = max(float(np.max(np.abs(jh.data), initial=0.0)), float(np.max(np.abs(jlh))))
    w = BORDER_WEIGHT * size / float(np.max(np.abs(border))) if size > 0.0 else 1.0
    coo = jh.tocoo()
    m = jlh.size
    index = np.arange(m + 1)
    rows = np.concatenate([coo.row, index[:-1], np.full(m + 1, m)])
    cols = np.concatenate([coo.col, np.full(m, m), index])
    data = np.concatenate([coo.data, jlh, w * border])
    return sp.csc_matrix((data, (rows, cols)), shape=(m + 1, m + 1)), w


def signed_log_det(fact: Factorization) -> tuple[int, float]:
    """``(sign, log |det|)`` of a factorised matrix, without overflow
    (:meth:`~rotorsim.solvers.linear.Factorization.slogdet`)."""
    return fact.slogdet()


@dataclass(frozen=True, eq=False)
class Tangent:
    """Unit tangent ``t`` (m + 1,) with ``border . t > 0`` and the determinant sign and
    ``log |det|`` of the bordered matrix (sign is that of the matrix bordered by ``t``)."""

    t: FloatArray
    det_sign: int
    log_det: float


def tangent(ev: Evaluation, border: FloatArray, stats: Stats) -> Tangent | None:
    """Tangent of the branch at ``ev.y`` from ``[[jh, jlh], [border^T]] z = e_{m+1}``.

    Returns None when the bordered matrix is singular (a branch point, a non-smooth point
    or a ``border`` orthogonal to the branch). Since ``border . z = 1`` the tangent keeps
    the orientation of ``border``, and the determinant with ``border`` in the last row
    has the sign of the determinant with ``t`` there (both are ``c . border`` and
    ``c . t`` for the same cofactor vector ``c`` parallel to ``t``).
    """
    matrix, weight = bordered(ev.jh, ev.jlh, border)
    try:
        fact = factor_bordered(matrix, stats, "tangent")
    except ConvergenceError:
        return None
    rhs = np.zeros(ev.y.size)
    rhs[-1] = weight
    z = fact.solve(rhs)
    size = float(np.linalg.norm(z))
    if not (math.isfinite(size) and size > 0.0):
        return None
    sign, log_det = signed_log_det(fact)
    return Tangent(z / size, sign, log_det - math.log(weight))
