"""Jump maps: the folds of a periodic branch continued in the forcing amplitude.

A fold (limit point) of an unbalance or housing-excitation branch is where the response
jumps in a run-up or run-down. Continued in a second parameter, the folds trace the
boundary of the region where two stable responses coexist. rotorsim's rotor HB problem
scales its periodic forcing by ``1 - p`` (gravity is not scaled), so tracking a fold in
``p`` with the extended system of seed 002 section 3.5.2.2
(:func:`~rotorsim.harmonic_balance.fold_tracking.track_folds`) gives the fold speed
against the forcing fraction ``1 - p``: the two folds of a hardening resonance approach as
the forcing drops and meet at a cusp, below which the response no longer jumps.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.fold_tracking import track_folds
from rotorsim.solvers.continuation import Branch, Continuation


@dataclass(frozen=True)
class ParameterMap:
    """Fold tracking in a model parameter ``mu``: ``vary(mu)`` returns the nonlinear
    elements (same nodes) or the whole rotor (same nodes, constraints and nonlinear DOFs;
    any parameter of the linear part), ``start`` must reproduce the model, and the folds are
    continued from ``start`` towards ``stop``."""

    vary: Callable[[float], Any]
    start: float
    stop: float
    name: str = "parameter"

    def __post_init__(self) -> None:
        if not callable(self.vary) or not np.isfinite(self.start) \
                or not np.isfinite(self.stop) or self.start == self.stop:
            raise ModelError("give a callable vary(mu) and a range start != stop",
                             "ParameterMap")


def fold_curves(residual: Any, branch: Branch, events: Sequence[Any],
                to_parameter: Callable[[Any], Any], max_points: int = 200,
                mu_range: tuple[float, float] = (0.0, 0.995),
                value: Callable[[Any], Any] = lambda mu: 1.0 - np.asarray(mu),
                key: str = "forcing", max_step: float = 0.05,
                tol: float = 1e-8) -> list[dict[str, Any]]:
    """Each located fold of ``events`` continued in the HB parameter ``mu`` of ``residual``
    over ``mu_range``: ``{key: value(mu), "parameter": [...], "status", "reason"}``
    (JSON-able; ``parameter`` in the branch's parameter units). By default ``mu`` is the
    forcing reduction of the rotor problem and ``key = "forcing"`` its fraction ``1 - mu``.
    ``tol`` is the corrector tolerance of the extended system: its Jacobian carries a
    difference quotient of the Jacobian along the null vector, which stalls Newton's
    convergence near the round-off of the residual (1e-10 is too tight for a Hertz contact
    with clearance)."""

    def two_parameter(x: Any, lam: float, mu: float) -> tuple[Any, Any, Any, Any]:
        ev = residual.evaluate(x, lam, mu, jacobian=True, d_omega=True, d_param=True)
        return ev.r, ev.jacobian, ev.d_omega, ev.d_param

    lo, hi = min(mu_range), max(mu_range)
    direction = 1 if mu_range[1] > mu_range[0] else -1
    span = hi - lo
    options = Continuation(initial_step=0.02, max_step=max_step, lam_min=lo, lam_max=hi,
                           max_points=max_points, direction=direction, lam_scale=span,
                           tol=tol)
    curves = []
    for event in events:
        if getattr(event, "kind", "") != "fold" or not getattr(event, "located", False):
            continue
        try:
            curve = track_folds(two_parameter, event, float(mu_range[0]), options,
                                x_scale=branch.x_scale, r_scale=branch.r_scale,
                                lam_scale=branch.lam_scale)
        except (ConvergenceError, ModelError) as exc:
            curves.append({key: np.atleast_1d(value(mu_range[0])).tolist(),
                           "parameter": [float(to_parameter(event.lam))],
                           "status": "FAILED", "reason": str(exc)})
            continue
        curves.append({key: np.asarray(value(np.asarray(curve.mu))).tolist(),
                       "parameter": np.asarray(to_parameter(np.asarray(curve.lam))).tolist(),
                       "status": curve.branch.status.name, "reason": curve.branch.reason})
    return curves
