"""Quadratic eigen solver on problems with closed-form answers, dense and sparse paths."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

import rotorsim as rs
from rotorsim.model.material import steel
from rotorsim.solvers.eigen import quadratic_eigen
from rotorsim.solvers.stats import Stats


def _chain(n: int, m: float, k: float, c: float):
    """Fixed-fixed spring-mass chain: w_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1)))."""
    main = np.full(n, 2.0)
    off = np.full(n - 1, -1.0)
    lap = sp.diags([off, main, off], [-1, 0, 1], format="csr")
    return m * sp.identity(n, format="csr"), c * sp.identity(n, format="csr"), k * lap


@pytest.mark.parametrize("sparse", [False, True])
def test_mass_proportional_damping_chain(sparse):
    """lam = -c/(2m) +/- i sqrt(w^2 - (c/2m)^2) for C = c I, M = m I (exact)."""
    n, m, k, c = 120, 2.0, 1e4, 3.0
    M, C, K = _chain(n, m, k, c)
    pairs = quadratic_eigen(M, C, K, 12, sparse=sparse)
    j = np.arange(1, 7)
    w = 2 * np.sqrt(k / m) * np.sin(j * np.pi / (2 * (n + 1)))
    expected = -c / (2 * m) + 1j * np.sqrt(w**2 - (c / (2 * m)) ** 2)
    upper = pairs.values[pairs.values.imag > 0]
    upper = upper[np.argsort(upper.imag)][:6]
    assert np.allclose(upper, expected, rtol=1e-9)
    residual = [(lam**2 * M + lam * C + K) @ pairs.vectors[:, i]
                for i, lam in enumerate(pairs.values)]
    assert max(np.linalg.norm(r) for r in residual) < 1e-8 * sp.linalg.norm(K)


def test_sparse_path_counts_one_factorisation():
    M, C, K = _chain(300, 1.0, 1.0, 0.0)
    stats = Stats()
    quadratic_eigen(M, C, K, 8, sparse=True, stats=stats)
    assert stats.factorizations == 1 and stats.eigen_solves == 1


def test_stiff_supports_with_repeated_pairs_converge():
    """Nearly rigid pinned supports (1e14 N/m) and x/y repeated pairs: the sparse path must
    agree with the dense one and with the pinned-pinned Euler-Bernoulli beam."""
    n = 40
    shaft = [rs.ShaftElement(L=1.0 / n, idl=0.0, odl=0.05, material=steel, shear_effects=False,
                             rotary_inertia=False, gyroscopic=False) for _ in range(n)]
    rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e14),
                                 rs.BearingElement(n=n, kxx=1e14)])
    sparse = rs.modal(rotor, 0.0, 4, sparse=True)
    dense = rs.modal(rotor, 0.0, 4, sparse=False)
    assert np.allclose(sparse.wn, dense.wn, rtol=1e-7)
    ei_rhoa = steel.E * (0.05**2 / 16.0) / steel.rho
    assert sparse.wn[0] == pytest.approx(np.pi**2 * np.sqrt(ei_rhoa), rel=1e-5)
