"""Periodic responses of rotors on nonlinear (rolling) bearings: harmonic balance with
continuation, Floquet stability and bifurcations.

``periodic(model, start=..., stop=...)`` traces the branch of periodic solutions of

    M q'' + (C + W G) q' + K q + r(q, q', phi, W) = f(t)

over the spin speed ``W`` (or, at a fixed speed, the frequency of a housing excitation):

1. the forcing present (unbalance, varying compliance of rolling bearings, housing motion)
   fixes the fundamental ``omega = f W`` (:mod:`~.periodic_excitation`; unbalance with
   varying compliance is quasi-periodic: the branch of tori is then computed instead,
   :mod:`~.torus`);
2. the rotor becomes a rotor-agnostic :class:`~rotorsim.harmonic_balance.problem.HBProblem`
   on its active DOFs (:mod:`~.periodic_problem`), discretised by HB-AFT with ``H``
   harmonics and condensed exactly onto the nonlinear DOFs;
3. the branch starts from the static equilibrium at ``start`` (harmonic 0), corrected by
   damped Newton (:func:`~rotorsim.harmonic_balance.solve.solve_point`), and is continued
   by pseudo-arclength in ``omega`` (:func:`~rotorsim.solvers.continuation.continue_branch`,
   with checkpoints, resume and a progress bar);
4. Floquet multipliers at every point (:mod:`~.periodic_stability`: Hill's method for small
   systems, Hsu's method otherwise, on the full or a Craig-Bampton reduced model) and
   located folds, branch points, period doublings and Neimark-Sacker points
   (:func:`~rotorsim.harmonic_balance.bifurcation.detect_bifurcations`);
5. a :class:`~rotorsim.results.periodic.PeriodicResult` with the coefficients of the kept
   DOFs recovered from the condensed unknowns (:mod:`~.periodic_output`).

References
----------
Seed 002 section 3.5.2 (HB-AFT eqs 3.30-3.36, Floquet eqs 3.37-3.38, arc-length
continuation eqs 3.39-3.42, housing excitation eq 3.43).
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.periodic.arguments import (
    PeriodicDefaults,
    PeriodicOptions,
    check_parameter,
    periodic_options,
)
from rotorsim.analyses.periodic.branch import start_branch
from rotorsim.analyses.periodic.excitation import ExcitationPlan, HarmonicBase, plan_excitation
from rotorsim.analyses.periodic.folds import ParameterMap
from rotorsim.analyses.periodic.output import Recovery, kept_dofs, periodic_result
from rotorsim.analyses.periodic.peaks import peak_columns, peak_records
from rotorsim.analyses.periodic.problem import (
    RotorPeriodicProblem,
    build_problem,
    check_discretization,
    spool_ratio,
)
from rotorsim.analyses.periodic.resume import finished_result, resumed
from rotorsim.analyses.periodic.stability import DEFAULT_TOL, stability_model
from rotorsim.analyses.periodic.torus import (
    one_vc_order,
    refuse_unsupported,
    torus_branch,
    two_spools,
)
from rotorsim.analyses.quasiperiodic.output import check_nodes
from rotorsim.analyses.statics.linearized_rotor import rolling_start
from rotorsim.analyses.statics.nonlinear_static import start_point
from rotorsim.analyses.system_input import nonlinear_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import NonlinearElement
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.bifurcation import BifurcationOptions, detect_bifurcations
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
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
from rotorsim.results.quasi_periodic import QuasiPeriodicResult
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.stats import Stats

WHERE = "periodic"


DEFAULTS = PeriodicDefaults(
    continuation=ContinuationOptions(max_step=0.05, max_points=1000),
    stability=StabilityOptions(tol=DEFAULT_TOL), checkpoint=Checkpointing(every=25),
    unused={"excitation": ("forces",),
            "output": ("every", "times", "rolling_elements", "velocities", "reducers",
                       "after")})
"""Defaults of the group fields left at None, and the fields ``periodic`` does not use."""


@checked_keywords
def periodic(
    model: Rotor | RotorSystem | Any,
    *,
    start: float,
    stop: float,
    parameter: str = "speed",
    speed: float | None = None,
    nonlinear: Sequence[NonlinearElement] = (),
    harmonics: int | Harmonics = 10,
    unbalance: Sequence[tuple[int, float, float]] = (),
    excitation: Excitation | None = None,
    varying_compliance: bool | None = None,
    shaft_angle: float = 0.0,
    continuation: ContinuationOptions | None = None,
    stability: str | StabilityOptions | None = "auto",
    nodes: Sequence[int] | None = None,
    output: Output | None = None,
    checkpoint: str | os.PathLike[str] | Checkpointing | None = None,
    fold_map: bool | ParameterMap = False,
    x0: ArrayLike | None = None,
    peaks: Sequence[tuple[int, str]] = (),
) -> PeriodicResult | QuasiPeriodicResult:
    """Branch of periodic responses from ``start`` to ``stop`` (module docstring).

    Parameters
    ----------
    model : Rotor, RotorSystem or Model
        The rotor with its nonlinear elements (rolling bearings), an assembled system, or a
        loaded model file (its ``rotor`` with its ``rolling_bearings``; loads still come
        from the arguments below).
    start, stop : float
        Range of the parameter [rad/s]; the branch starts at ``start``.
    parameter : {"speed", "frequency"}
        Continue in the spin speed ``W``, or (fixed ``speed``) in the frequency of the
        ``base`` excitation.
    speed : float, optional
        Fixed spin speed [rad/s] for ``parameter="frequency"``.
    nonlinear : sequence of NonlinearElement
        More nonlinear elements (with a Rotor).
    harmonics : int or Harmonics
        ``H >= 1`` harmonics of the fundamental, at least the harmonic of every forcing
        (unbalance, base excitation); refused when the estimated memory exceeds half the
        physical memory (:mod:`rotorsim.harmonic_balance.memory`). A
        :class:`~rotorsim.options.Harmonics` also sets the AFT samples per period, the
        fundamental and the condensation.
    unbalance : list of (node, me, angle)
        Unbalances [kg m, rad] at order 1 (or ``excitation.unbalance``, not both).
    excitation : Excitation, optional
        Gravity [m/s^2] and its direction, constant point loads [N, N m] (harmonic 0) and
        the housing motion ``base``: a :class:`~.periodic_excitation.HarmonicBase`
        displacement ``a cos(b phi + phase)`` (seed 002 eq 3.43), with
        ``parameter="frequency"`` ``a cos(Omega t + phase)`` at the continued ``Omega``.
        Default: standard gravity along ``-y``, nothing else.
    varying_compliance : bool, optional
        Rolling elements move with their cages (True: refused when the response is not
        periodic), are frozen at ``shaft_angle`` (False, recorded in
        ``result.approximation``), or (None) move: when the unbalance and the VC are
        incommensurate the response is a torus, computed by the two-frequency harmonic
        balance (:mod:`~.torus`; a housing excitation or an unbalance on a spool at
        another speed still freezes them, recorded in ``result.approximation``).
    shaft_angle : float
        Shaft angle ``phi0`` at ``t = 0`` [rad] (and the frozen angle).
    continuation : ContinuationOptions, optional
        First and largest scaled arclength step (the parameter range is 1, each DOF's
        scale is its typical static displacement; default ``max_step=0.05``, times the
        size of the response where it grows beyond that scale), points (default 1000),
        corrector tolerance on the scaled residual, or the full solver
        options (their bounds and direction are replaced by ``start`` and ``stop``, their
        scales kept when not the default 1).
    stability : {"auto", "hill", "hsu", "variational"}, None or StabilityOptions
        Floquet method (:mod:`~.periodic_stability`); None skips stability. A
        :class:`~rotorsim.options.StabilityOptions` also sets the fixed-interface modes of
        the stability model, the tolerance (stable when ``max |mu| < 1 + tol``, default
        1e-5) and whether bifurcations are detected and located.
    nodes : sequence of int, optional
        Nodes whose DOFs are kept (default all); the nonlinear DOFs are always kept
        (or ``output.nodes``, not both).
    output : Output, optional
        Kept nodes and the progress bar.
    checkpoint : path or Checkpointing, optional
        Checkpoint file, points between checkpoints (default 25) and resume, as in
        :func:`~rotorsim.solvers.continuation.continue_branch`. A finished run resumes to
        its result, also when its checkpoint was replaced by the results file
        (``rs.save(result, path)``; :mod:`~.periodic_resume`).
    fold_map : bool or ParameterMap
        Continue every fold of the branch in a second parameter (a jump map,
        :mod:`~.periodic_folds`): ``True`` in the forcing amplitude
        (``options["fold_map"]`` lists, per fold, the fold parameter against the forcing
        fraction from 1 down to the cusp); a :class:`~.periodic_folds.ParameterMap` in a
        model parameter of the nonlinear elements (e.g. the clearance; key ``"mu"``).
    x0 : array (ndof,), optional
        Starting displacement of the static start on all DOFs [m, rad] (e.g. a
        ``StaticResult.displacement``), as ``x0`` of
        :func:`~rotorsim.analyses.statics.static.static`.
        Default: the rolling-bearing statics of ``static`` (robust from the centred position
        inside a clearance), or the centred start for other nonlinear elements; Newton's
        method then falls back to the energy minimum when it fails.
    peaks : sequence of (node, dof)
        Locate the amplitude peaks along the branch of each DOF (``"ux"`` ... ``"rz"``:
        ``max |q(t)|``) or node orbit (``"orbit"``: largest radius of ``(ux, uy)``) into
        ``result.peaks`` (:mod:`~.peaks`); none by default (no cost).

    Returns
    -------
    PeriodicResult or QuasiPeriodicResult
        The latter for unbalance with incommensurate VC (:mod:`~.torus`).

    Raises
    ------
    ModelError
        For bad input (before any solve: e.g. ``harmonics`` not a positive integer, below
        the harmonic of a forcing, or needing too much memory), incommensurate forcing with
        ``varying_compliance=True``, speed-dependent linear bearings with speed
        continuation.
    ConvergenceError
        When the first point does not converge.

    Examples
    --------
    >>> import rotorsim as rs
    >>> from rotorsim.io.model_file import load_model
    >>> m = load_model("models/rolling_ball.toml")
    >>> res = periodic(m, start=300.0, stop=320.0, harmonics=4, nodes=[5],
    ...                continuation=rs.ContinuationOptions(max_points=4),
    ...                stability=rs.StabilityOptions(None, bifurcations=False))
    >>> res.parameter_name, round(res.order, 6), res.approximation == ""
    ('speed', 3.571948, True)
    >>> bool(res.amplitude(5, "uy", "mean")[0] < 0)      # sags under gravity
    True
    """
    clock = time.perf_counter()
    opts = periodic_options(WHERE, DEFAULTS, harmonics=harmonics, unbalance=unbalance,
                            excitation=excitation, continuation=continuation,
                            stability=stability, nodes=nodes, output=output,
                            checkpoint=checkpoint)
    h, e, st, ck = opts.harmonics, opts.excitation, opts.stability, opts.checkpoint
    system = _system(model, nonlinear)
    frequency = check_parameter(WHERE, parameter, start, stop, speed)
    elements = () if system.nonlinear is None else system.nonlinear.elements
    spools = not frequency and opts.base is None and two_spools(system, list(e.unbalance))
    if spools and system.nonlinear is None:
        raise ModelError("the unbalances of two spools on a linear machine: the response is "
                         "not a quasi-periodic torus to solve for but the sum of each "
                         "spool's unbalance response (rs.unbalance_response keeps the "
                         "spools' parts apart)", f"{WHERE}.unbalance")
    plan = None if spools else plan_excitation(
        elements, unbalance=bool(e.unbalance), base=opts.base,
        varying_compliance=varying_compliance, fundamental=h.fundamental,
        frequency_parameter=frequency, unbalance_ratio=spool_ratio(system, list(e.unbalance)))
    if plan is None or (plan.quasi_periodic and opts.base is None
                        and plan.unbalance_ratio == 1.0 and one_vc_order(elements)):
        refuse_unsupported(WHERE, spools, fold_map=fold_map is not False, peaks=bool(peaks),
                           checkpoint=ck.path is not None or ck.resume is not None,
                           x0=x0 is not None)
        check_nodes(system.dof_map.n_nodes, opts.output.nodes)
        return torus_branch(model, nonlinear, start=start, stop=stop, opts=opts, clock=clock,
                            spools=spools,
                            described={"parameter": parameter, "start": float(start),
                                       "stop": float(stop), "harmonics": int(h.count),
                                       "varying_compliance": varying_compliance})
    check_discretization(h.count, h.samples, plan, system, h.condense, WHERE)
    stats = Stats()
    q0 = start_point(system, x0, f"{WHERE}.x0") if x0 is not None else _static_guess(
        model, nonlinear, system, e,
        float(speed) if frequency and speed is not None else float(start), float(shaft_angle))
    rp = build_problem(system, plan, speed0=float(start),
                       fixed_speed=speed if frequency else None, phi0=float(shaft_angle),
                       unbalance=list(e.unbalance), gravity=e.gravity, direction=e.direction,
                       loads=list(e.loads), base=opts.base, stats=stats, x0=q0)
    residual = make_residual(rp.problem, h.count, samples=h.samples,
                             condense=h.condense and rp.problem.k > 0)
    peak_columns(system, rp, peaks, f"{WHERE}.peaks")
    recovery = Recovery(residual, *kept_dofs(system, rp, opts.output.nodes))
    to_lam = _lam_map(plan, frequency)
    stepping = opts.stepping()
    begun = start_branch(residual, system, rp, to_lam(start), to_lam(stop), stepping, stats)
    options = _describe(opts, parameter=parameter, start=start, stop=stop, speed=speed,
                        samples=residual.samples, plan=plan,
                        varying_compliance=varying_compliance, shaft_angle=shaft_angle,
                        begun=begun, fold_map=fold_map, x0=x0)
    done = None if ck.resume is None else finished_result(ck.resume)
    if done is not None and ck.resume is not None:
        return resumed(done, options, ck.resume)
    branch = begun.trace(unit=_unit(plan, parameter, frequency), checkpoint=ck.path,
                         checkpoint_every=opts.checkpoint_every, resume=ck.resume,
                         progress=opts.output.progress)
    sm = None if st.method is None else stability_model(
        residual, st.method, modes=st.modes, omega_max=float(np.max(branch.lam)),
        tol=st.tol)  # type: ignore[arg-type]
    result = periodic_result(system, rp, recovery, plan, branch, sm, st.bifurcations,
                             frequency, options, stats, clock)
    if fold_map is not False and result.bifurcations:
        result = _fold_map(result, residual, rp, system, branch, plan, frequency, fold_map,
                           h.count, h.samples)
    if peaks:
        to_parameter = (lambda v: v) if frequency else (lambda v: v / plan.order)
        result = dataclasses.replace(result, peaks=peak_records(
            residual, branch, system, rp, peaks, to_parameter, f"{WHERE}.peaks"))
    return result


def _fold_map(result: PeriodicResult, residual: Any, rp: RotorPeriodicProblem,
              system: RotorSystem, branch: Branch, plan: ExcitationPlan, frequency: bool,
              fold_map: bool | ParameterMap, harmonics: int, samples: int | None
              ) -> PeriodicResult:
    from rotorsim.analyses.periodic.folds import fold_curves

    fun = continuation_function(residual, "omega")
    folds = [e for e in detect_bifurcations(fun, branch, options=BifurcationOptions(
        kinds=("fold",))) if e.located]
    to_parameter = (lambda v: v) if frequency else (lambda v: v / plan.order)
    if isinstance(fold_map, ParameterMap):
        from rotorsim.analyses.periodic.variation import parametric_residual

        varied = parametric_residual(rp, system, fold_map.vary, harmonics, samples,
                                     abs(fold_map.stop - fold_map.start), fold_map.start)
        curves = fold_curves(varied, branch, folds, to_parameter,
                             mu_range=(fold_map.start, fold_map.stop),
                             value=lambda mu: np.asarray(mu), key="mu", max_step=0.5)
        entry: Any = {"name": fold_map.name, "curves": curves}
    else:
        entry = fold_curves(residual, branch, folds, to_parameter)
    return dataclasses.replace(result, options={**result.options, "fold_map": entry})


def _system(model: Any, nonlinear: Sequence[NonlinearElement]) -> RotorSystem:
    return nonlinear_system(model, nonlinear, WHERE)


def _static_guess(model: Any, nonlinear: Sequence[NonlinearElement], system: RotorSystem,
                  e: Excitation, speed: float, phi: float) -> NDArray[np.float64] | None:
    """Start of the static Newton iteration from the robust rolling-bearing statics (as the
    transient's static start), or None (an assembled system, other nonlinear elements, or
    that solve fails): the centred start inside a clearance may have no useful tangent."""
    if not isinstance(model, Rotor) and hasattr(model, "rotor"):
        model = model.rotor.with_nonlinear(tuple(getattr(model, "rolling_bearings", ())))
    if not isinstance(model, Rotor) or system.nonlinear is None:
        return None
    return rolling_start(model, nonlinear, system, e.gravity, e.direction, list(e.loads),
                         speed, phi)


def _lam_map(plan: ExcitationPlan, frequency: bool) -> Any:
    """Parameter -> continuation variable ``omega`` (``f W``, or the frequency itself)."""
    if frequency:
        return lambda value: float(value)
    return lambda value: float(plan.order * value)


def _unit(plan: ExcitationPlan, parameter: str, frequency: bool) -> Any:
    """``omega -> "speed 123.4 rad/s"`` for messages."""
    order = 1.0 if frequency else plan.order
    return lambda lam: f"{parameter} {lam / order:.6g} rad/s"


def _describe(opts: PeriodicOptions, *, parameter: str, start: float, stop: float,
              speed: float | None, samples: int, plan: ExcitationPlan,
              varying_compliance: bool | None, shaft_angle: float, begun: Any,
              fold_map: Any, x0: Any) -> dict[str, Any]:
    """JSON-able options of a run, the groups flattened into one table."""
    e, h, st, nodes = opts.excitation, opts.harmonics, opts.stability, opts.output.nodes
    return {
        "parameter": parameter, "start": float(start), "stop": float(stop),
        "speed": None if speed is None else float(speed),
        "harmonics": int(h.count), "samples": int(samples),
        "unbalance": [[float(v) for v in u] for u in e.unbalance],
        "gravity": e.gravity, "direction": [float(v) for v in np.ravel(e.direction)],
        "loads": [[int(n), str(d), float(v)] for n, d, v in e.loads],
        "base": None if opts.base is None else opts.base.describe(),
        "varying_compliance": varying_compliance, "fundamental": h.fundamental,
        "moving_elements": plan.moving_elements, "shaft_angle": float(shaft_angle),
        "condense": bool(h.condense),
        "continuation": dataclasses.asdict(begun.options), "run": begun.identity,
        "stability": st.method, "stability_modes": st.modes,
        "stability_tol": float(st.tol), "bifurcations": bool(st.bifurcations),  # type: ignore[arg-type]
        "fold_map_requested": fold_map is not False,
        "nodes": None if nodes is None else [int(n) for n in nodes],
        "x0_given": x0 is not None,
    }


__all__ = ["HarmonicBase", "periodic"]
