"""Pydantic schema of ``[rolling_bearings.rating]`` (ratings and life inputs of a rolling
bearing: ISO 281, ISO/TS 16281) and ``[rolling_bearings.mounting]`` (fits, temperatures and
speed of the operating clearance), keys of the tables of :mod:`rotorsim.io.rolling_schema`.
"""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from rotorsim.io.schema_types import (
    Force,
    Length,
    Modulus,
    NonNegLength,
    PositiveRatio,
    Ratio,
    SignedLength,
    Speed,
    Table,
    fail,
)


class RatingTable(Table):
    """``[rolling_bearings.rating]``: ratings and life inputs (ISO 281, ISO/TS 16281)."""

    C: Force | None = None
    C0: Force | None = None
    bm: PositiveRatio | None = None
    rotating_ring: Literal["inner", "outer"] = "inner"
    n_laminae: Annotated[int, Field(ge=1, le=10_000)] | None = None
    reliability: PositiveRatio = 90.0
    viscosity_ratio: PositiveRatio | None = None
    contamination: Ratio | None = None
    fatigue_load_limit: Force | None = None
    shoulder_heights: list[Length] | None = None

    @model_validator(mode="after")
    def _values(self) -> "RatingTable":
        for key in ("C", "C0", "fatigue_load_limit"):
            value = getattr(self, key)
            if value is not None and not value > 0:
                raise fail(f"must be > 0 N, got {value}", f".{key}")
        if not 90.0 <= self.reliability <= 99.95:
            raise fail(f"must be in [90, 99.95] %, got {self.reliability}", ".reliability")
        if self.contamination is not None and not 0.0 <= self.contamination <= 1.0:
            raise fail(f"must be in [0, 1], got {self.contamination}", ".contamination")
        keys = ("viscosity_ratio", "contamination", "fatigue_load_limit")
        given = [k for k in keys if getattr(self, k) is not None]
        if given and len(given) != len(keys):
            missing = [k for k in keys if k not in given]
            raise fail(f"a_ISO needs {', '.join(keys)} together", f".{missing[0]}")
        if self.shoulder_heights is not None and len(self.shoulder_heights) != 2:
            raise fail("give two heights [inner, outer]", ".shoulder_heights")
        return self


class MountingTable(Table):
    """``[rolling_bearings.mounting]``: fits, temperatures [K above mounting] and speed that
    turn the bearing's clearance into its operating clearance
    (:mod:`rotorsim.elements.rolling.rating.clearance`)."""

    bore: Length
    outside_diameter: Length
    shaft_interference: SignedLength = 0.0
    housing_interference: SignedLength = 0.0
    shaft_bore: NonNegLength = 0.0
    housing_outside_diameter: Length | None = None
    inner_temperature: Ratio = 0.0
    outer_temperature: Ratio = 0.0
    element_temperature: Ratio | None = None
    shaft_temperature: Ratio | None = None
    housing_temperature: Ratio | None = None
    speed: Speed = 0.0
    E_shaft: Modulus | None = None
    nu_shaft: Ratio | None = None
    E_housing: Modulus | None = None
    nu_housing: Ratio | None = None
    expansion_shaft: Ratio | None = None
    expansion_housing: Ratio | None = None
