"""Amplification factor of a resonance peak by the half-power method (API 684 SP6.8.2.1):
``AF = N_c / (N_2 - N_1)``, with ``N_c`` the speed of the peak and ``N_1 < N_c < N_2`` the
speeds where the amplitude is the peak amplitude over ``sqrt(2)``.

The peak and the two crossings are located on a sampled curve and then, when the
response can be evaluated at any speed, refined on it (the peak by a bounded scalar
search, the crossings by Brent's method), so the result does not depend on the grid.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError


@dataclass(frozen=True)
class HalfPower:
    """A resonance peak and its half-power band.

    Attributes
    ----------
    peak_speed, peak : float
        Speed [rad/s] and amplitude of the peak.
    low, high : float
        Speeds of the half-power points [rad/s]; NaN when the curve does not fall to
        ``peak / sqrt(2)`` on that side within the sampled range.
    af : float
        ``peak_speed / (high - low)`` (NaN when a half-power point is missing).
    """

    peak_speed: float
    peak: float
    low: float
    high: float

    @property
    def af(self) -> float:
        width = self.high - self.low
        return self.peak_speed / width if width > 0 else math.nan


def half_power(speeds: ArrayLike, amplitude: ArrayLike, index: int,
               response: Callable[[float], float] | None = None,
               rtol: float = 1e-10) -> HalfPower:
    """Half-power band of the peak at sample ``index`` of a sampled amplitude curve.

    Parameters
    ----------
    speeds : array (F,)
        Increasing speeds [rad/s].
    amplitude : array (F,)
        Amplitude at each speed (any unit).
    index : int
        A sample at (or next to) the peak, ``0 < index < F - 1`` for a refined peak.
    response : callable, optional
        ``response(speed) -> amplitude``: the exact curve, used to refine the peak and the
        crossings; without it the peak is the sample and the crossings are interpolated
        linearly between samples.
    rtol : float
        Relative tolerance of the refined speeds.

    Returns
    -------
    HalfPower

    Examples
    --------
    >>> w = np.linspace(0.5, 1.5, 2001)
    >>> zeta = 0.05
    >>> amp = lambda r: 1 / np.sqrt((1 - r**2) ** 2 + (2 * zeta * r) ** 2)
    >>> hp = half_power(w, amp(w), int(np.argmax(amp(w))), lambda r: float(amp(r)))
    >>> exact = np.sqrt(1 - 2 * zeta**2) / (np.sqrt(1 - 2 * zeta**2 + 2 * zeta * np.sqrt(
    ...     1 - zeta**2)) - np.sqrt(1 - 2 * zeta**2 - 2 * zeta * np.sqrt(1 - zeta**2)))
    >>> bool(abs(hp.af / exact - 1) < 1e-8), round(hp.af, 4)
    (True, 9.9499)
    """
    w = np.asarray(speeds, dtype=float)
    a = np.asarray(amplitude, dtype=float)
    if w.ndim != 1 or a.shape != w.shape or w.size < 3:
        raise ModelError(f"need matching 1-D speeds and amplitudes of >= 3 points, got "
                         f"{w.shape} and {a.shape}", "half_power")
    if not 0 <= index < w.size:
        raise ModelError(f"index {index} outside 0..{w.size - 1}", "half_power")
    peak_speed, peak = float(w[index]), float(a[index])
    if response is not None and 0 < index < w.size - 1:
        peak_speed, peak = _refine_peak(response, w[index - 1], w[index + 1], rtol)
    level = peak / math.sqrt(2.0)
    low = _crossing(w, a, peak_speed, level, -1, response, rtol)
    high = _crossing(w, a, peak_speed, level, +1, response, rtol)
    return HalfPower(peak_speed, peak, low, high)


def _refine_peak(response: Callable[[float], float], lo: float, hi: float, rtol: float
                 ) -> tuple[float, float]:
    from scipy.optimize import minimize_scalar

    found = minimize_scalar(lambda s: -response(s), bounds=(lo, hi), method="bounded",
                            options={"xatol": rtol * hi})
    return float(found.x), float(-found.fun)


def _crossing(w: np.ndarray, a: np.ndarray, peak_speed: float, level: float, step: int,
              response: Callable[[float], float] | None, rtol: float) -> float:
    """Speed where the curve falls to ``level`` walking from the peak by ``step``: the
    first sample beyond the peak below the level, bracketed with the nearest point between
    it and the peak at or above the level (a sample, or the peak itself)."""
    side = np.flatnonzero(w < peak_speed)[::-1] if step < 0 else np.flatnonzero(
        w > peak_speed)
    below = side[a[side] < level]
    if below.size == 0:
        return math.nan
    j = int(below[0])
    above = side[:int(np.flatnonzero(side == j)[0])]  # samples between the peak and j
    above = above[a[above] >= level]
    near_speed, near_amp = (float(w[above[-1]]), float(a[above[-1]])) if above.size else (
        peak_speed, level * math.sqrt(2.0))
    if response is None:
        return float(np.interp(level, [a[j], near_amp], [w[j], near_speed]))
    from scipy.optimize import brentq

    lo, hi = sorted((float(w[j]), near_speed))
    return float(brentq(lambda s: response(s) - level, lo, hi, xtol=rtol * hi))
