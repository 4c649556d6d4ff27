"""The banded factorisation of the linear DOFs' dynamic stiffness in the quasi-periodic
condensation (``rotorsim/harmonic_balance/banded_tones.py``).

Reference: the dense LU path of the same condensation (``scipy.linalg.lu_factor``), and
numpy's dense solve. Both are backward-stable LU factorisations with partial pivoting, so
on these damped, well-conditioned matrices (condition numbers below 1e4) they agree to
about 1e-12 of the solution; asserted at 1e-9, well above round-off on any BLAS and far
below any modelling effect.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError
from rotorsim.harmonic_balance.banded_tones import BandedTones
from rotorsim.harmonic_balance.quasi import QuasiProblem, TorusAFT, TorusHarmonics
from rotorsim.harmonic_balance.quasi.residual import LinearBlocks, condense


def _chain(n: int, k: float = 1e6, m: float = 1.0, c: float = 20.0, g: float = 0.05,
           free: bool = False) -> tuple[sp.csr_matrix, ...]:
    """A chain of masses on springs in two planes with gyroscopic coupling, held at both
    ends by springs (``free``: not held): banded (half-bandwidth 2 in the interleaved
    order)."""
    diagonal = 2 * k * np.ones(n)
    if free:
        diagonal[[0, -1]] = k
    K1 = sp.diags([-k * np.ones(n - 1), diagonal, -k * np.ones(n - 1)], [-1, 0, 1])
    K = sp.kron(K1, np.eye(2)).tocsr()
    M = sp.kron(sp.eye(n), m * np.eye(2)).tocsr()
    C = sp.kron(sp.eye(n), c * np.eye(2)).tocsr()
    G = sp.kron(sp.eye(n), g * np.array([[0.0, 1.0], [-1.0, 0.0]])).tocsr()
    return M, C, K, G


def test_a_banded_tone_factor_solves_as_the_dense_one() -> None:
    M, C, K, G = _chain(40)
    band = BandedTones.of({"K": K, "M": M, "C": C, "G": G})
    assert band is not None and (band.layout.kl, band.layout.ku) == (2, 2)
    w, spin = 1.7e3, 500.0
    Z = (K - w**2 * M + 1j * w * (C + spin * G)).toarray()
    rhs = np.random.default_rng(1).normal(size=(80, 3)) + 1j
    x = band.factorize(w, spin, "test").solve(rhs)
    assert np.allclose(x, np.linalg.solve(Z, rhs), rtol=1e-9, atol=0.0)
    assert np.allclose(band.factorize(w, spin, "test").solve(rhs.real),
                       np.linalg.solve(Z, rhs.real), rtol=1e-9, atol=0.0)


def test_a_wide_band_is_left_to_the_dense_lu() -> None:
    M, C, K, G = _chain(40)
    K = K + sp.csr_matrix(([1.0, 1.0], ([0, 79], [79, 0])), shape=K.shape)   # a far link
    assert BandedTones.of({"K": K, "M": M, "C": C, "G": G}) is None


def test_a_singular_tone_raises_naming_it() -> None:
    M, C, K, G = _chain(10, c=0.0, g=0.0, free=True)
    band = BandedTones.of({"K": K, "M": M, "C": C, "G": G})
    assert band is not None
    with pytest.raises(ConvergenceError, match="tone 7"):
        band.factorize(0.0, 0.0, "tone 7")          # a free chain at rest: K is singular
    M = M.tolil()
    M[3, 3] = np.inf
    band = BandedTones.of({"K": K, "M": M.tocsr(), "C": C + sp.eye(20), "G": G})
    assert band is not None
    with pytest.raises(ConvergenceError, match="not finite"):
        band.factorize(10.0, 0.0, "tone 2")


def test_the_condensation_is_the_same_banded_and_dense() -> None:
    """Schur complements and condensed loads of every tone of a box (2, 1) at a torus
    frequency pair: banded against the dense LU of the same blocks."""
    M, C, K, G = _chain(30)
    n = K.shape[0]
    aft = TorusAFT(TorusHarmonics.box(2, 1))
    P = np.zeros((aft.harmonics.rows, n))
    P[1, 30], P[2, 31] = 10.0, -4.0
    pb = QuasiProblem(M, C, K, G, nl_dofs=np.array([0, 1, 58, 59]), excitation=P,
                      spin=300.0)
    banded = LinearBlocks.of(pb)
    assert banded.band is not None
    dense = LinearBlocks(banded.N, banded.L, banded.blocks, banded.dense, None)
    a = condense(pb, aft, 310.0, 1130.0, banded)
    b = condense(pb, aft, 310.0, 1130.0, dense)
    assert not isinstance(a.factors[1], type(b.factors[1]))      # two different LUs
    scale = np.abs(b.S).max()
    assert np.abs(a.S - b.S).max() <= 1e-9 * scale
    assert np.abs(a.load - b.load).max() <= 1e-9 * np.abs(b.load).max()
