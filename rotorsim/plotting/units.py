"""Display units for speeds and frequencies in figures."""

from __future__ import annotations

import numpy as np

SPEED_UNITS = {"rad/s": 1.0, "rpm": 30.0 / np.pi, "Hz": 1.0 / (2.0 * np.pi)}


def speed_factor(units: str) -> float:
    """Factor converting rad/s to ``units`` (``"rad/s"``, ``"rpm"`` or ``"Hz"``)."""
    try:
        return SPEED_UNITS[units]
    except KeyError:
        raise TypeError(f"unknown units {units!r}; use one of {list(SPEED_UNITS)}") from None
