"""Rating options of the rolling bearings of a model file (``[rolling_bearings.rating]``)."""

from __future__ import annotations

from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.io.rating_schema import RatingTable
from rotorsim.io.rolling_schema import RollingTable


def rating_options(tables: list[RollingTable]) -> tuple[RatingOptions | None, ...]:
    """One :class:`RatingOptions` per rolling bearing (None without a rating table: the
    ratings then come from the ISO 281 geometry formulas)."""
    return tuple(_options(t.rating) for t in tables)


def _options(t: RatingTable | None) -> RatingOptions | None:
    if t is None:
        return None
    heights = None if t.shoulder_heights is None else (float(t.shoulder_heights[0]),
                                                       float(t.shoulder_heights[1]))
    return RatingOptions(C=t.C, C0=t.C0, bm=t.bm, rotating_ring=t.rotating_ring,
                         n_laminae=t.n_laminae, reliability=t.reliability,
                         viscosity_ratio=t.viscosity_ratio, contamination=t.contamination,
                         fatigue_load_limit=t.fatigue_load_limit, shoulder_heights=heights)
