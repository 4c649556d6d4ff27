"""Orbit ellipses of harmonic lateral motion.

A node moving as ``x = Re(X e^{i w t})``, ``y = Re(Y e^{i w t})`` traces an ellipse that is the
sum of a forward circle of radius ``|X + i Y| / 2`` and a backward circle of radius
``|X - i Y| / 2`` (``x + i y = f e^{i w t} + b e^{-i w t}``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True, eq=False)
class Ellipse:
    """Orbit ellipse parameters (arrays broadcast over the inputs).

    Attributes
    ----------
    major, minor : array
        Semi-axes [m] (``minor >= 0``).
    inclination : array
        Angle of the major axis from +x [rad].
    forward_radius, backward_radius : array
        Radii of the forward and backward circular components [m].
    whirl_ratio : array
        ``(rf - rb) / (rf + rb)``: +1 circular forward, -1 circular backward, 0 straight line.
    """

    major: NDArray[np.float64]
    minor: NDArray[np.float64]
    inclination: NDArray[np.float64]
    forward_radius: NDArray[np.float64]
    backward_radius: NDArray[np.float64]
    whirl_ratio: NDArray[np.float64]

    @property
    def direction(self) -> NDArray[np.str_]:
        """``"forward"``, ``"backward"`` or ``"line"`` per point."""
        return np.where(self.whirl_ratio > 1e-9, "forward",
                        np.where(self.whirl_ratio < -1e-9, "backward", "line"))


def ellipse(X: ArrayLike, Y: ArrayLike) -> Ellipse:
    """Ellipse of the orbit with complex amplitudes ``X`` (ux) and ``Y`` (uy).

    Examples
    --------
    >>> e = ellipse(1.0, -1j)          # x = cos wt, y = sin wt: forward circle
    >>> float(e.major), float(e.minor), float(e.whirl_ratio)
    (1.0, 1.0, 1.0)
    """
    X = np.asarray(X, dtype=complex)
    Y = np.asarray(Y, dtype=complex)
    f = (X + 1j * Y) / 2.0
    b = (np.conj(X) + 1j * np.conj(Y)) / 2.0
    rf, rb = np.abs(f), np.abs(b)
    total = rf + rb
    ratio = np.divide(rf - rb, total, out=np.zeros_like(total), where=total > 0)
    return Ellipse(
        major=rf + rb,
        minor=np.abs(rf - rb),
        inclination=(np.angle(f) + np.angle(b)) / 2.0,
        forward_radius=rf,
        backward_radius=rb,
        whirl_ratio=ratio,
    )
