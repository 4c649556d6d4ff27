"""The dynamic stiffness of the linear DOFs in band storage, factorised tone by tone.

The condensation (:func:`~rotorsim.harmonic_balance.quasi.residual.condense`) factorises
``Z_LL(Omega) = K_LL - Omega^2 M_LL + i Omega (C_LL + W G_LL)`` once per tone and speed:
on the default model's branch of tori, 33 tones at about 4 speeds per point: with dense LU
the condensation took 42 % of the branch (cProfile up to 1100 rpm). A shaft line numbers
its nodes along the shaft, so these blocks are banded (the default model's 138 linear DOFs:
half-bandwidths 10 and 10), and a banded LU (LAPACK ``zgbtrf``) costs ``O(n kl (kl +
ku))`` instead of ``O(n^3)``: measured 51 us against 0.35 ms for the dense ``Z_LL`` and its
LU at 138 DOFs (one thread), with the same partial pivoting, restricted to the rows that
hold non-zeros. The branch up to 1000 rpm took 3.8 s instead of 5.0 s.

:class:`BandedTones` keeps the four matrices' entries on the union of their patterns and
the :class:`~rotorsim.time_integration.banded_lu.BandLayout` of that pattern; it exists
only when the band is narrow: the banded LU's ``n kl (kl + ku)`` operations at most a
quarter of the dense LU's ``n^3 / 3`` (the alternative here is always the dense LU or
SuperLU). The smooth 102-DOF rotor of ``benchmarks/bench_periodic.py`` (88 linear DOFs,
half-bandwidths 10 and 10) qualifies; a narrower limit, as for the steppers, would refuse
it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.time_integration.banded_lu import BandedLU, BandLayout

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class BandedTones:
    """``K, M, C, G`` of the linear DOFs on one banded pattern.

    Attributes
    ----------
    layout : BandLayout
    values : dict of str to array (nnz,)
        Entries of ``"K"``, ``"M"``, ``"C"``, ``"G"`` on the pattern (CSC order).
    """

    layout: BandLayout
    values: dict[str, FloatArray]

    @classmethod
    def of(cls, blocks: dict[str, Any]) -> BandedTones | None:
        """From the ``LL`` blocks ``{"K": ..., "M": ..., "C": ..., "G": ...}`` (dense or
        sparse, one size); None when their joint band is too wide for a banded LU (module
        docstring)."""
        mats = {name: sp.csc_matrix(A) for name, A in blocks.items()}
        pattern = sum((abs(A) for A in mats.values()), sp.csc_matrix(
            next(iter(mats.values())).shape))
        pattern = sp.csc_matrix(pattern)
        pattern.sort_indices()
        n = pattern.shape[0]
        layout = BandLayout.of(pattern, widest=2 * n)
        if layout is None or 3 * layout.kl * (layout.kl + layout.ku) > n * n / 4:
            return None
        cols = np.repeat(np.arange(pattern.shape[1]), np.diff(pattern.indptr))
        rows = pattern.indices
        values = {name: np.asarray(A[rows, cols], dtype=float).ravel()
                  for name, A in mats.items()}
        return cls(layout, values)

    def factorize(self, w: float, spin: float, where: str) -> BandedLU:
        """Banded LU of ``Z_LL = K - w^2 M + i w (C + spin G)`` [N/m] at the tone ``w``
        and spin ``spin`` [rad/s].

        Raises
        ------
        ConvergenceError
            A zero or non-finite pivot (``Z_LL`` singular).
        """
        v = self.values
        data = np.empty(v["K"].size, dtype=complex)
        data.real = v["K"] - (w * w) * v["M"]
        data.imag = w * (v["C"] + spin * v["G"])
        return self.layout.factorize(data, where)
