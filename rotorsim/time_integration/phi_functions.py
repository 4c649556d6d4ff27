"""The ``phi_k`` functions of exponential integrators, ``phi_0 = e^z`` and ``phi_{k+1}(z) =
(phi_k(z) - 1/k!) / z``, for a complex vector: Taylor series near 0, the recurrence
elsewhere (used by :mod:`~rotorsim.time_integration.exponential_modes` for the weights of
a step).

References
----------
M. Hochbruck, A. Ostermann, *Exponential integrators*, Acta Numerica 19 (2010) 209-286,
section 2.3 (the ``phi_k`` functions, their recurrence and series, eq 2.10).
"""

from __future__ import annotations

import math

import numpy as np

from rotorsim.time_integration.base import FloatArray

ComplexArray = np.ndarray
TAYLOR_RADIUS = 1.0
"""``|z|`` below which ``phi_k`` is summed as its Taylor series (above: the recurrence,
whose cancellation then costs at most ``k / |z|`` of a digit per level)."""
TAYLOR_TERMS = 17
"""Terms of the series: the first left out is below ``1/18! < 1.6e-16`` at ``|z| <= 1``."""


def phi_functions(z: ComplexArray, kmax: int) -> ComplexArray:
    """``phi_0 .. phi_kmax`` (kmax + 1, len(z)) of a complex vector ``z``
    (``phi_0 = e^z``, ``phi_{k+1}(z) = (phi_k(z) - 1/k!) / z``).

    Examples
    --------
    >>> p = phi_functions(np.array([0.0, 2.0 + 0j]), 2)
    >>> bool(np.allclose(p[:, 0], [1.0, 1.0, 0.5]))
    True
    >>> bool(np.isclose(p[1, 1], (np.exp(2) - 1) / 2))
    True
    """
    z = np.asarray(z, dtype=complex).reshape(-1)
    out = np.empty((kmax + 1, z.size), dtype=complex)
    out[0] = cexp(z)
    if kmax == 0:
        return out
    small = np.abs(z) < TAYLOR_RADIUS
    count = int(np.count_nonzero(small))
    if count < z.size:
        fact = 1.0
        safe = np.where(small, 1.0, z)
        for k in range(1, kmax + 1):
            out[k] = (out[k - 1] - 1.0 / fact) / safe
            fact *= k
    if count:
        zs = z if count == z.size else z[small]
        powers = _powers(zs)
        # real coefficients times complex powers as one real product on the interleaved
        # real and imaginary parts (the same sums; numpy would cast the coefficients to
        # complex and multiply by zeros)
        series = (_series(kmax) @ powers.view(float)).view(complex)
        if count == z.size:
            out[1:] = series
        else:
            out[1:, small] = series
    return out


def cexp(z: ComplexArray) -> ComplexArray:
    """``e^z`` of a complex array as ``e^x (cos y + i sin y)`` from real functions.

    Equal to ``np.exp(z)`` to round-off, and not slowed down after a complex BLAS product:
    measured here (OpenBLAS 0.3.31, Haswell kernels), ``np.exp`` of 150 complex numbers
    took 80 us right after a ``zgemm`` instead of 4 us (the SSE code of the C library's
    ``cexp`` after AVX code that leaves the upper register halves dirty), while numpy's
    real ``exp``, ``cos`` and ``sin`` kept their speed.

    Examples
    --------
    >>> bool(np.allclose(cexp(np.array([0.0, 1j * np.pi])), [1.0, -1.0]))
    True
    """
    z = np.asarray(z, dtype=complex)
    out = np.empty(z.shape, dtype=complex)
    mag = np.exp(z.real)
    out.real = mag * np.cos(z.imag)
    out.imag = mag * np.sin(z.imag)
    return out


def _powers(z: ComplexArray) -> ComplexArray:
    """``z^m`` for ``m = 0 .. TAYLOR_TERMS - 1`` (TAYLOR_TERMS, len(z)), by products.

    Blocks of rows by doubling: rows ``b .. 2b - 1`` are rows ``0 .. b - 1`` times
    ``z^b`` (five products for 17 rows instead of 15 row by row, or ``cumprod``, which
    numpy runs about three times slower still on complex rows: measured 91 against 36 us
    for 150 values row by row). Each power is a product of at most five factors, so its
    relative round-off stays a few units of the last place."""
    rows = np.empty((TAYLOR_TERMS, z.size), dtype=complex)
    rows[0] = 1.0
    rows[1] = z
    b = 2
    while b < TAYLOR_TERMS:
        top = min(2 * b, TAYLOR_TERMS)
        np.multiply(rows[:top - b], rows[b - 1] * z, out=rows[b:top])
        b = top
    return rows


def _series(kmax: int) -> FloatArray:
    """Taylor coefficients ``1 / (m + k)!`` (kmax, TAYLOR_TERMS) of ``phi_1 .. phi_kmax``
    (``phi_k(z) = sum_m z^m / (m + k)!``, Hochbruck & Ostermann 2010, eq 2.10)."""
    found = _SERIES.get(kmax)
    if found is None:
        found = np.array([[1.0 / math.factorial(m + k) for m in range(TAYLOR_TERMS)]
                          for k in range(1, kmax + 1)])
        _SERIES[kmax] = found
    return found


_SERIES: dict[int, FloatArray] = {}
