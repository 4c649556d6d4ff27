"""Newton solver of the ring-and-roller problem: linear rings, ``Z`` nonlinear contacts.

The discrete problem is the minimum of the convex potential energy::

    Pi(U) = 1/2 U.K U - f.U + sum_j phi(Delta_j),      Delta = C^T U + Delta_0

(``K`` ring stiffness with supports, ``f`` loads, ``C`` the contact coupling of the inner
minus the outer raceway, ``Delta_0 = -g/2``, ``phi`` the condensed roller energy of
:mod:`~rotorsim.verification.ring_contact`). Its gradient is the residual
``r = f - K U - C Q(Delta)`` and its Hessian ``J = K + C diag(k) C^T``.

Only ``Z`` scalars are nonlinear, so ``J`` is a low-rank change of one fixed matrix:
``A = K + k_ref C C^T`` (every roller a linear spring ``k_ref``; this also holds the inner
ring, which is carried by the rollers alone) is factorised once, and each Newton step is
solved by the Woodbury identity with ``E = diag(k - k_ref)``::

    J^-1 r = z - Y (I + E H)^-1 E C^T z,    z = A^-1 r,  Y = A^-1 C,  H = C^T Y

(one back substitution and a ``Z x Z`` factorisation per iteration). Open contacts get the
stiffness ``1e-9 k_ref`` in ``J`` only, which keeps it regular when a ring would be free;
their residual is exact, so the converged point is unchanged. A backtracking (Armijo) line
search on ``Pi`` makes the iteration globally convergent (``Pi`` is convex and ``C^1``).
The start ``U_0`` is given by the caller (the rigid-ring equilibrium of
:func:`rigid_ring_start`: with a clearance, a start with every contact open would leave the
inner ring without stiffness).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats
from rotorsim.verification.ring_contact import ContactState, RollerContactLaw

FloatArray = NDArray[np.float64]

OPEN_STIFFNESS = 1e-9
"""Tangent stiffness of an open contact, relative to ``k_ref`` (Jacobian only)."""
ARMIJO = 1e-4
"""Sufficient-decrease constant of the line search."""
MAX_HALVINGS = 40
"""Line-search step halvings before giving up."""
ROUNDOFF = 16.0 * np.finfo(float).eps
"""Round-off level of ``K U``: ``||r||`` below ``ROUNDOFF || |K| |U| ||`` counts as converged."""


@dataclass(frozen=True, eq=False)
class ContactSystem:
    """The assembled ring problem (module docstring).

    Attributes
    ----------
    stiffness : sparse (n, n)
        ``K`` [N/m], symmetric positive semi-definite (the inner ring may be free).
    load : array (n,)
        ``f`` [N].
    coupling : sparse (n, Z)
        ``C`` (inner minus outer raceway patch vectors).
    offset : array (Z,)
        ``Delta_0`` [m].
    law : RollerContactLaw
        Condensed roller law.
    reference_stiffness : float
        ``k_ref`` [N/m].
    initial : array (n,)
        Start ``U_0`` [m].
    """

    stiffness: sp.csr_matrix
    load: FloatArray
    coupling: sp.csr_matrix
    offset: FloatArray
    law: RollerContactLaw
    reference_stiffness: float
    initial: FloatArray

    def approach(self, u: FloatArray) -> FloatArray:
        """``Delta = C^T U + Delta_0`` [m], shape ``(Z,)``."""
        return np.asarray(self.coupling.T @ u + self.offset)

    def residual(self, u: FloatArray, state: ContactState) -> FloatArray:
        """``r = f - K U - C Q_i`` [N], shape ``(n,)``."""
        return np.asarray(self.load - self.stiffness @ u - self.coupling @ state.inner_load)


@dataclass(frozen=True)
class ContactSolution:
    """Converged displacement and contact state.

    Attributes
    ----------
    displacement : array (n,)
        ``U`` [m].
    approach : array (Z,)
        ``Delta`` [m].
    contacts : ContactState
        Roller loads and deflections.
    iterations : int
        Newton iterations.
    residual : float
        Final ``||r|| / scale``.
    history : tuple of float
        Relative residual after each iteration (the first entry at the start).
    step_lengths : tuple of float
        Accepted line-search step of each iteration.
    """

    displacement: FloatArray
    approach: FloatArray
    contacts: ContactState
    iterations: int
    residual: float
    history: tuple[float, ...] = field(default_factory=tuple)
    step_lengths: tuple[float, ...] = field(default_factory=tuple)


@dataclass(frozen=True, eq=False)
class _Woodbury:
    """``A = K + k_ref C C^T`` factorised, with ``Y = A^-1 C`` and ``H = C^T Y``."""

    solve: Callable[[FloatArray], FloatArray]
    y: FloatArray
    h: FloatArray


def _prepare(system: ContactSystem, stats: Stats) -> _Woodbury:
    c = system.coupling
    a = (system.stiffness + system.reference_stiffness * (c @ c.T)).tocsc()
    lu = factorize(a, stats=stats, where="ring FE: K + k_ref C C^T")
    y = np.asarray(lu.solve(c.toarray()))
    return _Woodbury(lu.solve, y, np.asarray(c.T @ y))


def _newton_step(system: ContactSystem, wb: _Woodbury, r: FloatArray, k: FloatArray,
                 stats: Stats) -> FloatArray:
    z = np.asarray(wb.solve(r))
    e = np.maximum(k, OPEN_STIFFNESS * system.reference_stiffness) - system.reference_stiffness
    small = np.eye(e.size) + e[:, None] * wb.h
    w = factorize(small, stats=stats, where="ring FE: Woodbury capacitance").solve(
        e * (system.coupling.T @ z))
    return np.asarray(z - wb.y @ w)


def _line_search(system: ContactSystem, u: FloatArray, d: FloatArray, r: FloatArray,
                 state: ContactState, stats: Stats) -> tuple[float, FloatArray, ContactState]:
    """Backtracking on ``Pi(U + alpha d) - Pi(U)``, evaluated without cancellation.

    ``Pi`` itself is dominated by the rigid-body work of the load (the soft support lets the
    rings translate by far more than they deform), so the change is formed from small terms:
    ``alpha d.(K U - f) + alpha^2/2 d.K d + sum(phi(Delta_alpha) - phi(Delta))`` with
    ``K U - f = -r - C Q``.
    """
    cd = np.asarray(system.coupling.T @ d)
    linear = -float(r @ d) - float(cd @ state.inner_load)
    curvature = 0.5 * float(d @ (system.stiffness @ d))
    slope = -float(r @ d)
    alpha = 1.0
    for _ in range(MAX_HALVINGS):
        trial = u + alpha * d
        trial_state = system.law.evaluate(system.approach(trial))
        stats.residual_evaluations += 1
        contact = trial_state.energy - state.energy
        change = alpha * linear + alpha**2 * curvature + float(contact.sum())
        size = abs(alpha * linear) + alpha**2 * abs(curvature) + float(
            np.abs(trial_state.energy).sum() + np.abs(state.energy).sum())
        if change <= ARMIJO * alpha * min(slope, 0.0) + 64.0 * np.finfo(float).eps * size:
            return alpha, trial, trial_state
        alpha *= 0.5
        stats.rejected_steps += 1
    raise ConvergenceError("line search found no decrease of the potential energy",
                           "ring FE Newton")


def rigid_ring_start(law: RollerContactLaw, psi: FloatArray, offset: FloatArray,
                     load: FloatArray, max_iter: int = 100) -> FloatArray:
    """Inner-ring translation [m] (2,) that balances ``load`` on rigid rings.

    Damped Newton on the convex energy ``sum_j phi(Delta_0 + delta . e_j) - load . delta``
    (the same contact law; an open roller gets a tiny stiffness so the 2 x 2 tangent stays
    regular). Only a start for :func:`solve_contacts`: it is not required to be exact.

    Examples
    --------
    >>> law = RollerContactLaw(kn=1e9)
    >>> psi = 2 * np.pi * np.arange(12) / 12
    >>> d = rigid_ring_start(law, psi, np.full(12, -5e-6), np.array([1000.0, 0.0]))
    >>> bool(d[0] > 5e-6), abs(float(d[1])) < 1e-12
    (True, True)
    """
    e = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    scale = max(float(np.hypot(*load)), law.kn * 1e-6 ** law.exponent)
    k_floor = 1e-6 * law.kn * 1e-6 ** (law.exponent - 1.0)
    delta = np.zeros(2)
    for _ in range(max_iter):
        st = law.evaluate(offset + e @ delta)
        g = e.T @ st.inner_load - load
        if np.linalg.norm(g) <= 1e-12 * scale:
            break
        k = e.T @ ((np.maximum(st.stiffness, k_floor))[:, None] * e)
        step = -np.asarray(factorize(k, where="rigid-ring start").solve(g))
        size = np.abs(step).max()
        step *= min(1.0, 1e-5 / size) if size > 0 else 1.0  # at most 10 um a step
        delta = delta + step
    return delta


def solve_contacts(system: ContactSystem, *, tol: float = 1e-10, max_iter: int = 50,
                   stats: Stats | None = None) -> ContactSolution:
    """Equilibrium of the rings and rollers by Newton's method (module docstring).

    Parameters
    ----------
    system : ContactSystem
        Assembled problem.
    tol : float
        Converged when ``||r|| <= tol * max(||f||, ||C Q||)``, or when ``||r||`` is at the
        round-off level of ``K U`` (``16 eps || |K| |U| ||``: a soft support lets the
        rings translate far more than they deform, and the elastic forces of that
        translation cancel only to round-off).
    max_iter : int
        Newton iteration limit.
    stats : Stats, optional
        Counters (factorisations, solves, iterations, residual evaluations, rejected steps).

    Raises
    ------
    ConvergenceError
        When ``max_iter`` iterations do not reach ``tol``.
    """
    stats = stats if stats is not None else Stats()
    wb = _prepare(system, stats)
    u = np.array(system.initial, dtype=float)
    state = system.law.evaluate(system.approach(u))
    magnitude = abs(system.stiffness)
    history: list[float] = []
    steps: list[float] = []
    for iteration in range(max_iter + 1):
        r = system.residual(u, state)
        stats.residual_evaluations += 1
        scale = max(float(np.linalg.norm(system.load)),
                    float(np.linalg.norm(system.coupling @ state.inner_load)), 1e-300)
        history.append(float(np.linalg.norm(r)) / scale)
        floor = ROUNDOFF * float(np.linalg.norm(magnitude @ np.abs(u))) / scale
        if history[-1] <= max(tol, floor):
            return ContactSolution(u, system.approach(u), state, iteration, history[-1],
                                   tuple(history), tuple(steps))
        if iteration == max_iter:
            break
        stats.iterations += 1
        d = _newton_step(system, wb, r, state.stiffness, stats)
        alpha, u, state = _line_search(system, u, d, r, state, stats)
        steps.append(alpha)
    raise ConvergenceError(f"no convergence to tol {tol:g}", "ring FE Newton",
                           iteration=max_iter, residual=history[-1])
