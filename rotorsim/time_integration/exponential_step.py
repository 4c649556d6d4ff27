"""The runtime side of the exponential collocation stepper (:mod:`~.exponential`): the
modes and per-step-size weights of a run (:class:`StepCache`) and one attempted step
(:class:`Attempt`: Newton on the stage values of the bearing forces, end state, error).

References
----------
M. Hochbruck, A. Ostermann, *Exponential integrators*, Acta Numerica 19 (2010) 209-286,
section 2.3; E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, IV.8
(the Newton convergence test, eq 8.10).
"""

from __future__ import annotations

import cmath
import functools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.linalg.lapack as lapack

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import Counters, FloatArray, State
from rotorsim.time_integration.exponential_defect import (
    DefectOps,
    bearing_maps,
    defect_response,
    shared_weights,
)
from rotorsim.time_integration.exponential_modes import (
    LinearModes,
    StepWeights,
    lagrange_coefficients,
    lobatto_nodes,
)
from rotorsim.time_integration.motion_scale import MotionScale
from rotorsim.time_integration.problem import SecondOrderProblem

if TYPE_CHECKING:
    from rotorsim.time_integration.exponential import Exponential

LADDER = 4
"""Step sizes lie on ``h0 * 2^(j / LADDER)`` (the weights of a few sizes are reused)."""
CACHED_STEPS = 24
"""Step sizes whose weights are kept, the least recently used evicted first (24 sizes on
the ladder span a factor 64; at most about 0.3 MB each at the 400 unknowns of
:data:`~rotorsim.analyses.transient.auto_exponential.EXPONENTIAL_LIMIT`)."""
NEWTON_KAPPA = 0.03
"""Newton stops when its correction of the bearing displacements is below this fraction of
the local tolerance."""


@functools.lru_cache(maxsize=8)
def _node_tables(s: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The nodes, the monomial coefficients ``L`` of their Lagrange basis and those of the
    error interpolant (``L`` minus the basis through the stage nodes only), computed once
    per ``s`` (read-only: every run shares them)."""
    nodes = lobatto_nodes(s)
    L = lagrange_coefficients(nodes)
    low = np.zeros_like(L)
    low[1:, :s] = lagrange_coefficients(nodes[1:])
    out = (nodes, L, L - low)
    for a in out:
        a.setflags(write=False)
    return out


def meta(history: FloatArray, stages: int) -> FloatArray:
    """Ladder base, last Newton contraction and start time from the history rows."""
    return np.asarray(history[stages + 1:-2].reshape(-1)[:3])


@dataclass(eq=False)
class StepOps:
    """What a step of size ``h`` needs: the weights at the stage nodes, the maps ``Hq``,
    ``Hv`` (s k, s k) of the stage values of ``rho`` (nodes 1..s) to the bearing
    displacements and velocities at the stages, the error weights ``D`` (s + 1, N), the
    weights at the nodes and the defect's midpoints together (``shared``, one call) and
    the rest of the defect check (:mod:`~.exponential_defect`; built at its first use: an
    attempt that the interpolant's estimate rejects never needs its maps)."""

    weights: StepWeights
    Hq: FloatArray
    Hv: FloatArray
    D: Any
    shared: StepWeights
    defect: DefectOps | None = None


@dataclass(eq=False)
class StepCache:
    """Runtime state of a run: the modes, the motion scale, the step-size weights."""

    method: Exponential
    problem: SecondOrderProblem
    modes: LinearModes
    scales: MotionScale
    h0: float
    nodes: FloatArray
    L: FloatArray
    L_error: FloatArray
    damping: Any
    basis: Any = None
    """``T`` of a reduced problem (the motion and the error are measured on ``T q``)."""
    error_map: Any = None
    """Displacement error per unit modal error ``dz``: ``V[:n]``, or ``T V[:n]``."""
    ops: dict[float, StepOps] = field(default_factory=dict)
    rows: Any = None
    """The key and the rows of :meth:`output_rows` last asked for."""
    at_bearings: tuple[Any, ...] = ()
    """``V`` on the bearing displacements and velocities (transposed), the weights of the
    stage displacements, the identity of the Newton matrix and ``V`` on the bearing
    displacements and velocities (2 k, N)."""
    start_force: Any = None
    """The restoring force on the nonlinear DOFs at the state the modes were built about."""

    @classmethod
    def build(cls, method: Exponential, problem: SecondOrderProblem, q: FloatArray,
              v: FloatArray, t0: float, h0: float) -> StepCache:
        """Modes about the start ``(q, v)`` at ``t0`` (after a resume: the start kept in
        the history, so that the run continues with the same modes)."""
        where = f"{method.name}: linear part"
        batch = getattr(problem.restoring, "batch", None)
        if batch is None or problem.speed_terms is not None:
            raise ModelError("needs a restoring force with batch evaluation and no "
                             "speed-dependent linear terms", method.name)
        spin = problem.spin(t0)
        n = problem.n
        dense = (lambda A: np.zeros((n, n)) if A is None else  # noqa: E731
                 np.asarray(A.toarray() if hasattr(A, "toarray") else A, dtype=float))
        D = dense(problem.damping) + spin * dense(problem.gyroscopic)
        f0 = problem.external(t0)
        if not np.allclose(method.load(t0), f0, rtol=1e-10,
                           atol=1e-12 * float(np.max(np.abs(f0), initial=1.0))):
            raise ModelError("load does not match the problem's load", method.name)
        dofs, r0, K0, C0 = batch(q[None, :], v[None, :], np.array([t0]))
        modes = LinearModes.build(dense(problem.mass), dense(problem.stiffness), D,
                                  np.asarray(dofs, dtype=np.int64), K0[0], C0[0],
                                  method.load, where)
        s = method.stages
        nodes, L, L_error = _node_tables(s)
        weights = None if method.weights is None else np.asarray(method.weights)
        own = MotionScale.of(weights, q, method.motion)
        k = modes.dofs.size
        at = (np.ascontiguousarray(modes.V[modes.dofs].T),
              np.ascontiguousarray(modes.V[n + modes.dofs].T),
              np.tile(own.weights[modes.dofs], s), np.eye(s * k),
              np.ascontiguousarray(modes.V[np.concatenate([modes.dofs, n + modes.dofs])]))
        T = _basis(method, n)
        scales = own if T is None else MotionScale.of(
            None if method.basis_weights is None else np.asarray(method.basis_weights),
            T @ q, method.motion)
        emap = modes.V[:n] if T is None else T @ modes.V[:n]
        return cls(method, problem, modes, scales, h0, nodes, L, L_error, D, T,
                   error_map=np.ascontiguousarray(emap), at_bearings=at, start_force=r0[0])

    def moved(self, q: FloatArray, q0: FloatArray) -> FloatArray:
        """``|q - q0|`` per unknown, or per physical DOF (``|T (q - q0)|``) when reduced."""
        d = q - q0
        return np.abs(d if self.basis is None else self.basis @ d)

    def ladder(self, h: float, h_max: float) -> float:
        """The largest ``h0 * 2^(j / LADDER) <= min(h, h_max)``."""
        h = min(h, h_max)
        j = math.floor(LADDER * math.log2(h / self.h0) + 1e-9)
        return self.h0 * 2.0 ** (j / LADDER)

    def pack(self, rho: FloatArray, start: FloatArray, t0: float, z: Any,
             theta: float = 1.0) -> FloatArray:
        """History rows: ``rho`` at the nodes (s + 1 rows); the ladder base, the last
        Newton contraction and the start time ``t0``; the modal coordinates ``z`` (real
        and imaginary parts); the start ``q0``, ``v0`` (``start``, 2 rows: after a resume
        the modes are rebuilt from them, identical, and the run goes on from the stored
        ``z``, bit for bit)."""
        n = start.shape[1]
        meta = -(-3 // n)  # rows of the three numbers
        rows = -(-2 * z.size // n)
        out = np.zeros((rho.shape[0] + meta + rows + 2, n))
        out[:rho.shape[0], :rho.shape[1]] = rho
        out[rho.shape[0]:rho.shape[0] + meta].reshape(-1)[:3] = self.h0, theta, t0
        out[rho.shape[0] + meta:-2].reshape(-1)[:2 * z.size] = np.concatenate(
            [z.real, z.imag])
        out[-2:] = start
        return out

    def modal(self, state: State) -> Any:
        """The modal coordinates ``z`` kept in the state's history (propagated by the
        steps, never recomputed from ``q``, ``v``)."""
        n, N = state.q.size, self.modes.lam.size
        first = self.nodes.size + -(-3 // n)
        flat = state.history[first:-2].reshape(-1)
        return flat[:N] + 1j * flat[N:2 * N]

    def step_ops(self, h: float) -> StepOps:
        """The weights of the step size ``h`` (kept for the :data:`CACHED_STEPS` sizes
        used last)."""
        found = self.ops.pop(h, None)
        if found is not None:
            self.ops[h] = found  # most recently used last: the first is evicted
            return found
        m = self.modes
        shared = shared_weights(m, h, self.nodes, self.L)
        w = shared.select(slice(0, self.nodes.size - 1), self.L)
        # stage i's bearing motion per unit rho_j
        Hq, Hv = bearing_maps(self.bearing_rows, w.W, m.Bp, m.dofs.size)
        D = self.L_error @ w.mono[-1]  # the error weights at the end node (c_s = 1)
        if len(self.ops) >= CACHED_STEPS:
            self.ops.pop(next(iter(self.ops)))
        self.ops[h] = StepOps(w, Hq, Hv, D, shared)
        return self.ops[h]

    def defect_ops(self, h: float) -> DefectOps:
        """What the defect check of a step of size ``h`` needs (kept with its weights)."""
        ops = self.step_ops(h)
        if ops.defect is None:
            ops.defect = DefectOps.of(self.modes, h, self.nodes, self.L, self.bearing_rows,
                                      ops.shared)
        return ops.defect

    @property
    def bearing_rows(self) -> Any:
        """``V`` on the bearing displacements, then velocities (2 k, N)."""
        return self.at_bearings[4]

    def output_rows(self, dofs: Any) -> tuple[Any, Any]:
        """``V`` on the displacements and velocities of ``dofs``, transposed (N, m) each:
        kept for the last ``dofs`` asked (the recorder asks for the same ones at every
        sample; gathering them cost two copies of ``m x N`` per sample)."""
        key = np.asarray(dofs, dtype=np.int64).tobytes()
        if self.rows is None or self.rows[0] != key:
            at = np.asarray(dofs, dtype=np.int64)
            V, n = self.modes.V, self.modes.n
            self.rows = (key, np.ascontiguousarray(V[at].T),
                         np.ascontiguousarray(V[n + at].T))
        return self.rows[1], self.rows[2]

    def start_rho(self, q: FloatArray, v: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``rho`` and ``r`` on the nonlinear DOFs at the state ``(q, v)`` the modes were
        built about (its force kept from :meth:`build`)."""
        m, r = self.modes, self.start_force
        return m.K0 @ q[m.dofs] + m.C0 @ v[m.dofs] - r, r

    def net_force(self, q: FloatArray, v: FloatArray, r: FloatArray, t: float) -> FloatArray:
        """``K q + D v + r - f`` [N]."""
        p = self.problem
        g = p.stiffness @ q + self.damping @ v - self.method.load(t)
        g[self.modes.dofs] += r
        return np.asarray(g)

    def propagate(self, old: State, h: float, x: FloatArray, rho: FloatArray) -> Any:
        """Modal states (p, N) at the fractions ``x`` of a step from ``old`` whose
        ``rho`` at the nodes is ``rho`` (s + 1, k)."""
        m = self.modes
        w = StepWeights.of(m, h, x, self.L)
        return _stage_states(m, w, self.modal(old), old.t, rho)


def _stage_states(m: LinearModes, w: StepWeights, z: Any, t: float, rho: FloatArray) -> Any:
    """Modal states at the weights' fractions: exact linear part, loads and the
    interpolant of ``rho`` (s + 1, k)."""
    e = cmath.exp(1j * m.frequency * t)
    forced = w.E * z[None, :] + w.const + e * w.plus + np.conj(e) * w.minus
    return forced + np.einsum("pjn,nj->pn", w.W, m.Bp @ rho.T)


def _basis(method: Exponential, n: int) -> FloatArray | None:
    """The method's basis ``T`` (n_full, n) checked, or None."""
    if method.basis is None:
        return None
    T = np.asarray(method.basis, dtype=float)
    if T.ndim != 2 or T.shape[1] != n or not np.all(np.isfinite(T)):
        raise ModelError(f"basis must be a finite matrix with {n} columns, got shape "
                         f"{T.shape}", method.name)
    return T


class Attempt:
    """One try of a step of size ``h``: Newton on the stage values of ``rho``, then the
    end state and the error estimate."""

    def __init__(self, method: Exponential, cache: StepCache, state: State, h: float) -> None:
        if not (math.isfinite(h) and h > 0):
            raise ModelError(f"step size must be positive and finite, got {h!r}",
                             method.name)
        self.m, self.cache, self.s, self.h = method, cache, state, h
        self.count = {"residual_evaluations": 0, "iterations": 0, "solves": 0}
        self.theta = 1.0

    @property
    def tally(self) -> Counters:
        return Counters(**self.count, max_iterations=self.count["iterations"])

    def run(self) -> tuple[Any, ...] | None:
        """``(q, v, rho (s + 1, k), net force, z, peak motion, scaled error)`` or None when
        Newton failed."""
        m, s, h, cache = self.m, self.s, self.h, self.cache
        modes = cache.modes
        n, k, S = modes.n, modes.dofs.size, m.stages
        ops = cache.step_ops(h)
        z = cache.modal(s)
        rho0 = s.history[S, :k]  # rho at the end of the last step (or at the start)
        e = cmath.exp(1j * modes.frequency * s.t)
        w = ops.weights
        base = w.E * z[None, :] + w.const + e * w.plus + np.conj(e) * w.minus + \
            w.W[:, 0, :] * (modes.Bp @ rho0)[None, :]
        at = cache.at_bearings
        aq = (base @ at[0]).real.ravel()
        av = (base @ at[1]).real.ravel()
        rho = self._guess(s.history[:S + 1, :k], rho0).ravel()
        times = s.t + cache.nodes[1:] * h
        wb = at[2]
        tol = m.local_tol * cache.scales.scale(s.peak)
        Q, Vel = np.zeros((S, n)), np.zeros((S, n))
        eye = at[3]
        K0, C0 = modes.K0, modes.C0
        old_norm, theta = math.inf, float(meta(s.history, S)[1])
        for it in range(m.max_newton):
            qb, vb = aq + ops.Hq @ rho, av + ops.Hv @ rho
            Q[:, modes.dofs], Vel[:, modes.dofs] = qb.reshape(S, k), vb.reshape(S, k)
            _, r, Kt, Ct = cache.problem.restoring.batch(Q, Vel, times)  # type: ignore
            self.count["residual_evaluations"] += 1
            self.count["iterations"] += 1
            self.count["solves"] += 1
            R = rho - ((qb.reshape(S, k) @ K0.T + vb.reshape(S, k) @ C0.T) - r).ravel()
            J = eye - (np.matmul(K0[None] - Kt, ops.Hq.reshape(S, k, S * k)) +
                       np.matmul(C0[None] - Ct, ops.Hv.reshape(S, k, S * k))
                       ).reshape(S * k, S * k)
            if not np.isfinite(R).all():
                return None
            # LAPACK directly: numpy's solve costs about 30 us of checks and error-state
            # handling per call at this size (36 unknowns), several times the solve
            _, _, d, info = lapack.dgesv(J, -R, overwrite_a=True, overwrite_b=True)
            if info != 0:  # a zero pivot: the Newton matrix is singular
                return None
            rho = rho + d
            dq = ops.Hq @ d
            norm = float((wb * np.abs(dq)).max()) / tol
            # remaining error predicted from the contraction (Hairer & Wanner IV.8, 8.10)
            # the first iteration uses the contraction of the last step's final one
            rate = norm / old_norm if it > 0 else theta
            if norm <= NEWTON_KAPPA or (rate < 1.0 and rate / (1.0 - rate) * norm
                                        <= NEWTON_KAPPA):
                dv = ops.Hv @ d
                r_end = r[-1] + Kt[-1] @ dq[-k:] + Ct[-1] @ dv[-k:]
                self.theta = rate if it > 0 else theta
                return self._finish(base, rho0, rho.reshape(S, k), r_end)
            if it > 0 and norm >= old_norm:
                return None
            old_norm = norm
        return None

    def _guess(self, rho_prev: FloatArray, rho0: FloatArray) -> FloatArray:
        """Stage values of ``rho`` extrapolated from the last step's interpolant (``rho``
        at the start before the first step)."""
        s, cache = self.s, self.cache
        hp = s.history_dt
        if not (math.isfinite(hp) and hp > 0):
            return np.repeat(rho0[None, :], self.m.stages, axis=0)
        x = 1.0 + cache.nodes[1:] * self.h / hp
        powers = x[:, None] ** np.arange(cache.L.shape[1])[None, :]
        return np.asarray(powers @ cache.L.T @ rho_prev)

    def _finish(self, base: Any, rho0: FloatArray, rho: FloatArray, r: FloatArray
                ) -> tuple[Any, ...]:
        """End state, net force (``r`` the restoring force there) and scaled error."""
        cache, modes = self.cache, self.cache.modes
        n = modes.n
        ops = cache.step_ops(self.h)
        all_rho = np.concatenate([rho0[None, :], rho])
        loads = all_rho @ modes.Bp.T  # modal loads of rho at the nodes (s + 1, N)
        z_end = base[-1] + (ops.weights.W[-1, 1:] * loads[1:]).sum(axis=0)
        y = (modes.V @ z_end).real
        q, v = y[:n], y[n:]
        force = cache.net_force(q, v, r, self.s.t + self.h)
        sc = cache.scales
        peak = np.maximum(self.s.peak, cache.moved(q, self.s.history[-2]))
        unit = self.m.local_tol * sc.scale(peak)
        # two estimates of the error, the larger kept: the difference to the interpolant
        # of degree s - 1, and (for a step it would accept) the response to the defect
        # between the nodes, which sees a contact closing or opening inside the step
        err = self._norm((ops.D * loads).sum(axis=0), unit)
        if err <= 1.0 and not self.m.fixed:
            self.count["residual_evaluations"] += 1
            err = max(err, self._norm(defect_response(
                cache.defect_ops(self.h), modes, cache.bearing_rows, cache.problem.restoring,
                cache.modal(self.s), self.s.t, self.h, all_rho), unit))
        return q, v, all_rho, force, z_end, peak, err

    def _norm(self, dz: Any, unit: float) -> float:
        """The largest weighted displacement of the modal error ``dz``, in ``unit``."""
        sc = self.cache.scales
        return float((sc.weights * np.abs((self.cache.error_map @ dz).real)).max()) / unit
