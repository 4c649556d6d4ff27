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
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.statics.bearing_life import life_result
from rotorsim.analyses.statics.double_row_life import (
    combine_rows,
    double_row_of,
    double_row_rating,
)
from rotorsim.elements.rolling.rating.load_history import (
    RingDamage,
    history_life,
    ring_damage_density,
)
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import rated as cached_rating
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult

FloatArray = NDArray[np.float64]

_BLOCK_VALUES = 1 << 18
"""Contact values (elements x laminae or races) per block of samples: about 2 MB arrays."""


def history_life_result(element: Any, delta: ArrayLike, phi: ArrayLike, *, source: str,
                        options: RatingOptions | None = None,
                        record: dict[str, Any] | None = None) -> BearingLifeResult:
    """Life and peak pressures of a bearing over the history ``delta`` (T, 5) [m, rad] at
    shaft angles ``phi`` (T,) [rad], unwrapped. The rings turn at ``r_i phi`` and
    ``r_o phi`` with the element's ``inner_speed_ratio`` and ``outer_speed_ratio`` (default
    1 and 0: the inner ring turns with the shaft, the outer ring stands), the cage at
    ``(kappa r_i + (1 - kappa) r_o) phi``.

    Pressures and loads are those of each element at the sample of its largest load
    (balls) or largest damage density ``sum_k q_k^4`` (rollers: the most damaging
    instant, which a tilt may move away from the largest total load).

    A double-row bearing rates each row over its own displacement history and combines
    the rows (:mod:`~rotorsim.analyses.statics.double_row_life`).
    """
    t0 = time.perf_counter()
    opts = RatingOptions() if options is None else options
    d = np.asarray(delta, dtype=float)
    angle = np.asarray(phi, dtype=float)
    if d.ndim != 2 or d.shape[1] != 5 or angle.shape != (d.shape[0],):
        raise ModelError(f"delta must be (T, 5) and phi (T,), got {d.shape} and {angle.shape}",
                         source)
    ratios = (float(getattr(element, "inner_speed_ratio", 1.0)),
              float(getattr(element, "outer_speed_ratio", 0.0)))
    found = double_row_of(element)
    if found is not None:  # each row over its own history, the rows combined
        unit, factor = found
        rating = double_row_rating(unit, opts)
        own = unit.row_displacements(d * factor)
        rows = tuple(_rated_history(rating.row, ratios, own[k], angle, source, record, t0)
                     for k in range(2))
        return combine_rows(rating, (rows[0], rows[1]), P=np.nan, load=np.full(5, np.nan),
                            stats={"wall_time": time.perf_counter() - t0,
                                   "life_time": sum(r.stats["life_time"] for r in rows)},
                            tag=getattr(element, "tag", "") or "")
    return _rated_history(cached_rating(element, opts), ratios, d, angle, source, record, t0)


def _rated_history(rated: Any, ratios: tuple[float, float], d: FloatArray, angle: FloatArray,
                   source: str, record: dict[str, Any] | None, t0: float
                   ) -> BearingLifeResult:
    """:func:`history_life_result` of one single-row rating ``rated`` (rings turning at
    ``ratios`` times the shaft angle)."""
    r_i, r_o = ratios
    psi = rated.element_angles(angle, r_i, r_o)
    rings = np.stack([r_i * angle, r_o * angle], axis=1)
    n = rated.base.n_elements
    per_sample = n * (rated.reference.n_laminae if rated.kind == "roller" else 2)
    block = max(64, _BLOCK_VALUES // per_sample)  # samples per block: temporaries in cache
    damage: RingDamage | None = None
    peak_score, peak = np.full(n, -1.0), np.zeros(n, dtype=np.int64)
    for first in range(0, d.shape[0] - 1, block):
        part = slice(first, min(first + block + 1, d.shape[0]))  # blocks share one sample
        score, density, scale = rated.damage_density(d[part], psi[part])
        cells = ring_damage_density(rated.reference, density, psi[part], rings[part],
                                    rated.geometric_cage_ratio, rated.options.n_cells, scale,
                                    score)
        damage = cells if damage is None else damage.plus(cells)
        at = np.argmax(score, axis=0)
        better = score[at, np.arange(n)] > peak_score
        peak = np.where(better, at + first, peak)
        peak_score = np.where(better, score[at, np.arange(n)], peak_score)
    assert damage is not None
    life = history_life(rated.reference, damage)
    t_life = time.perf_counter() - t0
    pressures = rated.pressures(d[peak], psi[peak])
    peak_load = rated.loads(d[peak], psi[peak])[0][np.arange(n), np.arange(n)]
    diagonal = np.arange(n)
    pressures = _take_diagonal(pressures, diagonal)
    return life_result(rated, life, pressures, source=source, load=np.full(5, np.nan),
                       P=np.nan, angles=psi[peak, diagonal], loads=peak_load,
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
