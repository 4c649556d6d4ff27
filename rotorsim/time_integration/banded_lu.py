"""Banded LU of the iteration matrix of a shaft line (LAPACK ``gbtrf``/``gbtrs``).

A finite-element rotor numbers its nodes along the shaft, so its matrices are banded: the
226-node rotor of ``models/large_rotor.toml`` (726 unknowns) has a half-bandwidth of 10. A
banded LU of such a matrix costs ``O(n kl (kl + ku))``: a quarter of a sparse LU with its
fill-reducing ordering, and no more per solve. Run-ups factorise the iteration matrix at many
speed nodes (:mod:`~rotorsim.time_integration.newmark_step`), so the Newmark steppers use it
whenever the band is narrow (:data:`MAX_BAND`).

References
----------
E. Anderson et al., LAPACK Users' Guide, 3rd ed., SIAM 1999, section 2.4.2 (band storage,
``xGBTRF``, ``xGBTRS``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
_GBTRF, _GBTRS = sl.get_lapack_funcs(("gbtrf", "gbtrs"), (np.zeros((1, 1)),))
_ZGBTRF, _ZGBTRS = sl.get_lapack_funcs(("gbtrf", "gbtrs"), (np.zeros((1, 1), complex),))


def max_band(n: int) -> int:
    """Largest ``kl + ku`` for which a banded LU of an ``n x n`` matrix is used:
    ``2 sqrt(n)``, where the band's ``n (kl + ku)`` stored entries stay below about
    ``2 n^1.5`` (a sparse LU of a 1-D mesh with its fill stays near ``n``; the band's extra
    work is offset by LAPACK's blocked kernels and the saved ordering)."""
    return int(2.0 * math.sqrt(n))


@dataclass(frozen=True, eq=False)
class BandLayout:
    """Where each stored entry of a sparse pattern goes in LAPACK band storage.

    Attributes
    ----------
    n, kl, ku : int
        Size, lower and upper half-bandwidths.
    flat : int array (nnz,)
        Position of each stored entry in the Fortran-ordered ``(2 kl + ku + 1, n)`` array.
    """

    n: int
    kl: int
    ku: int
    flat: IntArray

    @classmethod
    def of(cls, A: sp.csc_matrix, widest: int | None = None) -> BandLayout | None:
        """Layout of the CSC pattern of ``A`` (sorted indices), or None when its ``kl + ku``
        exceeds ``widest`` (default :func:`max_band`)."""
        n = int(A.shape[0])
        cols = np.repeat(np.arange(n, dtype=np.int64), np.diff(A.indptr))
        rows = A.indices.astype(np.int64)
        offset = rows - cols
        kl = int(max(offset.max(initial=0), 0))
        ku = int(max(-offset.min(initial=0), 0))
        if kl + ku > (max_band(n) if widest is None else widest):
            return None
        band_rows = kl + ku + offset  # row of A[i, j] in band storage (LAPACK: kl + ku + i - j)
        return cls(n, kl, ku, cols * (2 * kl + ku + 1) + band_rows)

    def factorize(self, data: NDArray[np.float64] | NDArray[np.complex128], where: str
                  ) -> BandedLU:
        """Banded LU of the matrix with the entries ``data`` (real or complex) on this
        layout.

        Raises
        ------
        ConvergenceError
            When a pivot is zero, or not finite for complex data (the matrix is
            singular).
        """
        complex_ = np.iscomplexobj(data)
        ab = np.zeros((2 * self.kl + self.ku + 1, self.n), dtype=complex if complex_ else
                      float, order="F")
        ab.ravel(order="F")[self.flat] = data  # a view: ab is Fortran-ordered
        lu, piv, info = (_ZGBTRF if complex_ else _GBTRF)(ab, self.kl, self.ku, overwrite_ab=1)
        if info != 0:
            raise ConvergenceError(f"matrix is singular (zero pivot in column {info})", where)
        if complex_ and not np.all(np.isfinite(lu[self.kl + self.ku])):   # U's diagonal
            # the tone-by-tone condensation's check (the steppers catch non-finite states)
            raise ConvergenceError("matrix is singular (a pivot is not finite)", where)
        return BandedLU(self.n, self.kl, self.ku, lu, piv)


@dataclass(frozen=True, eq=False)
class BandedLU:
    """LU factors in band storage; duck-types :class:`~rotorsim.solvers.linear.Factorization`
    for the steppers (``n``, ``solve``)."""

    n: int
    kl: int
    ku: int
    lu: NDArray[Any]
    piv: NDArray[np.int32]

    def solve(self, b: NDArray[Any]) -> NDArray[Any]:
        """Solve ``A x = b`` for ``b`` of shape ``(n,)`` or ``(n, k)`` (complex ``b`` with
        real factors: its two parts in turn)."""
        if np.iscomplexobj(self.lu):
            rhs = np.asarray(b, dtype=complex)
            x, info = _ZGBTRS(self.lu, self.kl, self.ku, rhs.reshape(self.n, -1), self.piv)
        elif np.iscomplexobj(b):
            return self.solve(np.real(b)) + 1j * self.solve(np.imag(b))
        else:
            rhs = np.asarray(b, dtype=float)
            x, info = _GBTRS(self.lu, self.kl, self.ku, rhs.reshape(self.n, -1), self.piv)
        if info != 0:
            raise ValueError(f"gbtrs failed with info = {info}")
        return x.reshape(rhs.shape)
