"""Exponential collocation condensed onto the nonlinear DOFs, with step control.

For a rotor at constant speed whose only nonlinearity is local (rolling bearings) and whose
loads are constant plus an unbalance, the linear part is integrated exactly in the
eigenbasis of the shifted linear rotor (:mod:`~.exponential_modes`), and only the
nonlinear remainder ``rho`` on the ``k`` nonlinear DOFs is approximated: by its
interpolation polynomial through its value at the start of the step and at ``s`` stage
points (the Gauss-Lobatto nodes ``0 = c_0 < c_1 < ... < c_s = 1``). Each step's Newton
iteration works on the ``s k`` stage values of ``rho`` alone (36 unknowns for two bearings
with 6 DOFs each and ``s = 3``): the bearing displacements at the stages are affine in
them through ``k x k`` blocks precomputed per step size. Nothing of size ``n`` is
factorised after the start; a step costs ``O(n k)`` plus two products with the
eigenbasis.

Order: the interpolant of degree ``s`` has a local error ``O(h^{s+2})`` (global order
``s + 1``, 4 by default; ``tests/time_integration/test_exponential.py`` measures it). The
error estimate is the larger of two: the difference to the interpolant of degree ``s - 1``
through the stage nodes only (the error of the lower-order interpolant, so the estimate is
conservative where ``rho`` is smooth), and, for a step that passes the first, the response
to the *defect* of the step, the bearing forces evaluated on the step's dense output at the
midpoints between the nodes minus the interpolant (:mod:`~.exponential_defect`; one more
batch evaluation of the bearings): it sees a ball's contact closing or opening inside the
step, which the interpolant through the nodes alone cannot. Both are measured per unknown
against ``rtol`` times the motion (:mod:`~.motion_scale`), with the
step-size ladder of :mod:`~.radau`.

References
----------
M. Hochbruck, A. Ostermann, *Exponential integrators*, Acta Numerica 19 (2010) 209-286,
section 2.3 (exponential collocation); E. Hairer, G. Wanner, *Solving Ordinary
Differential Equations II*, IV.8 (step-size control).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.base import (
    Counters,
    FloatArray,
    IntArray,
    State,
    check_step_control,
    retry_step,
    step_size_failure,
)
from rotorsim.time_integration.exponential_modes import HarmonicLoad
from rotorsim.time_integration.exponential_step import (
    Attempt,
    StepCache,
    meta,
)
from rotorsim.time_integration.finite_checks import finite_vector
from rotorsim.time_integration.problem import SecondOrderProblem

LOCAL_FRACTION = 0.1
"""The local error per step is held to this fraction of ``rtol`` (as in :mod:`~.radau`)."""
FIRST_GROWTH = 1e4
"""Largest growth of the step size after the first step (which starts blind, a thousandth
of the span): the error estimate of that step sets the next (as CVODE's first-step
bound, 1e4)."""


@dataclass(frozen=True)
class Exponential:
    """Options of the exponential collocation stepper (module docstring).

    Parameters
    ----------
    load : HarmonicLoad
        The problem's load as ``constant + Re(amplitude e^{i W t})``; ``init`` checks it
        against the problem's load at the start.
    rtol : float
        Accuracy asked of the displacements relative to the motion.
    weights : tuple of float, optional
        Weight of every unknown in the error and the motion (1 if omitted).
    motion : float, optional
        A-priori estimate of the motion (the floor of the scale).
    stages : int
        ``s``: stage points per step (order ``s + 1``).
    max_newton : int
        Newton iterations per attempt before the step is retried smaller.
    max_growth, min_shrink : float
        Bounds of one change of the step size.
    dt_max : float
        Largest step [s].
    max_rejections : int
        Consecutive rejections allowed in one step.
    fixed : bool
        Take every step with the size given (``dt``) and no error control (to measure the
        order of the method).
    basis : array (n_full, n), optional
        For a reduced problem (``q = T x``): the basis ``T``. The local error is then
        measured on the physical displacements ``T e`` with ``basis_weights`` (one per
        physical DOF), not on the reduced coordinates (whose errors may cancel in ``T e``).
    basis_weights : tuple of float, optional
        Weights of the physical DOFs of ``basis`` (1 if omitted).

    Examples
    --------
    >>> f = HarmonicLoad(np.zeros(1), np.zeros(1, complex), 0.0)
    >>> Exponential(f, rtol=1e-5).name, Exponential(f).order
    ('exponential', 4)
    """

    load: HarmonicLoad = field(repr=False, compare=False)
    rtol: float = 1e-4
    weights: tuple[float, ...] | None = field(default=None, repr=False)
    motion: float | None = None
    stages: int = 3
    max_newton: int = 8
    max_growth: float = 4.0
    min_shrink: float = 0.2
    dt_max: float = math.inf
    max_rejections: int = 40
    fixed: bool = False
    basis: FloatArray | None = field(default=None, repr=False, compare=False)
    basis_weights: tuple[float, ...] | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        check_step_control("Exponential", self, ((
            2 <= self.stages <= 6, f"2 <= stages <= 6, got {self.stages!r}"),))

    @property
    def name(self) -> str:
        """``"exponential"``."""
        return "exponential"

    @property
    def order(self) -> int:
        """``stages + 1``."""
        return self.stages + 1

    @property
    def local_tol(self) -> float:
        return LOCAL_FRACTION * self.rtol

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0`` with first trial step ``dt`` (``a0`` is recomputed: the
        method needs the force balance at the start)."""
        n = problem.n
        q, v = finite_vector(q0, n, "q0"), finite_vector(v0, n, "v0")
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"dt must be positive and finite, got {dt!r}", "init")
        cache = StepCache.build(self, problem, q, v, float(t0), float(dt))
        rho0, r0 = cache.start_rho(q, v)
        state = State(float(t0), q, v, np.zeros(n), np.zeros(n), dt=min(float(dt),
                                                                        self.dt_max),
                      peak=np.zeros(cache.scales.weights.size), cache=cache,
                      counters=Counters(factorizations=1, residual_evaluations=1))
        history = cache.pack(np.repeat(rho0[None, :], self.stages + 1, axis=0),
                             np.stack([q, v]), float(t0), cache.modes.modal(q, v))
        force = cache.net_force(q, v, r0, float(t0))
        return dataclasses.replace(state, a=-cache.modes.minv @ force, force=force,
                                   history=history)

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """One accepted step; rejected attempts are retried with a smaller step.

        Raises
        ------
        ConvergenceError
            After ``max_rejections`` consecutive rejections.
        """
        cache = state.cache if isinstance(state.cache, StepCache) else StepCache.build(
            self, problem, state.history[-2], state.history[-1],
            float(meta(state.history, self.stages)[2]),
            float(meta(state.history, self.stages)[0]))
        h, rejected, tally = state.dt, False, Counters()
        for _ in range(self.max_rejections + 1):
            attempt = Attempt(self, cache, state, h)
            out = attempt.run()
            tally = tally.plus(attempt.tally)
            if self.fixed:
                if out is None:
                    raise ConvergenceError(f"Newton failed at t = {state.t:.9g} s with the "
                                           f"fixed step {h:.3e} s", self.name,
                                           step=state.step + 1)
                return dataclasses.replace(self._accepted(state, attempt, out, 1.0, tally),
                                           dt=h)
            if out is not None and out[-1] <= 1.0:
                factor = 0.9 * out[-1] ** (-1.0 / (self.stages + 1)) if out[-1] > 0 \
                    else self.max_growth
                cap = FIRST_GROWTH if state.step == 0 else self.max_growth
                grow = min(cap, factor) if not rejected else min(1.0, factor)
                return self._accepted(state, attempt, out, grow, tally)
            err = math.inf if out is None else out[-1]
            factor = 0.5 if out is None else 0.9 * err ** (-1.0 / (self.stages + 1))
            tally = tally.plus(Counters(rejected_steps=1, newton_failures=int(out is None)))
            h = retry_step(self, cache.ladder, h, factor, state.t, state.step + 1)
            rejected = True
        raise step_size_failure(self, h, state.t, state.step + 1)

    def _accepted(self, old: State, attempt: Attempt, out: tuple[Any, ...], factor: float,
                  tally: Counters) -> State:
        q, v, rho, force, z, motion, err = out
        cache, h = attempt.cache, attempt.h
        history = cache.pack(rho, old.history[-2:],
                             float(meta(old.history, self.stages)[2]), z, attempt.theta)
        counters = old.counters.plus(dataclasses.replace(
            tally, max_iterations=attempt.tally.max_iterations))
        return dataclasses.replace(old, t=old.t + h, q=q, v=v, a=-cache.modes.minv @ force,
                                   force=force, step=old.step + 1,
                                   dt=cache.ladder(h * factor, self.dt_max), error=err,
                                   peak=motion, history=history, history_dt=h,
                                   counters=counters, cache=cache)

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """``q`` and its slope from the step's own formula (exact linear part, the
        interpolant of ``rho``) at the times ``t``."""
        cache = new.cache if isinstance(new.cache, StepCache) else None
        if cache is None:
            raise ModelError("interpolation needs the run's cache", self.name)
        h = new.history_dt
        x = (np.asarray(t, dtype=float) - old.t) / h
        rho = new.history[:self.stages + 1, :cache.modes.dofs.size]
        z = cache.propagate(old, h, x, rho)
        Vq, Vv = cache.output_rows(dofs)
        return np.asarray((z @ Vq).real), np.asarray((z @ Vv).real)


