"""Sampling of time histories for spectral analysis: uniform-step checks, time windows
and DFT windows (shared by :mod:`rotorsim.results.spectra`,
:mod:`rotorsim.results.spectral_peaks`, :mod:`rotorsim.results.harmonic_fit` and
:mod:`rotorsim.results.order_tracking`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

MIN_SAMPLES = 8
"""Fewest samples a spectrum (or one waterfall segment) is computed from."""
UNIFORM_RTOL = 1e-6
"""Largest deviation of a time step from the mean step, relative to it, for uniform sampling."""


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

