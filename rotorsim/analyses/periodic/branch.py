"""Start and continuation of a rotor's periodic branch.

:func:`first_point` finds the periodic solution at the first parameter value: damped Newton
from the static equilibrium (harmonic 0), or, if that fails (a large response near a
resonance), a continuation of the periodic forcing from zero to its full value at fixed
frequency (the HB parameter ``p`` removes the fraction ``p`` of the forcing, see
:class:`~rotorsim.analyses.periodic.problem.PeriodicLoads`). :func:`start_branch` then
prepares its continuation in ``omega`` (:meth:`BranchStart.trace`). Unknowns are scaled
per DOF (:func:`unknown_scales`), the residual by its Jacobian row norms, and the
parameter by its range, so the default steps are dimensionless fractions of the range. A
branch that ends short of its end is not OK (:func:`judged`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.problem import RotorPeriodicProblem
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.errors import ConvergenceError, Status
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers.continuation import (
    Branch,
    Continuation,
    continue_branch,
    run_config,
)
from rotorsim.solvers.stats import Stats

WHERE = "periodic"

STALL_TOL = 1e-6
"""Scaled residual (force imbalance relative to the typical force) at which a stalled
corrector is accepted (:class:`~rotorsim.solvers.continuation.Continuation` ``stall_tol``):
rolling elements with contact damping make the HB residual non-Lipschitz where a sample
meets the contact onset; 1e-6 is far below the truncation error of any practical ``H``."""


@dataclass(frozen=True)
class Stepping:
    """Continuation settings of the periodic verbs (their
    :class:`~rotorsim.options.ContinuationOptions`: ``step``, ``max_step``, ``max_points``
    and ``tol``, or a full ``given`` solver Continuation with ``tol`` for the first point)."""

    step: float | None
    max_step: float | None
    max_points: int | None
    tol: float
    given: Continuation | None = None

    def options(self, lam0: float, lam1: float, x_scale: FloatArray) -> Continuation:
        """Continuation options: bounds and direction from ``lam0 -> lam1``, the scaled
        parameter range 1; a given ``Continuation`` keeps its scales unless default."""
        span = abs(lam1 - lam0)
        lo, hi, direction = min(lam0, lam1), max(lam0, lam1), 1 if lam1 > lam0 else -1
        if self.given is not None:
            defaults = Continuation()
            xs = tuple(x_scale) if self.given.x_scale == defaults.x_scale \
                else self.given.x_scale
            ls = span if self.given.lam_scale == defaults.lam_scale else self.given.lam_scale
            return dataclasses.replace(self.given, lam_min=lo, lam_max=hi,
                                       direction=direction, x_scale=xs, lam_scale=ls)
        assert self.max_step is not None and self.max_points is not None
        first = min(self.step if self.step is not None else 0.25 * self.max_step,
                    self.max_step)
        return Continuation(initial_step=first, max_step=self.max_step,
                            min_step=min(1e-6, first), max_points=self.max_points,
                            tol=self.tol, x_scale=tuple(x_scale), r_scale="auto",
                            lam_scale=span, lam_min=lo, lam_max=hi, direction=direction,
                            relative_step=True, stall_tol=max(self.tol, STALL_TOL))


def unknown_scales(system: RotorSystem, rp: RotorPeriodicProblem, residual: HBResidual,
                   x: FloatArray | None = None) -> FloatArray:
    """Scale of each HB unknown, the same in every harmonic: for translations the largest
    ``|value|`` of a translation among the unknowns' DOFs in the static solution and, when
    given, in the periodic solution ``x`` (at least 1 nm; 1 um when all are zero); for
    rotations the largest rotation, at least the translation scale over the rotor length."""
    pb = rp.problem
    cols = pb.nl_dofs if residual.dofs.size == pb.k else np.arange(pb.n)
    local = system.dof_map.free[rp.active[cols]] % DOFS_PER_NODE
    q = np.abs(rp.static[rp.active[cols]])
    if x is not None:
        q = np.maximum(q, np.abs(np.asarray(x).reshape(residual.aft.rows, -1)).max(axis=0))
    trans = float(np.max(q[local < 3], initial=0.0))
    trans = max(trans, 1e-9) if trans > 0 else 1e-6
    span = float(np.ptp(system.nodes_pos)) or 1.0
    rot = max(float(np.max(q[local >= 3], initial=0.0)), trans / span)
    per_dof = np.where(local < 3, trans, rot)
    return np.tile(per_dof, residual.aft.rows)


@dataclass(frozen=True, eq=False)
class BranchStart:
    """The first point ``x0`` at ``lam0`` of a branch towards ``lam1``, its continuation
    function and options, and :attr:`identity` of the run (what a checkpoint or a results
    file of the same run must match)."""

    fun: Any
    x0: FloatArray
    lam0: float
    lam1: float
    options: Continuation

    @property
    def identity(self) -> dict[str, Any]:
        """Size and hash of the start (:func:`~rotorsim.solvers.continuation.run_config`
        without the options, which the result stores in full)."""
        config = run_config(self.options, self.x0, self.lam0)
        return {"m": config["m"], "start": config["start"]}

    def trace(self, unit: Any = None, **driver: Any) -> Branch:
        """Continue towards ``lam1`` (``driver``: checkpoint, resume, progress, ...); a
        branch short of ``lam1`` is not OK (:func:`judged`, ``unit`` formats its reason)."""
        branch = continue_branch(self.fun, self.x0, self.lam0, self.options, **driver)
        return judged(branch, self.lam1, unit)


def start_branch(residual: HBResidual, system: RotorSystem, rp: RotorPeriodicProblem,
                 lam0: float, lam1: float, stepping: Stepping, stats: Stats) -> BranchStart:
    """Static start -> first point at ``lam0`` -> continuation options towards ``lam1``
    (the scales come from the static and the first solution; recomputed identically on
    resume)."""
    X0 = np.zeros((residual.aft.rows, rp.problem.n))
    X0[0] = rp.static[rp.active]
    x0 = residual.restrict(X0)
    x0 = first_point(residual, lam0, x0, unknown_scales(system, rp, residual), stepping.tol,
                     stats)
    opts = stepping.options(lam0, lam1, unknown_scales(system, rp, residual, x0))
    fun = continuation_function(residual, "omega", stats=stats, terms=True)
    return BranchStart(fun, x0, float(lam0), float(lam1), opts)


def reached(branch: Branch, end: float) -> bool:
    """Whether the branch's last point is on ``end`` (to the corrector's tolerance on the
    parameter, at least 1e-9 of the range)."""
    span = abs(end - float(branch.lam[0])) or 1.0
    return abs(float(branch.lam[-1]) - end) <= max(1e-9, 10.0 * branch.options.tol) * span


def judged(branch: Branch, end: float, unit: Any = None) -> Branch:
    """The branch with an honest status: one that ended short of ``end`` (``max_points``
    used up, a fold back to the start, a closed loop, a point on the bound that did not
    converge, a step below ``min_step``) is NOT_CONVERGED (or its failure status) with a
    reason that says where it stopped; ``unit(lam) -> str`` formats parameter values."""
    if reached(branch, end):
        return branch
    show = unit or (lambda v: f"{v:.6g}")
    status = Status.NOT_CONVERGED if branch.status == Status.OK else branch.status
    reason = (f"incomplete: the branch ended at {show(float(branch.lam[-1]))}, short of "
              f"its end {show(end)} ({branch.reason}). {advice(branch)}")
    return dataclasses.replace(branch, status=status, reason=reason)


def advice(branch: Branch) -> str:
    """What a user can change after a branch stopped for ``branch.reason``."""
    why = branch.reason
    if "max_points" in why:
        return ("Raise ContinuationOptions(max_points=...), or max_step for a smooth "
                "branch, or continue from this result (checkpoint=...).")
    if "closed loop" in why:
        return "The branch is an isola: it closed on its first point."
    if "did not converge" in why or "step size below" in why:
        turned = int(np.sum(np.diff(np.sign(branch.tangents[:, -1])) != 0))
        folds = f" after {turned} turns of the branch" if turned else ""
        return (f"The corrector failed{folds}: a contact that opens or closes between "
                "samples is the usual cause. Try more samples (Harmonics(samples=...), "
                "e.g. 4x the harmonics), more harmonics, a smaller ContinuationOptions("
                "max_step=...), or start a new branch just beyond this point.")
    if "evaluation failed" in why or "not finite" in why:
        return ("The residual could not be evaluated there (a singular linear block or "
                "an invalid bearing state): check the model near this parameter.")
    return ""


def first_point(residual: HBResidual, lam0: float, x0: FloatArray, x_scale: FloatArray,
                tol: float, stats: Stats) -> FloatArray:
    """Solution at ``lam0``: damped Newton from the static solution ``x0``; if it fails,
    continuation of the periodic forcing from 0 (``p = 1``, solved from ``x0``) to its full
    value (``p = 0``) at fixed ``lam0``.

    Raises
    ------
    ConvergenceError
        When neither reaches the full forcing.
    """
    ev = residual.evaluate(x0, lam0)
    assert ev.jacobian is not None
    rows = np.max(np.abs(ev.jacobian) * x_scale[None, :], axis=1)
    r_scale = np.where(rows > 0, rows, float(np.max(rows, initial=0.0)) or 1.0)
    try:
        sol = solve_point(residual, lam0, x0, x_scale=x_scale, r_scale=r_scale, tol=tol)
        stats.iterations += int(sol.stats["iterations"])
        return sol.x
    except ConvergenceError as direct:
        failure = direct
    unforced = solve_point(residual, lam0, x0, param=1.0, x_scale=x_scale, r_scale=r_scale,
                           tol=tol)
    homotopy = Continuation(direction=-1, lam_min=0.0, lam_max=1.0, max_step=0.1,
                            max_points=400, tol=tol, x_scale=tuple(x_scale),
                            r_scale=tuple(r_scale), relative_step=True,
                            stall_tol=max(STALL_TOL, tol))
    fun = continuation_function(residual, "param", omega=lam0, stats=stats,
                                terms=True)
    branch = continue_branch(fun, unforced.x, 1.0, homotopy)
    if not reached(branch, 0.0):
        raise ConvergenceError(f"no periodic solution found at the start: Newton from the "
                               f"static solution failed ({failure}) and the forcing "
                               f"homotopy stopped at {1 - branch.lam[-1]:.3g} of the forcing "
                               f"({branch.reason})", WHERE)
    stats.iterations += int(branch.stats["iterations"])
    return np.asarray(branch.x[-1])
