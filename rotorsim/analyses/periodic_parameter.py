"""Periodic branches over a model parameter of the nonlinear elements (clearance, preload,
contact law, ...) at a fixed speed.

``periodic_parameter(rotor, vary, speed=W, start=a, stop=b)`` continues the periodic
response of :func:`rotorsim.periodic` in a scalar ``mu`` that changes the nonlinear elements:
``vary(mu)`` returns them (same nodes and kinds) for each value, e.g. the rolling bearings
with a radial clearance ``mu``. The harmonic-balance problem is that of ``rs.periodic`` at
the speed ``W`` (same unknowns, condensation and forcing), with the force callback switched
to the elements of ``mu`` (an assembly per value, cached) and the continuation parameter
``mu`` (``d R / d mu`` by central differences). The first point comes from ``rs.periodic``'s
start (Newton from the static solution, or a forcing homotopy) at ``mu = start``; folds and
branch points in ``mu`` are detected and located, and Floquet multipliers are computed at
every point as in ``rs.periodic`` (the parameter reaches the force callback).
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.periodic_branch import Stepping, first_point, unknown_scales
from rotorsim.analyses.periodic_excitation import plan_excitation
from rotorsim.analyses.periodic_output import (
    Recovery,
    bifurcation_records,
    branch_arrays,
    kept_dofs,
)
from rotorsim.analyses.periodic_problem import RotorForce, build_problem
from rotorsim.analyses.periodic_stability import DEFAULT_TOL, stability_model
from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.assembly.system import assemble
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.bifurcation import BifurcationOptions, detect_bifurcations
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.model.rotor import Rotor
from rotorsim.results.periodic import PeriodicResult
from rotorsim.solvers.continuation import continue_branch
from rotorsim.solvers.stats import Stats

WHERE = "periodic_parameter"


def periodic_parameter(
    rotor: Rotor,
    vary: Callable[[float], Sequence[Any]] | str,
    *,
    speed: float,
    start: float,
    stop: float,
    name: str = "parameter",
    harmonics: int = 10,
    samples: int | None = None,
    unbalance: Sequence[tuple[int, float, float]] = (),
    gravity: float | None = STANDARD_GRAVITY,
    direction: ArrayLike = (0.0, -1.0, 0.0),
    loads: Sequence[tuple[int, str, float]] = (),
    step: float | None = None,
    max_step: float = 0.05,
    max_points: int = 200,
    tol: float = 1e-10,
    nodes: Sequence[int] | None = None,
    bifurcations: bool = True,
    stability: str | None = "auto",
    checkpoint: str | os.PathLike[str] | None = None,
    checkpoint_every: int = 25,
    resume: str | os.PathLike[str] | None = None,
    progress: bool = False,
) -> PeriodicResult:
    """Branch of periodic responses over the model parameter ``mu`` (module docstring).

    Parameters
    ----------
    rotor : Rotor
        The rotor with its linear bearings (its own nonlinear elements are replaced).
    vary : callable or "forcing"
        ``vary(mu) -> nonlinear elements`` (same nodes and kinds for every ``mu``), or
        ``"forcing"``: ``mu`` is the fraction of the periodic forcing (unbalance, housing
        excitation; gravity is not scaled) and the rotor keeps its own elements.
    speed : float
        Fixed spin speed [rad/s].
    start, stop : float
        Range of ``mu`` (in its own units).
    name : str
        Name of ``mu`` (``result.parameter_name``), e.g. ``"radial clearance [m]"``.
    harmonics, samples, unbalance, gravity, direction, loads, nodes, bifurcations, progress
        As in :func:`rotorsim.periodic`.
    stability : {"auto", "hill", "hsu", "variational"} or None
        Floquet multipliers at every point (as in :func:`rotorsim.periodic`, with the
        parameter passed to the force); None skips them.
    checkpoint, checkpoint_every, resume
        As in :func:`~rotorsim.solvers.continuation.continue_branch` (the first point is
        recomputed identically on resume).
    step, max_step, max_points, tol
        Continuation in ``mu``: steps in the scaled parameter (range 1), point budget and
        corrector tolerance.

    Returns
    -------
    PeriodicResult
        ``parameter`` the values of ``mu``; ``speed`` and ``fundamental`` constant; no
        multipliers.

    Raises
    ------
    ModelError
        Bad input (a ``vary`` whose elements change nodes, a zero range, no forcing).
    ConvergenceError
        When the first point does not converge.
    """
    clock = time.perf_counter()
    forcing = isinstance(vary, str) and vary == "forcing"
    if not isinstance(rotor, Rotor) or not (forcing or callable(vary)):
        raise ModelError("needs a Rotor and vary: a callable vary(mu) -> nonlinear elements "
                         "or 'forcing'", WHERE)
    if not (np.isfinite(speed) and speed > 0 and np.isfinite(start) and np.isfinite(stop)
            and start != stop):
        raise ModelError(f"need a positive speed and a range start != stop, got {speed!r}, "
                         f"{start!r}, {stop!r}", WHERE)
    base_rotor = rotor if forcing else rotor.with_nonlinear(
        tuple(vary(float(start))))  # type: ignore[operator]
    system = assemble(base_rotor)
    if system.nonlinear is None:
        raise ModelError("vary(mu) returned no nonlinear elements", WHERE)
    stats = Stats()
    plan = plan_excitation(system.nonlinear.elements, unbalance=bool(unbalance), base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False)
    rp = build_problem(system, plan, speed0=float(speed), fixed_speed=None, phi0=0.0,
                       unbalance=list(unbalance), gravity=gravity, direction=direction,
                       loads=list(loads), base=None, stats=stats)
    omega = float(plan.order * speed)
    standard = make_residual(rp.problem, harmonics, samples=samples, condense=True)
    X0 = np.zeros((standard.aft.rows, rp.problem.n))
    X0[0] = rp.static[rp.active]
    x0 = first_point(standard, omega, standard.restrict(X0),
                     unknown_scales(system, rp, standard), tol, stats)
    # the HB parameter: mu itself, or p = 1 - mu (the rotor problem scales its forcing by 1 - p)
    to_p = (lambda mu: 1.0 - mu) if forcing else (lambda mu: mu)
    if forcing:
        residual = standard
        if float(start) != 1.0:
            x0 = solve_point(standard, omega, x0, param=to_p(float(start)), tol=tol).x
    else:
        residual = parametric_residual(rp, system, vary, harmonics,  # type: ignore[arg-type]
                                       samples, abs(float(stop) - float(start)))
    fun = continuation_function(residual, "param", omega=omega, stats=stats)
    stepping = Stepping(step, max_step, max_points, tol, None)
    options = stepping.options(to_p(float(start)), to_p(float(stop)),
                               unknown_scales(system, rp, residual, x0))
    branch = continue_branch(fun, x0, to_p(float(start)), options, checkpoint=checkpoint,
                             checkpoint_every=checkpoint_every, resume=resume,
                             progress=progress)
    events = list(detect_bifurcations(fun, branch, options=BifurcationOptions(
        kinds=("fold", "branch_point")))) if bifurcations and len(branch) > 1 else []
    recovery = Recovery(_AtOmega(residual, omega),  # type: ignore[arg-type]
                        *kept_dofs(system, rp, nodes))
    lam = np.asarray(to_p(branch.lam.astype(float)), dtype=float)
    multipliers, method = _multipliers(residual, branch, omega, stability)
    return PeriodicResult(
        parameter=lam, parameter_name=name, speed=np.full(lam.shape, float(speed)),
        fundamental=np.full(lam.shape, omega), order=plan.order,
        harmonics=residual.harmonics, samples=residual.samples, dofs=recovery.dofs,
        **branch_arrays(recovery, branch), multipliers=multipliers,
        stability_method=method, stability_tol=DEFAULT_TOL,
        bifurcations=bifurcation_records(events, recovery, to_p, None),
        iterations=branch.iterations.astype(np.int64), residuals=branch.residuals,
        approximation=plan.approximation, held_dofs=system.dof_map.free[rp.held],
        dof_map=system.dof_map, nodes_pos=np.asarray(system.nodes_pos, dtype=float),
        options={"parameter": name, "start": float(start), "stop": float(stop),
                 "speed": float(speed), "harmonics": int(harmonics),
                 "unbalance": [[float(v) for v in u] for u in unbalance]},
        stats={**branch.stats, "wall_time": time.perf_counter() - clock},
        status=branch.status, reason=branch.reason, summary=dict(system.summary))


def parametric_residual(rp: Any, system: Any, vary: Callable[[float], Sequence[Any]],
                        harmonics: int, samples: int | None, scale: float) -> Any:
    """The HB residual of ``rp`` with the full forcing and the nonlinear elements of
    ``vary(p)`` for the HB parameter ``p`` (``d/dp`` by central differences relative to
    ``scale``)."""
    template = rp.problem.force
    if not isinstance(template, RotorForce) or system.nonlinear is None:
        raise ModelError("the rotor has no nonlinear DOFs to vary", WHERE)
    force = _ParametricForce(template, vary, system.dof_map.full_to_free,
                             system.dof_map.n_nodes, system.nonlinear.dofs)
    loads_at_full = rp.loads
    problem = dataclasses.replace(rp.problem, force=force,
                                  excitation=lambda w, p: loads_at_full(w, 0.0),
                                  param_scale=float(scale))
    return make_residual(problem, harmonics, samples=samples, condense=True)


def _multipliers(residual: Any, branch: Any, omega: float, stability: str | None
                 ) -> tuple[Any, str]:
    """Floquet multipliers (P, 2 n_s) of every branch point (NaN where Floquet failed or
    Hill's selection returned fewer) and the method used."""
    if stability is None:
        return np.zeros((len(branch), 0), dtype=complex), "none"
    sm = stability_model(residual, stability, modes="auto", omega_max=omega,
                         tol=DEFAULT_TOL)
    out = np.full((len(branch), sm.size), np.nan + 0j)
    for i, (x, mu) in enumerate(zip(branch.x, branch.lam, strict=True)):
        try:
            values = np.asarray(sm.floquet(x, omega, float(mu)).multipliers)
        except (ModelError, ConvergenceError, np.linalg.LinAlgError):
            continue
        out[i, : min(values.size, sm.size)] = values[: sm.size]
    return out, sm.method


class _ParametricForce:
    """The rotor force callback with the nonlinear elements of ``vary(p)`` (cached)."""

    def __init__(self, template: RotorForce, vary: Callable[[float], Sequence[Any]],
                 full_to_free: Any, n_nodes: int, dofs: Any) -> None:
        self.template, self.vary = template, vary
        self.full_to_free, self.n_nodes, self.dofs = full_to_free, n_nodes, dofs
        self.cache: dict[float, RotorForce] = {}

    def _at(self, p: float) -> RotorForce:
        key = float(p)
        if key not in self.cache:
            if len(self.cache) > 64:
                self.cache.clear()
            assembly = NonlinearAssembly.build(tuple(self.vary(key)), self.full_to_free,
                                               self.n_nodes)
            if not np.array_equal(assembly.dofs, self.dofs):
                raise ModelError(f"vary({key!r}) changed the nonlinear DOFs: keep the nodes",
                                 WHERE)
            self.cache[key] = dataclasses.replace(self.template, assembly=assembly)
        return self.cache[key]

    def __call__(self, q: Any, v: Any, tau: Any, omega: float, param: float) -> Any:
        return self._at(param)(q, v, tau, omega, 0.0)


class _AtOmega:
    """A residual whose ``expand`` is evaluated at the fixed fundamental (recovery of the
    kept DOFs of a parameter branch)."""

    def __init__(self, residual: Any, omega: float) -> None:
        self.residual, self.omega = residual, omega

    @property
    def aft(self) -> Any:
        return self.residual.aft

    def expand(self, x: Any, lam: float) -> Any:
        return self.residual.expand(x, self.omega, lam)
