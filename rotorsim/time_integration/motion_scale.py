"""The error scale of the motion: what ``rtol`` is relative to in the Radau stepper.

An engineer asks for the response "to 1e-5 of the motion", not of the static sag under
gravity. Every unknown gets a weight ``w_i`` that turns it into a length (1 for a
translation; for a rotation, the longest beam element: a rotation error ``e`` moves the
points of an element by up to ``e L``). The motion is the largest weighted displacement
from the start, ``S = max_i w_i |q_i - q_i(t0)|`` reached so far, never less than a floor
(an a-priori estimate of the motion, ``FLOOR`` of the largest weighted ``|q(t0)|`` and
``TINY``), and the local error of unknown ``i`` is measured as ``w_i |e_i| / (rtol S)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import FloatArray

FLOOR = 1e-8
"""Smallest scale relative to the largest weighted initial value: above the round-off
(1e-16 relative) of the unknowns even at ``rtol`` 1e-7."""
TINY = 1e-30
"""Absolute floor of the scale (a problem at rest)."""


@dataclass(frozen=True, eq=False)
class MotionScale:
    """Weights of the unknowns and the floor of the motion scale.

    Examples
    --------
    >>> s = MotionScale.of(np.array([1.0, 1.0, 0.5]), np.zeros(3))
    >>> s.scale(np.array([1e-6, -3e-6, 2e-5]))
    1e-05
    """

    weights: FloatArray
    floor: float

    @classmethod
    def of(cls, weights: FloatArray | None, q0: FloatArray,
           motion: float | None = None) -> MotionScale:
        """Scale of a run starting at ``q0``; ``weights`` None weighs all unknowns 1, and
        ``motion`` is an a-priori estimate of the motion (same units as ``w q``)."""
        n = q0.size
        w = np.ones(n) if weights is None else np.asarray(weights, dtype=float).reshape(-1)
        if w.shape != (n,) or not np.all(np.isfinite(w)) or np.any(w <= 0):
            raise ModelError(f"weights must be {n} positive finite numbers, got shape "
                             f"{w.shape}", "MotionScale")
        if motion is not None and not (np.isfinite(motion) and motion >= 0):
            raise ModelError(f"motion must be a finite scale >= 0, got {motion!r}",
                             "MotionScale")
        floor = max(FLOOR * float(np.max(w * np.abs(q0), initial=0.0)), TINY,
                    0.0 if motion is None else float(motion))
        return cls(w, floor)

    def scale(self, peak: FloatArray) -> float:
        """``S`` from ``peak = max |q - q0|`` per unknown (n,)."""
        # the array method: numpy's max() wrapper costs several us per call (in every step)
        return max(float((self.weights * peak).max(initial=0.0)), self.floor)
