"""Alternating frequency/time on a 2-torus: coefficients to samples by a 2-D inverse FFT,
forces back by a 2-D FFT, and the exact Jacobian of that discrete map.

Coefficient arrays have :attr:`TorusHarmonics.rows` rows: the mean, then ``(c_j, s_j)`` of
``cos(k_j . theta)`` and ``sin(k_j . theta)`` for each wave vector, and one column per DOF.
With the complex amplitude ``Z_j = c_j - i s_j`` a signal reads
``q = a_0 + Re sum_j Z_j e^{i k_j . theta}``; its grid spectrum holds ``Z_j / 2`` at
``k_j`` and the conjugate at ``-k_j`` (indices modulo the grid).

**Jacobian.** For a force ``f(q(theta))`` with tangent ``Kt(theta) = df/dq`` sampled on the
grid, and ``Khat[m]`` the discrete Fourier coefficients of ``Kt`` (``(1/N) sum_theta Kt
e^{-i m . theta}``), the derivative of the force's coefficients is, with
``A = Khat[k_j - k_l]`` and ``B = Khat[k_j + k_l]`` (indices modulo the grid, so this is
the exact derivative of the discrete AFT, aliasing included):

    d(c_j, s_j) / d(c_l, s_l) = [[Re(A + B), Im(A - B)], [-Im(A + B), Re(A - B)]],
    d(c_j, s_j) / d a_0 = (2 Re Khat[k_j], -2 Im Khat[k_j]),
    d a_0 / d(c_l, s_l) = (Re Khat[k_l], -Im Khat[k_l]),    d a_0 / d a_0 = Khat[0].

A velocity tangent ``Ct = df/dv`` enters the same way, times the derivative map of the
coefficients (:meth:`TorusAFT.derivative_matrix`).

References
----------
Seed 002 section 3.5.2.1 (AFT for one frequency); S. Schilder et al., *Int. J. Numer. Meth.
Eng.* 67 (2006) 629-671, and M. Krack, J. Gross, *Harmonic Balance for Nonlinear Vibration
Problems*, Springer 2019, section 4.2 (its extension to several frequencies).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi.harmonics import TorusHarmonics

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class TorusAFT:
    """Transforms between coefficients of ``harmonics`` and samples on an ``N1 x N2`` grid.

    Parameters
    ----------
    harmonics : TorusHarmonics
    samples : (int, int), optional
        Grid ``(N1, N2)``; :meth:`TorusHarmonics.default_samples` when omitted. Each must
        exceed twice the largest ``|k_i|`` (below that, two retained tones share a grid
        frequency).

    Examples
    --------
    >>> aft = TorusAFT(TorusHarmonics.box(1, 1))
    >>> X = np.zeros((aft.harmonics.rows, 1)); X[1 + 2 * aft.harmonics.index(1, 0)] = 2.0
    >>> float(aft.to_samples(X)[0, 0])          # 2 cos(theta1) at theta = (0, 0)
    2.0
    """

    harmonics: TorusHarmonics
    samples: tuple[int, int] | None = None

    def __post_init__(self) -> None:
        grid = self.samples or self.harmonics.default_samples()
        top = np.abs(self.harmonics.k).max(axis=0)
        if len(grid) != 2 or any(int(n) <= 2 * t for n, t in zip(grid, top, strict=True)):
            raise ModelError(f"samples {tuple(grid)} must exceed twice the largest "
                             f"|k1|, |k2| = {tuple(int(t) for t in top)}", "TorusAFT.samples")
        object.__setattr__(self, "samples", (int(grid[0]), int(grid[1])))

    @property
    def grid(self) -> tuple[int, int]:
        """``(N1, N2)``."""
        return self.samples  # type: ignore[return-value]

    @property
    def n_samples(self) -> int:
        return self.grid[0] * self.grid[1]

    @cached_property
    def angles(self) -> tuple[FloatArray, FloatArray]:
        """``theta1, theta2`` of every sample ``(N1 N2,)`` [rad], row-major over the grid."""
        t1, t2 = (2 * np.pi * np.arange(n) / n for n in self.grid)
        a1, a2 = np.meshgrid(t1, t2, indexing="ij")
        return a1.ravel(), a2.ravel()

    @cached_property
    def _positions(self) -> tuple[IntArray, IntArray]:
        """Grid indices of ``+k_j`` and ``-k_j``."""
        n1, n2 = self.grid
        k = self.harmonics.k
        return (k[:, 0] % n1) * n2 + k[:, 1] % n2, (-k[:, 0] % n1) * n2 + (-k[:, 1] % n2)

    def to_samples(self, X: FloatArray) -> FloatArray:
        """Samples ``(N1 N2, d)`` of the signals with coefficients ``X (rows, d)``."""
        n1, n2 = self.grid
        d = X.shape[1]
        Z = X[1::2] - 1j * X[2::2]
        spectrum = np.zeros((n1 * n2, d), dtype=complex)
        plus, minus = self._positions
        spectrum[0] = X[0]
        np.add.at(spectrum, plus, Z / 2)
        np.add.at(spectrum, minus, np.conj(Z) / 2)
        values = np.fft.ifft2(spectrum.reshape(n1, n2, d), axes=(0, 1)) * (n1 * n2)
        return np.ascontiguousarray(values.real.reshape(n1 * n2, d))

    def to_coefficients(self, f: FloatArray) -> FloatArray:
        """Coefficients ``(rows, d)`` of the retained tones of samples ``f (N1 N2, d)``."""
        spectrum = self._spectrum(f)
        plus, _ = self._positions
        out = np.empty((self.harmonics.rows, f.shape[1]))
        out[0] = spectrum[0].real
        out[1::2] = 2 * spectrum[plus].real
        out[2::2] = -2 * spectrum[plus].imag
        return out

    def _spectrum(self, f: FloatArray) -> ComplexArray:
        n1, n2 = self.grid
        shape = f.shape[1:]
        F = np.fft.fft2(f.reshape(n1, n2, *shape), axes=(0, 1)) / (n1 * n2)
        return F.reshape(n1 * n2, *shape)

    def derivative_matrix(self, w1: float, w2: float) -> FloatArray:
        """``D (rows, rows)`` with ``coefficients of dq/dt = D @ X``: for ``Omega_j = k_j .
        (w1, w2)``, ``c'_j = Omega_j s_j`` and ``s'_j = -Omega_j c_j``."""
        rows = self.harmonics.rows
        D = np.zeros((rows, rows))
        omega = self.harmonics.frequencies(w1, w2)
        j = np.arange(self.harmonics.size)
        D[1 + 2 * j, 2 + 2 * j] = omega
        D[2 + 2 * j, 1 + 2 * j] = -omega
        return D

    def jacobian(self, tangent: FloatArray) -> FloatArray:
        """``d(force coefficients) / d(coefficients)`` for sampled tangents ``(N1 N2, d, d)``.

        Returns
        -------
        array (rows d, rows d)
            Ordered harmonic-major: entry ``(r d + p, s d + q)`` is the derivative of row
            ``r``, DOF ``p`` with respect to row ``s``, DOF ``q``.
        """
        d = tangent.shape[1]
        K = self._spectrum(tangent)              # (N, d, d) complex
        diff, summ = self._pair_positions
        A, B = K[diff], K[summ]                  # (n_h, n_h, d, d)
        plus, _ = self._positions
        rows, n_h = self.harmonics.rows, self.harmonics.size
        # built in the (row, DOF, row, DOF) layout: advanced indices on both row axes put
        # the (n_h, n_h) axes first, matching A and B, and the final reshape is a view
        J = np.zeros((rows, d, rows, d))
        J[0, :, 0, :] = K[0].real
        J[0, :, 1::2, :] = K[plus].real.transpose(1, 0, 2)
        J[0, :, 2::2, :] = -K[plus].imag.transpose(1, 0, 2)
        J[1::2, :, 0, :] = 2 * K[plus].real
        J[2::2, :, 0, :] = -2 * K[plus].imag
        cos = (1 + 2 * np.arange(n_h))[:, None]
        sin = cos + 1
        J[cos, :, cos.T, :] = (A + B).real
        J[cos, :, sin.T, :] = (A - B).imag
        J[sin, :, cos.T, :] = -(A + B).imag
        J[sin, :, sin.T, :] = (A - B).real
        return J.reshape(rows * d, rows * d)

    @cached_property
    def _pair_positions(self) -> tuple[IntArray, IntArray]:
        """Grid indices of ``k_i - k_j`` and ``k_i + k_j`` ``(n_h, n_h)``."""
        n1, n2 = self.grid
        k = self.harmonics.k
        diff = ((k[:, None, 0] - k[None, :, 0]) % n1) * n2 + (k[:, None, 1] - k[None, :, 1]) % n2
        summ = ((k[:, None, 0] + k[None, :, 0]) % n1) * n2 + (k[:, None, 1] + k[None, :, 1]) % n2
        return diff, summ
