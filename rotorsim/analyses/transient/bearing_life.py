"""Bearing life and peak contact pressures over a transient (:class:`TransientResult`).

The rolling-element loads are recomputed from the kept displacements of the bearing's
nodes at every sample (one batched evaluation), the elements at their cage positions of
the shaft angle, and rated by Palmgren-Miner on the material of both rings
(:mod:`rotorsim.elements.rolling.rating.load_history`). The rings turn with the element's
``inner_speed_ratio`` and ``outer_speed_ratio`` times the shaft angle when it has them
(inter-shaft bearings), else the inner ring with the shaft and the outer ring not. The
time step must resolve the passage of the elements over a ring cell (``options.n_cells``
cells per ring).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorsim.analyses.statics.bearing_history import history_life_result
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult
from rotorsim.results.transient import TransientResult


def transient_life(result: TransientResult, element: Any, *,
                   options: RatingOptions | None = None, t_min: float | None = None,
                   t_max: float | None = None) -> BearingLifeResult:
    """ISO/TS 16281 ``L10r`` of a rolling bearing over a transient, by Palmgren-Miner.

    Parameters
    ----------
    result : TransientResult
        Must keep the DOFs of the bearing's nodes.
    element : RollingBearing
        The 2-node rolling-bearing element of the run (``model.rolling_bearings[i]``).
    options : RatingOptions, optional
        Ratings (``C`` catalogue or geometry), ``a_ISO`` inputs, cells per ring.
    t_min, t_max : float, optional
        The window of the history [s] (e.g. after the start-up).

    Returns
    -------
    BearingLifeResult
        ``L10r`` in million revolutions of the inner ring: the life if the window were
        repeated; pressures at each element's largest load.
    """
    if not hasattr(element, "relative") or not hasattr(element, "nodes"):
        raise ModelError(f"expected the RollingBearing element of the run, got "
                         f"{type(element).__name__}", "transient_life")
    sel = result.window(t_min, t_max)
    if int(sel.sum()) < 2:
        raise ModelError(f"fewer than 2 samples in the window [{t_min}, {t_max}] s",
                         "transient_life")
    u = np.hstack([result.node_displacement(int(node))[sel] for node in element.nodes])
    delta = element.relative(u)
    record = {"t_min": t_min, "t_max": t_max, "tag": getattr(element, "tag", None)}
    return history_life_result(element, delta, result.angle[sel], source="transient",
                               options=options, record=record)
