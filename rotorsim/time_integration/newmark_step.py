"""Newton iterations of one step of the Newmark family, with the iteration matrix's factors
cached across steps (the scheme and its parameters are in
:mod:`rotorsim.time_integration.newmark`).

The step solves for the new acceleration ``a`` with the exact iteration matrix
``S = (1 - alpha_m) M + (1 - alpha_f) (gamma h (C + s G + dr/dv) + beta h^2 (K + dr/dq))``.
Its LU factors are reused while ``h`` and the tangents are unchanged (bitwise, by digest);
with :class:`~.local_tangent.LocalMatrix` tangents only the constant part is factorised,
once per ``h`` and speed node, and each iteration adds a low-rank (Woodbury) update.

**Varying speed (run-ups).** ``S`` depends on the spin speed ``s``. Its factors are kept
at a *speed node* ``s_0`` while the iteration with the frozen matrix contracts fast: the
error obeys ``e_{k+1} = -S_0^-1 dS e_k``, ``dS = (1 - alpha_f) gamma h (s - s_0) G`` plus
the change of bearings tabulated over speed when they are folded into the node
(:mod:`~rotorsim.time_integration.folded_tables`; else they join the low-rank update at
each step's exact speed). It contracts by ``theta = kappa |s - s_0|``, ``kappa`` from a few
power iterations (:func:`~.speed_nodes.gyroscopic_sensitivity`) plus the tables' rate; a new
node (:func:`~.speed_nodes.new_node`) is factorised when ``theta`` would exceed
``Newmark.max_contraction``. The residual uses the exact ``s``, so the converged step is the
exact step. A linear step off its node takes at least two corrections and stops once the
predicted remaining correction ``theta / (1 - theta) h^2 beta |da|`` is within the Newton
tolerance (a simplified-Newton test, Hairer & Wanner, Solving ODEs II, section IV.8).
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.banded_lu import BandedLU
from rotorsim.time_integration.base import Counters, FloatArray, IntArray, State
from rotorsim.time_integration.finite_checks import check_finite, first_nonfinite_row
from rotorsim.time_integration.folded_tables import FoldedTables, piecewise_linear
from rotorsim.time_integration.local_tangent import (
    BaseFactors,
    LocalMatrix,
    LowRankSolve,
    embed,
)
from rotorsim.time_integration.merged_matrices import MergedMatrices
from rotorsim.time_integration.problem import (
    ForceEvaluation,
    Matrix,
    SecondOrderProblem,
    combine,
    matrix_digest,
)
from rotorsim.time_integration.speed_nodes import (
    FOLDED,
    POWER_ITERATIONS,
    FactorCache,
    gyroscopic_sensitivity,
    new_node,
    node_rate,
)

if TYPE_CHECKING:
    from rotorsim.time_integration.newmark import Newmark


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
        self.tables = piecewise_linear(problem.speed_terms) if problem.is_linear else None
        """Speed terms that may be folded into the iteration matrix at its node (tables)."""
        self.fold = True
        """Whether the node in use has the tables folded in (else exact at each step)."""
        self.theta = 0.0
        """Predicted contraction of the frozen iteration matrix (0 at its own speed)."""
        self.node = self.spin
        """Speed node of the iteration matrix in use [rad/s]."""

        self.old_scale: float | None = None
        """``max |q_n|`` [m, rad], computed on first use by :meth:`_tolerance`."""
        self.tally = {"factorizations": 0, "solves": 0, "residual_evaluations": 0,
                      "iterations": 0}

    def solve(self) -> State:
        a = self.s.a
        q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
        ev = self._forces(q, v)
        res = self._residual(a, ev)
        if self.p.is_linear:
            return self._solve_affine(a, res, ev)
        for k in range(self.m.max_iter):
            check_finite(res, "residual", self.m.name, self.t1, self.s.step + 1, k)
            da = -self._lu(ev).solve(res)
            self.tally["solves"] += 1
            self.tally["iterations"] += 1
            check_finite(da, "Newton correction", self.m.name, self.t1, self.s.step + 1, k)
            dq = self.bdt2 * np.abs(da)
            if float(np.max(dq)) <= self._tolerance(q):
                return self._accepted(q, v, a, ev, k + 1)
            a = a + da
            q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
            ev = self._forces(q, v)
            res = self._residual(a, ev)
        raise self._not_converged(dq, q, res)

    def _solve_affine(self, a: FloatArray, res: FloatArray, ev: ForceEvaluation) -> State:
        """Iterations on an affine step equation with one matrix: the first solve is exact
        at the matrix's own speed; with a matrix frozen at a speed node each further
        correction is about ``theta`` times the last and depends only on it
        (:meth:`_frozen_correction`). The step is accepted once the predicted remaining
        correction ``theta / (1 - theta) h^2 beta |da|`` is within the Newton tolerance,
        compared first with its floor at ``max |q_n|`` (which spares a reduction over
        ``q``). It takes at least two corrections: the first alone lags the change of the
        matrix since the node by a step, which destabilises undamped modes (see
        docs/benchmarks.md), and a non-finite first correction makes the second one
        non-finite, which the test then finds."""
        check_finite(res, "residual", self.m.name, self.t1, self.s.step + 1, 0)
        lu = self._lu(ev)
        da = -lu.solve(res)
        self.tally["solves"] += 1
        for k in range(self.m.max_iter):
            self.tally["iterations"] += 1
            a = a + da
            if k or self.theta == 0.0:
                size = float(np.abs(da).max())
                if not math.isfinite(size):
                    check_finite(da, "Newton correction", self.m.name, self.t1,
                                 self.s.step + 1, k)
                if self.theta == 0.0:
                    return self._accepted_affine(a, k + 1)
                remaining = self.theta / (1.0 - self.theta) * self.bdt2 * size
                if remaining <= self._floor_hint() or remaining <= self._tolerance(None) \
                        or remaining <= self._tolerance(self.q_base + self.bdt2 * a):
                    return self._accepted_affine(a, k + 1)
            if k + 1 < self.m.max_iter:
                da = self._frozen_correction(lu, da)
        raise self._not_converged(self.bdt2 * np.abs(da), self.q_base + self.bdt2 * a,
                                  self._frozen_part(da))

    def _accepted_affine(self, a: FloatArray, iterations: int) -> State:
        q, v = self.q_base + self.bdt2 * a, self.v_base + self.gdt * a
        return self._accepted(q, v, a, self._forces(q, v), iterations)

    def _frozen_correction(self, lu: Factorization | BandedLU | LowRankSolve,
                           da: FloatArray) -> FloatArray:
        """The next correction of a linear step after ``da``, ``-S_0^-1 dS da``: with the
        node's frozen map ``S_0^-1 dS / (s - s_node)`` (:meth:`FactorCache.frozen_map
        <rotorsim.time_integration.speed_nodes.FactorCache.frozen_map>`) one product,
        else a solve with the residual :meth:`_frozen_part`."""
        c = self.cache
        R = None if c is None else c.frozen_map(self.p, 1.0 - self.m.alpha_f, self.gdt,
                                                 self.spin)
        if R is None:
            self.tally["solves"] += 1
            return -np.asarray(lu.solve(self._frozen_part(da)))
        return (self.node - self.spin) * (R[1] @ da[R[0]])

    def _not_converged(self, dq: FloatArray, q: FloatArray,
                       res: FloatArray) -> ConvergenceError:
        worst, tol = int(np.argmax(dq)), self._tolerance(q)
        return ConvergenceError(
            f"Newton did not converge at t = {self.t1:.9g} s (h = {self.dt:.3g} s): "
            f"|dq| = {dq[worst]:.3e} > {tol:.3e} at DOF {worst}", self.m.name,
            step=self.s.step + 1, iteration=self.m.max_iter,
            residual=float(np.max(np.abs(res))))

    def _frozen_part(self, da: FloatArray) -> FloatArray:
        """The residual of a linear step equation after the correction ``da``: the part of
        the matrix left out at the speed node times it, ``(1 - alpha_f) gamma h (s - s_node)
        G da`` [N]."""
        G = self.p.gyroscopic_compact
        out = np.zeros(self.p.n) if G is None else \
            ((1.0 - self.m.alpha_f) * self.gdt * (self.spin - self.node)) * (G @ da)
        tables = None if self.cache is None else self.cache.tables
        if tables is not None:  # plus P D P^T da, D the tables' change since the node
            out[tables.terms.dofs] += tables.frozen(self.spin, da)
        return out

    def _residual(self, a: FloatArray, ev: ForceEvaluation) -> FloatArray:
        """Step equation ``(1 - alpha_m) M a + alpha_m M a_n + alpha_f g_n + (1 - alpha_f)
        g(a)`` [N]."""
        return (1.0 - self.m.alpha_m) * (self.p.mass @ a) + self.history \
            + (1.0 - self.m.alpha_f) * ev.net

    def _tolerance(self, q: FloatArray | None) -> float:
        """Newton tolerance on the displacement correction [m, rad]; with ``q = None``, its
        floor at the old displacements alone."""
        if self.old_scale is None:
            peak = int(np.argmax(np.abs(self.s.q)))
            self.old_scale = abs(float(self.s.q[peak]))
            if self.cache is not None:
                self.cache.peak = peak
        scale = self.old_scale if q is None else max(float(np.abs(q).max()), self.old_scale)
        return self.m.newton_atol + self.m.newton_rtol * scale

    def _floor_hint(self) -> float:
        """The tolerance at ``|q_n|`` of the DOF where it last peaked: at most the floor of
        :meth:`_tolerance` (so a test passed against it passes against the floor) and
        cheaper than a reduction over ``q_n``."""
        peak = 0 if self.cache is None else self.cache.peak
        return self.m.newton_atol + self.m.newton_rtol * abs(float(self.s.q[peak]))

    def charged(self, state: State) -> State:
        """``state`` with the cost of this attempt and its factorisation cache."""
        return self._with_cache(dataclasses.replace(
            state, counters=state.counters.plus(Counters(**self.tally))))

    def _forces(self, q: FloatArray, v: FloatArray) -> ForceEvaluation:
        if not self.p.is_linear:
            self.tally["residual_evaluations"] += 1
        return self.p.forces(q, v, self.t1, spin=self.spin, external=self.f1)

    def _lu(self, ev: ForceEvaluation) -> Factorization | BandedLU | LowRankSolve:
        c = self.cache
        if c is None and self._resumed_off_node():
            # after a resume: rebuild the factors at the stored node, as the run did
            self.fold = self.s.factor_tangent == FOLDED
            tangent, updates, dofs, _ = self._parts(ev)
            c = self._build(self.s.factor_spin, tangent, updates, dofs, None, None)
            c.kappa = self.s.factor_kappa
        node = self._node(c)
        tangent, updates, dofs, block = self._parts(ev)
        if c is not None and (c.dt, c.spin) == (self.dt, node) and \
                (c.base_matches(self.dt, node, dofs) if dofs is not None
                 else c.tangent == tangent):
            self.node = node
            if dofs is None:
                self.cache = c
                return c.lu
            assert c.base is not None and block is not None
            lu = LowRankSolve.build(c.base, block, self._where())
            self.cache = dataclasses.replace(c, tangent=tangent, lu=lu)
            return lu
        self.node = node
        new = self._build(node, tangent, updates, dofs, block, c)
        if c is not None and c.dt == self.dt:
            new.kappa = c.kappa  # rho(S_0^-1 G) barely moves between nearby speed nodes
            if new.tables is not None and self.theta:  # with the new node's rates
                self.theta = node_rate(new, node, self.spin) * abs(self.spin - node)
        self.cache = new
        return new.lu

    def _parts(self, ev: ForceEvaluation) -> tuple[int, list[tuple[float, Matrix | None]],
                                                   IntArray | None, FloatArray | None]:
        """The tangents' key, the terms added to the constant part, and for local ones
        their DOFs and block (None otherwise); speed terms folded at the node (``fold``)
        or exact at this step's speed."""
        kt, ct = ev.stiffness_tangent, ev.damping_tangent
        fold = self.tables is not None and self.fold
        Ks, Cs = (None, None) if fold else self.p.speed_matrices(self.spin)
        parts = (kt, ct, Ks, Cs)
        local = any(T is not None for T in parts) and all(
            T is None or isinstance(T, LocalMatrix) for T in parts)
        # local tangents: the k x k update is rebuilt every iteration (cheaper than hashing)
        tangent = FOLDED if fold else -2 if local else (
            matrix_digest(kt) * 1_000_003 + matrix_digest(ct) + 7 * matrix_digest(Ks)
            + 11 * matrix_digest(Cs)) % (2 ** 63)
        for name, T in (("dr/dq", kt), ("dr/dv", ct)):
            row = first_nonfinite_row(T)
            if row >= 0:
                raise ConvergenceError(f"tangent {name} is not finite at t = {self.t1:.9g} s "
                                       f"(DOF {row})", self.m.name, step=self.s.step + 1,
                                       iteration=self.tally["iterations"], residual=math.nan)
        w = 1.0 - self.m.alpha_f
        updates = [(w * self.gdt, ct), (w * self.bdt2, kt), (w * self.gdt, Cs),
                   (w * self.bdt2, Ks)]
        dofs, block = embed(updates) if local else (None, None)
        return tangent, updates, dofs, block

    def _where(self) -> str:
        return f"{self.m.name}: iteration matrix at t = {self.t1:.9g} s"

    def _build(self, node: float, tangent: int, updates: list[tuple[float, Matrix | None]],
               dofs: IntArray | None, block: FloatArray | None,
               previous: FactorCache | None) -> FactorCache:
        """Factorise the iteration matrix at the speed node ``node`` (for local tangents:
        its constant part, updated by ``block`` on ``dofs`` when given); ``previous`` lends
        its merged matrices when built for the same problem."""
        self.tally["factorizations"] += 1
        p, where = self.p, self._where()
        merged = previous.merged if previous is not None and previous.problem is p \
            else MergedMatrices.build([p.mass, p.damping, p.gyroscopic, p.stiffness], p.n,
                                      None if self.tables is None else
                                      (self.tables.dofs, self.tables.pattern))
        constant = self._constant(node)
        lu: Factorization | BandedLU
        if dofs is None:
            w = 1.0 - self.m.alpha_f
            tables = None if self.tables is None or tangent != FOLDED else \
                FoldedTables.at_node(self.tables, node, w * self.bdt2, w * self.gdt,
                                     None if previous is None else previous.tables)
            if any(T is not None for _, T in updates) or merged is None:
                folded: list[tuple[float, Matrix | None]] = [] if tables is None else \
                    [(1.0, LocalMatrix.trusted(p.n, tables.terms.dofs, tables.block))]
                lu = factorize(combine(constant + updates + folded, p.n), where=where)
            else:
                lu = merged.factorize([c for c, _ in constant], where,
                                      block=None if tables is None else tables.block)
            return FactorCache(self.dt, node, tangent, lu, merged=merged, problem=p,
                               tables=None if tables is None else tables.with_rates(lu))
        if merged is None:
            S0 = combine(constant, p.n)
            dense = max(DENSE_THRESHOLD, p.n) if not sp.issparse(S0) else DENSE_THRESHOLD
            lu = factorize(S0, where=where, dense_threshold=dense)
        else:
            dense = max(DENSE_THRESHOLD, p.n) if merged.dense else DENSE_THRESHOLD
            lu = merged.factorize([c for c, _ in constant], where, dense)
        base = BaseFactors.build(lu, dofs)
        if block is None:
            block = np.zeros((dofs.size, dofs.size))
        return FactorCache(self.dt, node, tangent, LowRankSolve.build(base, block, where),
                           base, merged=merged, problem=p)

    def _constant(self, node: float) -> list[tuple[float, Matrix | None]]:
        """The terms of the constant part ``S_0`` at the speed node ``node``."""
        m, p, w = self.m, self.p, 1.0 - self.m.alpha_f
        return [(1.0 - m.alpha_m, p.mass), (w * self.gdt, p.damping),
                (w * self.gdt * node, p.gyroscopic), (w * self.bdt2, p.stiffness)]

    def _resumed_off_node(self) -> bool:
        """True right after a resume whose factors were kept at another speed node."""
        s = self.s
        return ((self.p.gyroscopic is not None or self.tables is not None)
                and self.m.max_contraction > 0
                and s.factor_dt == self.dt and math.isfinite(s.factor_spin)
                and s.factor_spin != self.spin)

    def _node(self, c: FactorCache | None) -> float:
        """Speed node of this step's iteration matrix: the cached one while its predicted
        contraction ``theta`` stays within ``max_contraction`` and the speed still moves,
        else a new one (:meth:`_new_node`). Sets ``fold`` for the node."""
        self.theta, self.fold = 0.0, True
        p = self.p
        if c is None or c.dt != self.dt or c.spin == self.spin or self.m.max_contraction == 0 \
                or (p.gyroscopic is None and self.tables is None):
            if c is not None and c.dt == self.dt and c.spin == self.spin:
                self.fold = c.tangent == FOLDED
            return self.spin
        if math.isnan(c.kappa):
            c.kappa = 0.0
            if p.gyroscopic is not None:
                lu = c.base.lu if c.base is not None else c.lu
                c.kappa = (1.0 - self.m.alpha_f) * self.gdt * gyroscopic_sensitivity(
                    lu, p.gyroscopic, p.n)
                self.tally["solves"] += POWER_ITERATIONS
        previous = c.last[1] if c.last[0] == self.s.t else p.spin(self.s.t)
        theta = node_rate(c, c.spin, self.spin) * abs(self.spin - c.spin)
        if theta <= self.m.max_contraction and previous != self.spin:
            self.theta, self.fold = theta, c.tangent == FOLDED
            return c.spin
        return self._new_node(c, previous)

    def _new_node(self, c: FactorCache, previous: float) -> float:
        """A new speed node and whether it folds the tables (:func:`~.speed_nodes.new_node`);
        sets ``theta`` and ``fold``."""
        tables = None
        if self.tables is not None:
            w = 1.0 - self.m.alpha_f
            tables = c.tables if c.tables is not None else FoldedTables.at_node(
                self.tables, c.spin, w * self.bdt2, w * self.gdt).with_rates(c.lu)
        node, self.theta, self.fold = new_node(c.kappa, tables, self.spin, previous,
                                               self.m.max_contraction)
        return node

    def _accepted(self, q: FloatArray, v: FloatArray, a: FloatArray, ev: ForceEvaluation,
                  iterations: int) -> State:
        check_finite(ev.net, "net force", self.m.name, self.t1, self.s.step + 1, iterations)
        counters = self.s.counters.plus(Counters(**self.tally, max_iterations=iterations))
        new = dataclasses.replace(self.s, t=self.t1, q=q, v=v, a=a, force=ev.net,
                                  step=self.s.step + 1, counters=counters)
        if self.cache is not None:
            self.cache.last = (self.t1, self.spin)
        return self._with_cache(new)

    def _with_cache(self, state: State) -> State:
        c = self.cache
        if c is None:
            return state
        return dataclasses.replace(state, cache=c, factor_dt=c.dt, factor_spin=c.spin,
                                   factor_tangent=c.tangent, factor_kappa=c.kappa)
