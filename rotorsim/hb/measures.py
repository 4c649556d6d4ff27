"""Amplitude measures of harmonic-balance coefficients, vectorised over branch points.

Coefficients ``X`` (..., 2H + 1, n) in the layout ``[X_0, X_1c, X_1s, ..., X_Hc, X_Hs]`` of
:mod:`rotorsim.harmonic_balance.fourier` describe ``q(t) = X_0 + sum_h X_hc cos(h Omega t)
+ X_hs sin(h Omega t)``. The measures of one DOF:

* ``"harmonic"``: ``|X_h| = sqrt(X_hc^2 + X_hs^2)`` (``|X_0|`` for ``h = 0``); NLvib's
  amplitude ``a`` is ``|X_1|``, the ``"fundamental"``;
* ``"rms"``: ``sqrt(X_0^2 + sum_h |X_h|^2 / 2)`` (Parseval: the root mean square of
  ``q(t)`` over a period);
* ``"peak"``: ``max_t |q(t)|`` sampled on ``max(64, 16 H)`` phases;
* ``"peak_to_peak"``: ``(max q - min q) / 2`` on the same phases.
"""

from __future__ import annotations

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import AFT, FloatArray

MEASURES = ("fundamental", "harmonic", "rms", "peak", "peak_to_peak")


def harmonic_amplitudes(X: FloatArray, dof: int) -> FloatArray:
    """``|X_h|``, ``h = 0..H`` (..., H + 1) of DOF ``dof``."""
    q = np.asarray(X)[..., dof]
    return np.concatenate([np.abs(q[..., :1]), np.hypot(q[..., 1::2], q[..., 2::2])], axis=-1)


def amplitude(X: FloatArray, dof: int, measure: str = "fundamental",
              harmonic: int = 1) -> FloatArray:
    """The ``measure`` (module docstring) of DOF ``dof`` for coefficients ``X``
    (..., 2H + 1, n); shape (...).

    Examples
    --------
    >>> X = np.array([[0.5], [3.0], [4.0]])          # 0.5 + 3 cos + 4 sin
    >>> [round(float(amplitude(X, 0, m)), 6) for m in ("fundamental", "rms", "peak")]
    [5.0, 3.570714, 5.5]
    """
    X = np.asarray(X, dtype=float)
    H = (X.shape[-2] - 1) // 2
    if measure not in MEASURES:
        raise TypeError(f"unknown measure {measure!r}; valid: {', '.join(MEASURES)}")
    if not 0 <= dof < X.shape[-1]:
        raise ModelError(f"DOF {dof} is outside [0, {X.shape[-1]})", "amplitude")
    if measure in ("fundamental", "harmonic"):
        h = 1 if measure == "fundamental" else harmonic
        if not 0 <= h <= H:
            raise ModelError(f"harmonic {h} is outside [0, {H}]", "amplitude")
        return harmonic_amplitudes(X, dof)[..., h]
    if measure == "rms":
        a = harmonic_amplitudes(X, dof)
        return np.sqrt(a[..., 0] ** 2 + 0.5 * np.sum(a[..., 1:] ** 2, axis=-1))
    q = time_samples(X, dof, max(64, 16 * H))
    if measure == "peak":
        return np.abs(q).max(axis=-1)
    return 0.5 * (q.max(axis=-1) - q.min(axis=-1))


def time_samples(X: FloatArray, dof: int, samples: int) -> FloatArray:
    """``q(tau_j)`` of DOF ``dof`` at ``tau_j = 2 pi j / samples`` (..., samples)."""
    X = np.asarray(X, dtype=float)
    H = (X.shape[-2] - 1) // 2
    tau = 2.0 * np.pi * np.arange(samples) / samples
    return np.asarray(X[..., dof] @ AFT(H).basis(tau).T)
