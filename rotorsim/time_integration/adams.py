"""Enhanced fourth-order Adams method of seed 002 (Appendix F, eq 3.27).

The acceleration over a step ``[t_n, t_n + h]`` is the cubic through ``a_{n+1}``, ``a_n``,
``a_{n-1}``, ``a_{n-2}``; integrating it once and twice gives (seed 002 Appendix F, with
``a_2 = [a_{n+1} - 2 a_n + a_{n-1}] / (2 h^2)``: the printed ``1/3`` before ``a_{n+1}`` is a
misprint, since ``a_2`` must vanish for a constant acceleration)

    v_{n+1} = v_n + h (3/8 a_{n+1} + 19/24 a_n - 5/24 a_{n-1} + 1/24 a_{n-2})
    q_{n+1} = q_n + h v_n + h^2 (19/180 a_{n+1} + 19/40 a_n - 1/10 a_{n-1} + 7/360 a_{n-2})

(the ``v`` formula is the three-step Adams-Moulton rule). The step equation is solved for
``a = a_{n+1}`` with the iteration matrix of Appendix F

    S = M + 3/8 h (C + s G + C_2) + 19/180 h^2 (K + K_2).

Two ways of updating the nonlinear force (option ``force_update``):

* ``"residual"`` (default): Newton on the full equation of motion
  ``M a + g(q_{n+1}, v_{n+1}, t_{n+1}) = 0`` with ``C_2 = dr/dv``, ``K_2 = dr/dq`` at the
  iterate. Fourth order on smooth nonlinear problems.
* ``"averaged"``: the incremental equation of seed 002 eq 3.27,
  ``M (a - a_n) + Delta g_lin + (C_2(n) + C_2(n+1))/2 Delta v + (K_2(n) + K_2(n+1))/2
  Delta q = 0``, the nonlinear coefficients averaged over the step start and the iterate
  (fixed-point iterations with that matrix). The averaged increment is the trapezoidal rule
  on ``dr``, exact for a force quadratic in ``q`` but with an O(h^3) error per step in
  general: fourth order on linear problems, second order on nonlinear ones.

Start-up (option ``startup``): ``"rk4"`` (default) takes the first two steps, and any step
whose size differs from the history spacing (the clipped last step of a run), with the
classical Runge-Kutta method on ``(q, v)``, which needs a nonsingular ``M``; ``"constant"``
is the seed's start (section 3.5.1: zero increments at ``t = -2h, -h, 0``, i.e. the past
accelerations equal ``a_0``), which is inconsistent unless ``a`` is constant near ``t_0``
and lowers the global order to 2.

Storage of the history in :class:`~.base.State` (numbers and arrays only, so checkpoints
resume bit for bit): ``a`` holds ``a_n``, ``history`` holds ``[a_{n-1}, a_{n-2}]``, and
``history_dt`` the history spacing: ``+h`` when the last two steps (or the constant start)
have size ``h``, ``-h`` when only the last one has, NaN before the first step.

References
----------
Seed 002 (``/work/shared/seeds/002_754cbfdfcd1d2e7e.txt``), section 3.5.1.1 eqs 3.23-3.27
and Appendix F. E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential
Equations I*, 2nd ed., Springer 1993, section III.1 (Adams methods) and II.1 (RK4).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.base import Counters, FloatArray, IntArray, State, cubic_hermite
from rotorsim.time_integration.finite_checks import check_finite, finite_vector
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem, combine, matrix_digest

V_NEW, V_HISTORY = 3.0 / 8.0, (19.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0)
Q_NEW, Q_HISTORY = 19.0 / 180.0, (19.0 / 40.0, -1.0 / 10.0, 7.0 / 360.0)
FORCE_UPDATES = ("residual", "averaged")
STARTUPS = ("rk4", "constant")


@dataclass(frozen=True)
class Adams:
    """Options of the enhanced fourth-order Adams stepper (fixed step).

    Parameters
    ----------
    force_update : {"residual", "averaged"}
        Full-residual Newton (order 4) or the averaged coefficients of seed 002 eq 3.27
        (order 4 on linear, 2 on nonlinear problems).
    startup : {"rk4", "constant"}
        First two steps by RK4, or the seed's constant past accelerations (order 2).
    newton_rtol, newton_atol : float
        Converged when ``max |dq| <= newton_atol + newton_rtol * max |q|`` [m, rad].
    max_iter : int
        Iterations per step before :class:`~rotorsim.errors.ConvergenceError`.

    Examples
    --------
    >>> Adams().name, Adams().order, Adams(force_update="averaged").order
    ('adams4', 4, 2)
    """

    force_update: str = "residual"
    startup: str = "rk4"
    newton_rtol: float = 1e-12
    newton_atol: float = 0.0
    max_iter: int = 30

    def __post_init__(self) -> None:
        for option, valid in (("force_update", FORCE_UPDATES), ("startup", STARTUPS)):
            if getattr(self, option) not in valid:
                raise TypeError(f"unknown Adams {option} {getattr(self, option)!r}; valid: "
                                f"{', '.join(valid)}")
        if not (self.newton_rtol >= 0 and self.newton_atol >= 0
                and self.newton_rtol + self.newton_atol > 0):
            raise ModelError(f"need newton_rtol, newton_atol >= 0, not both 0; got "
                             f"{self.newton_rtol}, {self.newton_atol}", "Adams")
        if not (isinstance(self.max_iter, int) and self.max_iter >= 1):
            raise ModelError(f"max_iter must be an integer >= 1, got {self.max_iter!r}",
                             "Adams")

    @property
    def name(self) -> str:
        """``adams4`` or ``adams4_averaged`` (plus ``_constant_start``)."""
        suffix = "_averaged" if self.force_update == "averaged" else ""
        return "adams4" + suffix + ("_constant_start" if self.startup == "constant" else "")

    @property
    def order(self) -> int:
        """4 with the full residual and RK4 start-up, else 2 (see the module notes)."""
        return 4 if (self.force_update, self.startup) == ("residual", "rk4") else 2

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0``; ``a0`` solves ``M a0 = -g(q0, v0, t0)`` unless given.

        Raises
        ------
        ModelError
            For wrong shapes, non-finite values or ``dt <= 0``.
        ConvergenceError
            If ``M`` is singular or the initial force is not finite.
        """
        n = problem.n
        q, v = finite_vector(q0, n, "q0"), finite_vector(v0, n, "v0")
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"dt must be positive and finite, got {dt!r}", "init")
        counters = Counters(residual_evaluations=int(not problem.is_linear))
        net = problem.forces(q, v, float(t0)).net
        check_finite(net, "initial net force", self.name, float(t0), 0, 0)
        cache = _Cache()
        if a0 is None:
            a = -cache.mass(problem, self.name).solve(net)
            counters = counters.plus(Counters(factorizations=1, solves=1))
        else:
            a = finite_vector(a0, n, "a0")
        spacing = float(dt) if self.startup == "constant" else math.nan
        return State(float(t0), q, v, a, net, dt=float(dt), counters=counters,
                     history=np.stack([a, a]), history_dt=spacing, cache=cache)

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """One step of size ``state.dt`` (Adams if the history has that spacing, else RK4).

        Raises
        ------
        ConvergenceError
            If the iterations do not converge, or a value is NaN/Inf (time, step and DOF
            in the message).
        """
        h = state.dt
        if not (math.isfinite(h) and h > 0):
            raise ModelError(f"step size must be positive and finite, got {h!r}", self.name)
        cache = state.cache if isinstance(state.cache, _Cache) else _Cache()
        if state.history_dt == h:
            return _AdamsStep(self, problem, state, cache).solve()
        return _rk4_step(self, problem, state, cache)

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """Cubic Hermite on ``q`` with slopes ``v`` (O(h^4) in ``q``, O(h^3) in ``v``)."""
        return cubic_hermite(old, new, t, dofs)


@dataclass
class _Cache:
    """Runtime LU factors: of ``M`` (RK4 steps) and of the iteration matrix by key."""

    mass_lu: Factorization | None = None
    key: tuple[float, float, int] | None = None
    lu: Factorization | None = None

    def mass(self, problem: SecondOrderProblem, where: str) -> Factorization:
        if self.mass_lu is None:
            self.mass_lu = factorize(problem.mass, where=f"{where}: mass matrix")
        return self.mass_lu


def _shifted(state: State, t1: float, q: FloatArray, v: FloatArray, a: FloatArray,
             spacing: float, tally: Counters, iterations: int, cache: _Cache,
             mass: Any) -> State:
    """Accepted state at ``t1`` with the acceleration history shifted by one; the net
    force is ``g = -M a`` (the equation of motion at the new point)."""
    counters = state.counters.plus(dataclasses.replace(tally, max_iterations=iterations))
    key = cache.key or (math.nan, math.nan, -1)
    return dataclasses.replace(state, t=t1, q=q, v=v, a=a, force=-(mass @ a),
                               history=np.stack([state.a, state.history[0]]),
                               history_dt=spacing, step=state.step + 1, counters=counters,
                               factor_dt=key[0], factor_spin=key[1], factor_tangent=key[2],
                               cache=cache)


def _rk4_step(method: Adams, problem: SecondOrderProblem, state: State,
              cache: _Cache) -> State:
    """Classical RK4 on ``q' = v, v' = -M^-1 g(q, v, t)``; also gives ``a_{n+1}``."""
    h, t0, step = state.dt, state.t, state.step + 1
    fresh = cache.mass_lu is None
    lu = cache.mass(problem, method.name)
    evaluations = 0

    def acc(q: FloatArray, v: FloatArray, t: float) -> FloatArray:
        nonlocal evaluations
        evaluations += 1
        a = -lu.solve(problem.forces(q, v, t).net)
        check_finite(a, "RK4 acceleration", method.name, t, step, 0)
        return a

    k1q, k1v = state.v, state.a
    k2q = state.v + 0.5 * h * k1v
    k2v = acc(state.q + 0.5 * h * k1q, k2q, t0 + 0.5 * h)
    k3q = state.v + 0.5 * h * k2v
    k3v = acc(state.q + 0.5 * h * k2q, k3q, t0 + 0.5 * h)
    k4q = state.v + h * k3v
    k4v = acc(state.q + h * k3q, k4q, t0 + h)
    q = state.q + (h / 6.0) * (k1q + 2.0 * k2q + 2.0 * k3q + k4q)
    v = state.v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
    a = acc(q, v, t0 + h)
    spacing = h if abs(state.history_dt) == h else -h
    tally = Counters(factorizations=int(fresh), solves=evaluations,
                     residual_evaluations=evaluations * int(not problem.is_linear))
    return _shifted(state, t0 + h, q, v, a, spacing, tally, 0, cache, problem.mass)


class _AdamsStep:
    """Iterations of one Adams step (Newton or the averaged fixed point); tallies cost."""

    def __init__(self, method: Adams, problem: SecondOrderProblem, state: State,
                 cache: _Cache) -> None:
        self.m, self.p, self.s, self.cache = method, problem, state, cache
        h = state.dt
        self.h, self.t1 = h, state.t + h
        past = (state.a, state.history[0], state.history[1])
        self.q_base = state.q + h * state.v + (h * h) * sum(
            (c * x for c, x in zip(Q_HISTORY, past, strict=True)), np.zeros(problem.n))
        self.v_base = state.v + h * sum(
            (c * x for c, x in zip(V_HISTORY, past, strict=True)), np.zeros(problem.n))
        self.qc, self.vc = Q_NEW * h * h, V_NEW * h
        self.spin, self.f1 = problem.spin(self.t1), problem.external(self.t1)
        self.tally = {"factorizations": 0, "solves": 0, "residual_evaluations": 0,
                      "iterations": 0}
        self.start: tuple[FloatArray, Any, Any] | None = None
        if method.force_update == "averaged":
            self.start = self._linear_and_tangents(state.q, state.v, state.t,
                                                   problem.spin(state.t),
                                                   problem.external(state.t))

    def solve(self) -> State:
        a, m, s = self.s.a, self.m, self.s
        for k in range(m.max_iter):
            q, v = self.q_base + self.qc * a, self.v_base + self.vc * a
            res, kt, ct = self._residual(q, v, a)
            check_finite(res, "residual", m.name, self.t1, s.step + 1, k)
            da = -self._lu(kt, ct, k).solve(res)
            self.tally["solves"] += 1
            self.tally["iterations"] += 1
            check_finite(da, "correction", m.name, self.t1, s.step + 1, k)
            a = a + da
            dq = self.qc * np.abs(da)
            tol = m.newton_atol + m.newton_rtol * max(float(np.max(np.abs(q))),
                                                      float(np.max(np.abs(s.q))))
            if self.p.is_linear or float(np.max(dq)) <= tol:
                q, v = self.q_base + self.qc * a, self.v_base + self.vc * a
                return _shifted(s, self.t1, q, v, a, self.h, Counters(**self.tally), k + 1,
                                self.cache, self.p.mass)
        worst = int(np.argmax(dq))
        raise ConvergenceError(
            f"Adams iterations did not converge at t = {self.t1:.9g} s (h = {self.h:.3g} s): "
            f"|dq| = {dq[worst]:.3e} > {tol:.3e} at DOF {worst}", m.name,
            step=s.step + 1, iteration=m.max_iter, residual=float(np.max(np.abs(res))))

    def _residual(self, q: FloatArray, v: FloatArray, a: FloatArray) -> tuple[FloatArray,
                                                                              Any, Any]:
        """Step residual and the nonlinear coefficients ``K_2, C_2`` of the iteration."""
        p = self.p
        if self.start is None:
            if not p.is_linear:
                self.tally["residual_evaluations"] += 1
            ev = p.forces(q, v, self.t1, spin=self.spin, external=self.f1)
            return p.mass @ a + ev.net, _plain(ev.stiffness_tangent), \
                _plain(ev.damping_tangent)
        g0, k0, c0 = self.start
        g1, k1, c1 = self._linear_and_tangents(q, v, self.t1, self.spin, self.f1)
        kt, ct = _mean(k0, k1), _mean(c0, c1)
        res = p.mass @ (a - self.s.a) + (g1 - g0)
        if kt is not None:
            res = res + kt @ (q - self.s.q)
        if ct is not None:
            res = res + ct @ (v - self.s.v)
        return res, kt, ct

    def _linear_and_tangents(self, q: FloatArray, v: FloatArray, t: float, spin: float,
                             external: FloatArray) -> tuple[FloatArray, Any, Any]:
        """Linear net force ``(C + s G + C_s) v + (K + K_s) q - f`` and the tangents of ``r``
        at a point."""
        p = self.p
        g = p.linear_force(q, v, spin, external)
        if p.restoring is None:
            return g, None, None
        self.tally["residual_evaluations"] += 1
        out = p.restoring(q, v, t)
        return (g, None, None) if out is None else (g, _plain(out[1]), _plain(out[2]))

    def _lu(self, kt: Any, ct: Any, iteration: int) -> Factorization:
        tangent = (matrix_digest(kt) * 1_000_003 + matrix_digest(ct)) % (2 ** 63)
        key = (self.h, self.spin, tangent)
        if self.cache.key == key and self.cache.lu is not None:
            return self.cache.lu
        p = self.p
        Ks, Cs = p.speed_matrices(self.spin)
        S = combine([(1.0, p.mass), (self.vc, p.damping), (self.vc * self.spin, p.gyroscopic),
                     (self.vc, ct), (self.qc, p.stiffness), (self.qc, kt), (self.vc, Cs),
                     (self.qc, Ks)], p.n)
        where = f"{self.m.name}: iteration matrix at t = {self.t1:.9g} s"
        for T in (kt, ct):
            data = T.data if sp.issparse(T) else (np.zeros(0) if T is None else np.asarray(T))
            if not np.all(np.isfinite(data)):
                raise ConvergenceError(f"nonlinear tangent is not finite at t = {self.t1:.9g}"
                                       " s", self.m.name, step=self.s.step + 1,
                                       iteration=iteration, residual=math.nan)
        self.cache.lu, self.cache.key = factorize(S, where=where), key
        self.tally["factorizations"] += 1
        return self.cache.lu


def _plain(T: Any) -> Any:
    """A :class:`~.local_tangent.LocalMatrix` as a dense or CSR matrix (the averaged
    coefficients of eq 3.27 add tangents of two points); others unchanged."""
    if isinstance(T, LocalMatrix):
        return T.toarray() if T.n <= DENSE_THRESHOLD else T.tocsr()
    return T


def _mean(A: Any, B: Any) -> Any:
    """``(A + B) / 2`` of two tangents, ``None`` standing for zero."""
    if A is None and B is None:
        return None
    if A is None or B is None:
        return 0.5 * (B if A is None else A)
    return 0.5 * (A + B)
