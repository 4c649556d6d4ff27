"""Real Fourier series, alternating frequency-time (AFT) transforms and derivative operators.

Layout used by the whole package (harmonic-major)
-------------------------------------------------
A periodic signal with ``m`` components, written in the phase ``tau = omega t`` and
truncated to ``H`` harmonics,

    q(tau) = Q_0 + sum_{h=1..H} (Q_hc cos(h tau) + Q_hs sin(h tau)),

is stored as a *coefficient array* of shape ``(2H + 1, m)`` whose rows are
``[Q_0, Q_1c, Q_1s, Q_2c, Q_2s, ..., Q_Hc, Q_Hs]`` (row ``0`` the mean, row ``2h - 1`` the
cosine and row ``2h`` the sine of harmonic ``h``). Flattened (``X.reshape(-1)``) it is the
harmonic-balance unknown vector, index ``row * m + component``.

Relation to the other conventions: rotorsim's complex amplitude
``x(t) = Re(X_h e^{i h omega t})`` is ``X_h = Q_hc - i Q_hs`` (:func:`to_complex`); seed 002
eq 3.30 writes ``A_j cos - B_j sin``, so ``A_j = Q_jc`` and ``B_j = -Q_js``.

Time samples are ``tau_s = 2 pi s / N``, ``s = 0..N-1``; the projection back to the
coefficients is seed 002 eqs 3.34-3.36 (``Q_0`` the sample mean, ``Q_hc = 2/N sum f cos``,
``Q_hs = 2/N sum f sin``), evaluated with ``numpy.fft.rfft``. For ``N >= 2H + 1`` the
transform pair is exact on truncated series.

References
----------
Seed 002 (thesis, section 3.5.2.1), eqs 3.30-3.36. T. M. Cameron, J. H. Griffin, J. Appl.
Mech. 56 (1989) 149-154 (the AFT method).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]


def whole(value: object, minimum: int) -> bool:
    """Whether ``value`` is an integer (not a bool) ``>= minimum``.

    >>> whole(3, 1), whole(3.0, 1), whole(2.5, 1), whole(float("inf"), 1), whole(True, 0)
    (True, True, False, False, False)
    """
    if isinstance(value, bool):
        return False
    try:
        return int(value) == value and value >= minimum  # type: ignore[call-overload,operator]
    except (TypeError, ValueError, OverflowError):
        return False


def default_samples(harmonics: int) -> int:
    """Default number of time samples: ``2**ceil(log2(max(8 H, 16)))``.

    Examples
    --------
    >>> [default_samples(h) for h in (0, 1, 2, 5, 10)]
    [16, 16, 16, 64, 128]
    """
    return 2 ** math.ceil(math.log2(max(8 * int(harmonics), 16)))


def harmonic_numbers(harmonics: int) -> IntArray:
    """Harmonic number of each coefficient row: ``[0, 1, 1, 2, 2, ..., H, H]``."""
    return np.concatenate(([0], np.repeat(np.arange(1, harmonics + 1), 2))).astype(np.int64)


def resize(X: ArrayLike, harmonics: int) -> FloatArray:
    """Coefficient array truncated or zero-padded to ``harmonics`` harmonics.

    ``X`` has ``2H' + 1`` rows (any trailing shape); the result has ``2 * harmonics + 1``.

    Examples
    --------
    >>> resize(np.arange(5.0).reshape(5, 1), 1).ravel().tolist()
    [0.0, 1.0, 2.0]
    >>> resize([[1.0]], 1).ravel().tolist()
    [1.0, 0.0, 0.0]
    """
    X = np.asarray(X, dtype=float)
    rows = 2 * harmonics + 1
    if X.shape[0] % 2 != 1:
        raise ModelError(f"a coefficient array needs an odd number of rows, got {X.shape[0]}",
                         "fourier.resize")
    out = np.zeros((rows, *X.shape[1:]))
    keep = min(rows, X.shape[0])
    out[:keep] = X[:keep]
    return out


def to_complex(X: ArrayLike) -> ComplexArray:
    """Complex amplitudes ``(H + 1, ...)``: ``[Q_0, Q_1c - i Q_1s, ..., Q_Hc - i Q_Hs]``.

    Row ``h`` is the amplitude of harmonic ``h`` in ``x(t) = Re(X_h e^{i h omega t})``.

    Examples
    --------
    >>> to_complex([[1.0], [2.0], [3.0]]).ravel().tolist()
    [(1+0j), (2-3j)]
    """
    X = np.asarray(X, dtype=float)
    out = np.empty(((X.shape[0] + 1) // 2, *X.shape[1:]), dtype=complex)
    out[0] = X[0]
    out[1:] = X[1::2] - 1j * X[2::2]
    return out


def from_complex(Z: ArrayLike) -> FloatArray:
    """Inverse of :func:`to_complex` (the imaginary part of row 0 is dropped)."""
    Z = np.asarray(Z, dtype=complex)
    out = np.empty((2 * Z.shape[0] - 1, *Z.shape[1:]))
    out[0] = Z[0].real
    out[1::2] = Z[1:].real
    out[2::2] = -Z[1:].imag
    return out


def derivative(X: ArrayLike, order: int = 1) -> FloatArray:
    """Coefficients of ``d^order q / d tau^order`` (multiply by ``omega**order`` for time).

    ``d/dtau (Q_c cos h tau + Q_s sin h tau) = h Q_s cos h tau - h Q_c sin h tau``.

    Examples
    --------
    >>> derivative([[5.0], [1.0], [0.0]]).ravel().tolist()   # d/dtau cos = -sin
    [0.0, 0.0, -1.0]
    """
    out = np.array(X, dtype=float)
    for _ in range(order):
        h = harmonic_numbers((out.shape[0] - 1) // 2).reshape(-1, *([1] * (out.ndim - 1)))
        new = np.zeros_like(out)
        new[1::2] = h[2::2] * out[2::2]
        new[2::2] = -h[1::2] * out[1::2]
        out = new
    return out


def derivative_matrix(harmonics: int) -> FloatArray:
    """Matrix ``nabla`` (2H+1, 2H+1) with ``derivative(X) == nabla @ X``."""
    return derivative(np.eye(2 * harmonics + 1))


@dataclass(frozen=True)
class AFT:
    """Alternating frequency-time transforms for ``harmonics`` harmonics on ``samples`` points.

    Parameters
    ----------
    harmonics : int
        ``H >= 0``.
    samples : int, optional
        ``N >= 2H + 1`` time samples per period (default :func:`default_samples`). A
        nonlinearity of polynomial degree ``p`` is transformed without aliasing when
        ``N >= (p + 1) H + 1``; non-smooth forces need ``N >> H`` (check with
        :func:`rotorsim.harmonic_balance.solve.sample_convergence`).

    Examples
    --------
    >>> aft = AFT(2)
    >>> X = np.array([[1.0], [0.5], [0.0], [0.0], [0.25]])   # 1 + cos tau / 2 + sin 2 tau / 4
    >>> q = aft.to_time(X)
    >>> q.shape, float(q[0, 0]), np.allclose(aft.to_frequency(q), X)
    ((16, 1), 1.5, True)
    """

    harmonics: int
    samples: int = 0

    def __post_init__(self) -> None:
        H = self.harmonics
        if not whole(H, 0):
            raise ModelError(f"harmonics must be an integer >= 0, got {H!r}", "AFT")
        N = default_samples(H) if self.samples == 0 else self.samples
        if not whole(N, 2 * H + 1):
            raise ModelError(f"samples must be an integer >= 2 H + 1 = {2 * H + 1}, got "
                             f"{self.samples!r}", "AFT")
        object.__setattr__(self, "harmonics", int(H))
        object.__setattr__(self, "samples", int(N))

    @property
    def rows(self) -> int:
        """Number of coefficient rows ``2H + 1``."""
        return 2 * self.harmonics + 1

    @cached_property
    def tau(self) -> FloatArray:
        """Sample phases ``2 pi s / N`` (N,) [rad]."""
        return 2.0 * np.pi * np.arange(self.samples) / self.samples

    def to_time(self, X: ArrayLike) -> FloatArray:
        """Samples ``(N, ...)`` of the series with coefficients ``X`` ``(2H + 1, ...)``."""
        X = np.asarray(X, dtype=float)
        N, H = self.samples, self.harmonics
        spectrum = np.zeros((N // 2 + 1, *X.shape[1:]), dtype=complex)
        spectrum[0] = N * X[0]
        spectrum[1:H + 1] = (0.5 * N) * (X[1::2] - 1j * X[2::2])
        return np.fft.irfft(spectrum, n=N, axis=0)

    def to_frequency(self, x: ArrayLike) -> FloatArray:
        """Coefficients ``(2H + 1, ...)`` of the samples ``x`` ``(N, ...)`` (eqs 3.34-3.36)."""
        c = np.fft.rfft(np.asarray(x, dtype=float), axis=0)[: self.harmonics + 1]
        out = np.empty((self.rows, *c.shape[1:]))
        scale = 2.0 / self.samples
        out[0] = c[0].real / self.samples
        out[1::2] = scale * c[1:].real
        out[2::2] = -scale * c[1:].imag
        return out

    def basis(self, tau: ArrayLike) -> FloatArray:
        """Matrix ``Gamma`` (len(tau), 2H + 1) of ``[1, cos tau, sin tau, ..., sin H tau]``.

        ``Gamma @ X`` evaluates the series at arbitrary phases ``tau`` [rad].
        """
        t = np.asarray(tau, dtype=float).reshape(-1, 1)
        h = np.arange(1, self.harmonics + 1)[None, :]
        out = np.empty((t.shape[0], self.rows))
        out[:, 0] = 1.0
        out[:, 1::2] = np.cos(h * t)
        out[:, 2::2] = np.sin(h * t)
        return out

    def projection(self) -> FloatArray:
        """Matrix ``Gamma^+`` (2H + 1, N) with ``to_frequency(x) == Gamma^+ @ x``."""
        P = 2.0 / self.samples * self.basis(self.tau).T
        P[0] *= 0.5
        return P

    def tangent_jacobian(self, T: ArrayLike, *, derivative: bool = False) -> FloatArray:
        """Galerkin matrix of a periodic tangent: ``Gamma^+ diag(T(tau_s)) Gamma``.

        Parameters
        ----------
        T : array (N, k, k)
            Tangent samples, e.g. ``df/dq`` at the time samples.
        derivative : bool
            Multiply by ``nabla`` on the right (``Gamma^+ diag(T) Gamma nabla``, the
            velocity tangent acting on the displacement coefficients, without ``omega``).

        Returns
        -------
        array ((2H + 1) k, (2H + 1) k)
            In the harmonic-major layout, exactly equal to the sample sum (no aliasing
            approximation): it is assembled from the FFT of ``T`` up to harmonic ``2H``
            with the product rules ``cos a cos b = (cos(a+b) + cos(a-b)) / 2`` etc.
        """
        T = np.asarray(T, dtype=float)
        N, k, H2 = self.samples, T.shape[-1], 2 * self.harmonics
        c = np.fft.rfft(T, axis=0)
        if H2 > N // 2:   # harmonics above N/2 of the samples are conjugates (aliases)
            m = np.arange(H2 + 1)
            c = np.where((m > N // 2)[:, None, None], np.conj(c[np.minimum(N - m, N // 2)]),
                         c[np.minimum(m, N // 2)])
        c = c[: H2 + 1] / N
        table = np.empty((4, 2 * H2 + 1, k, k))          # [A, B, -A, -B] at m = -2H..2H
        table[0, H2:], table[0, :H2] = c.real, c.real[:0:-1]      # A(m) even
        table[1, H2:], table[1, :H2] = -c.imag, c.imag[:0:-1]     # B(m) odd
        np.negative(table[:2], out=table[2:])
        ix = self._derivative_index if derivative else self._index
        J = table[ix.kind_sum, ix.sum] + table[ix.kind_diff, ix.diff]
        J[0] *= 0.5                                       # weight 1/2 of the mean row
        out = J.transpose(0, 2, 1, 3).reshape(self.rows * k, self.rows * k)
        if derivative:   # column b of (. nabla) is h_b times column partner(b), signed
            out *= np.repeat(harmonic_numbers(self.harmonics), k)[None, :]
        return out

    @cached_property
    def _index(self) -> _ProductIndex:
        return _ProductIndex.build(self.harmonics)

    @cached_property
    def _derivative_index(self) -> _ProductIndex:
        return self._index.times_derivative()


@dataclass(frozen=True, eq=False)
class _ProductIndex:
    """Gather indices of :meth:`AFT.tangent_jacobian` (built once per ``H``).

    Row ``a`` (output coefficient) and column ``b`` (input coefficient) combine
    ``A(m) = mean(T cos m tau)`` or ``B(m) = mean(T sin m tau)`` at ``m = h_a + h_b`` and
    ``m = h_a - h_b``: cos-cos ``A(+) + A(-)``, cos-sin ``B(+) - B(-)``, sin-cos
    ``B(+) + B(-)``, sin-sin ``A(-) - A(+)`` (the mean is a cosine of harmonic 0; its row
    is halved). ``kind_*`` index the table ``[A, B, -A, -B]``, ``sum``/``diff`` the
    harmonic ``m + 2H``.
    """

    kind_sum: IntArray
    kind_diff: IntArray
    sum: IntArray
    diff: IntArray

    @classmethod
    def build(cls, H: int) -> _ProductIndex:
        h = harmonic_numbers(H)
        is_sin = np.zeros(2 * H + 1, dtype=bool)
        is_sin[2::2] = True
        sa, sb = is_sin[:, None], is_sin[None, :]
        kind = (sa ^ sb).astype(np.int64)                      # 1: B (one sine), 0: A
        kind_sum = kind + 2 * (sa & sb)                        # sin-sin: -A(+)
        kind_diff = kind + 2 * (~sa & sb)                      # cos-sin: -B(-)
        return cls(kind_sum, kind_diff, h[:, None] + h[None, :] + 2 * H,
                   h[:, None] - h[None, :] + 2 * H)

    def times_derivative(self) -> _ProductIndex:
        """Indices of ``J nabla`` up to the column factor ``h_b``: column ``cos h`` takes
        ``-`` column ``sin h``, column ``sin h`` takes column ``cos h``."""
        rows = self.sum.shape[0]
        partner = np.arange(rows)
        partner[1::2] += 1
        partner[2::2] -= 1
        flip = np.zeros(rows, dtype=np.int64)
        flip[1::2] = 2                                         # negate: A <-> -A, B <-> -B
        return _ProductIndex((self.kind_sum[:, partner] + flip) % 4,
                             (self.kind_diff[:, partner] + flip) % 4,
                             self.sum[:, partner], self.diff[:, partner])
