"""Periodic branches over a model parameter at a fixed speed: a parameter of the nonlinear
elements (clearance, preload, contact law), of the linear part (a damper coefficient, a
bearing stiffness, a disk), a static point load, or the forcing amplitude.

``periodic_parameter(rotor, vary, speed=W, start=a, stop=b)`` continues the periodic
response of :func:`rotorsim.periodic` in a scalar ``mu``:

* ``vary(mu)`` returns the nonlinear elements (same nodes and kinds) or a whole
  :class:`~rotorsim.model.rotor.Rotor` (same nodes, constraints and nonlinear DOFs) for each
  value; the harmonic-balance residual at ``mu`` is built as described in
  :mod:`~rotorsim.analyses.periodic.variation` (``d R / d mu`` by central differences);
* ``vary="loads"``: ``mu`` multiplies the static point loads ``loads`` (gravity stays);
* ``vary="forcing"``: ``mu`` is the fraction of the periodic forcing (unbalance, housing
  excitation).

The HB problem is that of ``rs.periodic`` at the speed ``W`` (same unknowns, condensation
and forcing). The first point comes from ``rs.periodic``'s start (Newton from the static
solution, or a forcing homotopy) at ``mu = start``; folds and branch points in ``mu`` are
detected and located, and Floquet multipliers are computed at every point as in
``rs.periodic`` (on the rotor of each ``mu`` when the linear part varies).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.periodic.arguments import PeriodicDefaults, periodic_options
from rotorsim.analyses.periodic.branch import first_point, judged, unknown_scales
from rotorsim.analyses.periodic.events import floquet_events
from rotorsim.analyses.periodic.excitation import plan_excitation
from rotorsim.analyses.periodic.output import (
    Recovery,
    bifurcation_records,
    branch_arrays,
    kept_dofs,
)
from rotorsim.analyses.periodic.problem import build_problem, check_discretization, spool_ratio
from rotorsim.analyses.periodic.stability import DEFAULT_TOL, stability_model
from rotorsim.analyses.periodic.variation import (
    RotorFamilyResidual,
    parametric_residual,
    static_load_residual,
)
from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.bifurcation import BifurcationOptions, detect_bifurcations
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.model.rotor import Rotor
from rotorsim.options import (
    Checkpointing,
    ContinuationOptions,
    Excitation,
    Harmonics,
    Output,
    StabilityOptions,
)
from rotorsim.results.periodic import PeriodicResult
from rotorsim.solvers.continuation import continue_branch
from rotorsim.solvers.stats import Stats

WHERE = "periodic_parameter"


DEFAULTS = PeriodicDefaults(
    continuation=ContinuationOptions(max_step=0.05, max_points=200),
    stability=StabilityOptions(tol=DEFAULT_TOL), checkpoint=Checkpointing(every=25),
    unused={"harmonics": ("fundamental", "condense"), "excitation": ("base", "forces"),
            "stability": ("modes", "tol"),
            "output": ("every", "times", "rolling_elements", "velocities",
                       "reducers", "after")})
"""Defaults of the group fields left at None, and the fields ``periodic_parameter`` does
not use."""


@checked_keywords
def periodic_parameter(
    rotor: Rotor,
    vary: Callable[[float], Any] | str,
    *,
    speed: float,
    start: float,
    stop: float,
    name: str = "parameter",
    harmonics: int | Harmonics = 10,
    unbalance: Sequence[tuple[int, float, float]] = (),
    excitation: Excitation | None = None,
    continuation: ContinuationOptions | None = None,
    stability: str | StabilityOptions | None = "auto",
    nodes: Sequence[int] | None = None,
    output: Output | None = None,
    checkpoint: str | os.PathLike[str] | Checkpointing | None = None,
) -> PeriodicResult:
    """Branch of periodic responses over the model parameter ``mu`` (module docstring).

    Parameters
    ----------
    rotor : Rotor
        The rotor (its nonlinear elements are replaced when ``vary`` returns elements, the
        whole rotor when it returns a Rotor).
    vary : callable, "loads" or "forcing"
        ``vary(mu) -> nonlinear elements`` (same nodes and kinds for every ``mu``),
        ``vary(mu) -> Rotor`` (any parameter of the linear or nonlinear part; same nodes,
        constraints and nonlinear DOFs), ``"loads"``: ``mu`` multiplies the point loads
        ``loads`` (e.g. ``loads=[(node, "uy", -1.0)]`` makes ``mu`` a downward force [N];
        gravity is not scaled), or ``"forcing"``: ``mu`` is the fraction of the periodic
        forcing (unbalance, housing excitation; gravity is not scaled).
    speed : float
        Fixed spin speed [rad/s].
    start, stop : float
        Range of ``mu`` (in its own units).
    name : str
        Name of ``mu`` (``result.parameter_name``), e.g. ``"radial clearance [m]"``.
    harmonics, unbalance, nodes, output
        As in :func:`rotorsim.periodic` (``output``: kept nodes and the progress bar).
    excitation : Excitation, optional
        Gravity and its direction, point loads, unbalance (no ``base`` motion, no
        ``forces``), as in :func:`rotorsim.periodic`.
    continuation : ContinuationOptions, optional
        Continuation in ``mu``: steps in the scaled parameter (range 1; default
        ``max_step=0.05``), point budget (default 200) and corrector tolerance.
    stability : {"auto", "hill", "hsu", "variational"}, None or StabilityOptions
        Floquet multipliers at every point (as in :func:`rotorsim.periodic`, with the
        parameter passed to the force; always the default stability model and
        tolerance); None skips them. ``StabilityOptions(bifurcations=False)`` skips
        the bifurcations.
    checkpoint : path or Checkpointing, optional
        As in :func:`~rotorsim.solvers.continuation.continue_branch` (the first point is
        recomputed identically on resume; default 25 points between checkpoints).

    Returns
    -------
    PeriodicResult
        ``parameter`` the values of ``mu``; ``speed`` and ``fundamental`` constant;
        Floquet multipliers unless ``stability=None``.

    Raises
    ------
    ModelError
        Bad input (a ``vary`` that changes nodes, constraints, nonlinear DOFs or
        varying-compliance orders; a zero range; no forcing; ``"loads"`` without loads).
    ConvergenceError
        When the first point does not converge.
    """
    clock = time.perf_counter()
    opts = periodic_options(WHERE, DEFAULTS, harmonics=harmonics, unbalance=unbalance,
                            excitation=excitation, continuation=continuation,
                            stability=stability, nodes=nodes, output=output,
                            checkpoint=checkpoint)
    h, e, c, ck = opts.harmonics, opts.excitation, opts.continuation, opts.checkpoint
    unbalance, loads, tol = e.unbalance, e.loads, c.tol
    mode = vary if isinstance(vary, str) else "model"
    if not isinstance(rotor, Rotor) or mode not in ("model", "loads", "forcing") \
            or not (mode != "model" or callable(vary)):
        raise ModelError("needs a Rotor and vary: a callable vary(mu) -> nonlinear elements "
                         "or Rotor, 'loads' or 'forcing'", WHERE)
    if not (np.isfinite(speed) and speed > 0 and np.isfinite(start) and np.isfinite(stop)
            and start != stop):
        raise ModelError(f"need a positive speed and a range start != stop, got {speed!r}, "
                         f"{start!r}, {stop!r}", WHERE)
    if mode == "loads" and not any(float(v) for _, _, v in loads):
        raise ModelError("vary='loads' needs nonzero point loads (node, dof, value)", WHERE)
    first = vary(float(start)) if callable(vary) else rotor
    base_rotor = first if isinstance(first, Rotor) else rotor.with_nonlinear(tuple(first))
    system = assemble(base_rotor)
    if system.nonlinear is None:
        raise ModelError(f"the rotor at {name} = {start!r} has no nonlinear elements", WHERE)
    stats = Stats()
    plan = plan_excitation(system.nonlinear.elements, unbalance=bool(unbalance), base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False,
                           unbalance_ratio=spool_ratio(system, list(unbalance)))
    harmonics, samples = h.count, h.samples
    check_discretization(harmonics, samples, plan, system, True, WHERE)
    scaled = [(n, d, float(start) * v) for n, d, v in loads] if mode == "loads" else loads
    rp = build_problem(system, plan, speed0=float(speed), fixed_speed=None, phi0=0.0,
                       unbalance=list(unbalance), gravity=e.gravity, direction=e.direction,
                       loads=list(scaled), base=None, stats=stats)
    omega = float(plan.order * speed)
    standard = make_residual(rp.problem, harmonics, samples=samples, condense=True)
    X0 = np.zeros((standard.aft.rows, rp.problem.n))
    X0[0] = rp.static[rp.active]
    x0 = first_point(standard, omega, standard.restrict(X0),
                     unknown_scales(system, rp, standard), tol, stats)
    # the HB parameter: mu itself, or p = 1 - mu (the rotor problem scales its forcing by 1 - p)
    to_p = (lambda mu: 1.0 - mu) if mode == "forcing" else (lambda mu: mu)
    residual, x0 = _branch_residual(mode, standard, rp, system, vary, loads, harmonics,
                                    samples, float(start), float(stop), omega, x0, tol)
    fun = continuation_function(residual, "param", omega=omega, stats=stats, terms=True)
    stepping = opts.stepping()
    options = stepping.options(to_p(float(start)), to_p(float(stop)),
                               unknown_scales(system, rp, residual, x0))
    branch = judged(continue_branch(fun, x0, to_p(float(start)), options,
                                    checkpoint=ck.path, checkpoint_every=opts.checkpoint_every,
                                    resume=ck.resume, progress=opts.output.progress),
                    to_p(float(stop)), lambda p: f"{name} {to_p(p):.6g}")
    recovery = Recovery(_AtOmega(residual, omega),  # type: ignore[arg-type]
                        *kept_dofs(system, rp, opts.output.nodes))
    lam = np.asarray(to_p(branch.lam.astype(float)), dtype=float)
    floquet, multipliers, events = _stability(fun, branch, residual, omega,
                                              opts.stability.method,
                                              opts.stability.bifurcations)
    return PeriodicResult(
        parameter=lam, parameter_name=name, speed=np.full(lam.shape, float(speed)),
        fundamental=np.full(lam.shape, omega), order=plan.order,
        harmonics=residual.harmonics, samples=residual.samples, dofs=recovery.dofs,
        **branch_arrays(recovery, branch), peaks=(), multipliers=multipliers,
        stability_method=floquet.method if floquet is not None else "none",
        stability_tol=DEFAULT_TOL,
        bifurcations=bifurcation_records(events, recovery, to_p, floquet),
        iterations=branch.iterations.astype(np.int64), residuals=branch.residuals,
        approximation=plan.approximation, held_dofs=system.dof_map.free[rp.held],
        dof_map=system.dof_map, nodes_pos=np.asarray(system.nodes_pos, dtype=float),
        options={"parameter": name, "vary": mode, "start": float(start),
                 "stop": float(stop), "speed": float(speed), "harmonics": int(harmonics),
                 "unbalance": [[float(v) for v in u] for u in unbalance]},
        stats={**branch.stats, "wall_time": time.perf_counter() - clock},
        status=branch.status, reason=branch.reason, summary=dict(system.summary))


def _branch_residual(mode: str, standard: Any, rp: Any, system: RotorSystem, vary: Any,
                     loads: Sequence[tuple[int, str, float]], harmonics: int,
                     samples: int | None, start: float, stop: float, omega: float,
                     x0: Any, tol: float) -> tuple[Any, Any]:
    """The residual continued in the parameter (``"forcing"``: the standard one in
    ``p = 1 - mu``; ``"loads"``: a factor on the point loads; ``"model"``: ``vary(mu)``) and
    the start ``x0`` at ``start``."""
    span = abs(stop - start)
    if mode == "forcing":
        if start != 1.0:
            x0 = solve_point(standard, omega, x0, param=1.0 - start, tol=tol).x
        return standard, x0
    if mode == "loads":
        return static_load_residual(rp, system, loads, start, harmonics, samples, span), x0
    return parametric_residual(rp, system, vary, harmonics, samples, span, start), x0


def _stability(fun: Any, branch: Any, residual: Any, omega: float, method: str | None,
               bifurcations: bool) -> tuple[ParameterStability | None, Any, list[Any]]:
    """Floquet multipliers of every point (none without a ``method``) and the located
    bifurcations (folds and branch points; with multipliers also period doublings and
    Neimark-Sacker points)."""
    floquet = ParameterStability(residual, omega, method) if method else None
    multipliers = floquet.at_points(branch) if floquet is not None \
        else np.zeros((len(branch), 0), dtype=complex)
    events: list[Any] = []
    if bifurcations and len(branch) > 1:
        events = list(detect_bifurcations(fun, branch, options=BifurcationOptions(
            kinds=("fold", "branch_point"))))
        if floquet is not None:
            events += floquet_events(fun, branch, floquet, multipliers)
    return floquet, multipliers, events


class ParameterStability:
    """Floquet multipliers of the points ``(x, mu)`` of a parameter branch at the fixed
    fundamental ``omega``: one stability model for a branch over the nonlinear elements, the
    forcing or the loads (``mu`` reaches the force callback), one per value of ``mu`` when
    the linear part varies (:class:`RotorFamilyResidual`). Quacks like
    :class:`~rotorsim.analyses.periodic.stability.StabilityModel` for
    :func:`~rotorsim.analyses.periodic.events.floquet_events` (``floquet(x, mu)``)."""

    def __init__(self, residual: Any, omega: float, method: str) -> None:
        self.residual, self.omega, self.tol = residual, float(omega), DEFAULT_TOL
        self.requested = method
        family = isinstance(residual, RotorFamilyResidual)
        self.shared = None if family else self._model(residual)
        self.method = self.shared.method if self.shared is not None else method
        self.size = self.shared.size if self.shared is not None else 0

    def _model(self, residual: Any) -> Any:
        return stability_model(residual, self.requested, modes="auto",
                               omega_max=self.omega, tol=DEFAULT_TOL)

    def floquet(self, x: Any, mu: float) -> Any:
        """Floquet result of the point ``x`` at ``mu``."""
        if self.shared is not None:
            return self.shared.floquet(x, self.omega, float(mu))
        model = self._model(self.residual.at(float(mu)))
        self.method, self.size = model.method, max(self.size, model.size)
        return model.floquet(x, self.omega, 0.0)

    def at_points(self, branch: Any) -> Any:
        """Multipliers (P, 2 n_s) of every branch point (NaN where Floquet failed or Hill's
        selection returned fewer)."""
        rows: list[Any] = []
        for x, mu in zip(branch.x, branch.lam, strict=True):
            try:
                rows.append(np.asarray(self.floquet(x, float(mu)).multipliers))
            except (ModelError, ConvergenceError, np.linalg.LinAlgError):
                rows.append(None)
        out = np.full((len(branch), self.size), np.nan + 0j)
        for i, values in enumerate(rows):
            if values is not None:
                out[i, : min(values.size, self.size)] = values[: self.size]
        return out


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
