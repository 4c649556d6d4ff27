"""Three-stage Radau IIA with step control, on the second-order problem (order 5).

The collocation method of order 5 (stage order 3, L-stable, stiffly accurate) integrates
``y = (q, v)``, ``y' = (v, a)``, ``M a + g(q, v, t) = 0``. Each step solves the collocation
equations ``Z = h (A x I) F(y_n + Z)`` by simplified Newton iterations in the eigenbasis of
``A^-1`` (one real and one complex linear system per iteration; Hairer & Wanner IV.8), each
condensed onto the displacements and solved with factors of the constant part and a
low-rank update for the bearing tangents (:mod:`~.radau_linear`). The three stages share
one call of the nonlinear elements when the restoring force offers ``batch`` (a rotor's
:class:`~rotorsim.analyses.transient.loads.RestoringForce` does).

Step control: the embedded error estimate of Hairer & Wanner (IV.8, eqs 8.19-8.20, with the
second evaluation after a rejection), measured per unknown against ``rtol`` times the
motion of its group (:mod:`~.motion_scale`); the new step ``h * safety * err^(-1/4)`` is
rounded down onto the ladder ``h0 * 2^(j/4)``, so that the factors of a few step sizes
are kept and reused (at constant speed a run factorises a handful of times). Dense output
is the quintic Hermite interpolant of ``q`` through ``(q, v, a)`` at both ends (O(h^6)).

References
----------
E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., Springer 1996,
sections IV.5 (Radau IIA, Table 5.6), IV.8 (implementation, error estimate, step control).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import (
    Counters,
    FloatArray,
    IntArray,
    State,
    check_step_control,
    retry_step,
    step_size_failure,
)
from rotorsim.time_integration.finite_checks import finite_vector
from rotorsim.time_integration.hermite import quintic_hermite
from rotorsim.time_integration.motion_scale import MotionScale
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau_stage import StageSystem, Tangent, pack, unpack

S6 = math.sqrt(6.0)
NODES = np.array([(4.0 - S6) / 10.0, (4.0 + S6) / 10.0, 1.0])
"""Collocation points ``c_i``."""
RK_MATRIX = np.array([
    [(88.0 - 7.0 * S6) / 360.0, (296.0 - 169.0 * S6) / 1800.0, (-2.0 + 3.0 * S6) / 225.0],
    [(296.0 + 169.0 * S6) / 1800.0, (88.0 + 7.0 * S6) / 360.0, (-2.0 - 3.0 * S6) / 225.0],
    [(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0]])
"""Radau IIA ``A`` (Hairer & Wanner Table IV.5.6)."""
ERROR_WEIGHTS = np.array([-13.0 - 7.0 * S6, -13.0 + 7.0 * S6, -1.0]) / 3.0
"""``e_i`` of the embedded estimate ``(gamma/h - J)^-1 (f(y_n) + sum e_i Z_i / h)``."""


def _eigenbasis() -> tuple[FloatArray, FloatArray, float, complex]:
    """Real ``T`` with ``A^-1 = T diag(gamma, [[alpha, beta], [-beta, alpha]]) T^-1``."""
    w, V = np.linalg.eig(np.linalg.inv(RK_MATRIX))
    real = int(np.argmin(np.abs(w.imag)))
    pair = int(np.flatnonzero(w.imag > 0)[0])
    T = np.column_stack([V[:, real].real, V[:, pair].real, V[:, pair].imag])
    return T, np.linalg.inv(T), float(w[real].real), complex(w[pair].real, -w[pair].imag)


TRANSFORM, TRANSFORM_INV, GAMMA, ALPHA_BETA = _eigenbasis()
"""``T``, ``T^-1``, the real eigenvalue and ``alpha - i beta`` of ``A^-1``."""
LADDER = 4
"""Step sizes lie on ``h0 * 2^(j / LADDER)``."""
NEWTON_KAPPA = 0.03
"""Newton stops at this fraction of the local tolerance (:attr:`Radau.newton_tol`). It was
``min(0.03, sqrt(local tolerance))`` (1e-3 at rtol 1e-5): 0.03 takes 9 to 26 % fewer
residual evaluations on the benchmark rotors at the same accuracy
(``benchmarks/bench_transient.py``)."""
LOCAL_FRACTION = 0.1
"""The local error per step is held to this fraction of ``rtol``: the global error, the
local errors carried forward, measured 0.05 to 8 times the local tolerance on the benchmark
rotors (``benchmarks/bench_transient.py``, a few hundred to a thousand steps) and on a
damped oscillator, so ``rtol`` is met as a bound on the motion's error over such runs."""


@dataclass(frozen=True)
class Radau:
    """Options of the error-controlled Radau IIA stepper (order 5).

    Parameters
    ----------
    rtol : float
        Accuracy asked of the displacements relative to the motion (the largest weighted
        ``|q - q0|`` so far; :mod:`~.motion_scale`); each step's local error is held to
        ``LOCAL_FRACTION * rtol``.
    weights : tuple of float, optional
        Weight of every unknown in the error and the motion (e.g. 1 for translations, an
        element length for rotations [m/rad]); 1 if omitted.
    motion : float, optional
        Smallest motion scale (units of the weighted unknowns): an a-priori estimate of
        the motion, so that the first steps are not measured against the vanishing motion
        of the start.
    max_newton : int
        Simplified-Newton iterations per attempt before the step is retried smaller.
    max_growth, min_shrink : float
        Bounds of one change of the step size.
    dt_max : float
        Largest step [s].
    max_rejections : int
        Consecutive rejections allowed in one step.

    Examples
    --------
    >>> Radau(rtol=1e-5).name, Radau().order
    ('radau5', 5)
    """

    rtol: float = 1e-4
    weights: tuple[float, ...] | None = field(default=None, repr=False)
    motion: float | None = None
    max_newton: int = 7
    max_growth: float = 8.0
    min_shrink: float = 0.2
    dt_max: float = math.inf
    max_rejections: int = 40

    def __post_init__(self) -> None:
        check_step_control("Radau", self)

    @property
    def name(self) -> str:
        """``"radau5"``."""
        return "radau5"

    @property
    def order(self) -> int:
        """5 (3 at the stages)."""
        return 5

    @property
    def local_tol(self) -> float:
        """Tolerance of the local error per step: ``LOCAL_FRACTION * rtol``."""
        return LOCAL_FRACTION * self.rtol

    @property
    def newton_tol(self) -> float:
        """Convergence threshold ``kappa`` of the scaled Newton corrections: iterate until
        the predicted remaining error is below ``kappa`` times the local tolerance
        (Hairer & Wanner IV.8, eq 8.10 and the choice ``kappa`` in [0.01, 0.1] that
        follows; RADAU5's ``fnewt`` caps it at 0.03), above the round-off of the unknowns.
        ``NEWTON_KAPPA`` regardless of ``rtol``: the remaining Newton error stays a few per
        cent of the error the step is allowed."""
        return max(10.0 * np.finfo(float).eps / self.local_tol, NEWTON_KAPPA)

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0`` with first trial step ``dt``; ``a0`` solves ``M a0 = -g``."""
        n = problem.n
        q, v = finite_vector(q0, n, "q0"), finite_vector(v0, n, "v0")
        if not (math.isfinite(dt) and dt > 0):
            raise ModelError(f"dt must be positive and finite, got {dt!r}", "init")
        system = StageSystem(problem, self.name)
        net, tangent = system.point(q, v, float(t0))
        a = -system.mass_solve(net) if a0 is None else finite_vector(a0, n, "a0")
        cache = _Cache(system, MotionScale.of(self._weights(n), q, self.motion), float(dt))
        history = np.concatenate([np.zeros((6, n)), q[None, :],
                                  pack(1.0, float(dt), tangent, n)])
        return State(float(t0), q, v, a, net, dt=min(float(dt), self.dt_max),
                     peak=np.zeros(n), history=history, cache=cache,
                     counters=Counters(factorizations=1, solves=1,
                                       residual_evaluations=int(not problem.is_linear)))

    def _weights(self, n: int) -> FloatArray | None:
        if self.weights is None:
            return None
        if len(self.weights) != n:
            raise ModelError(f"weights has {len(self.weights)} entries for {n} unknowns",
                             "Radau.weights")
        return np.asarray(self.weights, dtype=float)

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """One accepted step; rejected attempts are retried with a smaller step.

        Raises
        ------
        ConvergenceError
            After ``max_rejections`` consecutive rejections or when the step falls below
            1e-14 of ``t``.
        """
        cache = state.cache if isinstance(state.cache, _Cache) else self._rebuild(problem,
                                                                                 state)
        h, rejected, tally = state.dt, False, Counters()
        for _ in range(self.max_rejections + 1):
            attempt = _Attempt(self, cache, state, h)
            new, err, factor = attempt.run(rejected)
            tally = tally.plus(attempt.tally)
            if new is not None and err <= 1.0:
                grow = min(self.max_growth, factor) if not rejected else min(1.0, factor)
                return self._accepted(state, new, attempt, err, grow, tally)
            tally = tally.plus(Counters(rejected_steps=1,
                                        newton_failures=int(new is None)))
            h = retry_step(self, cache.ladder, h, factor, state.t, state.step + 1)
            rejected = True
        raise step_size_failure(self, h, state.t, state.step + 1)

    def _accepted(self, old: State, new: _Solution, attempt: _Attempt,
                  err: float, factor: float, tally: Counters) -> State:
        q, v, a, net, Zq, Zv = new.q, new.v, new.a, new.net, new.Zq, new.Zv
        contraction, tangent = new.contraction, new.tangent
        cache = attempt.cache
        history = np.concatenate([Zq, Zv, old.history[6:7], pack(contraction, cache.h0,
                                                                 tangent, q.size)])
        motion = np.maximum(old.peak, np.abs(q - history[6]))
        h = attempt.h
        counters = old.counters.plus(dataclasses.replace(
            tally, max_iterations=attempt.tally.max_iterations))
        return dataclasses.replace(old, t=old.t + h, q=q, v=v, a=a, force=net,
                                   step=old.step + 1, dt=cache.ladder(h * factor,
                                                                      self.dt_max),
                                   error=err, peak=motion, history=history,
                                   history_dt=h, counters=counters, cache=cache)

    def _rebuild(self, problem: SecondOrderProblem, state: State) -> _Cache:
        """Runtime cache after a resume: the scale from the start state, the ladder base
        from the history (the factors are rebuilt on demand)."""
        system = StageSystem(problem, self.name)
        h0 = unpack(state.history[7:])[1]
        scales = MotionScale.of(self._weights(problem.n), state.history[6], self.motion)
        return _Cache(system, scales, h0)

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """Quintic Hermite of ``q`` through ``(q, v, a)`` at both ends, and its slope."""
        return quintic_hermite(old, new, t, dofs)


@dataclass(frozen=True, eq=False)
class _Solution:
    """The end of a converged step: state, net force, stage increments (3, n), Newton
    contraction and the tangents at the last stage."""

    q: FloatArray
    v: FloatArray
    a: FloatArray
    net: FloatArray
    Zq: FloatArray
    Zv: FloatArray
    contraction: float
    tangent: Tangent


@dataclass(eq=False)
class _Cache:
    """Runtime state of a run: the stage system with its factors, the motion scale and the
    base of the step-size ladder."""

    system: StageSystem
    scales: MotionScale
    h0: float

    def ladder(self, h: float, h_max: float) -> float:
        """The largest ``h0 * 2^(j / LADDER) <= min(h, h_max)``."""
        h = min(h, h_max)
        j = math.floor(LADDER * math.log2(h / self.h0) + 1e-9)
        return self.h0 * 2.0 ** (j / LADDER)


class _Attempt:
    """One try of a step of size ``h``: Newton on the stages, error estimate."""

    def __init__(self, method: Radau, cache: _Cache, state: State, h: float) -> None:
        if not (math.isfinite(h) and h > 0):
            raise ModelError(f"step size must be positive and finite, got {h!r}",
                             method.name)
        self.m, self.cache, self.s, self.h = method, cache, state, h
        self.count = {"factorizations": 0, "solves": 0, "residual_evaluations": 0,
                      "iterations": 0}

    def _charge(self, **counts: int) -> None:
        for key, value in counts.items():
            self.count[key] += value

    @property
    def tally(self) -> Counters:
        """The cost of this attempt."""
        return Counters(**self.count, max_iterations=self.count["iterations"])

    def run(self, rejected: bool) -> tuple[_Solution | None, float, float]:
        """The new point (None when Newton failed), the scaled error and the proposed
        step-size factor.

        Convergence test of Hairer & Wanner (IV.8, eq 8.10): with the contraction ``theta``
        of the last two corrections, stop when ``theta / (1 - theta) |dZ| < newton_tol``;
        the first correction uses the contraction of the previous step.
        """
        m, s, h, system = self.m, self.s, self.h, self.cache.system
        times = s.t + NODES * h
        # the tangents of the state itself (the cache is shared by the states of a run)
        solves = system.solvers(h, GAMMA, ALPHA_BETA, s.t, unpack(s.history[7:])[2])
        scale_q = m.local_tol * self.cache.scales.scale(s.peak) / self.cache.scales.weights
        Z = self._guess()
        loads = system.loads(times)
        W = TRANSFORM_INV @ Z
        n = s.q.size
        old_norm, contraction = math.inf, max(float(s.history[7, 0]), 1e-16) ** 0.8
        for k in range(m.max_newton):
            g, tangent = system.stage_forces(s.q + Z[:, :n], s.v + Z[:, n:], times, loads)
            self._charge(residual_evaluations=1, iterations=1, solves=2)
            if not np.all(np.isfinite(g)):
                return None, math.inf, 0.5
            dW = solves.correction(W, s.v + Z[:, n:], g, h)
            W = W + dW
            dZ = TRANSFORM @ dW
            Z = Z + dZ
            norm = float(np.max(np.abs(dZ[:, :n]) / scale_q))
            if k > 0:
                rate = norm / old_norm
                if rate >= 1.0 or rate ** (m.max_newton - k) / (1 - rate) * norm \
                        > m.newton_tol:
                    return None, math.inf, 0.5
                contraction = rate / (1.0 - rate)
            if contraction * norm < m.newton_tol:
                end = system.end_force(g[2], tangent, dZ[2, :n], dZ[2, n:],
                                       float(loads[1][2]))
                return self._finish(Z[:, :n], Z[:, n:], end, tangent, solves, rejected,
                                    k + 1, contraction)
            old_norm = norm
        return None, math.inf, 0.5

    def _guess(self) -> FloatArray:
        """Stage increments (3, 2n) extrapolated from the last step's collocation
        polynomial (zero before the first step)."""
        s = self.s
        hp = s.history_dt
        if not (math.isfinite(hp) and hp > 0):
            return np.zeros((3, 2 * s.q.size))
        # polynomial through (0, 0), (c_i, Z_i) of the last step, minus its value at 1
        last = np.concatenate([s.history[0:3], s.history[3:6]], axis=1)
        return _collocation_values(last, 1.0 + NODES * self.h / hp) - last[2][None, :]

    def _finish(self, Zq: FloatArray, Zv: FloatArray, net: FloatArray, tangent: Tangent,
                solves: Any, rejected: bool, iterations: int, contraction: float
                ) -> tuple[_Solution, float, float]:
        s, h, system, m = self.s, self.h, self.cache.system, self.m
        q, v = s.q + Zq[2], s.v + Zv[2]
        a = -system.mass_solve(net)
        eq, ev = solves.error(s, Zq, Zv, h, ERROR_WEIGHTS)
        sc = self.cache.scales
        tol = m.local_tol * sc.scale(np.maximum(s.peak, np.abs(q - s.history[6])))
        err = _norm(eq, sc.weights, tol)
        self._charge(solves=2)
        if err > 1.0 and (rejected or s.step == 0):
            eq, ev = solves.error(s, Zq, Zv, h, ERROR_WEIGHTS, again=(eq, ev))
            err = _norm(eq, sc.weights, tol)
            self._charge(residual_evaluations=1, solves=1)
        safety = 0.9 * (2 * m.max_newton + 1) / (2 * m.max_newton + iterations)
        factor = safety * err ** -0.25 if err > 0 else m.max_growth
        self._charge(factorizations=solves.fresh)
        return _Solution(q, v, a, net, Zq, Zv, contraction, tangent), err, factor


def _collocation_values(Z: FloatArray, x: FloatArray) -> FloatArray:
    """Values at ``x`` (3,) of the cubic through ``(0, 0)`` and ``(c_i, Z_i)`` (Lagrange
    form; the node at 0 carries zero). Every ``x`` lies beyond the nodes (``x > 1``)."""
    diff = x[:, None] - _ALL_NODES[None, :]  # (3, 4), no zero entry
    weights = np.prod(diff, axis=1)[:, None] / diff[:, 1:] / _DENOMINATORS[None, :]
    return weights @ Z


_ALL_NODES = np.concatenate([[0.0], NODES])
_DENOMINATORS = np.array([np.prod(NODES[j] - np.delete(_ALL_NODES, j + 1)) for j in range(3)])


def _norm(eq: FloatArray, weights: FloatArray, tol: float) -> float:
    """Largest weighted displacement error over ``tol``."""
    return float(np.max(weights * np.abs(eq))) / tol
