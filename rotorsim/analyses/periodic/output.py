"""Post-processing of a periodic branch into a :class:`~rotorsim.results.periodic.PeriodicResult`.

Each point's unknowns are expanded to all active DOFs (the condensed residual recovers the
linear DOFs exactly, one factorisation per harmonic and point), placed among ALL DOFs
(held and fixed DOFs are zero) and reduced to the kept DOFs. Amplitude measures are taken on
``max(4 N, 256)`` phases per period.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, TypedDict

import numpy as np

from rotorsim.analyses.periodic.confirm import Artefact, Review, confirmed_events
from rotorsim.analyses.periodic.events import FloquetModel
from rotorsim.analyses.periodic.excitation import ExcitationPlan
from rotorsim.analyses.periodic.problem import RotorPeriodicProblem
from rotorsim.analyses.periodic.stability import DEFAULT_TOL, StabilityModel
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.bifurcation import BifurcationEvent
from rotorsim.harmonic_balance.fourier import AFT
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.results.periodic import PeriodicBifurcation, PeriodicResult
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.stats import Stats

IntArray = np.ndarray


@dataclass(frozen=True, eq=False)
class Recovery:
    """Maps a branch point ``(x, lam)`` to the coefficients of the kept DOFs.

    Attributes
    ----------
    residual : HBResidual
    columns : int array (m,)
        Active-DOF index of each kept DOF.
    dofs : int array (m,)
        The kept DOFs among ALL DOFs.
    """

    residual: HBResidual
    columns: IntArray
    dofs: IntArray

    def coefficients(self, x: FloatArray, lam: float) -> FloatArray:
        """Coefficients (2H + 1, m) of the kept DOFs [m, rad]."""
        return self.residual.expand(x, lam)[:, self.columns]

    def measures(self, C: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``max |q|`` and ``max q - min q`` (m,) over a period of the coefficients ``C``."""
        q = self._basis @ C
        return np.abs(q).max(axis=0), q.max(axis=0) - q.min(axis=0)

    @cached_property
    def _basis(self) -> FloatArray:
        aft = self.residual.aft
        count = max(4 * aft.samples, 256)
        return AFT(aft.harmonics).basis(2.0 * np.pi * np.arange(count) / count)


def kept_dofs(system: RotorSystem, rp: RotorPeriodicProblem,
              nodes: Sequence[int] | None) -> tuple[IntArray, IntArray]:
    """Active columns and ALL-DOF indices of the kept DOFs: the DOFs of ``nodes`` (all when
    None) plus the nonlinear DOFs, held DOFs excluded."""
    dm = system.dof_map
    active_all = dm.free[rp.active]
    if nodes is None:
        keep = np.ones(active_all.size, dtype=bool)
    else:
        chosen = []
        for node in nodes:
            if isinstance(node, bool) or not 0 <= int(node) < dm.n_nodes:
                raise ModelError(f"node {node!r} outside 0..{dm.n_nodes - 1}",
                                 "periodic.nodes")
            chosen.append(DOFS_PER_NODE * int(node) + np.arange(DOFS_PER_NODE))
        keep = np.isin(active_all, np.concatenate(chosen)) if chosen else \
            np.zeros(active_all.size, dtype=bool)
        keep[rp.problem.nl_dofs] = True
    columns = np.flatnonzero(keep).astype(np.int64)
    return columns, active_all[columns].astype(np.int64)


class BranchArrays(TypedDict):
    """The recovered arrays of every branch point (fields of ``PeriodicResult``)."""

    coefficients: FloatArray
    max_abs: FloatArray
    peak_to_peak: FloatArray


def branch_arrays(recovery: Recovery, branch: Branch) -> BranchArrays:
    """Coefficients (P, 2H + 1, m) and amplitude measures (P, m) of every point."""
    P, m = len(branch), recovery.columns.size
    rows = recovery.residual.aft.rows
    coeffs, max_abs, ptp = np.zeros((P, rows, m)), np.zeros((P, m)), np.zeros((P, m))
    for i, (x, lam) in enumerate(zip(branch.x, branch.lam, strict=True)):
        coeffs[i] = recovery.coefficients(x, float(lam))
        max_abs[i], ptp[i] = recovery.measures(coeffs[i])
    return {"coefficients": coeffs, "max_abs": max_abs, "peak_to_peak": ptp}


def floquet_arrays(model: StabilityModel | None, branch: Branch) -> tuple[np.ndarray, float]:
    """Multipliers (P, 2 n_s) of every point (NaN rows where Floquet failed) and the time
    spent [s]."""
    if model is None:
        return np.zeros((len(branch), 0), dtype=complex), 0.0
    out = np.full((len(branch), model.size), np.nan + 0j)
    spent = 0.0
    for i, (x, lam) in enumerate(zip(branch.x, branch.lam, strict=True)):
        try:
            fl = model.floquet(x, float(lam))
        except (ModelError, ConvergenceError, np.linalg.LinAlgError):
            continue
        mu = np.asarray(fl.multipliers)
        # Hill's selection may drop a shifted copy and return fewer than 2 n_s exponents:
        # the set stays sorted by modulus, the missing ones are left NaN at the end
        out[i, : min(mu.size, model.size)] = mu[: model.size]
        spent += fl.stats.get("wall_time", 0.0)
    return out, spent


def bifurcation_records(events: Sequence[BifurcationEvent], recovery: Recovery,
                        to_parameter: Any, model: FloquetModel | None
                        ) -> tuple[PeriodicBifurcation, ...]:
    """Result records of located events, with the amplitudes and the critical multiplier
    at each event (NaN without a stability model)."""
    out = []
    for e in sorted(events, key=lambda e: (e.index, float(e.lam))):
        C = recovery.coefficients(e.x, e.lam)
        max_abs, ptp = recovery.measures(C)
        mu = e.multipliers
        if mu is None and model is not None:
            try:
                mu = model.floquet(e.x, e.lam).multipliers
            except (ModelError, ConvergenceError, np.linalg.LinAlgError):
                mu = None
        out.append(PeriodicBifurcation(e.kind, float(to_parameter(e.lam)), int(e.index),
                                       bool(e.located), e.method, critical_multiplier(
                                           e.kind, mu), max_abs, ptp))
    return tuple(out)


def unresolved_records(artefacts: Sequence[Artefact], branch: Branch, recovery: Recovery,
                       to_parameter: Any) -> tuple[PeriodicBifurcation, ...]:
    """Records of the sign changes that did not survive confirmation (amplitudes at the
    interval's first point)."""
    out = []
    for a in artefacts:
        C = recovery.coefficients(branch.x[a.i], float(branch.lam[a.i]))
        max_abs, ptp = recovery.measures(C)
        lo, hi = (float(to_parameter(v)) for v in a.lam)
        out.append(PeriodicBifurcation(
            a.kind, 0.5 * (lo + hi), a.i, False,
            f"unresolved between {lo:.6g} and {hi:.6g}: {a.reason}",
            complex(math.nan, math.nan), max_abs, ptp))
    return tuple(out)


def critical_multiplier(kind: str, mu: Any) -> complex:
    """The multiplier on the unit circle at a bifurcation of ``kind``: nearest -1 (period
    doubling), the complex one nearest the circle (Neimark-Sacker), nearest +1 (fold,
    branch point); NaN without multipliers."""
    if mu is None or np.size(mu) == 0:
        return complex(math.nan, math.nan)
    m = np.asarray(mu, dtype=complex)
    if kind == "period_doubling":
        return complex(m[np.argmin(np.abs(m + 1.0))])
    if kind == "neimark_sacker":
        complex_ = m[np.abs(m.imag) > 1e-6 * np.maximum(np.abs(m), 1.0)]
        pool = complex_ if complex_.size else m
        return complex(pool[np.argmin(np.abs(np.abs(pool) - 1.0))])
    return complex(m[np.argmin(np.abs(m - 1.0))])


def periodic_result(system: RotorSystem, rp: RotorPeriodicProblem, recovery: Recovery,
            plan: ExcitationPlan, branch: Branch, sm: StabilityModel | None,
            bifurcations: bool, frequency: bool, options: dict[str, Any], stats: Stats,
            clock: float) -> PeriodicResult:
    """The result of a traced branch: bifurcations located on it, recovered arrays,
    Floquet multipliers, the run's options and statistics (``clock``: its start time)."""
    residual = recovery.residual
    multipliers, floquet_time = floquet_arrays(sm, branch)
    review = Review((), (), {})
    located = time.perf_counter()
    if bifurcations and len(branch) > 1:
        review = confirmed_events(residual, branch, sm, multipliers)
    located = time.perf_counter() - located
    lam = branch.lam.astype(float)
    speed = np.full(lam.shape, float(options["speed"])) if frequency else lam / plan.order
    to_parameter = (lambda v: v) if frequency else (lambda v: v / plan.order)
    run_stats = {**branch.stats, "start_iterations": float(stats.iterations),
                 "condensation_factorizations": float(stats.factorizations),
                 "floquet_time": floquet_time, "bifurcation_time": located, **review.stats,
                 "wall_time": time.perf_counter() - clock}
    return PeriodicResult(
        parameter=lam if frequency else speed, parameter_name="frequency" if frequency
        else "speed", speed=speed, fundamental=lam, order=0.0 if frequency else plan.order,
        harmonics=residual.harmonics, samples=residual.samples, dofs=recovery.dofs,
        **branch_arrays(recovery, branch), peaks=(), multipliers=multipliers,
        stability_method="none" if sm is None else sm.method,
        stability_tol=DEFAULT_TOL if sm is None else sm.tol,
        bifurcations=bifurcation_records(review.events, recovery, to_parameter, sm),
        unresolved=unresolved_records(review.artefacts, branch, recovery, to_parameter),
        iterations=branch.iterations.astype(np.int64), residuals=branch.residuals,
        approximation=plan.approximation,
        held_dofs=system.dof_map.free[rp.held].astype(np.int64), dof_map=system.dof_map,
        nodes_pos=np.asarray(system.nodes_pos, dtype=float),
        options={**options, "stability_model_modes": None if sm is None else sm.modes},
        stats=run_stats, status=branch.status, reason=branch.reason,
        summary=dict(system.summary))
