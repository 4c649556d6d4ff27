"""Display units for speeds, frequencies and amplitudes in figures, and the axes helper
shared by the figure modules."""

from __future__ import annotations

from typing import Any

import numpy as np

SPEED_UNITS = {"rad/s": 1.0, "rpm": 30.0 / np.pi, "Hz": 1.0 / (2.0 * np.pi)}


def speed_factor(units: str) -> float:
    """Factor converting rad/s to ``units`` (``"rad/s"``, ``"rpm"`` or ``"Hz"``)."""
    try:
        return SPEED_UNITS[units]
    except KeyError:
        raise TypeError(f"unknown units {units!r}; use one of {list(SPEED_UNITS)}") from None

AMPLITUDE_UNITS = {"m": 1.0, "mm": 1e3, "um": 1e6, "nm": 1e9}


def amplitude_scale(units: str) -> float:
    """Factor converting metres to ``units`` (``"m"``, ``"mm"``, ``"um"`` or ``"nm"``)."""
    try:
        return AMPLITUDE_UNITS[units]
    except KeyError:
        raise TypeError(f"unknown amplitude units {units!r}; use one of "
                        f"{list(AMPLITUDE_UNITS)}") from None


def figure_axes(ax: Any, **kw: Any) -> tuple[Any, Any]:
    """``(figure, ax)`` of a given axes, or a new figure made by ``plt.subplots(**kw)``."""
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt

    return plt.subplots(**kw)
