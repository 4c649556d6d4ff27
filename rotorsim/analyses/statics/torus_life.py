"""Bearing life and peak contact pressures along a quasi-periodic response (a 2-torus).

A quasi-periodic point (``rs.quasi_periodic_point``: shaft frequency ``W`` and the
rolling elements' varying compliance ``Z kappa W``) is sampled in time from shaft angle 0
over enough shaft revolutions for the cage to turn ``cage_revolutions`` times relative to
the outer ring, and the samples are rated as a load history: element loads at the cage
positions of the shaft angle ``phi = W t``, Palmgren-Miner on the ring cells
(:mod:`rotorsim.elements.rolling.rating.load_history`). The two frequencies being
incommensurate, no finite window closes the torus: the life converges as the window grows
(the tests show the convergence), as the time average of the damage over the torus.

The point is read through its ``speed`` and ``state(t)`` only (one call per sample, about
50 us each), so this module does not depend on the quasi-periodic solver.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.analyses.statics.bearing_history import history_life_result
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import rated
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult


def quasi_periodic_life(point: Any, element: Any, *, options: RatingOptions | None = None,
                        samples: int = 64, cage_revolutions: float = 8.0
                        ) -> BearingLifeResult:
    """ISO/TS 16281 ``L10r`` of a rolling bearing along a quasi-periodic response.

    Parameters
    ----------
    point : QuasiPeriodicPoint
        ``rs.quasi_periodic_point(...)`` of the model the element belongs to.
    element : RollingBearing
        The 2-node rolling-bearing element (``model.nonlinear_elements[i]``).
    options : RatingOptions, optional
    samples : int
        Samples per shaft revolution (>= 8).
    cage_revolutions : float
        Cage revolutions relative to the outer ring in the window (> 0).

    Returns
    -------
    BearingLifeResult
        ``source="quasi_periodic"``; ``options`` record the window (shaft revolutions,
        samples).
    """
    where = "quasi_periodic_life"
    if not hasattr(element, "relative") or not hasattr(element, "nodes"):
        raise ModelError(f"expected a RollingBearing element, got {type(element).__name__}",
                         where)
    if samples < 8 or not cage_revolutions > 0:
        raise ModelError("samples must be >= 8 and cage_revolutions > 0", where)
    speed = float(point.speed)
    if not (math.isfinite(speed) and speed > 0):
        raise ModelError(f"the shaft does not turn (speed {speed})", where)
    relative = abs(float(getattr(element, "inner_speed_ratio", 1.0))
                   - float(getattr(element, "outer_speed_ratio", 0.0)))
    if relative == 0.0:
        raise ModelError("the rings of the bearing turn together: no over-rolling", where)
    kappa = rated(element, options or RatingOptions()).geometric_cage_ratio * relative
    revolutions = max(1, math.ceil(cage_revolutions / kappa))
    t = np.arange(revolutions * samples + 1) * (2.0 * math.pi / speed / samples)
    q = np.array([point.state(float(ti))[0] for ti in t])  # (T, 6 n_nodes)
    u = np.hstack([q[:, 6 * int(node):6 * int(node) + 6] for node in element.nodes])
    record = {"shaft_revolutions": revolutions, "samples": samples,
              "tag": getattr(element, "tag", None)}
    return history_life_result(element, element.relative(u), speed * t,
                               source="quasi_periodic", options=options, record=record)
