"""Integrals of the line load ``Kn delta(xi)^n`` along a roller (used by RollerBearing).

A roller's deflection ``delta(xi)`` on ``xi`` in ``[-1/2, 1/2]`` gives its load, load moment,
tangent weights and energy as integrals along its length: in closed form for a straight,
tilted roller (:func:`tilted_line_integrals`, seed 000 eqs 7-9 and 22-23) or by the
midpoint rule over slices (:func:`line_moments`, seed 002 eqs 2.7, 2.12). The constants
``Kn`` of the line law are in :mod:`~rotorsim.elements.rolling.contact.hertz_line`.

References
----------
Seed 000 eqs 7-9, 22-23 (tilted roller); seed 002 eqs 2.7, 2.12 (slices).
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.base import frozen_scalar

FloatArray = NDArray[np.float64]

_SERIES_LIMIT = 0.1
"""Below this slope ``|beta|`` the moments use their power series (cancellation-free)."""
_SERIES_TERMS = 8
_BATCH_LIMIT = 32768  # size up to which the moments are evaluated as one stacked array


# 0-d arrays: cheaper operands than Python floats (same values)
_ZERO, _HALF, _ONE = frozen_scalar(0.0), frozen_scalar(0.5), frozen_scalar(1.0)


def _power(x: FloatArray, exponent: float) -> FloatArray:
    """``x^exponent`` for ``x >= 0``; twice as fast for ninths (``cbrt(cbrt(x)) = x^(1/9)``)."""
    whole = math.floor(exponent)
    if abs(exponent - whole - 1.0 / 9.0) > 1e-12:
        return np.asarray(x**exponent)
    out = np.cbrt(np.cbrt(x))
    for _ in range(whole):
        out = out * x
    return np.asarray(out)


@functools.lru_cache(maxsize=64)
def _series_coefficients(m: float, k: int) -> tuple[float, ...]:
    """Coefficients ``c_l`` of ``j_k(m, beta) = beta^(k%2) sum_l c_l beta^(2l)``.

    ``j_k(m, beta) = int_{-1/2}^{1/2} s^k (1 + beta s)^m ds
    = sum_i binom(m, i) beta^i mu_{k+i}`` with ``mu_q = 2^-q / (q+1)`` for even ``q``.
    """
    coefficients = []
    for i in range(k % 2, 2 * _SERIES_TERMS + k % 2, 2):
        binom = math.prod((m - t) / (t + 1) for t in range(i))
        q = k + i
        coefficients.append(binom * 0.5**q / (q + 1))
    return tuple(coefficients)


@functools.lru_cache(maxsize=64)
def _coefficient_columns(specs: tuple[tuple[int, float], ...], ndim: int
                         ) -> tuple[FloatArray, ...]:
    """Series coefficients of the moments ``(k, m)`` of ``specs``, highest power first,
    each ``(len, 1, ...)`` to broadcast against ``ndim``-dimensional arrays. Read-only."""
    table = np.array([_series_coefficients(m, k) for k, m in specs])
    columns = tuple(np.array(col).reshape(len(specs), *(1,) * ndim) for col in table[:, ::-1].T)
    for col in columns:
        col.flags.writeable = False
    return columns


def _moments(specs: tuple[tuple[int, float], ...], beta: FloatArray, beta2: FloatArray,
             small: NDArray[np.bool_], closed: FloatArray | None) -> FloatArray:
    """``j_k(m, beta)`` of every ``(k, m)`` in ``specs``, stacked ``(len, ...)``: the
    closed forms ``closed`` where ``|beta|`` is not small, else the series (one batched
    Horner evaluation); ``closed=None`` when every ``|beta|`` is small."""
    if closed is not None and not small.any():
        return closed
    highest, *columns = _coefficient_columns(specs, beta.ndim)
    series = np.empty((len(specs), *beta.shape))
    series[...] = highest
    # one batched evaluation of small arrays (few operations), else moment by moment
    # (each pass over the data stays in cache)
    parts = [series] if series.size <= _BATCH_LIMIT else [x[None] for x in series]
    for i, part in enumerate(parts):
        for column in columns:
            part *= beta2
            part += column if len(parts) == 1 else column[i]
    for i, (k, _) in enumerate(specs):
        if k % 2:
            series[i] *= beta
    return series if closed is None else np.asarray(np.where(small, series, closed))


def tilted_line_integrals(v: FloatArray, lw: FloatArray, exponent: float,
                          energy_only: bool = False) -> tuple[FloatArray, ...]:
    """Closed-form integrals of a straight roller's line load (seed 000 eqs 7-9, 22-23).

    The deflection ``delta(xi) = v + xi lw`` on ``xi`` in ``[-1/2, 1/2]`` is positive on
    the loaded zone of eq 8, where it runs linearly from ``u_1`` to ``u_2``. With the zone
    centre ``xi_c``, its length ``h``, the mean ``a = (u_1 + u_2)/2`` and
    ``beta = (u_2 - u_1)/a`` in ``[-2, 2]``:
    ``int xi^p delta^m dxi = h a^m int (xi_c + h s)^p (1 + beta s)^m ds``, whose moments
    ``j_k = int s^k (1 + beta s)^m ds`` are evaluated in closed form or, for
    ``|beta| < 0.1``, by their binomial series (no cancellation when the roller is not
    tilted).

    Parameters
    ----------
    v, lw : array (S, N)
        Centre deflection ``V`` [m] and tilt ``L omega`` [m] of each roller.
    exponent : float
        ``n``.
    energy_only : bool
        Compute only the energy integral (the others are returned as zeros).

    Returns
    -------
    tuple of arrays (S, N)
        ``int delta^(n+1)/(n+1)``, ``int delta^n``, ``int xi delta^n``,
        ``int xi^p delta^(n-1)`` for ``p = 0, 1, 2``, and the peak deflection [m].

    Examples
    --------
    >>> out = tilted_line_integrals(np.array([[1.0]]), np.array([[0.0]]), 2.0)
    >>> [round(float(x[0, 0]), 6) for x in out]
    [0.333333, 1.0, 0.0, 1.0, 0.0, 0.083333, 1.0]
    """
    return _tilted(v, lw, float(exponent), not energy_only, True)


def _tilted(v: FloatArray, lw: FloatArray, n: float, forces: bool, energy: bool
            ) -> tuple[Any, ...]:
    """:func:`tilted_line_integrals`; ``forces=False``: only the energy (zeros for the
    rest), ``energy=False``: ``None`` for the energy and the peak deflection."""
    d_lo, d_hi = v - _HALF * lw, v + _HALF * lw
    u1, u2 = np.maximum(d_lo, _ZERO), np.maximum(d_hi, _ZERO)
    peak = np.maximum(u1, u2)
    a = _HALF * (u1 + u2)
    a_s = np.where(a > _ZERO, a, _ONE)
    w_lo, w_hi = u1 / a_s, u2 / a_s
    span = np.abs(lw)
    full = (d_lo > _ZERO) & (d_hi > _ZERO)
    h = np.where(full, _ONE, peak / np.where(span > _ZERO, span, _ONE))
    beta = w_hi - w_lo
    small = np.abs(beta) < _SERIES_LIMIT
    b1 = np.where(small, _ONE, beta)
    beta2 = beta * beta
    p_hi, p_lo = _power(w_hi, n), _power(w_lo, n)
    big_w2 = (p_hi * w_hi * w_hi - p_lo * w_lo * w_lo) / (n + 2.0)
    a_n = _power(a_s, n)
    if not forces:
        j = _moments(((0, n + 1.0),), beta, beta2, small, (big_w2 / b1)[None])[0]
        out = h * a_n * a_s * j / (n + 1.0)
        zero = np.zeros_like(v)
        return out, zero, zero, zero, zero, zero, peak
    big_w0 = (p_hi - p_lo) / n
    big_w1 = (p_hi * w_hi - p_lo * w_lo) / (n + 1.0)
    cen = _HALF * (_ONE - h) * np.sign(u2 - u1)
    m = n - 1.0
    specs = ((0, n), (1, n), (0, m), (1, m), (2, m)) + (((0, n + 1.0),) if energy else ())
    closed: FloatArray | None = None
    if not small.all():  # the closed forms (b1 = beta where they are used)
        closed = np.empty((len(specs), *v.shape))
        np.divide(big_w1, b1, out=closed[0])
        np.divide(big_w2 - big_w1, b1**2, out=closed[1])
        np.divide(big_w0, b1, out=closed[2])
        np.divide(big_w1 - big_w0, b1**2, out=closed[3])
        np.divide(big_w2 - 2.0 * big_w1 + big_w0, b1**3, out=closed[4])
        if energy:
            np.divide(big_w2, b1, out=closed[5])
    j0, j1, k0, k1, k2, *rest = _moments(specs, beta, beta2, small, closed)
    scaled = h * a_n
    load = scaled * j0
    load_moment = scaled * (cen * j0 + h * j1)
    scale = scaled / a_s
    t0 = scale * k0
    t1 = scale * (cen * k0 + h * k1)
    t2 = scale * (cen * cen * k0 + 2.0 * cen * h * k1 + h * h * k2)
    if not energy:
        return None, load, load_moment, t0, t1, t2, None
    return scaled * a_s * rest[0] / (n + 1.0), load, load_moment, t0, t1, t2, peak


def line_moments(deflection: FloatArray, xi: FloatArray, exponent: float,
                 energy_only: bool = False) -> tuple[FloatArray, ...]:
    """Slice sums of the line load (midpoint rule over ``K`` equal slices, seed 002 eq 2.12).

    Parameters
    ----------
    deflection : array (S, N, K)
        Slice deflections ``delta_k`` [m] (negative: no contact).
    xi : array (K,)
        Slice centres.
    exponent : float
        ``n``.
    energy_only : bool
        Compute only the energy sum (the others are returned as zeros).

    Returns
    -------
    tuple of arrays (S, N)
        As :func:`tilted_line_integrals`, each integral ``int f dxi`` replaced by
        ``sum_k f(xi_k) / K``.

    Examples
    --------
    >>> out = line_moments(np.full((1, 1, 4), 1.0), np.array([-.375, -.125, .125, .375]), 2.0)
    >>> [round(float(x[0, 0]), 6) for x in out]
    [0.333333, 1.0, 0.0, 1.0, 0.0, 0.078125, 1.0]
    """
    n = float(exponent)
    if energy_only:
        n_slices = xi.shape[0]
        pos = np.maximum(deflection, 0.0)
        peak = pos.max(axis=-1)
        energy = _power(pos, n + 1.0).sum(axis=-1) / (n_slices * (n + 1.0))
        zero = np.zeros_like(peak)
        return energy, zero, zero, zero, zero, zero, peak
    return _slice_sums(deflection, slice_weights(xi), n, True)


def slice_weights(xi: FloatArray) -> FloatArray:
    """``(1, xi_k, xi_k^2) / K`` (K, 3): the midpoint-rule weights of the slice sums."""
    return np.stack([np.ones_like(xi), xi, xi * xi], axis=1) / xi.shape[0]


def _slice_sums(deflection: FloatArray, weights: FloatArray, n: float, energy: bool
                ) -> tuple[Any, ...]:
    """:func:`line_moments` with the :func:`slice_weights`; ``energy=False``: ``None``
    for the energy and the peak deflection."""
    n_slices = weights.shape[0]
    pos = np.maximum(deflection, _ZERO)
    tangent = _power(pos, n - 1.0) if n > 1.0 else (deflection > 0.0).astype(float)
    load = tangent * pos
    flat = (-1, n_slices)
    t = tangent.reshape(flat) @ weights
    q = load.reshape(flat) @ weights[:, :2]
    out_shape = deflection.shape[:-1]
    sums = (q[:, 0].reshape(out_shape), q[:, 1].reshape(out_shape),
            t[:, 0].reshape(out_shape), t[:, 1].reshape(out_shape),
            t[:, 2].reshape(out_shape))
    if not energy:
        return None, *sums, None
    total = (load * pos).reshape(flat).sum(axis=1) / (n_slices * (n + 1.0))
    return total.reshape(out_shape), *sums, pos.max(axis=-1)
