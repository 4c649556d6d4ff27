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

whose LU factors are cached and reused while ``h``, ``s`` and the tangents are unchanged
(bitwise, by digest): a linear problem with a constant schedule is factorised once. When
the tangents are :class:`~.local_tangent.LocalMatrix` (a rotor's bearings), only the
constant part of ``S`` is factorised, once per ``h`` and ``s``, and each Newton iteration
updates it by a low-rank (Woodbury) solve on the nonlinear DOFs.

References
----------
N. M. Newmark, J. Eng. Mech. Div. ASCE 85 (1959) 67-94. H. M. Hilber, T. J. R. Hughes,
R. L. Taylor, Earthq. Eng. Struct. Dyn. 5 (1977) 283-292. J. Chung, G. M. Hulbert, J. Appl.
Mech. 60 (1993) 371-375 (eqs 6-8, 17, 25). O. C. Zienkiewicz, Y. M. Xie, Earthq. Eng.
Struct. Dyn. 20 (1991) 871-887 (local error estimate).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.base import (
    Counters,
    FloatArray,
    IntArray,
    State,
    cubic_hermite,
)
from rotorsim.time_integration.local_tangent import (
    BaseFactors,
    LocalMatrix,
    LowRankSolve,
    embed,
)
from rotorsim.time_integration.problem import (
    ForceEvaluation,
    SecondOrderProblem,
    combine,
    matrix_digest,
)


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
        q, v = (_vector(x, n, name) for x, name in ((q0, "q0"), (v0, "v0")))
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"dt must be positive and finite, got {dt!r}", "init")
        ev = problem.forces(q, v, float(t0))
        counters = Counters(residual_evaluations=int(not problem.is_linear))
        _check_finite(ev.net, "initial net force", self.name, float(t0), 0, 0)
        if a0 is None:
            lu = factorize(problem.mass, where=f"{self.name}: initial acceleration")
            a = -lu.solve(ev.net)
            counters = counters.plus(Counters(factorizations=1, solves=1))
        else:
            a = _vector(a0, n, "a0")
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
        solver = _StepSolver(self, problem, state, dt)
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


@dataclass(frozen=True, eq=False)
class _FactorCache:
    """The iteration matrix's factors, and for local tangents those of its constant part."""

    dt: float
    spin: float
    tangent: int
    lu: Factorization | LowRankSolve
    base: BaseFactors | None = None

    def base_matches(self, dt: float, spin: float, dofs: IntArray) -> bool:
        """True when the cached constant part was built for ``dt``, ``spin`` and ``dofs``."""
        return (self.base is not None and (self.dt, self.spin) == (dt, spin)
                and np.array_equal(self.base.dofs, dofs))


class _StepSolver:
    """Newton iterations of one step; tallies its own cost."""

    def __init__(self, method: Newmark, problem: SecondOrderProblem, state: State,
                 dt: float) -> None:
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"step size must be positive and finite, got {dt!r}",
                             method.name)
        self.m, self.p, self.s, self.dt = method, problem, state, dt
        self.t1 = state.t + dt
        self.bdt2, self.gdt = method.beta * dt * dt, method.gamma * dt
        self.q_base = state.q + dt * state.v + ((0.5 - method.beta) * dt * dt) * state.a
        self.v_base = state.v + ((1.0 - method.gamma) * dt) * state.a
        self.spin = problem.spin(self.t1)
        self.f1 = problem.external(self.t1)
        self.history = method.alpha_f * state.force
        if method.alpha_m != 0.0:
            self.history = self.history + method.alpha_m * (problem.mass @ state.a)
        self.cache: _FactorCache | None = state.cache
        self.tally = {"factorizations": 0, "solves": 0, "residual_evaluations": 0,
                      "iterations": 0}

    def solve(self) -> State:
        a = self.s.a
        for k in range(self.m.max_iter):
            q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
            ev = self._forces(q, v)
            res = (1.0 - self.m.alpha_m) * (self.p.mass @ a) + self.history \
                + (1.0 - self.m.alpha_f) * ev.net
            _check_finite(res, "residual", self.m.name, self.t1, self.s.step + 1, k)
            da = -self._lu(ev).solve(res)
            self.tally["solves"] += 1
            self.tally["iterations"] += 1
            _check_finite(da, "Newton correction", self.m.name, self.t1, self.s.step + 1, k)
            if self.p.is_linear:
                a = a + da
                q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
                return self._accepted(q, v, a, self._forces(q, v), k + 1)
            dq = self.bdt2 * np.abs(da)
            tol = self.m.newton_atol + self.m.newton_rtol * max(
                float(np.max(np.abs(q))), float(np.max(np.abs(self.s.q))))
            if float(np.max(dq)) <= tol:
                return self._accepted(q, v, a, ev, k + 1)
            a = a + da
        worst = int(np.argmax(dq))
        raise ConvergenceError(
            f"Newton did not converge at t = {self.t1:.9g} s (h = {self.dt:.3g} s): "
            f"|dq| = {dq[worst]:.3e} > {tol:.3e} at DOF {worst}", self.m.name,
            step=self.s.step + 1, iteration=self.m.max_iter,
            residual=float(np.max(np.abs(res))))

    def charged(self, state: State) -> State:
        """``state`` with the cost of this attempt and its factorisation cache."""
        return self._with_cache(dataclasses.replace(
            state, counters=state.counters.plus(Counters(**self.tally))))

    def _forces(self, q: FloatArray, v: FloatArray) -> ForceEvaluation:
        if not self.p.is_linear:
            self.tally["residual_evaluations"] += 1
        return self.p.forces(q, v, self.t1, spin=self.spin, external=self.f1)

    def _lu(self, ev: ForceEvaluation) -> Factorization | LowRankSolve:
        kt, ct = ev.stiffness_tangent, ev.damping_tangent
        local = any(T is not None for T in (kt, ct)) and all(
            T is None or isinstance(T, LocalMatrix) for T in (kt, ct))
        # local tangents: the k x k update is rebuilt every iteration (cheaper than hashing)
        tangent = -2 if local else (matrix_digest(kt) * 1_000_003 + matrix_digest(ct)) % (2 ** 63)
        c = self.cache
        if not local and c is not None and \
                (c.dt, c.spin, c.tangent) == (self.dt, self.spin, tangent):
            return c.lu
        m, p = self.m, self.p
        for name, T in (("dr/dq", kt), ("dr/dv", ct)):
            row = _first_nonfinite_row(T)
            if row >= 0:
                raise ConvergenceError(f"tangent {name} is not finite at t = {self.t1:.9g} s "
                                       f"(DOF {row})", m.name, step=self.s.step + 1,
                                       iteration=self.tally["iterations"], residual=math.nan)
        w = 1.0 - m.alpha_f
        constant = [(1.0 - m.alpha_m, p.mass), (w * self.gdt, p.damping),
                    (w * self.gdt * self.spin, p.gyroscopic), (w * self.bdt2, p.stiffness)]
        updates = [(w * self.gdt, ct), (w * self.bdt2, kt)]
        where = f"{m.name}: iteration matrix at t = {self.t1:.9g} s"
        base = None
        if local:
            dofs, block = embed(updates)
            base = c.base if c is not None and c.base_matches(self.dt, self.spin, dofs) \
                else None
            if base is None:
                S0 = combine(constant, p.n)
                dense = max(DENSE_THRESHOLD, p.n) if not sp.issparse(S0) else DENSE_THRESHOLD
                base = BaseFactors.build(factorize(S0, where=where, dense_threshold=dense),
                                         dofs)
                self.tally["factorizations"] += 1
            lu: Factorization | LowRankSolve = LowRankSolve.build(base, block, where)
        else:
            lu = factorize(combine(constant + updates, p.n), where=where)
            self.tally["factorizations"] += 1
        self.cache = _FactorCache(self.dt, self.spin, tangent, lu, base)
        return lu

    def _accepted(self, q: FloatArray, v: FloatArray, a: FloatArray, ev: ForceEvaluation,
                  iterations: int) -> State:
        _check_finite(ev.net, "net force", self.m.name, self.t1, self.s.step + 1, iterations)
        counters = self.s.counters.plus(Counters(**self.tally, max_iterations=iterations))
        new = dataclasses.replace(self.s, t=self.t1, q=q, v=v, a=a, force=ev.net,
                                  step=self.s.step + 1, counters=counters)
        return self._with_cache(new)

    def _with_cache(self, state: State) -> State:
        c = self.cache
        if c is None:
            return state
        return dataclasses.replace(state, cache=c, factor_dt=c.dt, factor_spin=c.spin,
                                   factor_tangent=c.tangent)


def _vector(x: ArrayLike, n: int, name: str) -> FloatArray:
    arr = np.array(x, dtype=float).reshape(-1)
    if arr.shape != (n,) or not np.all(np.isfinite(arr)):
        raise ModelError(f"must be {n} finite numbers, got shape {np.shape(x)}", name)
    return arr


def _first_nonfinite_row(T: object) -> int:
    """Row of the first NaN/Inf entry of a dense or sparse matrix (-1 if none or None)."""
    if T is None:
        return -1
    if isinstance(T, LocalMatrix):
        bad_rows = ~np.isfinite(T.block).all(axis=-1)
        return int(T.dofs[np.argmax(bad_rows)]) if bad_rows.any() else -1
    if sp.issparse(T):
        coo = sp.coo_matrix(T)
        bad = ~np.isfinite(coo.data)
        return int(coo.row[np.argmax(bad)]) if bad.any() else -1
    rows = ~np.isfinite(np.asarray(T, dtype=float)).all(axis=-1)
    return int(np.argmax(rows)) if rows.any() else -1


def _check_finite(x: FloatArray, what: str, where: str, t: float, step: int,
                  iteration: int) -> None:
    """Raise ConvergenceError naming the first non-finite DOF of ``x``."""
    bad = ~np.isfinite(x)
    if bad.any():
        dof = int(np.argmax(bad))
        raise ConvergenceError(f"{what} is not finite at t = {t:.9g} s (DOF {dof})", where,
                               step=step, iteration=iteration, residual=float("nan"))
