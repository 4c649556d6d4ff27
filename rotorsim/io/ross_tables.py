"""Bearing and seal coefficients of ROSS rotor files as rotorsim tables over speed.

ROSS (3.x) interpolates a coefficient tabulated over the rotor speed with a
shape-preserving piecewise cubic (``interpolation = "pchip"``, linear with two points or
``"linear"``) and extrapolates linearly with the end slopes outside the table;
:class:`~rotorsim.elements.linear_bearing.BearingElement` interpolates linearly and holds the
end values. :func:`coefficient_tables` therefore samples ROSS's curve: at the table
points, ``refine`` points inside each interval (linear interpolation between samples then
follows the cubic to a few parts in 10^4 of the change over the interval), and, when a
speed range is given beyond the table, at its ends by ROSS's linear extrapolation. At
the table points the coefficients are ROSS's exactly.

References
----------
Fritsch, F.N., Carlson, R.E. (1980), "Monotone piecewise cubic interpolation", SIAM J.
Numer. Anal. 17(2) (the pchip interpolant, ``scipy.interpolate.PchipInterpolator``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

ROSS_COEFFICIENTS = ("kxx", "kxy", "kyx", "kyy", "kzz", "cxx", "cxy", "cyx", "cyy", "czz",
                     "mxx", "mxy", "myx", "myy")
"""ROSS bearing coefficients with a rotorsim counterpart of the same name."""
DIRECT = ("kxx", "kyy", "kzz", "cxx", "cyy", "czz", "mxx", "myy")


def coefficient_tables(data: Mapping[str, Any], where: str, *, speed_key: str = "speed",
                       refine: int = 8, speed_range: tuple[float, float] | None = None
                       ) -> tuple[dict[str, Any], FloatArray | None]:
    """The coefficients of one ROSS bearing as rotorsim ``BearingElement`` arguments.

    Parameters
    ----------
    data : mapping
        The element's table of the ROSS file.
    where : str
        Name of the element in messages.
    speed_key : str
        Key of the speed axis (``"speed"``; ``"frequency"`` in files of ROSS < 3).
    refine : int
        Samples inside each interval of a cubic table (0: the table points only).
    speed_range : (float, float), optional
        Speeds [rad/s] the table must cover: it is extended to them by ROSS's linear
        extrapolation.

    Returns
    -------
    coefficients : dict
        ``{name: float or array}`` for :class:`~rotorsim.elements.linear_bearing.BearingElement`.
    frequency : array or None
        The speeds [rad/s] of the arrays (None for constant coefficients).

    Raises
    ------
    ModelError
        Tables of different lengths from their speeds, non-increasing speeds, a direct
        coefficient below 0 where the table is extended.
    """
    values = {key: np.atleast_1d(np.asarray(data.get(key, 0.0), dtype=float))
              for key in ROSS_COEFFICIENTS}
    speeds = data.get(speed_key)
    if all(v.size == 1 for v in values.values()):
        return {key: float(v[0]) for key, v in values.items()}, None
    if speeds is None:
        raise ModelError(f"coefficient tables without the '{speed_key}' they are given at",
                         where)
    axis = np.asarray(speeds, dtype=float)
    if axis.ndim != 1 or np.any(np.diff(axis) <= 0):
        raise ModelError(f"'{speed_key}' must be increasing speeds [rad/s]", where)
    for key, v in values.items():
        if v.size not in (1, axis.size):
            raise ModelError(f"{key} has {v.size} values but '{speed_key}' has {axis.size}",
                             where)
    cubic = str(data.get("interpolation", "pchip")) == "pchip" and axis.size > 2
    grid = _grid(axis, refine if cubic else 0, speed_range)
    table = np.stack([np.broadcast_to(v, axis.shape) for v in values.values()], axis=1)
    sampled = _ross_curve(axis, table, grid, cubic)
    out: dict[str, Any] = {}
    for j, key in enumerate(values):
        column = sampled[:, j]
        if key in DIRECT and np.any(column < 0):
            bad = grid[int(np.argmax(column < 0))]
            raise ModelError(f"{key} extrapolated by ROSS's end slope is < 0 at "
                             f"{bad:.6g} rad/s: narrow the speed range", where)
        out[key] = float(column[0]) if np.all(column == column[0]) else column
    return out, grid


def _grid(axis: FloatArray, refine: int, speed_range: tuple[float, float] | None
          ) -> FloatArray:
    """The table speeds, ``refine`` points inside each interval, and the range's ends."""
    t = np.linspace(0.0, 1.0, refine + 2)[:-1]
    inner = (axis[:-1, None] + np.diff(axis)[:, None] * t[None, :]).ravel()
    points = [inner, axis[-1:]]
    if speed_range is not None:
        low, high = (float(s) for s in speed_range)
        points += [np.array([low])] if low < axis[0] else []
        points += [np.array([high])] if high > axis[-1] else []
    return np.unique(np.concatenate(points))


def _ross_curve(axis: FloatArray, table: FloatArray, x: FloatArray, cubic: bool
                ) -> FloatArray:
    """ROSS's interpolated coefficients (rows of ``table`` at ``axis``) at speeds ``x``:
    pchip or linear inside, linear with the end slopes outside."""
    from scipy.interpolate import PchipInterpolator

    if axis.size == 1:
        return np.broadcast_to(table[0], (x.size, table.shape[1])).copy()
    if cubic:
        curve = PchipInterpolator(axis, table, axis=0)
        slope = curve.derivative()
        ends = (slope(axis[0]), slope(axis[-1]))
    else:
        def curve(s: FloatArray) -> FloatArray:
            return np.stack([np.interp(s, axis, col) for col in table.T], axis=1)
        ends = ((table[1] - table[0]) / (axis[1] - axis[0]),
                (table[-1] - table[-2]) / (axis[-1] - axis[-2]))
    clipped = np.clip(x, axis[0], axis[-1])
    offset = (x - clipped)[:, None]
    slope_at = np.where((x < axis[0])[:, None], ends[0][None, :], ends[1][None, :])
    return np.asarray(curve(clipped)) + offset * slope_at
