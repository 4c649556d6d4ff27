"""Rating options (``[rolling_bearings.rating]``) and mounting conditions
(``[rolling_bearings.mounting]``) of the rolling bearings of a model file."""

from __future__ import annotations

import math
from typing import Any

from rotorsim.elements.rolling.rating.clearance import (
    MountingConditions,
    with_operating_clearance,
)
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.io.rating_schema import MountingTable, RatingTable
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


def mounted_model(model: Any, t: MountingTable | None) -> Any:
    """``model`` with the operating clearance of its ``[rolling_bearings.mounting]`` table
    (the model itself without one)."""
    if t is None:
        return model
    given = {k: getattr(t, k) for k in ("E_shaft", "nu_shaft", "E_housing", "nu_housing",
                                        "expansion_shaft", "expansion_housing",
                                        "element_temperature", "shaft_temperature",
                                        "housing_temperature") if getattr(t, k) is not None}
    housing = math.inf if t.housing_outside_diameter is None else t.housing_outside_diameter
    conditions = MountingConditions(
        bore=t.bore, outside_diameter=t.outside_diameter,
        shaft_interference=t.shaft_interference, housing_interference=t.housing_interference,
        shaft_bore=t.shaft_bore, housing_outside_diameter=housing,
        inner_temperature=t.inner_temperature, outer_temperature=t.outer_temperature,
        speed=t.speed, **given)
    return with_operating_clearance(model, conditions)[0]
