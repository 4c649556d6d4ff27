"""Branch switching on a rotor's periodic branch: ``switch_branch(model, result, event)``.

From a :class:`~rotorsim.results.periodic.PeriodicResult` of :func:`~.periodic.periodic`
and one of its located bifurcations:

* a **period doubling**: the period-2 branch, computed with the fundamental ``omega / 2``
  (:func:`~rotorsim.harmonic_balance.branch_switching.subharmonic_problem`: the spin, the
  unbalance and the rolling-element angles stay those of ``W``; the result's ``order`` is
  half the branch's, its ``harmonics`` count harmonics of ``omega / 2``, ``2 H`` by
  default);
* a **branch point**: the second branch through it (same discretisation).

The result does not keep the model, so the model is passed again; the problem is rebuilt
from the result's options (:func:`rebuilt`), the branch point's unknowns from the stored
coefficients of the nonlinear DOFs (always kept), and the point is re-corrected at the
located parameter before the switch (:mod:`rotorsim.harmonic_balance.branch_switching`).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.periodic.arguments import periodic_options
from rotorsim.analyses.periodic.branch import Stepping, judged, unknown_scales
from rotorsim.analyses.periodic.excitation import (
    ExcitationPlan,
    HarmonicBase,
    plan_excitation,
)
from rotorsim.analyses.periodic.output import Recovery, kept_dofs, periodic_result
from rotorsim.analyses.periodic.periodic import DEFAULTS, _system
from rotorsim.analyses.periodic.problem import RotorPeriodicProblem, build_problem, spool_ratio
from rotorsim.analyses.periodic.stability import stability_model
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray, NonlinearElement
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.branch_switching import (
    switch_branch_point,
    switch_period_doubling,
)
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function, make_residual
from rotorsim.options import ContinuationOptions, StabilityOptions
from rotorsim.results.periodic import PeriodicBifurcation, PeriodicResult
from rotorsim.solvers.continuation import Branch, Continuation
from rotorsim.solvers.continuation_core import ScaledSystem, correct
from rotorsim.solvers.continuation_switch import locate_branch_point, scaled_system
from rotorsim.solvers.stats import Stats

WHERE = "switch_branch"
SWITCHABLE = ("period_doubling", "branch_point")


@dataclass(frozen=True, eq=False)
class Rebuilt:
    """The problem of a stored branch: system, plan, rotor problem, residual, kept DOFs."""

    system: RotorSystem
    plan: ExcitationPlan
    rp: RotorPeriodicProblem
    residual: HBResidual
    columns: Any
    dofs: Any

    def unknowns(self, result: PeriodicResult, point: int) -> FloatArray:
        """The residual's unknowns at a stored point (from the kept coefficients)."""
        X = np.zeros((self.residual.aft.rows, self.rp.problem.n))
        X[:, self.columns] = result.coefficients[point]
        return self.residual.restrict(X)


def rebuilt(model: Any, result: PeriodicResult, nonlinear: Sequence[NonlinearElement],
            stats: Stats) -> Rebuilt:
    """Rebuild the HB problem of ``result`` for ``model`` (ModelError if they differ)."""
    o = result.options
    system = _system(model, nonlinear)
    frequency = result.parameter_name == "frequency"
    base = None if o.get("base") is None else HarmonicBase(**o["base"])
    elements = () if system.nonlinear is None else system.nonlinear.elements
    unbalance = [(int(n), float(me), float(a)) for n, me, a in o["unbalance"]]
    plan = plan_excitation(elements, unbalance=bool(o["unbalance"]), base=base,
                           varying_compliance=o["varying_compliance"],
                           fundamental=o["fundamental"], frequency_parameter=frequency,
                           unbalance_ratio=spool_ratio(system, unbalance))
    held = np.flatnonzero(np.isin(system.dof_map.free, result.held_dofs)).astype(np.int64)
    rp = build_problem(system, plan, speed0=float(o["start"]),
                       fixed_speed=o["speed"] if frequency else None,
                       phi0=float(o["shaft_angle"]),
                       unbalance=unbalance, gravity=o["gravity"], direction=o["direction"],
                       loads=[(int(n), str(d), float(v)) for n, d, v in o["loads"]],
                       base=base, stats=stats, held=held)
    condense = bool(o["condense"]) and rp.problem.k > 0
    residual = make_residual(rp.problem, result.harmonics, samples=result.samples,
                             condense=condense)
    columns, dofs = kept_dofs(system, rp, o["nodes"])
    if plan.order != result.order or not np.array_equal(dofs, result.dofs):
        raise ModelError("the model differs from the one of the result (fundamental order "
                         "or DOFs)", WHERE)
    if not condense and columns.size != rp.problem.n:
        raise ModelError("a branch computed without condensation can be switched only when "
                         "all its nodes were kept (nodes=None)", WHERE)
    return Rebuilt(system, plan, rp, residual, columns, dofs)


@checked_keywords
def switch_branch(model: Any, result: PeriodicResult,
                  bifurcation: PeriodicBifurcation | int, *, stop: float,
                  harmonics: int | None = None, samples: int | None = None,
                  sign: int = 1, step: float | None = None,
                  continuation: ContinuationOptions | None = None,
                  stability: str | StabilityOptions | None = "auto",
                  nonlinear: Sequence[NonlinearElement] = ()) -> PeriodicResult:
    """Continue the branch born at a period doubling or a branch point of ``result``.

    Parameters
    ----------
    model : Rotor, RotorSystem or Model
        The model ``result`` was computed for (with the same ``nonlinear`` elements).
    result : PeriodicResult
        A branch of :func:`~rotorsim.analyses.periodic.periodic.periodic`.
    bifurcation : PeriodicBifurcation or int
        One of ``result.bifurcations`` (or its index), of kind "period_doubling" or
        "branch_point"; a record of ``result.unresolved`` is accepted too (the singular
        values in ``options["switched_from"]`` then say whether a bifurcation is there).
    stop : float
        End of the new branch in the result's parameter [rad/s] (it may also end on the
        far end of ``result``'s range, then it is not OK and says so).
    harmonics, samples : int, optional
        Of the new branch: period doubling, harmonics of ``omega / 2`` (default ``2 H``)
        and samples per period ``2 T`` (default ``2 N``); branch point, default ``H``, ``N``.
    sign : {1, -1}
        Side of the jump off the bifurcation along its critical direction (period
        doubling: both give the same orbit shifted by one period ``T``).
    step : float, optional
        Scaled length of the jump (default the first continuation step).
    continuation, stability
        As for ``periodic`` (the parameter range scaled to 1 is ``|stop - parameter|``).

    Returns
    -------
    PeriodicResult
        The new branch; its first point is the jumped one, ``options["switched_from"]``
        records the bifurcation and the critical direction's singular values.

    Raises
    ------
    ModelError
        For a bifurcation of another kind, a model that differs from the result's, or bad
        options; :class:`~rotorsim.errors.ConvergenceError` when the jump fails.
    """
    clock, stats = time.perf_counter(), Stats()
    event = _event(result, bifurcation)
    opts = periodic_options(WHERE, DEFAULTS, harmonics=result.harmonics, unbalance=(),
                            excitation=None, continuation=continuation, stability=stability,
                            nodes=None, output=None, checkpoint=None)
    rb = rebuilt(model, result, nonlinear, stats)
    to_lam = (lambda v: float(v)) if result.parameter_name == "frequency" \
        else (lambda v: float(v) * result.order)
    x, lam, along, xs = _located(rb, result, event, to_lam(event.parameter),
                                 opts.stepping())
    if event.kind == "period_doubling":
        return _period_two(rb, result, event, x, lam, xs, float(stop), opts, harmonics,
                           samples, sign, step, stats, clock)
    if harmonics is not None or samples is not None:
        raise ModelError("a branch point is switched in the discretisation it was located "
                         "in: leave harmonics and samples unset", WHERE)
    options = _bounded(opts.stepping(), result, lam, to_lam(stop), to_lam, xs, 1.0)
    branch, jump = switch_branch_point(rb.residual, x, lam, along, options, step=step,
                                       sign=sign)
    recovery = Recovery(rb.residual, rb.columns, rb.dofs)
    assert jump.singular_values is not None
    return _result(rb, result, event, rb.rp, rb.plan, recovery, branch, to_lam(stop),
                   float(stop), opts, {"singular_values": jump.singular_values.tolist(),
                                       "located_parameter": _parameter(result, lam)},
                   stats, clock)


def _event(result: PeriodicResult, which: PeriodicBifurcation | int) -> PeriodicBifurcation:
    if not isinstance(result, PeriodicResult):
        raise ModelError(f"result must be a PeriodicResult of rs.periodic, got "
                         f"{type(result).__name__}", WHERE)
    event = which if isinstance(which, PeriodicBifurcation) else None
    if event is None:
        if isinstance(which, bool) or not isinstance(which, int | np.integer) \
                or not -len(result.bifurcations) <= int(which) < len(result.bifurcations):
            raise ModelError(f"bifurcation {which!r} is not an index of the result's "
                             f"{len(result.bifurcations)} bifurcations", WHERE)
        event = result.bifurcations[int(which)]
    if event.kind not in SWITCHABLE:
        raise ModelError(f"a {event.kind} has no second branch to switch to; give one of "
                         f"kind {' or '.join(SWITCHABLE)}", WHERE)
    if not 0 <= event.index < len(result) - 1:
        raise ModelError(f"bifurcation index {event.index} outside the branch", WHERE)
    return event


def _located(rb: Rebuilt, result: PeriodicResult, event: PeriodicBifurcation, lam: float,
             stepping: Stepping) -> tuple[FloatArray, float, FloatArray, FloatArray]:
    """The bifurcation point re-found between the stored points of its bracket, the known
    branch's direction ``(dx, dlam)`` there and the unknowns' scales. A branch point is
    re-located (Illinois on the bordered determinant); a period doubling starts at the
    located parameter on the branch (the odd block then places it)."""
    i = event.index
    x0, x1 = rb.unknowns(result, i), rb.unknowns(result, i + 1)
    l0, l1 = float(result.fundamental[i]), float(result.fundamental[i + 1])
    xs = unknown_scales(rb.system, rb.rp, rb.residual, x0)
    fun = continuation_function(rb.residual, "omega", terms=True)
    options = stepping.options(l0, l1 if l1 != l0 else l0 + 1.0, xs)
    system, fixed = scaled_system(fun, x0, l0, options)
    y0, y1 = system.to_y(x0, l0), system.to_y(x1, l1)
    chord = (y1 - y0) / np.linalg.norm(y1 - y0)
    if event.kind == "branch_point":
        found = locate_branch_point(system, fixed, y0, y1)
        if found is None:
            raise ModelError(f"no branch point between points {i} and {i + 1} of the "
                             "rebuilt problem (a model other than the result's?)", WHERE)
        x, lam_c = system.from_y(found[0])
        return x, lam_c, _physical(system, chord), xs
    e_lam = np.zeros(y0.size)
    e_lam[-1] = 1.0
    frac = 0.0 if l1 == l0 else min(1.0, max(0.0, (lam - l0) / (l1 - l0)))
    start = y0 + frac * (y1 - y0)
    corr = correct(system, start, e_lam, float(start[-1]), fixed.corrector, stats=Stats())
    x, lam_c = system.from_y(corr.y if corr.converged else start)
    return x, lam_c, _physical(system, chord), xs


def _physical(system: ScaledSystem, t: FloatArray) -> FloatArray:
    """A scaled direction ``(dx, dlam)`` in physical units."""
    return np.append(t[:-1] * system.x_scale, t[-1] * system.lam_scale)


def _bounded(stepping: Stepping, result: PeriodicResult, lam: float, lam_stop: float,
             to_lam: Any, x_scale: FloatArray, factor: float) -> Continuation:
    """Options of the new branch (parameter ``lam / factor``): from the bifurcation towards
    ``stop``, which bounds it on its side; on the other side the bound is the far end of
    the original range, so that a branch turning back from the bifurcation is followed."""
    options = stepping.options(lam / factor, lam_stop / factor, x_scale)
    ends = [to_lam(result.options["start"]) / factor, to_lam(result.options["stop"]) / factor]
    if lam_stop >= lam:
        return dataclasses.replace(options, lam_min=min(options.lam_min, *ends))
    return dataclasses.replace(options, lam_max=max(options.lam_max, *ends))


def _period_two(rb: Rebuilt, result: PeriodicResult, event: PeriodicBifurcation,
                x: FloatArray, lam: float, xs: FloatArray, stop: float, opts: Any,
                harmonics: int | None, samples: int | None, sign: int, step: float | None,
                stats: Stats, clock: float) -> PeriodicResult:
    H2 = 2 * rb.residual.harmonics if harmonics is None else int(harmonics)
    rows = 2 * H2 + 1
    per_dof = xs.reshape(rb.residual.aft.rows, -1).max(axis=0)
    to_lam = (lambda v: float(v)) if result.parameter_name == "frequency" \
        else (lambda v: float(v) * result.order)
    lam_stop = to_lam(stop)
    options = _bounded(opts.stepping(), result, lam, lam_stop, to_lam,
                       np.tile(per_dof, rows), 2.0)
    branch, pd, _ = switch_period_doubling(rb.residual, x, lam, options, harmonics=H2,
                                              samples=samples, x_scale=xs, step=step,
                                              sign=sign)
    rp2 = dataclasses.replace(rb.rp, problem=pd.residual.problem)
    plan2 = dataclasses.replace(rb.plan, order=rb.plan.order / 2.0,
                                unbalance_harmonic=2 * rb.plan.unbalance_harmonic,
                                base_harmonic=2 * rb.plan.base_harmonic)
    recovery = Recovery(pd.residual, rb.columns, rb.dofs)
    out = _result(rb, result, event, rp2, plan2, recovery, branch, lam_stop / 2.0, stop,
                  opts, {"singular_values": pd.singular_values.tolist(),
                         "doubled_basis_parameter": _parameter(result, 2.0 * pd.omega)},
                  stats, clock)
    if result.parameter_name != "frequency":
        return out
    # the frequency parameter is the excitation's, twice the new fundamental
    return dataclasses.replace(out, parameter=2.0 * out.fundamental, bifurcations=tuple(
        dataclasses.replace(b, parameter=2.0 * b.parameter) for b in out.bifurcations))


def _parameter(result: PeriodicResult, omega: float) -> float:
    """The result's parameter at the period-1 fundamental ``omega``."""
    return float(omega) if result.parameter_name == "frequency" else float(omega) / result.order


def _result(rb: Rebuilt, result: PeriodicResult, event: PeriodicBifurcation,
            rp: RotorPeriodicProblem, plan: ExcitationPlan, recovery: Recovery,
            branch: Branch, lam_stop: float, stop: float, opts: Any, extra: dict[str, Any],
            stats: Stats, clock: float) -> PeriodicResult:
    frequency = result.parameter_name == "frequency"
    branch = judged(branch, lam_stop)
    st = opts.stability
    sm = None if st.method is None else stability_model(
        recovery.residual, st.method, modes=st.modes, omega_max=float(np.max(branch.lam)),
        tol=st.tol)
    h = recovery.residual
    options = {**result.options, "harmonics": int(h.harmonics), "samples": int(h.samples),
               "fundamental": None if frequency else plan.order,
               "start": float(event.parameter), "stop": float(stop),
               "stability": st.method,
               "stability_tol": float(st.tol), "bifurcations": bool(st.bifurcations),
               "continuation": dataclasses.asdict(branch.options),
               "switched_from": {"kind": event.kind, "parameter": float(event.parameter),
                                 "index": int(event.index), **extra}}
    return periodic_result(rb.system, rp, recovery, plan, branch, sm, st.bifurcations,
                           frequency, options, stats, clock)
