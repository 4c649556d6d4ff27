"""What the motion is where a torus is unstable: :class:`MotionBeyond`, found by
:func:`~rotorsim.analyses.quasiperiodic.beyond.motion_beyond` (issue 17 part 2)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
KINDS = ("stays on the torus", "another torus", "doubled torus", "subharmonic torus",
         "chaotic", "third frequency")
"""What the motion can be: it stays on the unstable torus (a contradiction of the
exponents, to be investigated), jumps to another torus of the same two frequencies, doubles
the torus (tones of order 1/2), locks to a subharmonic of order 3 or more, is chaotic
(positive Lyapunov exponent), or carries a third, unlocked frequency."""


@dataclass(frozen=True, eq=False)
class MotionBeyond:
    """The motion of a rotor at the speed of an unstable torus.

    Attributes
    ----------
    speed : float
        [rad/s].
    kind : str
        One of :data:`KINDS`.
    order : int
        The subharmonic order ``q`` whose tones explain the record (0: none does).
    unexplained : array (ORDERS,)
        Largest share of a nonlinear DOF's variance left by the tones of order ``q = 1,
        2, ...`` (NaN: not tried, too many tones for the record).
    frequency : float
        [rad/s]: the strongest line left after the ``q = 1`` tones, or NaN when the order
        is 1.
    lyapunov : float
        Largest Lyapunov exponent of the recorded motion [1/s]: the growth rate of its
        distance to a twin started 1e-9 of the motion away.
    resolution : float
        [1/s]: ``ln(1e4) / T`` of the record; a chaotic motion also needs its twin to part
        by 1e4 within it.
    departure : float
        Largest distance of the record from the torus, over the torus's peak-to-peak
        (nonlinear DOFs).
    revolutions : (int, int)
        Revolutions run before the record, and recorded.
    """

    speed: float
    kind: str
    order: int
    unexplained: FloatArray
    frequency: float
    lyapunov: float
    resolution: float
    departure: float
    revolutions: tuple[int, int]

    def summary(self) -> str:
        """One line: the kind with its evidence."""
        left = ", ".join("-" if not np.isfinite(u) else f"{u:.1e}" for u in self.unexplained)
        extra = f", new line at {self.frequency:.6g} rad/s" if np.isfinite(self.frequency) \
            else ""
        return (f"{self.kind} (order {self.order}; unexplained by q = 1..{self.unexplained.size}"
                f": {left}; Lyapunov from a twin {self.lyapunov:.4g} 1/s against "
                f"{self.resolution:.3g}; {self.departure:.3g} of the torus away{extra})")
