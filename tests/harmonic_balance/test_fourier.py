"""Fourier layout, AFT transforms and the Galerkin matrix of periodic tangents.

References: the explicit sums of seed 002 eqs 3.34-3.36 (with ``D_i = -Q_is``), the
closed-form series, and the dense product ``Gamma^+ diag(T) Gamma``.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import (
    AFT,
    default_samples,
    derivative,
    derivative_matrix,
    from_complex,
    harmonic_numbers,
    resize,
    to_complex,
)

RNG = np.random.default_rng(7)


@pytest.mark.parametrize(("H", "N"), [(0, 1), (1, 3), (3, 16), (4, 9), (5, 12), (10, 128)])
def test_transform_pair_is_exact_on_truncated_series(H, N):
    aft = AFT(H, N)
    X = RNG.standard_normal((aft.rows, 3))
    q = aft.to_time(X)
    tau = aft.tau[:, None]
    direct = X[0] + 0.0 * tau + sum(X[2 * h - 1] * np.cos(h * tau) + X[2 * h] * np.sin(h * tau)
                        for h in range(1, H + 1))
    assert q == pytest.approx(direct, abs=1e-13)
    assert aft.to_frequency(q) == pytest.approx(X, abs=1e-13)
    assert aft.basis(aft.tau) @ X == pytest.approx(q, abs=1e-13)


def test_projection_is_the_seed_sums():
    """Seed 002 eqs 3.34-3.36: C_0 = mean, C_i = 2/N sum F cos, D_i = -2/N sum F sin."""
    aft = AFT(3, 16)
    f = RNG.standard_normal(16)
    n = np.arange(16)
    C = [2 / 16 * np.sum(f * np.cos(2 * np.pi * i * n / 16)) for i in (1, 2, 3)]
    D = [-2 / 16 * np.sum(f * np.sin(2 * np.pi * i * n / 16)) for i in (1, 2, 3)]
    Q = aft.to_frequency(f)
    assert Q[0] == pytest.approx(f.mean(), abs=1e-14)
    assert Q[1::2] == pytest.approx(C, abs=1e-14)
    assert Q[2::2] == pytest.approx(-np.array(D), abs=1e-14)     # Q_hs = -D_h
    assert aft.projection() @ f == pytest.approx(Q, abs=1e-14)


def test_complex_amplitudes_follow_the_re_x_exp_convention():
    X = np.array([0.3, 1.0, 2.0, -0.5, 0.25])
    Z = to_complex(X)
    tau = np.linspace(0, 2 * np.pi, 7)
    series = AFT(2).basis(tau) @ X
    assert series == pytest.approx(
        Z[0].real + sum((Z[h] * np.exp(1j * h * tau)).real for h in (1, 2)), abs=1e-14)
    assert from_complex(Z) == pytest.approx(X, abs=0)


def test_derivative_operator_matches_the_analytic_derivative():
    aft = AFT(4, 32)
    X = RNG.standard_normal((aft.rows, 2))
    tau = aft.tau[:, None]
    exact = sum(h * (-X[2 * h - 1] * np.sin(h * tau) + X[2 * h] * np.cos(h * tau))
                for h in range(1, 5))
    assert aft.to_time(derivative(X)) == pytest.approx(exact, abs=1e-12)
    assert derivative(X, 2) == pytest.approx(derivative_matrix(4) @ derivative_matrix(4) @ X)
    assert np.diag(derivative_matrix(4) @ derivative_matrix(4)) == pytest.approx(
        -harmonic_numbers(4) ** 2)


@pytest.mark.parametrize(("H", "N"), [(3, 16), (3, 7), (4, 11), (6, 13), (10, 128)])
@pytest.mark.parametrize("with_derivative", [False, True])
def test_tangent_jacobian_equals_the_dense_galerkin_product(H, N, with_derivative):
    """Also for N < 4H, where harmonics up to 2H of the tangent alias (wrapped FFT)."""
    aft, k = AFT(H, N), 3
    T = RNG.standard_normal((N, k, k))
    G, P = aft.basis(aft.tau), aft.projection()
    dense = np.einsum("as,sij,sb->aibj", P, T, G).reshape(aft.rows * k, aft.rows * k)
    if with_derivative:
        dense = dense @ np.kron(derivative_matrix(H), np.eye(k))
    assert aft.tangent_jacobian(T, derivative=with_derivative) == pytest.approx(dense,
                                                                                abs=1e-12)


def test_default_samples_and_validation():
    assert [default_samples(h) for h in (1, 3, 7, 10, 20)] == [16, 32, 64, 128, 256]
    assert AFT(10).samples == 128
    with pytest.raises(ModelError, match="samples"):
        AFT(3, 6)
    with pytest.raises(ModelError, match="harmonics"):
        AFT(-1)
    assert resize(np.ones((3, 2)), 2)[3:].sum() == 0 and resize(np.ones((7, 1)), 1).shape == (
        3, 1)
