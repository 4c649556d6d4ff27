"""Amplitudes of known tones in a sampled signal, by linear least squares (issue 17).

A quasi-periodic response ``y(t) = a_0 + sum_j (a_j cos(W_j t) + b_j sin(W_j t))`` with
incommensurate ``W_j = k1 w1 + k2 w2`` has no period, so an FFT over any window leaks
every tone into its neighbours. With the frequencies known, the coefficients are the
least-squares solution of the overdetermined system whose columns are ``1``,
``cos(W_j t)`` and ``sin(W_j t)`` sampled at ``t``: exact (to round-off) for a signal that
contains only those tones, and with an error of order ``1 / (T dW)`` of the leaked tones
otherwise (``T`` the window, ``dW`` the distance of a missing tone to the nearest fitted
one), so the fitted set should contain every tone of appreciable size.

Used by the quasi-periodic validation (``tests/validation/test_quasi_periodic_validation.py``,
``scripts/quasi_validation.py``) and ``benchmarks/bench_quasi.py`` to compare the
harmonic-balance tones with long integrations in time. Needs numpy only.

References
----------
Linear least-squares harmonic analysis (e.g. A. Schuster's periodogram generalised to
known frequencies; any text on the method of least squares).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def tone_frequencies(k: ArrayLike, w1: float, w2: float) -> FloatArray:
    """``|k1 w1 + k2 w2|`` [rad/s] of the wave vectors ``k (n, 2)``."""
    k = np.asarray(k, dtype=float).reshape(-1, 2)
    return np.abs(k[:, 0] * float(w1) + k[:, 1] * float(w2))


def fit_tones(t: ArrayLike, y: ArrayLike, frequencies: ArrayLike) -> ComplexArray:
    """Complex amplitudes ``a_j - i b_j`` of the tones ``frequencies`` in ``y(t)``.

    Parameters
    ----------
    t : array (m,)
        Sample times [s].
    y : array (m,) or (m, c)
        The signal (``c`` channels fitted at once).
    frequencies : array (n,)
        Distinct positive angular frequencies [rad/s]; the mean is always fitted too.

    Returns
    -------
    complex array (n + 1,) or (n + 1, c)
        Row 0: the mean; row ``j + 1``: ``a_j - i b_j`` of ``frequencies[j]``, whose modulus
        is the tone's amplitude (``y = Re(c e^{i W t})``).

    Raises
    ------
    ValueError
        Non-positive or repeated frequencies, fewer samples than unknowns, or a mismatch of
        ``t`` and ``y``.

    Examples
    --------
    >>> t = np.linspace(0.0, 50.0, 4001)
    >>> y = 0.5 + 2.0 * np.cos(1.0 * t) + 0.1 * np.sin(np.sqrt(2.0) * t)
    >>> c = fit_tones(t, y, [1.0, np.sqrt(2.0)])
    >>> np.round(np.abs(c), 10).tolist()
    [0.5, 2.0, 0.1]
    """
    t = np.asarray(t, dtype=float).ravel()
    y = np.asarray(y, dtype=float)
    w = np.asarray(frequencies, dtype=float).ravel()
    if y.shape[0] != t.size:
        raise ValueError(f"y has {y.shape[0]} samples, t has {t.size}")
    if np.any(w <= 0) or np.unique(w).size != w.size:
        raise ValueError("frequencies must be positive and distinct (the mean is fitted "
                         "anyway)")
    if t.size < 2 * w.size + 1:
        raise ValueError(f"{t.size} samples for {2 * w.size + 1} unknowns")
    tc = t - 0.5 * (t[0] + t[-1])  # centred: better conditioned columns
    phase = np.outer(tc, w)
    A = np.concatenate([np.ones((t.size, 1)), np.cos(phase), np.sin(phase)], axis=1)
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    a, b = coef[1:1 + w.size], coef[1 + w.size:]
    shift = np.exp(-1j * w * 0.5 * (t[0] + t[-1]))  # back to the phase at t = 0
    if y.ndim > 1:
        shift = shift[:, None]
    return np.concatenate([coef[:1].astype(complex), (a - 1j * b) * shift], axis=0)
