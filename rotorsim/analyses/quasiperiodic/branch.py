"""``rs.quasi_periodic``: quasi-periodic unbalance responses over a speed range, each point
started from the previous one, with the torus's stability along the way (issue 17).

The speed is stepped from ``start`` to ``stop`` (natural-parameter continuation: the shaft
and VC frequencies both follow the speed, ``w2 = Z kappa W``). A point that does not
converge halves the step; below ``min_step`` the branch stops with the reason, keeping
what it has (a fold of the torus branch, or a torus that ceases to exist, stops it; the
Lyapunov exponent says which points are stable).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.point import (
    QuasiPeriodicPoint,
    solve_at,
    system_of,
    torus_of,
)
from rotorsim.analyses.quasiperiodic.problem import WHERE
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.quasi import TorusAFT
from rotorsim.options import Excitation

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class QuasiPeriodicBranch:
    """Tori over speed.

    Attributes
    ----------
    points : tuple of QuasiPeriodicPoint
    exponents : array (P,)
        Largest Lyapunov exponent of each torus [1/s] (NaN when not computed).
    status : str
        ``"ok"`` (reached ``stop``) or ``"stopped"``.
    reason : str
        Why the branch stopped (empty when it reached ``stop``).
    """

    points: tuple[QuasiPeriodicPoint, ...]
    exponents: FloatArray
    status: str
    reason: str

    @property
    def speeds(self) -> FloatArray:
        """[rad/s]."""
        return np.array([p.speed for p in self.points])

    @property
    def stable(self) -> NDArray[np.bool_]:
        """Negative exponent (False where it was not computed)."""
        return np.asarray(self.exponents < 0.0)

    def amplitude(self, node: int, dof: str, k1: int, k2: int) -> FloatArray:
        """Amplitude of the tone ``k1 W + k2 w2`` of ``(node, dof)`` at every speed."""
        return np.array([p.amplitude(node, dof, k1, k2) for p in self.points])

    def __len__(self) -> int:
        return len(self.points)


def quasi_periodic(model: Any, *, start: float, stop: float, step: float | None = None,
                   unbalance: Sequence[tuple[int, float, float]] = (),
                   harmonics: int | tuple[int, int] = (10, 3), truncation: str = "box",
                   samples: tuple[int, int] | None = None,
                   excitation: Excitation | None = None, nonlinear: Sequence[Any] = (),
                   stability: bool = True, periods: int = 40, tol: float = 1e-9
                   ) -> QuasiPeriodicBranch:
    """Quasi-periodic responses from ``start`` to ``stop`` [rad/s] (module docstring).

    Parameters
    ----------
    step : float, optional
        Speed step [rad/s] (default 1/50 of the range); halved where a point fails, down to
        1e-4 of the range.
    harmonics, truncation, samples, excitation, nonlinear, tol
        As :func:`~rotorsim.analyses.quasiperiodic.point.quasi_periodic_point` (default
        box ``(10, 3)``: ten harmonics of the shaft frequency, three of the VC frequency).
    stability : bool
        Compute the largest Lyapunov exponent of every torus (over ``periods``
        revolutions).

    Raises
    ------
    ModelError
        Bad range or step, or a model the point solver refuses.
    ConvergenceError
        The first point does not converge.
    """
    for name, value in (("start", start), ("stop", stop)):
        if not (np.isfinite(value) and value > 0):
            raise ModelError(f"must be a positive speed [rad/s], got {value!r}",
                             f"{WHERE}.{name}")
    if stop == start:
        raise ModelError("start and stop are equal", WHERE)
    span = abs(stop - start)
    h = span / 50 if step is None else float(step)
    if not (np.isfinite(h) and 0 < h <= span):
        raise ModelError(f"step must be in (0, {span:g}] rad/s, got {step!r}", f"{WHERE}.step")
    direction = 1.0 if stop > start else -1.0
    system = system_of(model, nonlinear)
    torus = torus_of(harmonics, truncation)
    aft = TorusAFT(torus, samples)
    ex = excitation if excitation is not None else Excitation()
    unbalance = tuple(unbalance) or tuple(ex.unbalance or ())
    points = [solve_at(system, float(start), torus, aft, ex, unbalance, tol)]
    status, reason, speed = "ok", "", float(start)
    min_step = 1e-4 * span
    while direction * (stop - speed) > 1e-12 * span:
        trial = speed + direction * min(h, abs(stop - speed))
        previous = points[-1]
        try:
            point = solve_at(system, trial, torus, aft, ex, unbalance, tol,
                             start=previous.solution.X[:, previous.rotor_problem.problem.nl_dofs])
        except ConvergenceError as exc:
            h /= 2
            if h < min_step:
                status, reason = "stopped", (f"no torus beyond {speed:.6g} rad/s: the step fell "
                                             f"below {min_step:.3g} rad/s ({exc})")
                break
            continue
        points.append(point)
        speed = trial
        h = min(2 * h, span / 50 if step is None else float(step))
    exponents = np.array([p.stability(periods=periods).exponent if stability else np.nan
                          for p in points])
    return QuasiPeriodicBranch(tuple(points), exponents, status, reason)
