"""Amplitude spectra of time histories (numpy/scipy only).

Every amplitude is *amplitude-corrected*: a sinusoid ``A cos(w t + p)`` on a frequency bin
gives a peak of ``A`` whatever the window. Phases follow ``x(t) = Re(X e^{i w t})`` with
``X = A e^{i p}`` referred to ``t = 0``, so a positive phase leads. Frequencies are in rad/s
(``frequency_hz`` gives Hz).

Built on these: interpolated peaks (:mod:`rotorsim.results.spectral_peaks`), least-squares
harmonic fits (:mod:`rotorsim.results.harmonic_fit`), run-up waterfalls and order tracks
(:mod:`rotorsim.results.order_tracking`); the sampling checks are in
:mod:`rotorsim.results.sampling`. :class:`Peak`, :func:`peaks`, :class:`HarmonicFit`,
:func:`harmonic_fit` and the sampling functions are importable from here too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.results.harmonic_fit import HarmonicFit, harmonic_fit
from rotorsim.results.sampling import (
    MIN_SAMPLES,
    UNIFORM_RTOL,
    FloatArray,
    sampling_step,
    time_window,
    window_samples,
)
from rotorsim.results.spectral_peaks import Peak, peaks

ComplexArray = NDArray[np.complex128]

__all__ = [
    "MIN_SAMPLES",
    "UNIFORM_RTOL",
    "HarmonicFit",
    "Peak",
    "Spectrum",
    "amplitude_spectrum",
    "harmonic_fit",
    "peaks",
    "sampling_step",
    "single_sided",
    "time_window",
    "window_samples",
]

_DETRENDS = ("mean", "linear", "none")


@dataclass(frozen=True, eq=False)
class Spectrum:
    """Single-sided, amplitude-corrected spectrum of uniformly sampled signals.

    Attributes
    ----------
    frequency : array (n_bins,)
        Bin frequencies ``2 pi j / (N dt)`` [rad/s], ``j = 0 .. N // 2``.
    amplitude : array (n_bins,) or (n_bins, m)
        Amplitude of each bin [signal units]; a sinusoid on a bin gives its amplitude.
    phase : array like ``amplitude``
        Phase of each bin referred to ``t = 0`` [rad] (exact for a sinusoid on the bin).
    window, detrend : str
        Window (a :func:`scipy.signal.get_window` name) and detrending used.
    n_samples : int
        Number of samples ``N`` transformed.
    dt, t_start : float
        Sampling step and time of the first sample [s].
    """

    frequency: FloatArray
    amplitude: FloatArray
    phase: FloatArray
    window: str
    detrend: str
    n_samples: int
    dt: float
    t_start: float

    @property
    def frequency_hz(self) -> FloatArray:
        """Bin frequencies [Hz]."""
        return self.frequency / (2.0 * math.pi)

    @property
    def resolution(self) -> float:
        """Bin spacing ``2 pi / (N dt)`` [rad/s]."""
        return 2.0 * math.pi / (self.n_samples * self.dt)

    @property
    def complex_amplitude(self) -> ComplexArray:
        """``amplitude * exp(i phase)``."""
        return self.amplitude * np.exp(1j * self.phase)



# ---------------------------------------------------------------------------- spectra
def single_sided(x: FloatArray, window: FloatArray, detrend: str) -> ComplexArray:
    """Amplitude-corrected single-sided spectra of the columns of ``x`` (N, m) -> (bins, m).

    ``window`` (N,) holds the window samples and ``detrend`` is ``"mean"``, ``"linear"`` or
    ``"none"``; phases are referred to the first sample.
    """
    if detrend not in _DETRENDS:
        raise TypeError(f"unknown detrend {detrend!r}; valid: {', '.join(_DETRENDS)}")
    if detrend != "none":
        from scipy.signal import detrend as remove_trend

        x = remove_trend(x, axis=0, type="constant" if detrend == "mean" else "linear")
    spec = np.fft.rfft(x * window[:, None], axis=0) * (2.0 / window.sum())
    spec[0] /= 2.0  # the mean is not split between +/- frequencies
    if x.shape[0] % 2 == 0:
        spec[-1] /= 2.0  # nor is the Nyquist component
    return np.asarray(spec, dtype=complex)


def amplitude_spectrum(t: ArrayLike, x: ArrayLike, *, t_min: float | None = None,
                       t_max: float | None = None, window: str = "hann",
                       detrend: str = "mean") -> Spectrum:
    """Single-sided amplitude spectrum of uniformly sampled signals.

    Parameters
    ----------
    t : array (k,)
        Uniform sample times [s].
    x : array (k,) or (k, m)
        Signal(s), one column per signal.
    t_min, t_max : float, optional
        Only samples with ``t_min <= t <= t_max`` are used [s] (skip a start-up transient).
    window : str
        :func:`scipy.signal.get_window` name (periodic form); ``"boxcar"`` for none.
    detrend : {"mean", "linear", "none"}
        What is removed before windowing.

    Returns
    -------
    Spectrum
        ``amplitude[j]`` is the amplitude of a sinusoid on bin ``j`` (window-corrected).

    Raises
    ------
    ModelError
        If the samples are not uniform or fewer than :data:`MIN_SAMPLES`.

    Examples
    --------
    >>> t = np.arange(400) * 1e-3                           # 0.4 s: 2.5 Hz bins
    >>> s = amplitude_spectrum(t, 2.0 * np.cos(2 * np.pi * 50.0 * t + 0.3))
    >>> j = int(np.argmax(s.amplitude))
    >>> float(s.frequency_hz[j]), round(float(s.amplitude[j]), 12), round(float(s.phase[j]), 12)
    (50.0, 2.0, 0.3)
    """
    t, x = time_window(t, x, t_min, t_max, "amplitude_spectrum")
    dt = sampling_step(t, "amplitude_spectrum")
    w = window_samples(window, t.size)
    spec = single_sided(x.reshape(t.size, -1), w, detrend)
    frequency = np.asarray(2.0 * math.pi * np.fft.rfftfreq(t.size, dt), dtype=float)
    spec *= np.exp(-1j * frequency * t[0])[:, None]  # refer phases to t = 0
    spec = spec.reshape(spec.shape[0], *x.shape[1:])
    return Spectrum(frequency, np.abs(spec), np.angle(spec), window, detrend, int(t.size),
                    dt, float(t[0]))

