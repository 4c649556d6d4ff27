"""Bearing life over a sampled history of ring displacements (transients, periodic orbits).

Shared by :mod:`rotorsim.analyses.transient.bearing_life` and
:mod:`rotorsim.analyses.periodic.bearing_life`: the element loads are recomputed from the
ring displacements with the rolling elements at their cage positions, and rated by
Palmgren-Miner on the ring cells (:mod:`rotorsim.elements.rolling.rating.load_history`).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.statics.bearing_life import life_result
from rotorsim.elements.rolling.rating.load_history import history_life, ring_damage
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import rated as cached_rating
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult


def history_life_result(element: Any, delta: ArrayLike, phi: ArrayLike, *, source: str,
                        options: RatingOptions | None = None,
                        record: dict[str, Any] | None = None) -> BearingLifeResult:
    """Life and peak pressures of a bearing over the history ``delta`` (T, 5) [m, rad] at
    shaft angles ``phi`` (T,) [rad], unwrapped; the inner ring turns with the shaft, the
    outer ring is fixed.

    Pressures are those of each element at the sample of its largest load.
    """
    t0 = time.perf_counter()
    rated = cached_rating(element, RatingOptions() if options is None else options)
    d = np.asarray(delta, dtype=float)
    angle = np.asarray(phi, dtype=float)
    if d.ndim != 2 or d.shape[1] != 5 or angle.shape != (d.shape[0],):
        raise ModelError(f"delta must be (T, 5) and phi (T,), got {d.shape} and {angle.shape}",
                         source)
    psi = rated.element_angles(angle)
    loads, u = rated.loads(d, psi)
    rings = np.stack([angle, np.zeros_like(angle)], axis=1)
    damage = ring_damage(rated.reference, u, psi, rings, rated.geometric_cage_ratio,
                         rated.options.n_cells)
    life = history_life(rated.reference, damage)
    t_life = time.perf_counter() - t0
    peak = np.argmax(loads, axis=0)  # (N,) sample of each element's largest load
    pressures = rated.pressures(d[peak], psi[peak])
    diagonal = np.arange(loads.shape[1])
    pressures = _take_diagonal(pressures, diagonal)
    return life_result(rated, life, pressures, source=source, load=np.full(5, np.nan),
                       P=np.nan, angles=psi[peak, diagonal], loads=loads[peak, diagonal],
                       stats={"wall_time": time.perf_counter() - t0, "life_time": t_life,
                              "samples": float(d.shape[0]),
                              "revolutions": damage.revolutions},
                       options=record)


def _take_diagonal(pressures: Any, index: Any) -> Any:
    """The pressures of element ``j`` at sample ``j`` (sample axis of length N), as one
    sample ``(1, N, ...)``."""
    import dataclasses

    changes = {}
    for f in dataclasses.fields(pressures):
        value = getattr(pressures, f.name)
        if isinstance(value, np.ndarray) and value.ndim >= 2 and value.shape[0] == index.size \
                and value.shape[1] == index.size:
            changes[f.name] = value[index, index][None]
    return dataclasses.replace(pressures, **changes)
