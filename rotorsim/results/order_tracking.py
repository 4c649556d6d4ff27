"""Run-up post-processing: short-time spectra (waterfalls) and order tracks.

Amplitudes are amplitude-corrected as in :mod:`rotorsim.results.spectra`; order phases
follow ``x = Re(X e^{i k phi})`` referred to shaft angle ``phi = 0`` (positive leading).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.results.sampling import (
    MIN_SAMPLES,
    FloatArray,
    sampling_step,
    time_window,
    window_samples,
)
from rotorsim.results.spectra import single_sided

if TYPE_CHECKING:
    from scipy.interpolate import CubicSpline


@dataclass(frozen=True, eq=False)
class Waterfall:
    """Short-time amplitude spectra of one signal (e.g. over a run-up).

    Attributes
    ----------
    times : array (s,)
        Centre time of each segment [s].
    speeds : array (s,)
        Mean spin speed over each segment [rad/s].
    frequency : array (n_bins,)
        Bin frequencies [rad/s].
    amplitude : array (s, n_bins)
        Amplitude-corrected spectrum of each segment [signal units].
    window : str
    segment_samples : int
        Samples per segment.
    overlap : float
        Overlap fraction of consecutive segments.
    """

    times: FloatArray
    speeds: FloatArray
    frequency: FloatArray
    amplitude: FloatArray
    window: str
    segment_samples: int
    overlap: float

    @property
    def frequency_hz(self) -> FloatArray:
        """Bin frequencies [Hz]."""
        return self.frequency / (2.0 * math.pi)


@dataclass(frozen=True, eq=False)
class OrderTrack:
    """Amplitude and phase of shaft orders per block of whole revolutions.

    Attributes
    ----------
    orders : array (o,)
        Tracked orders (multiples of the shaft speed; need not be integers).
    speed : array (B,)
        Spin speed at the angular centre of each block [rad/s], where the (symmetric)
        window is centred.
    times : array (B,)
        Time at the angular centre of each block [s].
    amplitude, phase : arrays (B, o)
        Amplitude [signal units] and phase referred to shaft angle ``phi = 0`` [rad] of each
        order: ``x ~ Re(X e^{i order phi})``.
    order_axis : array (n_bins,)
        Orders of the FFT bins of a block (spacing ``1 / R``).
    order_spectrum : array (B, n_bins)
        Amplitude-corrected order spectrum of each block [signal units].
    revolutions_per_block, samples_per_revolution : int
    window : str
    """

    orders: FloatArray
    speed: FloatArray
    times: FloatArray
    amplitude: FloatArray
    phase: FloatArray
    order_axis: FloatArray
    order_spectrum: FloatArray
    revolutions_per_block: int
    samples_per_revolution: int
    window: str


# ---------------------------------------------------------------------------- waterfall
def waterfall(t: ArrayLike, x: ArrayLike, speed: ArrayLike, *, segment: float,
              overlap: float = 0.5, window: str = "hann", detrend: str = "mean") -> Waterfall:
    """Short-time amplitude spectra of one uniformly sampled signal (a run-up waterfall).

    Parameters
    ----------
    t : array (k,)
        Uniform sample times [s].
    x : array (k,)
        Signal.
    speed : array (k,)
        Spin speed at the samples [rad/s]; its mean over a segment labels the segment.
    segment : float
        Segment duration [s] (rounded to whole samples); sets the resolution
        ``2 pi / segment`` [rad/s].
    overlap : float
        Fraction of a segment shared with the next, in ``[0, 1)``.
    window, detrend : str
        As in :func:`rotorsim.results.spectra.amplitude_spectrum`.

    Returns
    -------
    Waterfall

    Examples
    --------
    >>> t = np.arange(2000) * 1e-3
    >>> w = waterfall(t, np.cos(2 * np.pi * 100.0 * t), np.full(t.size, 50.0), segment=0.2)
    >>> w.amplitude.shape, float(w.frequency_hz[np.argmax(w.amplitude[3])])
    ((19, 101), 100.0)
    """
    t, x = time_window(t, x, None, None, "waterfall")
    speed = np.asarray(speed, dtype=float)
    if x.ndim != 1 or speed.shape != t.shape:
        raise ModelError(f"x and speed must be (k,) like t {t.shape}; got {x.shape}, "
                         f"{speed.shape}", "waterfall")
    dt = sampling_step(t, "waterfall")
    n = round(segment / dt)
    if not MIN_SAMPLES <= n <= t.size:
        raise ModelError(f"segment {segment} s holds {n} samples; need {MIN_SAMPLES} to "
                         f"{t.size} (the record is {t[-1] - t[0]:.6g} s)", "waterfall")
    if not 0.0 <= overlap < 1.0:
        raise ModelError(f"overlap must be in [0, 1), got {overlap}", "waterfall")
    hop = max(1, round(n * (1.0 - overlap)))
    starts = np.arange(0, t.size - n + 1, hop)
    index = starts[None, :] + np.arange(n)[:, None]  # (n, segments)
    spec = single_sided(x[index], window_samples(window, n), detrend)
    return Waterfall(t[starts] + 0.5 * (n - 1) * dt, speed[index].mean(axis=0),
                     np.asarray(2.0 * math.pi * np.fft.rfftfreq(n, dt), dtype=float),
                     np.abs(spec).T, window, int(n), float(overlap))


# ---------------------------------------------------------------------------- orders
def _angle_grid(t: FloatArray, angle: FloatArray, revolutions: int, per_rev: int
                ) -> tuple[FloatArray, CubicSpline]:
    """Uniform angles of whole blocks from ``angle[0]``, and the spline ``t(angle)``."""
    from scipy.interpolate import CubicSpline  # slow to import: on first use

    n_blocks = int((angle[-1] - angle[0]) / (2.0 * math.pi * revolutions) + 1e-9)
    if n_blocks < 1:
        raise ModelError(f"the record turns {(angle[-1] - angle[0]) / (2 * math.pi):.3g} "
                         f"revolutions, fewer than one block of {revolutions}; lower "
                         "revolutions_per_block or integrate longer", "order_track")
    step = 2.0 * math.pi / per_rev
    grid = angle[0] + step * np.arange(n_blocks * revolutions * per_rev + 1)
    grid[-1] = min(grid[-1], angle[-1])  # rounding at the very end of the record
    return grid, CubicSpline(angle, t)


def order_track(t: ArrayLike, x: ArrayLike, angle: ArrayLike, orders: ArrayLike, *,
                revolutions_per_block: int = 8, samples_per_revolution: int | None = None,
                window: str = "hann", interpolation: str = "cubic") -> OrderTrack:
    """Amplitude and phase of shaft orders against speed, from angle-domain resampling.

    The signal is resampled at uniform shaft angle (``t(phi)`` and ``x(t)`` by cubic
    splines, or linear ``np.interp``), cut into blocks of ``revolutions_per_block`` whole
    revolutions and each block windowed. The FFT of a block gives the order spectrum (bins
    ``1 / R`` apart); each requested order, integer or not (e.g. the varying-compliance
    order ``Z kappa``), is evaluated exactly by a single-frequency DFT at that order.

    Parameters
    ----------
    t : array (k,)
        Increasing sample times [s] (need not be uniform).
    x : array (k,)
        Signal.
    angle : array (k,)
        Shaft angle ``phi`` at the samples [rad], strictly increasing (speed > 0).
    orders : array-like (o,)
        Orders tracked (> 0).
    revolutions_per_block : int
        ``R``; the order resolution is ``1 / R`` and each block is one speed point.
    samples_per_revolution : int, optional
        Angular sampling; by default the power of two that matches the time sampling at
        the mean speed (at least 64 and 4 x the largest order). Content above half of it
        (in orders) aliases.
    window : str
        Window over each block (:func:`scipy.signal.get_window` name).
    interpolation : {"cubic", "linear"}

    Returns
    -------
    OrderTrack

    Examples
    --------
    >>> t = np.linspace(0.0, 2.0, 20001)
    >>> phi = 100.0 * t + 50.0 * t**2                       # run-up 100 -> 300 rad/s
    >>> x = 0.3 * np.cos(phi + 0.2) + 0.1 * np.cos(3.6 * phi)
    >>> track = order_track(t, x, phi, [1.0, 3.6], revolutions_per_block=5)
    >>> bool(np.allclose(track.amplitude, [0.3, 0.1], rtol=1e-4))
    True
    """
    t, x = time_window(t, x, None, None, "order_track")
    angle, orders = np.asarray(angle, dtype=float), np.atleast_1d(np.asarray(orders, float))
    if x.ndim != 1 or angle.shape != t.shape:
        raise ModelError(f"x and angle must be (k,) like t {t.shape}", "order_track")
    if t.size < MIN_SAMPLES or np.any(np.diff(t) <= 0) or np.any(np.diff(angle) <= 0):
        raise ModelError(f"need at least {MIN_SAMPLES} samples with increasing time and shaft "
                         "angle (speed > 0)", "order_track")
    if orders.ndim != 1 or np.any(orders <= 0):
        raise ModelError(f"orders must be positive, got {orders}", "order_track")
    if interpolation not in ("cubic", "linear"):
        raise TypeError(f"unknown interpolation {interpolation!r}; valid: cubic, linear")
    R = int(revolutions_per_block)
    per_rev = int(samples_per_revolution or _default_per_rev(t, angle, orders))
    if R < 1 or per_rev < 4:
        raise ModelError(f"need revolutions_per_block >= 1 and samples_per_revolution >= 4, "
                         f"got {R} and {per_rev}", "order_track")
    from scipy.interpolate import CubicSpline  # slow to import: on first use

    grid, time_of = _angle_grid(t, angle, R, per_rev)
    t_grid = time_of(grid[:-1])
    x_grid = CubicSpline(t, x)(t_grid) if interpolation == "cubic" else np.interp(t_grid, t, x)
    n = R * per_rev
    blocks = x_grid.reshape(-1, n)  # (B, n)
    blocks = blocks - blocks.mean(axis=1, keepdims=True)
    w = window_samples(window, n)
    spectrum = single_sided(blocks.T, w, "none")
    phase = np.exp(-1j * np.outer(np.arange(n) * (2.0 * math.pi / per_rev), orders))
    start = grid[:-1:n]
    X = (blocks * w) @ phase * (2.0 / w.sum()) * np.exp(-1j * np.outer(start, orders))
    centre = start + math.pi * R  # the window's centroid: where the amplitudes belong
    return OrderTrack(orders, 1.0 / time_of(centre, 1), time_of(centre), np.abs(X),
                      np.angle(X), np.arange(n // 2 + 1) / R, np.abs(spectrum).T, R,
                      int(per_rev), window)


def _default_per_rev(t: FloatArray, angle: FloatArray, orders: FloatArray) -> int:
    """Power of two matching the time sampling at the mean speed, >= 64 and >= 4 max order."""
    mean_dt = (t[-1] - t[0]) / (t.size - 1)
    matching = 2.0 * math.pi / ((angle[-1] - angle[0]) / (t[-1] - t[0]) * mean_dt)
    need = max(64.0, 4.0 * float(orders.max()), matching)
    return int(2 ** math.ceil(math.log2(need)))
