"""Checks of a harmonic-balance Floquet result, with shooting as the fallback.

:func:`checked_floquet` takes the multipliers that Hill's, Hsu's or the variational method
found along an HB orbit and runs two cheap checks on them:

* **Liouville** (:mod:`~.liouville`): ``sum log|mu|`` against the integrated trace. A
  failure proves a modulus error above the stability tolerance. It catches an inaccurate
  Hill selection or integration, but never Hsu's sampling error (its product of
  exponentials satisfies the identity exactly).
* **Tangent jumps** (:mod:`~.tangent_switches`): the force tangent jumps in time along the
  orbit (a contact with a stiffness step). Every method that works on the HB orbit then
  inherits the Gibbs ripple of the truncated series at the contact, whose duration it
  misjudges; on NLvib's unilateral spring (H = 21) the multipliers are off by up to 1.0.

Both together cost one batched force call on the ``N`` phases of the HB grid (about one
residual evaluation) plus a few small ones for locating jumps. On that grid the trapezoidal
trace of a velocity-dependent tangent is the one Hsu's method uses, so for Hsu the
Liouville check tests round-off only. When either check fails, the point falls back to
:func:`~.shooting.shoot` from the HB state (the real trajectory's periodic orbit and its
monodromy), for problems of at most :data:`SHOOTING_LIMIT` unknowns whose fastest mode
keeps the explicit integration short (:data:`SHOOTING_MAX_STEPS`); the
:class:`FloquetCheck` record says what was done. A check can fail on errors in heavily
damped multipliers that do not matter for stability (Hill at a low ``H`` on a rotor with
stiff bearings: ``sum log|mu|`` off by 0.2 out of -340, the leading multipliers right to
2e-6); the record then says so, and the cost cap keeps such branches from paying for
shooting at every point.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.floquet import FloquetResult
from rotorsim.harmonic_balance.liouville import LIOUVILLE_TOL, TraceModel, liouville_error
from rotorsim.harmonic_balance.monodromy import PeriodicTangents, state_matrices
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.harmonic_balance.tangent_switches import find_jumps

SHOOTING_LIMIT = 40
"""Largest number of unknowns ``n`` for which a failed check falls back to shooting (the
augmented system has ``4 n^2`` unknowns and an explicit stepper)."""
SHOOTING_MAX_STEPS = 600
"""Largest *estimated* number of DOP853 steps per period for which a failed check falls
back to shooting: ``16 rho(A) / omega``, 16 steps per period of the fastest mode (the
``rho(A)`` of the first-order matrix at phase 0) at ``rtol = 1e-10``. Measured: 130 steps
for NLvib's gap spring (estimate 210, 0.1 s per period); 1900 for the 14-DOF stability
model of ``models/rolling_ball.toml`` (estimate 1830, about 10 s per point); 1830 for the
16-DOF Craig-Bampton model of ``models/clearance_rotor.toml`` near 363 rad/s (estimate
1000: contact switches add rejected steps), 3 periods of Newton in 8 s, the cost of about
180 of its branch points, for the same largest |mu| (1.000000) as Hsu's. Above it the
failed check is recorded ("no shooting: ... stiff") and the first method's multipliers are
kept. The integration itself stops at 5 times this."""


@dataclass(frozen=True)
class FloquetCheck:
    """What the checks found at one point and which multipliers were kept.

    Attributes
    ----------
    method : str
        Method of the kept multipliers ("hill", "hsu", "variational" or "shooting").
    liouville_error : float
        :func:`~.liouville.liouville_error` of the first method (NaN: not applicable).
    tangent_jumps : int
        Jumps of the force tangent over one period of the HB orbit.
    passed : bool
        Both checks passed for the first method.
    fallback : str
        "" (none needed), "shooting", or why shooting was not used or failed.
    fallback_liouville_error : float
        Liouville error of the shooting result against the trace integrated along its
        trajectory (NaN without shooting).
    """

    method: str
    liouville_error: float
    tangent_jumps: int
    passed: bool
    fallback: str = ""
    fallback_liouville_error: float = math.nan


def run_checks(residual: HBResidual, x: ArrayLike, omega: float, param: float,
               result: FloquetResult, trace: TraceModel | None = None
               ) -> tuple[float, int]:
    """Liouville error and number of tangent jumps of ``result`` at the HB point ``x``."""
    pb = residual.problem
    trace = trace if trace is not None else TraceModel(pb)
    if pb.force is None:
        return liouville_error(result, trace.integral(omega), size=2 * pb.n), 0
    tangents = _tangents(residual, x, omega, param)
    S = residual.samples
    tau = 2.0 * np.pi * np.arange(S) / S
    Kt, Ct = tangents.at(tau)
    values = Kt.reshape(S, -1) if Ct is None else np.hstack((Kt.reshape(S, -1),
                                                             Ct.reshape(S, -1)))
    jumps = find_jumps(tangents.entries, tau, values)
    error = liouville_error(result, trace.integral(omega, Ct), size=2 * pb.n)
    return error, jumps.count


def _tangents(residual: HBResidual, x: ArrayLike, omega: float, param: float
              ) -> PeriodicTangents:
    """Tangents along the orbit; a condensed ``x`` already holds the nonlinear DOFs'
    coefficients, so the linear DOFs are not recovered (they do not enter the tangents)."""
    pb, rows = residual.problem, residual.aft.rows
    if residual.size != rows * pb.k or pb.k == pb.n:
        return PeriodicTangents.of(residual, x, omega, param)
    X = np.zeros((rows, pb.n))
    X[:, pb.nl_dofs] = np.asarray(x, dtype=float).reshape(rows, pb.k)
    return PeriodicTangents(pb, residual.aft, X, float(omega), float(param))


def checked_floquet(residual: HBResidual, x: ArrayLike, omega: float, param: float,
                    result: FloquetResult, *, trace: TraceModel | None = None,
                    shooting_limit: int = SHOOTING_LIMIT
                    ) -> tuple[FloquetResult, FloquetCheck]:
    """Check ``result`` (module docstring) and fall back to shooting when a check fails.

    Parameters
    ----------
    residual : HBResidual
        The residual ``result`` was computed on; its problem is the one shot.
    x : array (residual.size,)
        The HB solution at ``omega`` [rad/s] and ``param``.
    result : FloquetResult
        From :func:`~.floquet.hill`, :func:`~.monodromy.hsu` or
        :func:`~.monodromy.variational` (a forced, non-autonomous problem).
    trace : TraceModel, optional
        Reused across the points of a branch.
    shooting_limit : int
        No shooting above this many unknowns (the failed check is still recorded).

    Returns
    -------
    (FloquetResult, FloquetCheck)
        The multipliers to use (``wall_time`` includes the checks and any shooting) and
        the record.
    """
    clock = time.perf_counter()
    error, jumps = run_checks(residual, x, omega, param, result, trace)
    passed = not (error > LIOUVILLE_TOL) and jumps == 0        # NaN: not applicable
    record = FloquetCheck(result.method, error, jumps, passed)
    kept = result
    if not passed:
        kept, record = _fallback(residual, x, omega, param, result, record, shooting_limit)
    spent = result.stats.get("wall_time", 0.0) + time.perf_counter() - clock
    return dataclasses.replace(kept, stats={**kept.stats, "wall_time": spent}), record


def _fallback(residual: HBResidual, x: ArrayLike, omega: float, param: float,
              result: FloquetResult, record: FloquetCheck, limit: int
              ) -> tuple[FloquetResult, FloquetCheck]:
    """Shooting from the HB state, or the reason it was not used."""
    from rotorsim.harmonic_balance.shooting import hb_state, shoot  # only when needed

    pb = residual.problem
    if pb.n > limit:
        return result, dataclasses.replace(
            record, fallback=f"no shooting: {pb.n} unknowns > {limit}")
    try:
        A = state_matrices(pb, _tangents(residual, x, omega, param), np.zeros(1))[0]
        estimate = 16.0 * float(np.abs(np.linalg.eigvals(A)).max()) / omega
        if estimate > SHOOTING_MAX_STEPS:
            return result, dataclasses.replace(
                record, fallback=f"no shooting: about {estimate:.0f} steps per period "
                                 f"(stiff) > {SHOOTING_MAX_STEPS}")
        sol = shoot(pb, omega, hb_state(residual, x, omega, param), param,
                    max_steps=5 * SHOOTING_MAX_STEPS)
    except (ConvergenceError, ModelError, np.linalg.LinAlgError) as exc:
        return result, dataclasses.replace(record, fallback=f"shooting failed: {exc}")
    return sol.floquet, dataclasses.replace(
        record, method="shooting", fallback="shooting",
        fallback_liouville_error=sol.liouville_error)
