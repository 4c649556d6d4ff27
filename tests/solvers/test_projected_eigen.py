"""The dense projected eigensolvers of the reduced Campbell: eigenvalues without vectors,
vectors by inverse iteration, and the fall-back to a full solve for close eigenvalues.

The reference is ``numpy.linalg.eig`` of the companion form ``[[0, I], [-M^-1 K, -M^-1 D]]``
(an independent linearisation). Tolerances: eigenvalues of the same problem from two LAPACK
paths agree to ``eps ||T|| / |mu|`` relative (about 1e-13 here; 1e-9 allowed); an eigenvector
from one step of inverse iteration on an exact eigenvalue has a residual at the rounding
level of ``||A(lam)|| ||y||`` (1e-10 relative allowed).
"""

from __future__ import annotations

import numpy as np

from rotorsim.analyses.linear.campbell_ritz import Block, Spectrum
from rotorsim.solvers.projected_eigen import (
    inverse_iteration,
    projected_quadratic_eigen,
    projected_quadratic_values,
)


def _gyroscopic(m: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A damped gyroscopic problem: M, K symmetric positive definite, C PSD, G skew."""
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((m, m))
    M = A @ A.T / m + np.eye(m)
    B = rng.standard_normal((m, m))
    K = 1e4 * (B @ B.T / m + np.eye(m))
    C = 0.5 * np.diag(rng.uniform(0.0, 2.0, m))
    S = rng.standard_normal((m, m))
    G = 3.0 * (S - S.T)
    return M, C, G, K


def _companion_eigenvalues(M, D, K) -> np.ndarray:
    m = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-Minv @ K, -Minv @ D]])
    return np.linalg.eigvals(A)


def test_values_match_the_companion_form_and_the_eig_path() -> None:
    M, C, G, K = _gyroscopic(24, 1)
    D = C + 10.0 * G
    lam = projected_quadratic_values(M, D, K, 50.0)
    lam_eig, _ = projected_quadratic_eigen(M, D, K, 50.0)
    reference = _companion_eigenvalues(M, D, K)
    assert lam.size == 48
    np.testing.assert_allclose(lam, lam_eig, rtol=1e-9)
    nearest = np.array([reference[np.argmin(np.abs(reference - v))] for v in lam])
    np.testing.assert_allclose(lam, nearest, rtol=1e-9)


def test_inverse_iteration_gives_eigenvectors() -> None:
    M, C, G, K = _gyroscopic(30, 2)
    D = C + 25.0 * G
    lam = projected_quadratic_values(M, D, K, 40.0)[:12]
    Y = inverse_iteration(M, D, K, lam)
    np.testing.assert_allclose(np.linalg.norm(Y, axis=0), 1.0, rtol=1e-12)
    for j, value in enumerate(lam):
        A = value**2 * M + value * D + K
        residual = np.linalg.norm(A @ Y[:, j]) / np.linalg.norm(A, 2)
        assert residual < 1e-10, (j, residual)


def test_close_eigenvalues_fall_back_to_a_full_solve() -> None:
    """Two identical decoupled subsystems give every eigenvalue twice: inverse iteration
    would return one vector for both, so the block's pairs come from the full dense solve
    and the two copies get independent eigenvectors."""
    M1, C1, G1, K1 = _gyroscopic(6, 3)
    z = np.zeros((6, 6))
    M, C, G, K = (np.block([[X, z], [z, X]]) for X in (M1, C1, G1, K1))
    block = Block(np.arange(12), np.eye(12))
    block.reduced = {"M": M, "C": C, "G": G, "K": K}
    spectrum = Spectrum(block, 7.0, 20.0, n_candidates=6)
    assert spectrum._Y is not None  # the fall-back was taken
    pair = np.flatnonzero(np.isclose(spectrum.values, spectrum.values[0], rtol=1e-8))
    assert pair.size == 2
    Y = spectrum.vectors(pair)
    assert np.linalg.matrix_rank(Y, tol=1e-8) == 2


def test_separated_eigenvalues_use_inverse_iteration() -> None:
    M, C, G, K = _gyroscopic(10, 4)
    block = Block(np.arange(10), np.eye(10))
    block.reduced = {"M": M, "C": C, "G": G, "K": K}
    spectrum = Spectrum(block, 7.0, 20.0, n_candidates=6)
    assert spectrum._Y is None
    lam_eig, Y_eig = projected_quadratic_eigen(M, C + 7.0 * G, K, 20.0)
    Y = spectrum.vectors(np.arange(4))
    np.testing.assert_allclose(spectrum.values, lam_eig, rtol=1e-9)
    for j in range(4):  # the same eigenvector up to a complex factor
        a, b = Y[:, j], Y_eig[:, j]
        mac = abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real)
        assert mac > 1 - 1e-10
