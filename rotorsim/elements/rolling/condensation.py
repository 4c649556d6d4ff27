"""Batched inner Newton on internal DOFs and static condensation (seed 001 eqs 20-26).

Many small independent systems (one per rolling element and sample) each have a potential
``Pi(y, z)`` in ``m`` internal DOFs ``y`` and ``e`` external (master) DOFs ``z``. For given
``z`` the internal DOFs sit at a minimum of ``Pi``, ``dPi/dy = 0`` (eq 22). Eliminating
them gives the condensed potential ``Pi*(z) = Pi(y*(z), z)`` whose gradient and Hessian are
(eqs 23-26, with ``g = dPi/d(y, z)`` and ``H`` its Hessian)::

    g*  = g_z - H_zy H_yy^-1 g_y          (eq 25: P_local = P_ext - K_rr^T K_roll^-1 P_roll)
    H*  = H_zz - H_zy H_yy^-1 H_yz        (eq 26: the Schur complement)

``g_y`` vanishes at convergence; keeping the term makes ``g*`` accurate to second order in
the inner residual.

:class:`InnerNewton` minimises all systems at once: Newton steps from a modified
(pivot-floored) LDL^T factorisation of ``H_yy`` (:func:`cholesky_solve`), a per-system step
cap and a backtracking (Armijo) line search on ``Pi``. Only the systems still iterating are
evaluated; the Python loops run over iterations and the few DOFs of a system, never over
systems.

Layout: the system index is the **last** axis of every array (``grad (a, M)``,
``hess (a, a, M)``, ``y (m, M)``), so that each entry of the small matrices is one
contiguous vector over the systems.

Everything here is model-agnostic: the flexible-ring roller
(:mod:`~rotorsim.elements.rolling.flexible_ring.roller`) supplies the potential.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]


class LocalProblem(NamedTuple):
    """Potential of ``M`` systems and its derivatives in all ``a = m + e`` DOFs (internal
    first), systems on the last axis.

    Attributes
    ----------
    energy : array (M,)
        ``Pi`` [J].
    grad : array (a, M)
        ``dPi/d(y, z)``.
    hess : array (a, a, M)
        Hessian of ``Pi`` (symmetric).
    scale : array (M,)
        Force scale [N] of each system for the convergence test (e.g. its contact loads).
    aux : array (q, M)
        Model quantities carried along with the solution (e.g. contact loads).
    """

    energy: FloatArray
    grad: FloatArray
    hess: FloatArray
    scale: FloatArray
    aux: FloatArray


Evaluate = Callable[[FloatArray, IntArray], LocalProblem]
"""``evaluate(y, index)``: the systems ``index`` (A,) at internal DOFs ``y`` (m, A)."""


@dataclass(frozen=True)
class InnerNewtonStats:
    """Cost and outcome of one batched inner solve.

    Attributes
    ----------
    iterations : int
        Newton iterations of the slowest system.
    system_iterations : int
        Newton iterations summed over all systems.
    evaluations : int
        System evaluations (starting points, Newton points and line-search trials).
    backtracks : int
        Line-search step halvings.
    failures : int
        Systems not converged.
    systems : int
        Number of systems ``M``.
    """

    iterations: int = 0
    system_iterations: int = 0
    evaluations: int = 0
    backtracks: int = 0
    failures: int = 0
    systems: int = 0


@dataclass(frozen=True, eq=False)
class InnerSolution:
    """Outcome of :meth:`InnerNewton.solve`: ``y`` (m, M), the problem at ``y``, the
    per-system convergence flag, the scaled residual (M,) and the cost counters."""

    y: FloatArray
    local: LocalProblem
    converged: BoolArray
    residual: FloatArray
    stats: InnerNewtonStats


def cholesky_solve(matrix: FloatArray, rhs: FloatArray, floor: FloatArray) -> FloatArray:
    """Solve ``A x = b`` for ``M`` small symmetric matrices by a modified LDL^T factorisation.

    Pivots below ``floor`` (a positive stiffness per DOF) are raised to it: for a positive
    definite ``A`` with pivots above the floor the solution is exact; a singular or
    indefinite ``A`` (a roller touching neither ring) is replaced by a positive definite
    one, so that ``-A^-1 g`` is a descent direction. Unrolled over the ``m`` DOFs,
    vectorised over the systems.

    Parameters
    ----------
    matrix : array (m, m, M)
    rhs : array (m, r, M)
    floor : array (m,) or (m, M)
        Smallest admissible pivot of each DOF.

    Returns
    -------
    array (m, r, M)

    Examples
    --------
    >>> a = np.array([[4.0, 2.0], [2.0, 3.0]])[:, :, None]
    >>> x = cholesky_solve(a, np.array([[2.0], [1.0]])[:, :, None], np.full(2, 1e-12))
    >>> x.ravel().tolist()
    [0.5, 0.0]
    """
    m = matrix.shape[0]
    fl = np.asarray(floor, dtype=float)
    fl = fl[:, None] if fl.ndim == 1 else fl
    low: list[list[FloatArray]] = [[] for _ in range(m)]  # low[i][k] = L_ik, k < i
    ld: list[list[FloatArray]] = [[] for _ in range(m)]  # ld[i][k] = L_ik D_k
    piv: list[FloatArray] = []
    for j in range(m):
        d = np.array(matrix[j, j])
        for k in range(j):
            d -= low[j][k] * ld[j][k]
        piv.append(np.maximum(d, fl[j]))
        for i in range(j + 1, m):
            c = np.array(matrix[i, j])
            for k in range(j):
                c -= low[i][k] * ld[j][k]
            low[i].append(c / piv[j])
            ld[i].append(c)
    x = [np.array(rhs[i]) for i in range(m)]  # each (r, M)
    for i in range(m):  # forward: L w = b
        for k in range(i):
            x[i] -= low[i][k] * x[k]
    for i in range(m):
        x[i] /= piv[i]
    for i in range(m - 1, -1, -1):  # backward: L^T x = w / D
        for k in range(i + 1, m):
            x[i] -= low[k][i] * x[k]
    return np.stack(x)


def condense(local: LocalProblem, n_internal: int, floor: FloatArray
             ) -> tuple[FloatArray, FloatArray]:
    """Condensed gradient ``g*`` (e, M) and Hessian ``H*`` (e, e, M) (eqs 25-26).

    Parameters
    ----------
    local : LocalProblem
        Gradient and Hessian in all DOFs, internal first.
    n_internal : int
        ``m``.
    floor : array (m,) or (m, M)
        Pivot floor of :func:`cholesky_solve` (only reached where ``H_yy`` is singular,
        where the coupling ``H_zy`` then vanishes too).

    Examples
    --------
    Springs of stiffness 2 (internal DOF to ground) and 1 (internal DOF to ``z``) in
    series, a force 1 on ``z``: seen from ``z`` the stiffness is 2/3.

    >>> h = np.array([[3.0, -1.0], [-1.0, 1.0]])[:, :, None]
    >>> loc = LocalProblem(np.zeros(1), np.array([[0.0], [1.0]]), h, np.ones(1),
    ...                    np.zeros((0, 1)))
    >>> g, k = condense(loc, 1, np.full(1, 1e-12))
    >>> round(float(g[0, 0]), 12), round(float(k[0, 0, 0]), 12)
    (1.0, 0.666666666667)
    """
    m = n_internal
    h = local.hess
    h_yz = h[:m, m:]  # (m, e, M)
    rhs = np.concatenate([h_yz, local.grad[:m, None, :]], axis=1)
    sol = cholesky_solve(h[:m, :m], rhs, floor)  # (m, e + 1, M)
    g_star = local.grad[m:] - np.einsum("jiM,jM->iM", h_yz, sol[:, -1])
    h_star = h[m:, m:] - np.einsum("jiM,jkM->ikM", h_yz, sol[:, :-1])
    return g_star, 0.5 * (h_star + np.swapaxes(h_star, 0, 1))


@dataclass(frozen=True)
class InnerNewton:
    """Options of the batched Newton minimisation of many small potentials.

    Parameters
    ----------
    tol : float
        A system is converged when ``max_j |g_j| r_j <= tol * ref`` (``r_j`` the
        residual scale of DOF ``j``, ``ref`` the largest force scale of the systems of its
        group, e.g. of all rollers of one sample).
    max_iter : int
        Newton iteration limit.
    max_backtracks : int
        Step halvings of the line search before a system is declared failed.
    """

    tol: float = 1e-10
    max_iter: int = 50
    max_backtracks: int = 40

    def __post_init__(self) -> None:
        if not (isinstance(self.tol, float | int) and 0.0 < self.tol < 1e-2):
            raise ModelError(f"tol must be in (0, 1e-2), got {self.tol!r}", "InnerNewton")
        for name in ("max_iter", "max_backtracks"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ModelError(f"{name} must be an integer >= 1, got {value!r}",
                                 "InnerNewton")

    def solve(self, evaluate: Evaluate, y0: FloatArray, group_size: int,
              residual_scale: FloatArray, max_step: FloatArray, floor: FloatArray,
              force_floor: float) -> InnerSolution:
        """Minimise ``Pi`` over the internal DOFs of ``M`` systems, all at once.

        Parameters
        ----------
        evaluate : callable
            :data:`Evaluate`.
        y0 : array (m, M)
            Starting internal DOFs.
        group_size : int
            Systems ``g * group_size ... (g + 1) * group_size - 1`` form group ``g`` (the
            rolling elements of one sample); ``M`` is a multiple of it.
        residual_scale : array (m,)
            Converts each gradient component to a force [N] (e.g. 1/length for a moment).
        max_step : array (m,) or (m, M)
            Longest Newton step of each DOF (of each system).
        floor : array (m,)
            Pivot floor of :func:`cholesky_solve` [N/m or N m].
        force_floor : float
            Smallest reference force [N] of a group.

        Examples
        --------
        >>> def quartic(y, index):  # Pi = y^4/4 + y^2/2 - y, minimum at y = 0.6823
        ...     return LocalProblem((y**4 / 4 + y**2 / 2 - y)[0], y**3 + y - 1.0,
        ...                         (3 * y**2 + 1.0)[None], np.ones(y.shape[1]),
        ...                         np.zeros((0, y.shape[1])))
        >>> sol = InnerNewton(tol=1e-12).solve(quartic, np.zeros((1, 3)), 3, np.ones(1),
        ...                                    np.ones(1), np.full(1, 1e-9), 1.0)
        >>> sol.y.round(6).tolist(), sol.stats.iterations, sol.stats.failures
        ([[0.682328, 0.682328, 0.682328]], 6, 0)
        """
        y = np.array(y0, dtype=float)
        m, n_sys = y.shape
        cap_all = np.broadcast_to(np.asarray(max_step, dtype=float).reshape(m, -1), (m, n_sys))
        scale = np.asarray(residual_scale, dtype=float)[:, None]
        every = np.arange(n_sys)
        local = evaluate(y, every)
        converged = np.zeros(n_sys, dtype=bool)
        failed = np.zeros(n_sys, dtype=bool)
        counts = {"evaluations": n_sys, "backtracks": 0, "system_iterations": 0}
        iterations = 0
        while True:
            ref = np.maximum(local.scale.reshape(-1, group_size).max(axis=1), force_floor)
            ref = np.repeat(ref, group_size)
            residual = np.abs(local.grad[:m] * scale).max(axis=0) / ref
            converged |= residual <= self.tol
            active = np.flatnonzero(~(converged | failed))
            if active.size == 0 or iterations == self.max_iter:
                break
            iterations += 1
            counts["system_iterations"] += active.size
            # with most systems active, stepping all is cheaper than gathering the active
            # ones (a converged system takes a step of round-off size)
            whole = active.size > 0.7 * n_sys and not failed.any()
            if whole:
                active = every
            sub = local if whole else _take(local, active)
            step = -cholesky_solve(sub.hess[:m, :m], sub.grad[:m, None], floor)[:, 0]
            cap = cap_all if whole else cap_all[:, active]
            size = np.abs(step / cap).max(axis=0)
            step *= np.minimum(1.0, 1.0 / np.where(size > 0.0, size, 1.0))
            y_old = y if whole else y[:, active]
            y_new, trial, ok = self._line_search(evaluate, active, y_old, sub, step,
                                                 ref[active], counts)
            tiny = np.abs(y_new - y_old) <= 4e-16 * np.abs(y_new) + 1e-15 * cap
            stuck = ~ok | tiny.all(axis=0)
            if whole:
                y, local = y_new, trial
            else:
                y[:, active] = y_new
                _put(local, active, trial)
            # round-off floor: no progress at a small residual is as good as it gets
            small = residual[active] <= 1e3 * self.tol
            converged[active] |= stuck & small
            failed[active] |= stuck & ~small
        stats = InnerNewtonStats(iterations, counts["system_iterations"],
                                 counts["evaluations"], counts["backtracks"],
                                 int((~converged).sum()), n_sys)
        return InnerSolution(y, local, converged, residual, stats)

    def _line_search(self, evaluate: Evaluate, active: IntArray, y: FloatArray,
                     local: LocalProblem, step: FloatArray, ref: FloatArray,
                     counts: dict[str, int]) -> tuple[FloatArray, LocalProblem, BoolArray]:
        """Armijo backtracking along ``step``; systems without descent keep their point."""
        slope = np.einsum("jM,jM->M", local.grad[:y.shape[0]], step)
        slack = 1e-12 * ref * np.abs(step).max(axis=0) + 1e-14 * np.abs(local.energy)
        t = np.ones(y.shape[1])
        trial = evaluate(y + step, active)
        counts["evaluations"] += active.size
        ok = trial.energy <= local.energy + 1e-4 * slope + slack
        for _ in range(self.max_backtracks):
            if ok.all():
                break
            redo = np.flatnonzero(~ok)
            t[redo] *= 0.5
            again = evaluate(y[:, redo] + t[redo] * step[:, redo], active[redo])
            counts["evaluations"] += redo.size
            counts["backtracks"] += redo.size
            _put(trial, redo, again)
            ok = trial.energy <= local.energy + 1e-4 * t * slope + slack
        bad = np.flatnonzero(~ok)
        if bad.size:
            t[bad] = 0.0
            _put(trial, bad, _take(local, bad))
        return y + t * step, trial, ok


def _take(local: LocalProblem, index: IntArray) -> LocalProblem:
    return LocalProblem(*(a[..., index] for a in local))


def _put(local: LocalProblem, index: IntArray, values: LocalProblem) -> None:
    """Write ``values`` into ``local`` at the systems ``index`` (in place: the arrays are
    the solver's own)."""
    for a, b in zip(local, values, strict=True):
        a[..., index] = b
