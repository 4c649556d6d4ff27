"""Spectra of time histories: amplitude spectra, interpolated peaks and least-squares
harmonic fits (numpy/scipy only); run-up waterfalls and order tracks build on these in
:mod:`rotorsim.results.order_tracking`.

Every amplitude is *amplitude-corrected*: a sinusoid ``A cos(w t + p)`` on a frequency bin
gives a peak of ``A`` whatever the window. Phases follow ``x(t) = Re(X e^{i w t})`` with
``X = A e^{i p}`` referred to ``t = 0``, so a positive phase leads. Frequencies are in rad/s
(``frequency_hz`` gives Hz).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

MIN_SAMPLES = 8
"""Fewest samples a spectrum (or one waterfall segment) is computed from."""
UNIFORM_RTOL = 1e-6
"""Largest deviation of a time step from the mean step, relative to it, for uniform sampling."""
_DETRENDS = ("mean", "linear", "none")
_INTERPOLATIONS = ("ratio", "log-parabolic", "parabolic")


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


@dataclass(frozen=True)
class Peak:
    """A spectral peak located between bins by interpolation.

    Attributes
    ----------
    frequency : float
        Interpolated frequency [rad/s].
    amplitude, phase : float
        Amplitude and phase (referred to ``t = 0``) [signal units, rad], corrected for the
        window's response at the offset from the bin.
    bin : float
        Fractional bin index of the peak.
    column : int
        Signal column the peak belongs to.
    """

    frequency: float
    amplitude: float
    phase: float
    bin: float
    column: int = 0

    @property
    def frequency_hz(self) -> float:
        """Interpolated frequency [Hz]."""
        return self.frequency / (2.0 * math.pi)


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


# ---------------------------------------------------------------------------- sampling
def window_samples(name: str, n: int) -> FloatArray:
    """Periodic (DFT-even) window of ``n`` samples; ``TypeError`` for an unknown name."""
    if not isinstance(name, str):
        raise TypeError(f"window must be a name such as 'hann', 'flattop' or 'boxcar', "
                        f"got {name!r}")
    from scipy.signal import get_window  # scipy.signal is slow to import: only when used

    try:
        return np.asarray(get_window(name, n, fftbins=True), dtype=float)
    except ValueError as exc:
        raise TypeError(f"unknown window {name!r}; use e.g. 'hann', 'hamming', 'blackman', "
                        "'flattop' or 'boxcar'") from exc


def time_window(t: ArrayLike, x: ArrayLike, t_min: float | None, t_max: float | None,
                where: str) -> tuple[FloatArray, FloatArray]:
    """``t`` (k,) and ``x`` (k,) or (k, m) as float arrays, restricted to
    ``t_min <= t <= t_max``; :class:`ModelError` naming ``where`` for other shapes."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.ndim != 1 or x.ndim not in (1, 2) or x.shape[0] != t.size:
        raise ModelError(f"t must be (k,) and x (k,) or (k, m); got {t.shape} and {x.shape}",
                         where)
    keep = (t >= (-np.inf if t_min is None else t_min)) & \
        (t <= (np.inf if t_max is None else t_max))
    return t[keep], x[keep]


def sampling_step(t: ArrayLike, where: str = "sampling_step",
                  min_samples: int = MIN_SAMPLES) -> float:
    """Step [s] of uniformly sampled times ``t``.

    Raises
    ------
    ModelError
        If ``t`` has fewer than ``min_samples`` samples, does not increase, or its steps
        differ from their mean by more than :data:`UNIFORM_RTOL` of it.

    Examples
    --------
    >>> sampling_step(np.linspace(0.0, 1.0, 11))
    0.1
    """
    t = np.asarray(t, dtype=float)
    if t.size < min_samples:
        raise ModelError(f"{t.size} samples are too few (need at least {min_samples}); "
                         "lengthen the window or lower t_min", where)
    steps = np.diff(t)
    dt = float((t[-1] - t[0]) / (t.size - 1))
    if not dt > 0 or np.any(steps <= 0):
        raise ModelError("sample times must increase", where)
    spread = float(np.max(np.abs(steps - dt))) / dt
    if spread > UNIFORM_RTOL:
        raise ModelError(
            f"sampling is not uniform (steps differ by {spread:.2g} of the mean step); keep "
            "samples at uniform times, e.g. OutputSpec(times=np.linspace(...)), or resample "
            "with np.interp first", where)
    return dt


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


def _kernel(w: FloatArray, offset: ArrayLike) -> ComplexArray:
    """Window response ``sum_n w_n e^{2 pi i d n / N}`` at bin offsets ``d``."""
    n = np.arange(w.size)
    phases = np.exp(2j * math.pi * np.multiply.outer(offset, n) / w.size)
    return np.asarray(phases @ w, dtype=complex)


def _ratio_offset(w: FloatArray, ratio: float) -> float:
    """Offset ``d`` in [0, 1/2] at which the window's response one bin further, relative to
    its response at ``d``, equals ``ratio`` (the larger neighbour over the peak bin)."""
    def gap(d: float) -> float:
        return float(abs(_kernel(w, 1.0 - d)) - ratio * abs(_kernel(w, d)))

    lo, hi = gap(0.0), gap(0.5)
    if lo >= 0.0 or hi <= 0.0:  # outside the single-sinusoid range: noise or two peaks
        return 0.0 if lo >= 0.0 else 0.5
    from scipy import optimize  # slow to import: on first use

    return float(optimize.brentq(gap, 0.0, 0.5, xtol=1e-13))


def _offsets(mag: FloatArray, j: NDArray[np.int64], method: str, w: FloatArray
             ) -> FloatArray:
    """Fractional bin offsets of the peaks at bins ``j`` from their neighbours."""
    a, b, c = mag[j - 1], mag[j], mag[j + 1]
    if method == "ratio":
        right = c >= a
        ratio = np.where(right, c, a) / b
        return np.where(right, 1.0, -1.0) * np.array([_ratio_offset(w, r) for r in ratio])
    if method == "log-parabolic":
        tiny = np.finfo(float).tiny
        a, b, c = (np.log(np.maximum(v, tiny)) for v in (a, b, c))
    return np.asarray(0.5 * (a - c) / (a - 2.0 * b + c))


def peaks(spectrum: Spectrum, n: int = 5, *, min_height: float = 0.0, column: int = 0,
          interpolation: str = "ratio") -> list[Peak]:
    """The ``n`` largest local maxima of one column of ``spectrum``, interpolated between bins.

    Parameters
    ----------
    spectrum : Spectrum
    n : int
        Number of peaks returned (fewer if there are fewer maxima).
    min_height : float
        Smallest bin amplitude of a peak [signal units].
    column : int
        Signal column (for a spectrum of several signals).
    interpolation : {"ratio", "log-parabolic", "parabolic"}
        ``"ratio"`` finds the offset at which the window's response gives the observed
        ratio of the larger neighbour to the peak bin (exact for an isolated sinusoid, any
        window; for Hann the ratio is ``(1 + d) / (2 - d)``); ``"log-parabolic"`` fits a
        parabola through the logarithms of three bins, ``"parabolic"`` through the
        amplitudes.

    Returns
    -------
    list of Peak
        Largest first; amplitude and phase corrected by the window's response at the
        interpolated offset.

    Examples
    --------
    >>> t = np.arange(1000) * 1e-3                          # 1 Hz bins
    >>> s = amplitude_spectrum(t, 1.5 * np.cos(2 * np.pi * 40.3 * t))
    >>> p = peaks(s, n=1)[0]
    >>> round(p.frequency_hz, 4), round(p.amplitude, 4)
    (40.3, 1.5)
    """
    if interpolation not in _INTERPOLATIONS:
        raise TypeError(f"unknown interpolation {interpolation!r}; valid: "
                        f"{', '.join(_INTERPOLATIONS)}")
    amp = spectrum.amplitude.reshape(spectrum.amplitude.shape[0], -1)
    if not 0 <= column < amp.shape[1]:
        raise ModelError(f"column {column} outside 0..{amp.shape[1] - 1}", "peaks")
    mag = amp[:, column]
    from scipy.signal import find_peaks

    found, _ = find_peaks(mag, height=max(min_height, np.finfo(float).tiny))
    found = found[np.argsort(mag[found])[::-1][:n]]
    w = window_samples(spectrum.window, spectrum.n_samples)
    offset = np.clip(_offsets(mag, found, interpolation, w), -0.5, 0.5)
    # a bin's corrected value times sum(w) / W(d), and the phase referred back to t = 0
    gain = w.sum() / _kernel(w, offset) * np.exp(-1j * offset * spectrum.resolution *
                                                 spectrum.t_start)
    cplx = spectrum.complex_amplitude.reshape(mag.size, -1)[found, column] * gain
    fbin = found + offset
    return [Peak(float(f), float(abs(z)), float(np.angle(z)), float(k), column)
            for f, z, k in zip(fbin * spectrum.resolution, cplx, fbin, strict=True)]


# ---------------------------------------------------------------------------- harmonic fit
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
