"""Adaptive step size for the Newmark family: local error estimate, rejection, growth limits.

After each step the local displacement error is estimated as (Zienkiewicz & Xie 1991,
extended to the alpha methods, see :attr:`Newmark.error_constant`)

    e = c h^2 (a_{n+1} - a_n),   c = beta - 1/6 + (alpha_m - alpha_f) / 2,

and measured as ``err = max_i |e_i| / (atol + rtol * p_i)`` with ``p_i`` the largest
``|q_i|`` reached so far (an amplitude: the instantaneous ``|q_i|`` vanishes at each zero
crossing of a vibration, where the estimate, proportional to the jerk, peaks). A step with
``err > 1`` is rejected and retried with ``h * max(min_shrink, safety * err^(-1/3))`` (the
local error is O(h^3)); a failed Newton solve is retried with ``h / 4``. An accepted step
proposes ``h * min(max_growth, safety * err^(-1/3))``, kept at ``h`` when that ratio lies in
the band ``hold`` (each new step size costs a factorisation of a linear problem's iteration
matrix) and never grown right after a rejection. Rejections are counted in
``State.counters``.

The linear-acceleration method (``c = 0``) has no estimate of this form and is refused.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.base import Counters, FloatArray, IntArray, State
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem


@dataclass(frozen=True)
class Adaptive:
    """Error-controlled step size around a Newmark-family method.

    Parameters
    ----------
    method : Newmark
        The fixed-step method (default: average acceleration).
    rtol, atol : float
        Local error tolerance on ``q``: ``atol + rtol * (largest |q_i| so far)`` [m, rad].
    safety : float
        Factor on the optimal step size (0 < safety < 1).
    max_growth, min_shrink : float
        Bounds on the step-size ratio of one change (``max_growth > 1 > min_shrink > 0``).
    hold : (float, float)
        Proposed ratios ``hold[0] <= ratio < hold[1]`` keep the step size
        (``hold[0] <= 1 <= hold[1]``).
    dt_min, dt_max : float
        Bounds on the step size [s]; below ``dt_min`` the run stops with
        :class:`~rotorsim.errors.ConvergenceError`.
    max_rejections : int
        Consecutive rejections allowed in one step.

    Examples
    --------
    >>> Adaptive(Newmark.hht(alpha=-0.1), rtol=1e-5).name
    'adaptive hht'
    """

    method: Newmark = field(default_factory=Newmark)
    rtol: float = 1e-4
    atol: float = 1e-8
    safety: float = 0.8
    max_growth: float = 2.0
    min_shrink: float = 0.2
    hold: tuple[float, float] = (0.9, 1.3)
    dt_min: float = 0.0
    dt_max: float = math.inf
    max_rejections: int = 40

    def __post_init__(self) -> None:
        where = f"Adaptive({self.method.name})"
        if abs(self.method.error_constant) < 1e-12:
            raise ModelError("the local error estimate c h^2 (a_{n+1} - a_n) vanishes for "
                             "this method (c = beta - 1/6 + (alpha_m - alpha_f)/2 = 0); use "
                             "average acceleration, HHT or generalised-alpha", where)
        checks = [(self.rtol >= 0 and self.atol >= 0 and self.rtol + self.atol > 0,
                   "rtol, atol >= 0, not both 0"), (0 < self.safety < 1, "0 < safety < 1"),
                  (self.max_growth > 1 > self.min_shrink > 0, "max_growth > 1 > min_shrink > 0"),
                  (len(self.hold) == 2 and self.hold[0] <= 1 <= self.hold[1],
                   "hold = (low, high) with low <= 1 <= high"),
                  (0 <= self.dt_min < self.dt_max, "0 <= dt_min < dt_max"),
                  (self.max_rejections >= 1, "max_rejections >= 1")]
        for ok, text in checks:
            if not ok:
                raise ModelError(f"need {text}", where)

    @property
    def name(self) -> str:
        """``"adaptive <method>"``."""
        return f"adaptive {self.method.name}"

    @property
    def order(self) -> int:
        """Order of the underlying method."""
        return self.method.order

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0`` with first trial step ``dt`` (clipped to ``[dt_min, dt_max]``)."""
        state = self.method.init(problem, t0, q0, v0, dt=dt, a0=a0)
        return dataclasses.replace(state, dt=min(max(dt, self.dt_min), self.dt_max),
                                   peak=np.abs(state.q))

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """One accepted step, retrying smaller steps until the error test passes.

        Raises
        ------
        ConvergenceError
            When the step would fall below ``dt_min`` (or ~1e-14 of ``t``) or after
            ``max_rejections`` consecutive rejections.
        """
        dt, rejected = state.dt, False
        for _ in range(self.max_rejections + 1):
            new, failure = self.method.attempt(problem, state, dt)
            if failure is None:
                err = self.error_norm(state, new)
                if err <= 1.0:
                    return dataclasses.replace(new, dt=self._next(dt, err, rejected),
                                               error=err, peak=np.maximum(new.peak,
                                                                          np.abs(new.q)))
                factor = max(self.min_shrink, self.safety * err ** (-1.0 / 3.0))
                state = _rejected(state, new, Counters(rejected_steps=1))
            else:
                factor = 0.25
                state = _rejected(state, new, Counters(rejected_steps=1, newton_failures=1))
            dt, rejected = dt * factor, True
            if dt < max(self.dt_min, 1e-14 * abs(state.t)):
                raise ConvergenceError(
                    f"step size {dt:.3e} s fell below the minimum at t = {state.t:.9g} s",
                    self.name, step=state.step + 1)
        raise ConvergenceError(f"{self.max_rejections} consecutive rejections at "
                               f"t = {state.t:.9g} s", self.name, step=state.step + 1)

    def error_norm(self, old: State, new: State) -> float:
        """Scaled local error of the step ``old -> new`` (accepted when <= 1)."""
        e = np.abs(self.method.local_error(old, new))
        peak = old.peak if old.peak.shape == old.q.shape else np.abs(old.q)
        scale = self.atol + self.rtol * np.maximum(peak, np.abs(new.q))
        return float(np.max(e / scale))

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """The method's interpolant."""
        return self.method.interpolate(old, new, t, dofs)

    def _next(self, dt: float, err: float, rejected: bool) -> float:
        factor = self.max_growth if err == 0 else min(self.max_growth,
                                                      self.safety * err ** (-1.0 / 3.0))
        if rejected:
            factor = min(factor, 1.0)
        if self.hold[0] <= factor < self.hold[1]:
            factor = 1.0
        return min(dt * factor, self.dt_max)


def _rejected(state: State, attempt: State, charge: Counters) -> State:
    """``state`` (unchanged solution) with the cost and factorisation cache of ``attempt``."""
    return dataclasses.replace(
        state, counters=attempt.counters.plus(charge), cache=attempt.cache,
        factor_dt=attempt.factor_dt, factor_spin=attempt.factor_spin,
        factor_tangent=attempt.factor_tangent, factor_kappa=attempt.factor_kappa)
