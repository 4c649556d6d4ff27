"""Implicit Newmark family: average and linear acceleration, HHT-alpha, generalised-alpha.

All four are one scheme (Chung & Hulbert 1993) with parameters ``gamma, beta, alpha_m,
alpha_f``. From the state ``(q_n, v_n, a_n, g_n)`` at ``t_n`` the step to
``t_{n+1} = t_n + h`` solves for ``a = a_{n+1}``

    q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a)
    v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a)
    (1 - alpha_m) M a + alpha_m M a_n + (1 - alpha_f) g_{n+1} + alpha_f g_n = 0

with the net force ``g = (C + s G) v + K q + r(q, v, t) - f(t)`` evaluated at the step
points (the force-weighted form of the alpha methods). Newton iterations on ``a`` use the
exact iteration matrix

    S = (1 - alpha_m) M + (1 - alpha_f) (gamma h (C + s G + dr/dv) + beta h^2 (K + dr/dq)),

whose LU factors are cached and reused while ``h`` and the tangents are unchanged (bitwise,
by digest) and the speed ``s`` stays near the speed at which they were built (a run-up
refactorises at a few speed nodes, not at every step): a linear problem with a constant
schedule is factorised once. When
the tangents are :class:`~.local_tangent.LocalMatrix` (a rotor's bearings), only the
constant part of ``S`` is factorised, once per ``h`` and ``s``, and each Newton iteration
updates it by a low-rank (Woodbury) solve on the nonlinear DOFs. The iterations of one step
are in :mod:`~rotorsim.time_integration.newmark_step`.

References
----------
N. M. Newmark, J. Eng. Mech. Div. ASCE 85 (1959) 67-94. H. M. Hilber, T. J. R. Hughes,
R. L. Taylor, Earthq. Eng. Struct. Dyn. 5 (1977) 283-292. J. Chung, G. M. Hulbert, J. Appl.
Mech. 60 (1993) 371-375 (eqs 6-8, 17, 25). O. C. Zienkiewicz, Y. M. Xie, Earthq. Eng.
Struct. Dyn. 20 (1991) 871-887 (local error estimate).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.base import (
    Counters,
    FloatArray,
    IntArray,
    State,
    cubic_hermite,
)
from rotorsim.time_integration.finite_checks import check_finite, finite_vector
from rotorsim.time_integration.newmark_step import StepSolver
from rotorsim.time_integration.problem import SecondOrderProblem


@dataclass(frozen=True)
class Newmark:
    """Options of the Newmark-family stepper (fixed step; see ``Adaptive`` for control).

    Parameters
    ----------
    gamma, beta : float
        Newmark parameters (defaults: average acceleration, 1/2 and 1/4).
    alpha_m, alpha_f : float
        Weights of the old inertia and of the old net force (0 for Newmark).
    newton_rtol, newton_atol : float
        A Newton iteration has converged when the next displacement correction satisfies
        ``max |dq| <= newton_atol + newton_rtol * max |q|`` [m, rad].
    max_iter : int
        Newton iterations per step before :class:`~rotorsim.errors.ConvergenceError`.
    max_contraction : float
        At a varying speed, the iteration matrix factorised at an earlier speed is reused
        while its predicted contraction per iteration stays below this (see
        :mod:`~rotorsim.time_integration.newmark_step`); 0 factorises at every new speed.
    method : str
        Name reported in results and checkpoints.

    Examples
    --------
    >>> ga = Newmark.generalized_alpha(rho_inf=0.5)
    >>> ga.order, round(ga.alpha_m, 6), round(ga.alpha_f, 6)
    (2, 0.0, 0.333333)
    """

    gamma: float = 0.5
    beta: float = 0.25
    alpha_m: float = 0.0
    alpha_f: float = 0.0
    newton_rtol: float = 1e-10
    newton_atol: float = 0.0
    max_iter: int = 20
    max_contraction: float = 1e-3
    method: str = "average_acceleration"

    def __post_init__(self) -> None:
        where = f"Newmark({self.method})"
        if not (self.gamma > 0 and self.beta > 0):
            raise ModelError(f"need gamma > 0 and beta > 0, got {self.gamma}, {self.beta}",
                             where)
        if not (self.alpha_m < 1 and 0 <= self.alpha_f < 1):
            raise ModelError(f"need alpha_m < 1 and 0 <= alpha_f < 1, got {self.alpha_m}, "
                             f"{self.alpha_f}", where)
        if not (self.newton_rtol >= 0 and self.newton_atol >= 0
                and self.newton_rtol + self.newton_atol > 0 and self.max_iter >= 1):
            raise ModelError("need newton_rtol, newton_atol >= 0 (not both 0) and "
                             "max_iter >= 1", where)
        if not 0.0 <= self.max_contraction < 0.5:
            raise ModelError(f"need 0 <= max_contraction < 0.5, got {self.max_contraction}",
                             where)

    @classmethod
    def average_acceleration(cls, **options: Any) -> Newmark:
        """Trapezoidal rule (gamma = 1/2, beta = 1/4): unconditionally stable, no
        numerical damping, energy-conserving on linear undamped systems."""
        return cls(0.5, 0.25, method="average_acceleration", **options)

    @classmethod
    def linear_acceleration(cls, **options: Any) -> Newmark:
        """gamma = 1/2, beta = 1/6: stable for ``omega h <= 2 sqrt(3)`` only."""
        return cls(0.5, 1.0 / 6.0, method="linear_acceleration", **options)

    @classmethod
    def hht(cls, alpha: float = -0.05, **options: Any) -> Newmark:
        """Hilber-Hughes-Taylor with ``alpha`` in [-1/3, 0]; spectral radius at infinite
        ``omega h``: ``(1 + alpha) / (1 - alpha)``."""
        if not -1.0 / 3.0 <= alpha <= 0.0:
            raise ModelError(f"alpha must lie in [-1/3, 0], got {alpha}", "Newmark.hht")
        return cls(0.5 - alpha, (1.0 - alpha) ** 2 / 4.0, 0.0, -alpha, method="hht",
                   **options)

    @classmethod
    def generalized_alpha(cls, rho_inf: float = 0.8, **options: Any) -> Newmark:
        """Chung-Hulbert generalised-alpha with spectral radius ``rho_inf`` in [0, 1] at
        infinite ``omega h`` (eq 25 of the 1993 paper)."""
        if not 0.0 <= rho_inf <= 1.0:
            raise ModelError(f"rho_inf must lie in [0, 1], got {rho_inf}",
                             "Newmark.generalized_alpha")
        am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
        af = rho_inf / (rho_inf + 1.0)
        return cls(0.5 - am + af, (1.0 - am + af) ** 2 / 4.0, am, af,
                   method="generalized_alpha", **options)

    @classmethod
    def from_name(cls, method: str, **options: Any) -> Newmark:
        """Stepper by name: 'average_acceleration', 'linear_acceleration', 'hht',
        'generalized_alpha'.

        Raises
        ------
        TypeError
            For an unknown name (the message lists the valid ones).
        """
        makers = {"average_acceleration": cls.average_acceleration,
                  "linear_acceleration": cls.linear_acceleration,
                  "hht": cls.hht, "generalized_alpha": cls.generalized_alpha}
        if method not in makers:
            raise TypeError(f"unknown Newmark method {method!r}; valid: {', '.join(makers)}")
        return makers[method](**options)

    @property
    def name(self) -> str:
        """Method name (``method``)."""
        return self.method

    @property
    def order(self) -> int:
        """2 when ``gamma = 1/2 - alpha_m + alpha_f`` (all named members), else 1."""
        return 2 if abs(self.gamma - (0.5 - self.alpha_m + self.alpha_f)) < 1e-12 else 1

    @property
    def error_constant(self) -> float:
        """``c`` in the local displacement error ``c h^2 (a_{n+1} - a_n)``.

        ``beta - 1/6`` for Newmark (Zienkiewicz-Xie); the alpha methods add
        ``(alpha_m - alpha_f) / 2`` because their ``a_n`` approximates the acceleration at
        ``t_n + (alpha_m - alpha_f) h`` (Arnold & Bruls 2007, Multibody Syst. Dyn. 18).
        """
        return self.beta - 1.0 / 6.0 + 0.5 * (self.alpha_m - self.alpha_f)

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0``; the acceleration solves ``M a0 = -g(q0, v0, t0)`` unless given.

        Raises
        ------
        ModelError
            For wrong shapes, non-finite values or ``dt <= 0``.
        ConvergenceError
            If ``M`` is singular (give ``a0`` then) or the initial force is not finite.
        """
        n = problem.n
        q, v = (finite_vector(x, n, name) for x, name in ((q0, "q0"), (v0, "v0")))
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"dt must be positive and finite, got {dt!r}", "init")
        ev = problem.forces(q, v, float(t0))
        counters = Counters(residual_evaluations=int(not problem.is_linear))
        check_finite(ev.net, "initial net force", self.name, float(t0), 0, 0)
        if a0 is None:
            lu = factorize(problem.mass, where=f"{self.name}: initial acceleration")
            a = -lu.solve(ev.net)
            counters = counters.plus(Counters(factorizations=1, solves=1))
        else:
            a = finite_vector(a0, n, "a0")
        return State(float(t0), q, v, np.asarray(a, dtype=float), ev.net, dt=float(dt),
                     counters=counters)

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """One step of size ``state.dt``.

        Raises
        ------
        ConvergenceError
            If Newton does not converge, or a residual or solution is NaN/Inf (the message
            gives the time and the worst DOF).
        """
        new, failure = self.attempt(problem, state, state.dt)
        if failure is not None:
            raise failure
        return new

    def attempt(self, problem: SecondOrderProblem, state: State,
                dt: float) -> tuple[State, ConvergenceError | None]:
        """Try a step of size ``dt``: ``(new state, None)`` on success, else ``(state with
        the cost of the attempt added, the error)``."""
        solver = StepSolver(self, problem, state, dt)
        try:
            new = solver.solve()
        except ConvergenceError as failure:
            return solver.charged(state), failure
        return new, None

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """Cubic Hermite on ``q`` with slopes ``v`` (see :func:`~.base.cubic_hermite`)."""
        return cubic_hermite(old, new, t, dofs)

    def local_error(self, old: State, new: State) -> FloatArray:
        """Local displacement error estimate ``c h^2 (a_new - a_old)`` (n,) [m, rad]."""
        h = new.t - old.t
        return (self.error_constant * h * h) * (new.a - old.a)
