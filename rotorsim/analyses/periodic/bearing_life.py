"""Bearing life and peak contact pressures of a periodic solution (one branch point), or of
a torus of a quasi-periodic branch.

The orbit is repeated over enough periods for the cage to turn ``cage_revolutions`` times
relative to the outer ring, with the rolling elements at their cage positions of the
shaft angle ``phi = phi_0 + W t`` (the shaft turns at the point's speed ``W``), and rated
by Palmgren-Miner on the material of both rings
(:mod:`rotorsim.elements.rolling.rating.load_history`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.analyses.statics.bearing_history import history_life_result
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult
from rotorsim.results.periodic import PeriodicResult
from rotorsim.results.quasi_periodic import QuasiPeriodicResult


def periodic_life(result: PeriodicResult | QuasiPeriodicResult, element: Any, point: int, *,
                  options: RatingOptions | None = None, samples: int = 64,
                  cage_revolutions: float = 2.0) -> BearingLifeResult:
    """ISO/TS 16281 ``L10r`` of a rolling bearing along one periodic orbit.

    Parameters
    ----------
    result : PeriodicResult or QuasiPeriodicResult
        Must keep the DOFs of the bearing's nodes. A torus is sampled along time over
        the cage revolutions rated (it never repeats).
    element : RollingBearing
        The 2-node rolling-bearing element of the model.
    point : int
        Branch point.
    options : RatingOptions, optional
    samples : int
        Samples per period.
    cage_revolutions : float
        Cage revolutions relative to the outer ring rated (the orbit repeated).
    """
    where = "periodic_life"
    if not 0 <= point < len(result):
        raise ModelError(f"point {point} outside 0..{len(result) - 1}", where)
    if samples < 8 or cage_revolutions <= 0:
        raise ModelError("samples must be >= 8 and cage_revolutions > 0", where)
    if not hasattr(element, "relative"):
        raise ModelError(f"expected a RollingBearing element, got {type(element).__name__}",
                         where)
    speed = float(result.speed[point])
    if speed <= 0:
        raise ModelError(f"point {point}: the shaft does not turn (speed {speed})", where)
    relative = abs(float(getattr(element, "inner_speed_ratio", 1.0))
                   - float(getattr(element, "outer_speed_ratio", 0.0)))
    if relative == 0.0:
        raise ModelError("the rings of the bearing turn together: no over-rolling", where)
    kappa = _cage_ratio(element, options) * relative  # cage relative to the outer ring
    duration = cage_revolutions * 2.0 * math.pi / (kappa * speed)
    if isinstance(result, QuasiPeriodicResult):
        # a torus never repeats: sample it along time, ``samples`` per period of its
        # faster base frequency, over the cage revolutions rated
        fast = max(speed, float(result.vc_frequency[point]))
        steps = max(samples, math.ceil(duration * fast * samples / (2.0 * math.pi)))
        time_axis = np.linspace(0.0, duration, steps + 1)
        q = result.time_response(point, time_axis)
        n_periods = 0
    else:
        q = result.time_response(point, samples)[1]
        period = 2.0 * math.pi / float(result.fundamental[point])
        n_periods = max(1, math.ceil(duration / period))
        steps = n_periods * samples
        time_axis = np.arange(steps + 1, dtype=np.float64) * (period / samples)
        q = q[np.arange(steps + 1) % samples]
    u = np.hstack([_node_dofs(result, q, int(node)) for node in element.nodes])
    history = element.relative(u)
    phi = float(result.options.get("shaft_angle", 0.0)) + speed * time_axis
    record = {"point": point, "samples": samples, "periods": n_periods,
              "tag": getattr(element, "tag", None)}
    return history_life_result(element, history, phi, source="periodic", options=options,
                               record=record)


def _cage_ratio(element: Any, options: RatingOptions | None) -> float:
    from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing

    return RatedBearing(element, options or RatingOptions()).geometric_cage_ratio


def _node_dofs(result: PeriodicResult | QuasiPeriodicResult, q: np.ndarray, node: int
               ) -> np.ndarray:
    """The 6 DOFs of ``node`` (samples, 6) from the kept DOFs ``q``; fixed DOFs are 0."""
    out = np.zeros((q.shape[0], 6))
    kept = {int(d): j for j, d in enumerate(result.dofs)}
    for j in range(6):
        full = result.dof_map.index(node, j)
        if full in kept:
            out[:, j] = q[:, kept[full]]
        elif result.dof_map.full_to_free[full] >= 0 and full not in set(
                int(d) for d in result.held_dofs):
            raise ModelError(f"node {node} DOF {j} was not kept: run the periodic analysis "
                             "keeping the bearing nodes", "periodic_life")
    return out
