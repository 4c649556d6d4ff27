"""Least-squares harmonic fit of one known frequency (plus a constant) to a time history,
to compare a steady state with a frequency-domain solution. Sampling need not be uniform.

Phases follow ``x(t) = Re(X e^{i w t})`` with ``X = A e^{i p}`` referred to ``t = 0``, as in
:mod:`rotorsim.results.spectra`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError
from rotorsim.results.sampling import FloatArray, time_window

ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class HarmonicFit:
    """Least-squares fit ``x(t) = mean + Re(X e^{i w t})`` of one known frequency.

    Attributes
    ----------
    frequency : float
        The fitted frequency ``w`` [rad/s].
    amplitude, phase, mean : arrays of shape ``()`` or ``(m,)``
        ``|X|``, ``arg X`` [rad] (positive leading, referred to ``t = 0``) and the constant.
    residual_rms : array like ``amplitude``
        RMS of the fit residual [signal units].
    t_start, t_end : float
        Time window of the fit [s].
    n_samples : int
    """

    frequency: float
    amplitude: FloatArray
    phase: FloatArray
    mean: FloatArray
    residual_rms: FloatArray
    t_start: float
    t_end: float
    n_samples: int

    @property
    def complex_amplitude(self) -> ComplexArray:
        """``X = amplitude * exp(i phase)``."""
        return np.asarray(self.amplitude * np.exp(1j * self.phase))



def harmonic_fit(t: ArrayLike, x: ArrayLike, frequency: float, *, t_min: float | None = None,
                 t_max: float | None = None) -> HarmonicFit:
    """Least-squares amplitude and phase of one known frequency (plus a constant).

    Fits ``x(t) ~ c + Re(X e^{i w t}) = c + a cos(w t) + b sin(w t)`` with ``X = a - i b``,
    the convention of the frequency-domain analyses, so that a steady state can be
    compared with a harmonic solution. Sampling need not be uniform.

    Parameters
    ----------
    t : array (k,)
        Sample times [s].
    x : array (k,) or (k, m)
        Signal(s).
    frequency : float
        ``w`` [rad/s], > 0.
    t_min, t_max : float, optional
        Fit window [s]; best a whole number of periods of the steady state.

    Returns
    -------
    HarmonicFit

    Raises
    ------
    ModelError
        If ``frequency <= 0`` or fewer than 3 samples lie in the window.

    Examples
    --------
    >>> t = np.linspace(0.0, 0.1, 101)
    >>> fit = harmonic_fit(t, 0.5 + 2.0 * np.sin(100.0 * t), 100.0)
    >>> round(float(fit.amplitude), 12), round(float(fit.phase), 12), round(float(fit.mean), 12)
    (2.0, -1.570796326795, 0.5)
    """
    t, x = time_window(t, x, t_min, t_max, "harmonic_fit")
    if t.size < 3:
        raise ModelError(f"{t.size} samples are too few for a harmonic fit (need 3)",
                         "harmonic_fit")
    if not frequency > 0:
        raise ModelError(f"frequency must be > 0 rad/s, got {frequency}", "harmonic_fit")
    basis = np.column_stack([np.ones_like(t), np.cos(frequency * t), np.sin(frequency * t)])
    coef, *_ = np.linalg.lstsq(basis, x.reshape(t.size, -1), rcond=None)
    residual = x.reshape(t.size, -1) - basis @ coef
    X = (coef[1] - 1j * coef[2]).reshape(x.shape[1:])
    rms = np.sqrt(np.mean(residual**2, axis=0)).reshape(x.shape[1:])
    return HarmonicFit(float(frequency), np.asarray(np.abs(X)), np.asarray(np.angle(X)),
                       np.asarray(coef[0].reshape(x.shape[1:])), np.asarray(rms), float(t[0]),
                       float(t[-1]), int(t.size))
