"""Newton iterations of one step of the Newmark family, with the iteration matrix's factors
cached across steps (the scheme and its parameters are in
:mod:`rotorsim.time_integration.newmark`).

The step solves for the new acceleration ``a`` with the exact iteration matrix
``S = (1 - alpha_m) M + (1 - alpha_f) (gamma h (C + s G + dr/dv) + beta h^2 (K + dr/dq))``.
Its LU factors are reused while ``h``, ``s`` and the tangents are unchanged (bitwise, by
digest); with :class:`~.local_tangent.LocalMatrix` tangents only the constant part is
factorised, once per ``h`` and ``s``, and each iteration adds a low-rank (Woodbury) update.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.base import Counters, FloatArray, IntArray, State
from rotorsim.time_integration.finite_checks import check_finite, first_nonfinite_row
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

if TYPE_CHECKING:
    from rotorsim.time_integration.newmark import Newmark


@dataclass(frozen=True, eq=False)
class FactorCache:
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


class StepSolver:
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
        self.cache: FactorCache | None = state.cache
        self.tally = {"factorizations": 0, "solves": 0, "residual_evaluations": 0,
                      "iterations": 0}

    def solve(self) -> State:
        a = self.s.a
        for k in range(self.m.max_iter):
            q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
            ev = self._forces(q, v)
            res = (1.0 - self.m.alpha_m) * (self.p.mass @ a) + self.history \
                + (1.0 - self.m.alpha_f) * ev.net
            check_finite(res, "residual", self.m.name, self.t1, self.s.step + 1, k)
            da = -self._lu(ev).solve(res)
            self.tally["solves"] += 1
            self.tally["iterations"] += 1
            check_finite(da, "Newton correction", self.m.name, self.t1, self.s.step + 1, k)
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
            row = first_nonfinite_row(T)
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
        self.cache = FactorCache(self.dt, self.spin, tangent, lu, base)
        return lu

    def _accepted(self, q: FloatArray, v: FloatArray, a: FloatArray, ev: ForceEvaluation,
                  iterations: int) -> State:
        check_finite(ev.net, "net force", self.m.name, self.t1, self.s.step + 1, iterations)
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
