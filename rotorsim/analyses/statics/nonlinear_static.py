"""Static equilibrium of a rotor with nonlinear elements: ``K q + r(q) = f``.

Newton's method on the whole system with the exact tangent ``K + P K_t P^T`` (``K_t`` the
gathered element tangent on the nonlinear DOFs), a backtracking line search on the residual
norm. When a full-load Newton fails (typically a shaft that starts inside a bearing
clearance, where the tangent is singular or nearly so), the minimum of the total potential
energy (:func:`rotorsim.analyses.statics.rotor_energy.energy_equilibrium`, a trust-region method
that needs no line search) is sought from the same start and polished by Newton; if an
element has no energy or that fails too, the load is applied in fractions (load stepping),
each solution starting the next. Free rigid-body motions (e.g. torsion, or axial motion on
cylindrical roller bearings) are held at their starting value.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.solvers.stats import Stats

POLISH_SHIFT = 1e-6
"""Newton's polish of an energy minimum adds this multiple of the nominal tangent to the
tangent: a motion that no loaded contact resists (a rigid rotor rocking about its one loaded
ball) then takes bounded steps, while the other directions converge as before (the shift
changes each step by about 1e-6 relative, not the solution)."""


@dataclass(frozen=True, eq=False)
class NonlinearEquilibrium:
    """Solution of :func:`nonlinear_equilibrium` on the free DOFs."""

    q: FloatArray
    iterations: int
    residual: float
    load_steps: int
    method: str = "newton"
    """``"newton"`` (full load), ``"energy"`` (energy minimum polished by Newton) or
    ``"load steps"``."""


def nonlinear_equilibrium(system: RotorSystem, f: FloatArray, *, speed: float = 0.0,
                          phi: float = 0.0, q0: FloatArray | None = None,
                          held: Sequence[int] = (), tol: float = 1e-10, max_iter: int = 50,
                          max_load_steps: int = 64, nominal: sp.spmatrix | None = None,
                          stats: Stats | None = None) -> NonlinearEquilibrium:
    """Solve ``K(W) q + r(q, 0, phi, W) = f`` on the free DOFs (module docstring).

    Parameters
    ----------
    system : RotorSystem
        Assembled with its nonlinear elements.
    f : array (n_free,)
        Static load [N, N m].
    speed, phi : float
        Spin speed [rad/s] (speed-dependent bearings, centrifugal effects) and shaft angle
        [rad] that places the rolling elements.
    q0 : array (n_free,), optional
        Starting point (default zero).
    held : sequence of int
        Free DOFs held at their starting value (free rigid motions).
    tol : float
        Converged when ``||K q + r - f||_inf <= tol * max(||f||_inf, ||r||_inf, 1 N)``.
    max_iter : int
        Newton iterations per load step.
    max_load_steps : int
        Largest number of load increments tried.
    nominal : sparse matrix (n_free, n_free), optional
        A nominal tangent of the nonlinear elements (e.g. their mean tangent over probe
        displacements). Without ``q0`` the start solves ``(K + nominal) q = f``, and it is
        added to a singular Newton tangent (an unloaded bearing with clearance has none).

    Raises
    ------
    ConvergenceError
        When no load stepping down to ``1 / max_load_steps`` converges; the message gives
        the residual and its worst DOF.
    """
    stats = stats if stats is not None else Stats()
    n = system.n_free
    K = system.matrices(speed).K
    keep = np.setdiff1d(np.arange(n), np.asarray(held, dtype=np.int64))
    solver = _Newton(system, K, float(speed), float(phi), keep, tol, max_iter, stats, nominal)
    if q0 is not None:
        q = np.array(q0, dtype=float)
    elif nominal is not None:
        q = np.zeros(n)
        q[keep] = factorize(sp.csr_matrix(K + nominal)[keep][:, keep], stats=stats,
                            where="nonlinear static: start").solve(f[keep])
    else:
        q = np.zeros(n)
    try:
        q, it, res = solver.solve(q, f)
        return NonlinearEquilibrium(q, it, res, 1)
    except ConvergenceError as first:
        failure = first
    found = _energy_equilibrium(system, solver, f, q, held)
    if found is not None:
        return found
    steps = 2
    while steps <= max_load_steps:
        try:
            qs, total = q.copy(), 0
            for j in range(1, steps + 1):
                qs, it, res = solver.solve(qs, f * (j / steps))
                total += it
            return NonlinearEquilibrium(qs, total, res, steps, "load steps")
        except ConvergenceError as exc:
            failure = exc
            steps *= 2
    raise ConvergenceError(f"static equilibrium failed even with {max_load_steps} load "
                           f"steps: {failure}", "nonlinear static",
                           iteration=max_iter, residual=failure.residual)


def _energy_equilibrium(system: RotorSystem, solver: _Newton, f: FloatArray, q: FloatArray,
                        held: Sequence[int]) -> NonlinearEquilibrium | None:
    """Minimum of the potential energy from ``q``, polished by Newton; None when an element
    has no energy or either step fails (the caller then steps the load)."""
    from rotorsim.analyses.statics.rotor_energy import energy_equilibrium

    if solver.nominal is None:
        solver.nominal = sp.csr_matrix(nominal_tangent(system))[solver.keep][:, solver.keep]
    try:
        eq = energy_equilibrium(system, f, speed=solver.speed, phi=solver.phi, q0=q, held=held)
        solver.shift = POLISH_SHIFT
        polished, it, res = solver.solve(eq.q, f)
    except (ModelError, ConvergenceError):
        return None
    finally:
        solver.shift = 0.0
    solver.stats.iterations += eq.iterations
    return NonlinearEquilibrium(polished, eq.iterations + it, res, 1, "energy")


def start_point(system: RotorSystem, x0: ArrayLike, where: str) -> FloatArray:
    """A user's starting displacement on all DOFs (``(ndof,)`` [m, rad], e.g. a
    ``StaticResult.displacement``) as a vector on the free DOFs.

    Raises
    ------
    ModelError
        Not ``ndof`` finite numbers, or a nonzero value on a fixed (or unconnected) DOF.
    """
    ndof = system.dof_map.ndof
    try:
        x = np.asarray(x0, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"must be an array of {ndof} numbers (all DOFs) [m, rad], got "
                         f"{type(x0).__name__}", where) from None
    if x.shape != (ndof,):
        raise ModelError(f"must have shape ({ndof},) (all DOFs of the rotor), got shape "
                         f"{x.shape}", where)
    bad = np.flatnonzero(~np.isfinite(x))
    names = system.dof_map.names()
    if bad.size:
        raise ModelError(f"must be finite; DOF {names[bad[0]]} is {x[bad[0]]}", where)
    free = system.dof_map.free
    held = np.setdiff1d(np.arange(ndof), free)
    moved = held[x[held] != 0.0]
    if moved.size:
        raise ModelError(f"is {x[moved[0]]:.6g} on DOF {names[moved[0]]}, which is fixed "
                         "(or connected to nothing); it must be 0 there", where)
    return np.array(x[free])


class _Newton:
    def __init__(self, system: RotorSystem, K: sp.csr_matrix, speed: float, phi: float,
                 keep: NDArray[np.int64], tol: float, max_iter: int, stats: Stats,
                 nominal: sp.spmatrix | None) -> None:
        if system.nonlinear is None:
            raise ModelError("the system has no nonlinear elements", "nonlinear static")
        self.nl, self.K, self.speed, self.phi = system.nonlinear, K, speed, phi
        self.keep, self.tol, self.max_iter, self.stats = keep, tol, max_iter, stats
        self.nominal = None if nominal is None else sp.csr_matrix(nominal)[keep][:, keep]
        self.shift = 0.0  # multiple of the nominal tangent added to every tangent

    def residual(self, q: FloatArray, f: FloatArray) -> tuple[FloatArray, FloatArray, float]:
        nl = self.nl
        out = nl.evaluate(q[nl.dofs], np.zeros(nl.k), self.phi, self.speed)
        self.stats.residual_evaluations += 1
        r = np.zeros_like(q)
        r[nl.dofs] = out.f[0]
        R = self.K @ q + r - f
        scale = max(float(np.max(np.abs(f), initial=0.0)),
                    float(np.max(np.abs(r), initial=0.0)), 1.0)
        return R, out.K[0], scale

    def solve(self, q: FloatArray, f: FloatArray) -> tuple[FloatArray, int, float]:
        R, kt, scale = self.residual(q, f)
        norm = float(np.max(np.abs(R[self.keep])))
        for it in range(self.max_iter):
            if norm <= self.tol * scale:
                return q, it, norm / scale
            dq = np.zeros_like(q)
            dq[self.keep] = -self._factors(kt, it, norm).solve(R[self.keep])
            self.stats.iterations += 1
            q, R, kt, scale, norm = self._line_search(q, dq, f, norm)
        worst = int(self.keep[np.argmax(np.abs(R[self.keep]))])
        raise ConvergenceError(f"no convergence in {self.max_iter} iterations: residual "
                               f"{norm:.3e} N at free DOF {worst}", "nonlinear static",
                               iteration=self.max_iter, residual=norm)

    def _factors(self, kt: FloatArray, it: int, norm: float) -> Factorization:
        """LU of the tangent, regularised by the nominal tangent when singular."""
        J = self._tangent(kt)
        if self.shift and self.nominal is not None:
            J = J + self.shift * self.nominal
        try:
            return factorize(J, stats=self.stats, where="nonlinear static")
        except ConvergenceError as exc:
            if self.nominal is None:
                raise ConvergenceError(f"singular tangent at iteration {it}: {exc}",
                                       "nonlinear static", iteration=it,
                                       residual=norm) from None
        return factorize(J + self.nominal, stats=self.stats, where="nonlinear static")

    def _tangent(self, kt: FloatArray) -> sp.csr_matrix:
        dofs = self.nl.dofs
        rows = np.repeat(dofs, dofs.size)
        cols = np.tile(dofs, dofs.size)
        Kt = sp.csr_matrix((kt.ravel(), (rows, cols)), shape=self.K.shape)
        J = sp.csr_matrix(self.K + Kt)
        return J[self.keep][:, self.keep]

    def _line_search(self, q: FloatArray, dq: FloatArray, f: FloatArray, norm: float
                     ) -> tuple[FloatArray, FloatArray, FloatArray, float, float]:
        """Backtracking until the Euclidean residual norm decreases (a simple-decrease
        rule: near a contact onset the first Newton steps may reduce it very little)."""
        R0, _, _ = self.residual(q, f)
        l2 = float(np.linalg.norm(R0[self.keep]))
        step = 1.0
        for _ in range(30):
            trial = q + step * dq
            R, kt, scale = self.residual(trial, f)
            new = float(np.max(np.abs(R[self.keep])))
            if new <= self.tol * scale or float(np.linalg.norm(R[self.keep])) < l2:
                return trial, R, kt, scale, new
            step *= 0.5
        raise ConvergenceError(f"line search failed: residual {norm:.3e} N does not "
                               "decrease along the Newton direction", "nonlinear static",
                               residual=norm)


def nominal_tangent(system: RotorSystem) -> sp.csr_matrix:
    """Mean symmetric tangent of the nonlinear elements over probe displacements of 1, 10
    and 100 um (or urad) along each of their DOFs, on the free DOFs: it reveals the rigid
    motions no element restrains (torsion; axial motion on cylindrical rollers) and starts
    the static Newton iteration."""
    nl = system.nonlinear
    assert nl is not None
    probes = np.vstack([s * np.eye(nl.k) * sign for s in (1e-6, 1e-5, 1e-4)
                        for sign in (1.0, -1.0)])
    kt = nl.evaluate(probes, np.zeros_like(probes), 0.0, 0.0).K.mean(axis=0)
    rows, cols = np.repeat(nl.dofs, nl.k), np.tile(nl.dofs, nl.k)
    n = system.n_free
    return sp.csr_matrix((0.5 * (kt + kt.T).ravel(), (rows, cols)), shape=(n, n))
