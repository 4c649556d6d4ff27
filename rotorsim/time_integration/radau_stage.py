"""The problem side of a Radau IIA step: net forces at the three stages, the tangents at a
point, and the Newton correction and error estimate condensed onto the displacements
(:mod:`~.radau_linear`; the stepper is :mod:`~.radau`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp

from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.time_integration.base import FloatArray, IntArray, State
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.radau_linear import ShiftedFactors, ShiftedSolve

CACHED_STEPS = 8
"""Step sizes whose factors are kept (least recently used dropped)."""
SPIN_DRIFT = 0.02
"""Factors at the schedule value ``s_f`` are reused while ``|s(t) - s_f| h`` stays below
this (the gyroscopic mismatch, relative to the inertia term, that slows the simplified
Newton iterations by at most a few per cent)."""


@dataclass(frozen=True, eq=False)
class Tangent:
    """Tangents of the restoring force on ``dofs``: ``dr/dq``, ``dr/dv`` blocks (k, k)."""

    dofs: IntArray
    stiffness: FloatArray | None
    damping: FloatArray | None


NO_TANGENT = Tangent(np.zeros(0, dtype=np.int64), None, None)
"""The tangent of a problem without restoring force."""


def pack(contraction: float, h0: float, tangent: Tangent, n: int) -> FloatArray:
    """Rows (r, n) holding the Newton contraction, the base of the step-size ladder and
    ``tangent`` (a checkpoint stores only arrays: a resumed run then continues with the
    very numbers of the uninterrupted one)."""
    parts = [np.array([contraction, h0, tangent.dofs.size, tangent.stiffness is not None,
                       tangent.damping is not None], dtype=float),
             tangent.dofs.astype(float)]
    parts += [T.ravel() for T in (tangent.stiffness, tangent.damping) if T is not None]
    flat = np.concatenate(parts)
    rows = -(-flat.size // n)
    out = np.zeros(rows * n)
    out[:flat.size] = flat
    return out.reshape(rows, n)


def unpack(rows: FloatArray) -> tuple[float, float, Tangent]:
    """Inverse of :func:`pack`: contraction, ladder base, tangent."""
    flat = rows.ravel()
    k, has_k, has_c = int(flat[2]), bool(flat[3]), bool(flat[4])
    dofs = flat[5:5 + k].astype(np.int64)
    pos, blocks = 5 + k, []
    for present in (has_k, has_c):
        blocks.append(flat[pos:pos + k * k].reshape(k, k).copy() if present else None)
        pos += k * k if present else 0
    return float(flat[0]), float(flat[1]), Tangent(dofs, blocks[0], blocks[1])


def local_tangent(kt: Any, ct: Any, n: int) -> Tangent:
    """A :class:`Tangent` from the tangents a restoring force returns (LocalMatrix, dense,
    sparse or None); general matrices are taken on all ``n`` unknowns."""
    present = [T for T in (kt, ct) if T is not None]
    if not present:
        return NO_TANGENT
    if all(isinstance(T, LocalMatrix) for T in present):
        dofs = present[0].dofs
        if all(np.array_equal(T.dofs, dofs) for T in present):
            return Tangent(dofs, None if kt is None else kt.block,
                           None if ct is None else ct.block)
    dofs = np.arange(n, dtype=np.int64)

    def full(T: Any) -> FloatArray | None:
        if T is None:
            return None
        if isinstance(T, LocalMatrix) or sp.issparse(T):
            return np.asarray(T.toarray())
        return np.asarray(T, dtype=float)

    return Tangent(dofs, full(kt), full(ct))


def merged(a: Tangent, b: Tangent) -> Tangent:
    """``a + b`` on the union of their DOFs (either may be :data:`NO_TANGENT`)."""
    if not b.dofs.size:
        return a
    if not a.dofs.size:
        return b
    dofs = np.union1d(a.dofs, b.dofs).astype(np.int64)
    blocks: list[FloatArray | None] = []
    for name in ("stiffness", "damping"):
        parts = [(T.dofs, getattr(T, name)) for T in (a, b) if getattr(T, name) is not None]
        if not parts:
            blocks.append(None)
            continue
        block = np.zeros((dofs.size, dofs.size))
        for d, B in parts:
            pos = np.searchsorted(dofs, d)
            block[np.ix_(pos, pos)] += B
        blocks.append(block)
    return Tangent(dofs, blocks[0], blocks[1])


def _apply(A: Any, X: FloatArray) -> FloatArray:
    """``(A @ X.T).T`` for rows ``X`` (s, n) and a dense or sparse ``A``."""
    if A is None:
        return np.zeros_like(X)
    if isinstance(A, np.ndarray):
        return X @ A.T
    return np.asarray((A @ X.T).T)


class StageSystem:
    """Forces and linear solves of one problem; keeps the factors between steps."""

    def __init__(self, problem: Any, where: str) -> None:
        self.p, self.where = problem, where
        self._mass: Factorization | None = None
        self._factors: dict[float, tuple[float, ShiftedFactors, ShiftedFactors]] = {}

    def mass_solve(self, b: FloatArray) -> FloatArray:
        """``M^-1 b`` (the mass matrix is factorised on first use)."""
        if self._mass is None:
            self._mass = factorize(self.p.mass, where=f"{self.where}: mass matrix")
        return np.asarray(self._mass.solve(b))

    def point(self, q: FloatArray, v: FloatArray, t: float) -> tuple[FloatArray, Tangent]:
        """Net force ``g`` at one point and the tangents of the restoring force and the
        speed terms there."""
        ev = self.p.forces(q, v, t)
        tangent = local_tangent(ev.stiffness_tangent, ev.damping_tangent, self.p.n)
        return ev.net, merged(tangent, self._speed_tangent(self.p.spin(t)))

    def _speed_tangent(self, spin: float) -> Tangent:
        """``K_s``, ``C_s`` of the problem's speed terms at ``spin`` (none without)."""
        terms = self.p.speed_terms
        if terms is None:
            return NO_TANGENT
        K, C = terms(spin)
        return Tangent(terms.dofs, K, C)

    def loads(self, times: FloatArray) -> tuple[FloatArray, FloatArray]:
        """External loads (s, n) and schedule values (s,) at the stage times."""
        many = getattr(self.p.load, "many", None)  # a rotor's loads: all stages at once
        f = np.asarray(many(times)) if many is not None and times.size > 1 else \
            np.stack([self.p.external(float(t)) for t in times])
        return f, np.array([self.p.spin(float(t)) for t in times])

    def stage_forces(self, Q: FloatArray, V: FloatArray, times: FloatArray,
                     loads: tuple[FloatArray, FloatArray]) -> tuple[FloatArray, Tangent]:
        """Net forces ``g`` (s, n) at the stages ``(Q, V)`` (s, n), and the tangents of the
        restoring force at the last stage."""
        p = self.p
        f, spins = loads
        g = _apply(p.stiffness, Q) - f
        if p.damping is not None:
            g += _apply(p.damping, V)
        if p.gyroscopic is not None:
            g += spins[:, None] * _apply(p.gyroscopic, V)
        speed = NO_TANGENT
        if p.speed_terms is not None:
            d = p.speed_terms.dofs
            for i, spin in enumerate(spins):
                K, C = p.speed_terms(float(spin))
                g[i, d] += K @ Q[i, d] + C @ V[i, d]
            speed = self._speed_tangent(float(spins[-1]))
        r = p.restoring
        if r is None:
            return g, speed
        batch = getattr(r, "batch", None)
        if batch is not None:
            dofs, rl, kl, cl = batch(Q, V, times)
            g[:, dofs] += rl
            return g, merged(Tangent(dofs, kl[-1], cl[-1]), speed)
        tangent = NO_TANGENT
        for i, t in enumerate(times):
            out = r(Q[i], V[i], float(t))
            if out is not None:
                g[i] += np.asarray(out[0], dtype=float).reshape(-1)
                tangent = local_tangent(out[1], out[2], p.n)
        return g, merged(tangent, speed)

    def end_force(self, g: FloatArray, tangent: Tangent, dq: FloatArray, dv: FloatArray,
                  spin: float) -> FloatArray:
        """Net force after the last stage moved by ``(dq, dv)``: ``g`` plus the tangent
        change (exact to the square of the last Newton correction)."""
        p = self.p
        out = g + p.stiffness @ dq
        if p.damping is not None:
            out += p.damping @ dv
        if p.gyroscopic is not None:
            out += spin * (p.gyroscopic @ dv)
        d = tangent.dofs
        if tangent.stiffness is not None:
            out[d] += tangent.stiffness @ dq[d]
        if tangent.damping is not None:
            out[d] += tangent.damping @ dv[d]
        return out

    def solvers(self, h: float, gamma: float, alpha_beta: complex, t: float,
                tangent: Tangent) -> StepSolves:
        """The real and complex condensed solvers of a step of size ``h`` from ``t``."""
        spin = self.p.spin(t)
        entry = self._factors.get(h)
        fresh = 0
        if entry is None or abs(spin - entry[0]) * h > SPIN_DRIFT or \
                not np.array_equal(entry[1].dofs, tangent.dofs):
            where = f"{self.where}: iteration matrix at t = {t:.9g} s"
            entry = (spin, ShiftedFactors.build(self.p, gamma / h, spin, tangent.dofs, where),
                     ShiftedFactors.build(self.p, alpha_beta / h, spin, tangent.dofs, where))
            fresh = 2
            if len(self._factors) >= CACHED_STEPS:
                self._factors.pop(next(iter(self._factors)))
        else:
            self._factors.pop(h)
        self._factors[h] = entry
        where = f"{self.where}: step at t = {t:.9g} s"
        real = ShiftedSolve.build(entry[1], tangent.stiffness, tangent.damping, where)
        cplx = ShiftedSolve.build(entry[2], tangent.stiffness, tangent.damping, where)
        return StepSolves(self, entry[0], tangent, real, cplx, fresh)


@dataclass(eq=False)
class StepSolves:
    """Newton corrections and error estimates of one step (module docstring of
    :mod:`~.radau_linear` for the condensation)."""

    system: StageSystem
    spin: float
    tangent: Tangent
    real: ShiftedSolve
    cplx: ShiftedSolve
    fresh: int

    def _condensed(self, solve: ShiftedSolve, mu: Any, bq: Any, Mbv: Any) -> tuple[Any, Any]:
        """``(mu I - J)^-1 (b_q, b_v)`` given ``M b_v``, with the frozen
        ``D_t = C + s_f G + dr/dv`` (``mu M + C + s_f G`` is the factors' ``coupling``)."""
        rhs = solve.base.coupling @ bq + Mbv
        tg = self.tangent
        if tg.damping is not None:
            d = tg.dofs
            rhs[d] += tg.damping @ bq[d]
        xq = solve.solve(rhs)
        return xq, mu * xq - bq

    def correction(self, W: FloatArray, V: FloatArray, g: FloatArray, h: float
                   ) -> FloatArray:
        """Simplified-Newton correction of the transformed stage increments ``W`` (3, 2n)
        from the stage velocities ``V`` and net forces ``g`` (3, n)."""
        from rotorsim.time_integration.radau import ALPHA_BETA, GAMMA, TRANSFORM_INV

        n = V.shape[1]
        TV, TG = TRANSFORM_INV @ V, TRANSFORM_INV @ g
        MW = _apply(self.system.p.mass, W[:, n:])  # M W_v of the three stages
        out = np.empty_like(W)
        mu = GAMMA / h
        bq = TV[0] - mu * W[0, :n]
        out[0, :n], out[0, n:] = self._condensed(self.real, mu, bq, -TG[0] - mu * MW[0])
        mc = ALPHA_BETA / h
        bqc = (TV[1] + 1j * TV[2]) - mc * (W[1, :n] + 1j * W[2, :n])
        xq, xv = self._condensed(self.cplx, mc, bqc,
                                 -(TG[1] + 1j * TG[2]) - mc * (MW[1] + 1j * MW[2]))
        out[1, :n], out[2, :n] = xq.real, xq.imag
        out[1, n:], out[2, n:] = xv.real, xv.imag
        return out

    def error(self, s: State, Zq: FloatArray, Zv: FloatArray, h: float, weights: FloatArray,
              again: tuple[FloatArray, FloatArray] | None = None
              ) -> tuple[FloatArray, FloatArray]:
        """Embedded error estimate ``(gamma/h - J)^-1 (f(y_n) + sum e_i Z_i / h)`` of ``q``
        and ``v``; with ``again`` (a first estimate) ``f`` is evaluated at ``y_n`` plus it."""
        from rotorsim.time_integration.radau import GAMMA

        M = self.system.p.mass
        zq, zv = (weights @ Zq) / h, (weights @ Zv) / h
        if again is None:
            v, g = s.v, s.force
        else:
            v = s.v + again[1]
            g = self.system.p.forces(s.q + again[0], v, s.t).net
        mu = GAMMA / h
        return self._condensed(self.real, mu, v + zq, -g + M @ zv)
