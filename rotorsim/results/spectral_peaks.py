"""Spectral peaks located between bins: the largest local maxima of an amplitude spectrum,
with frequency, amplitude and phase corrected for the window's response at the offset from
the bin (amplitude-corrected as in :mod:`rotorsim.results.spectra`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError
from rotorsim.results.sampling import FloatArray, window_samples

if TYPE_CHECKING:
    from rotorsim.results.spectra import Spectrum

ComplexArray = NDArray[np.complex128]

_INTERPOLATIONS = ("ratio", "log-parabolic", "parabolic")


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
    >>> from rotorsim.results.spectra import amplitude_spectrum
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

