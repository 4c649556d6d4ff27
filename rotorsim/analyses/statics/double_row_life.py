"""Life and contact pressures of a double-row bearing from the lives of its two rows.

Each row is rated as a single-row bearing (ISO/TS 16281) with its own rolling-element
loads, computed from the ring displacement carried to the row in its own frame
(:meth:`~rotorsim.elements.rolling.double_row.DoubleRowBearing.row_displacements`), and
its share of the unit's rating (``C_row = C / 2^0.7`` balls, ``C / 2^(7/9)`` rollers,
:class:`~rotorsim.elements.rolling.rating.double_row.DoubleRowRating`). The rows then
combine by the Weibull weakest link of ISO 281 (the rule that gives ``C`` its ``i^0.7``)::

    L10r = (L_row0^(-e) + L_row1^(-e))^(-1/e),   e = 10/9 (balls), 9/8 (rollers),
    P_ref = C L10r^(-1/p),

and each ring's life is the same combination of that ring's lives in the two rows; its
equivalent load is the one giving that life on one row's raceway, ``Q_c L_ring^(-1/p)``.
ISO 281's ``L10`` uses the unit's ``C`` and the double-row ``X, Y`` factors. Per-element
arrays list the elements of row 0 first; ``row_life`` keeps both rows' ``L10r``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Any

import numpy as np

from rotorsim.elements.rolling.double_row import DoubleRowBearing
from rotorsim.elements.rolling.rating.double_row import DoubleRowRating
from rotorsim.elements.rolling.rating.iso16281 import LIFE_EXPONENTS
from rotorsim.elements.rolling.rating.life_factor import (
    life_modification_factor,
    reliability_factor,
)
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.errors import ModelError
from rotorsim.results.bearing_life import BearingLifeResult

_MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
_PER_ELEMENT = ("max_pressure", "semi_major", "semi_minor", "shoulder_margin",
                "slice_pressure", "element_angles", "element_load")


def double_row_of(model: Any) -> tuple[DoubleRowBearing, np.ndarray] | None:
    """The :class:`DoubleRowBearing` inside ``model`` (a ``RollingBearing`` element, a
    ``ReversedBearing`` or the bearing itself) and the factor on ``delta`` (the mirror of a
    reversed mounting); None for any other bearing."""
    factor = np.ones(5)
    while True:
        if isinstance(model, DoubleRowBearing):
            return model, factor
        if isinstance(model, ReversedBearing):
            factor = factor * _MIRROR
            model = model.bearing
        elif hasattr(model, "relative") and getattr(model, "bearing", None) is not None:
            model = model.bearing
        else:
            return None


@functools.lru_cache(maxsize=32)
def double_row_rating(bearing: DoubleRowBearing, options: RatingOptions) -> DoubleRowRating:
    """:class:`DoubleRowRating` of ``bearing`` with ``options``, built once."""
    return DoubleRowRating(bearing, options)


def split_rows(bearing: DoubleRowBearing, factor: np.ndarray, delta: Any, psi: Any
               ) -> tuple[np.ndarray, np.ndarray]:
    """Each row's displacement in its own frame (2, S, 5) and element angles (2, S, N)."""
    d = np.atleast_2d(np.asarray(delta, dtype=float)) * factor
    p = np.atleast_2d(np.asarray(psi, dtype=float))
    n = int(bearing.row.n_elements)
    if d.shape[1] != 5 or p.shape[-1] != 2 * n:
        raise ModelError(f"expected delta (S, 5) and psi (S, {2 * n}), got {d.shape} and "
                         f"{p.shape}", bearing.label)
    return bearing.row_displacements(d), np.stack([p[..., :n], p[..., n:]])


def take_sample(result: Any, k: int) -> Any:
    """Sample ``k`` of a batched life or pressure result (arrays with a leading sample
    axis; ``reference_load`` and the slice positions ``xi`` are shared) as a batch of 1."""
    changes = {f.name: getattr(result, f.name)[k:k + 1] for f in dataclasses.fields(result)
               if f.name not in ("reference_load", "xi")
               and isinstance(getattr(result, f.name), np.ndarray)}
    return dataclasses.replace(result, **changes)


def unit_equivalent_load(rating: DoubleRowRating, load: np.ndarray) -> float:
    """ISO 281 ``P`` of the unit from the radial and axial parts of ``load`` (5,) (NaN
    where no double-row ``X, Y`` table applies, e.g. a cylindrical roller pair)."""
    radial, axial = math.hypot(load[0], load[1]), abs(float(load[2]))
    try:
        return float(rating.equivalent_load(radial, axial))
    except ModelError:
        return math.nan


def combine_rows(rating: DoubleRowRating, rows: tuple[BearingLifeResult, BearingLifeResult],
                 *, P: float, load: np.ndarray, stats: dict[str, float],
                 tag: str = "") -> BearingLifeResult:
    """The unit's :class:`BearingLifeResult` from its rows' (module docstring)."""
    unit = rating.rating
    p, slope = LIFE_EXPONENTS[unit.kind]
    row_life = np.array([rows[0].L10r, rows[1].L10r])
    ring_lives = np.stack([rows[0].ring_life, rows[1].ring_life])  # (rows, rings)
    with np.errstate(divide="ignore"):
        l10r = float(np.sum(row_life ** (-slope)) ** (-1.0 / slope))
        ring_life = np.sum(ring_lives ** (-slope), axis=0) ** (-1.0 / slope)
    reference = np.asarray(rows[0].reference_load, dtype=float)
    p_ref = unit.C * l10r ** (-1.0 / p)
    o = rating.row.options
    given = rating.options or RatingOptions()
    l10 = float(unit.basic_life(P)) if math.isfinite(P) and P > 0 else math.nan
    a1 = reliability_factor(o.reliability)
    a_iso_r = a_iso = 1.0
    if o.life_factor:
        a_iso_r, a_iso = _a_iso(unit.kind, o, p_ref), _a_iso(unit.kind, o, P)
    joined: dict[str, Any] = {name: np.concatenate([getattr(r, name) for r in rows], axis=0)
              for name in _PER_ELEMENT}
    first = rows[0]
    return dataclasses.replace(
        first, C=unit.C, C0=math.nan if unit.C0 is None else unit.C0,
        rating_source=unit.source, load=load, P=P, L10=l10, L10r=l10r, P_ref=p_ref,
        ring_life=ring_life, equivalent_load=reference * ring_life ** (-1.0 / p),
        a1=a1, a_iso=a_iso_r, Lnmr=a1 * a_iso_r * l10r, Lnm=a1 * a_iso * l10,
        row_life=row_life, stats={**first.stats, **stats},
        options={**first.options, "C": given.C, "C0": given.C0, "rows": 2,
                 "row_spacing": rating.bearing.row_spacing,
                 "arrangement": rating.bearing.arrangement},
        summary={"bearing": "DoubleRowBearing", "n_elements": rating.bearing.n_elements,
                 "tag": tag}, **joined)


def _a_iso(kind: str, o: RatingOptions, load: float) -> float:
    if not (math.isfinite(load) and load > 0):
        return math.nan
    return float(life_modification_factor(kind, float(o.viscosity_ratio or 0.0),
                                          float(o.contamination or 0.0),
                                          float(o.fatigue_load_limit or 0.0), load))
