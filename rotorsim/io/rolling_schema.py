"""Pydantic schema of the ``[[rolling_bearings]]`` tables of model files (ball and roller
bearings of :mod:`rotorsim.elements.rolling`), split from :mod:`rotorsim.io.model_schema`.
"""

import math
from typing import Annotated, Any, Literal

from pydantic import Field, model_validator

from rotorsim.elements.rolling.geometry import interference_problem
from rotorsim.errors import ModelError
from rotorsim.io.rating_schema import MountingTable, RatingTable
from rotorsim.io.schema_types import (
    Angle,
    Length,
    LinearizationValue,
    Linked,
    Modulus,
    NonNegLength,
    PositiveRatio,
    SignedLength,
    Table,
    Time,
    fail,
    load_deflection_constant,
    show,
    suggest,
    validate_table,
)


class ProfileTable(Table):
    """Roller profile: straight, crowned (circular) or logarithmic."""

    type: Literal["straight", "crowned", "logarithmic"]
    crown_drop: NonNegLength | None = None
    crown_length: Length | None = None
    crown_radius: Length | None = None
    scale: Length | None = None
    shape: PositiveRatio | None = None
    end_drop: Length | None = None

    @model_validator(mode="after")
    def _keys(self) -> "ProfileTable":
        allowed = {"straight": (), "crowned": ("crown_drop", "crown_length", "crown_radius"),
                   "logarithmic": ("scale", "shape", "end_drop")}[self.type]
        for key in ("crown_drop", "crown_length", "crown_radius", "scale", "shape", "end_drop"):
            if getattr(self, key) is not None and key not in allowed:
                raise fail(f"is not a key of a {self.type} profile (keys: "
                           f"{', '.join(allowed) or 'none'})", f".{key}")
        pairs = {"crowned": ("crown_drop", "crown_radius"), "logarithmic": ("shape", "end_drop")}
        if self.type in pairs:
            a, b = pairs[self.type]
            if getattr(self, a) is not None and getattr(self, b) is not None:
                raise fail(f"give {a} or {b}, not both", f".{b}")
        if self.type == "crowned" and self.crown_drop is None and self.crown_radius is None:
            raise fail("give crown_drop (or crown_radius and crown_length)", ".crown_drop")
        if self.crown_radius is not None and self.crown_length is None:
            raise fail("field required with crown_radius", ".crown_length")
        if self.type == "logarithmic" and self.scale is None:
            raise fail("field required", ".scale")
        return self


class RollingTable(Linked):
    """Keys shared by ball and roller bearings."""

    type: str
    tag: str | None = None
    pitch_diameter: Length
    Kn: Any = None
    contact_angle: Angle = 0.0
    radial_clearance: SignedLength | None = None
    diametral_clearance: SignedLength | None = None
    exponent: PositiveRatio | None = None
    psi0: Angle = 0.0
    cage: Literal["rotating", "fixed"] = "rotating"
    contact_damping: Literal["none", "proportional"] = "none"
    damping_factor: Time = 0.0
    axial_direction: Literal["+z", "-z"] = "+z"
    linearize: LinearizationValue = ("static", None)
    rating: RatingTable | None = None
    mounting: MountingTable | None = None
    rows: Literal[1, 2] = 1
    row_spacing: Length | None = None
    arrangement: Literal["back_to_back", "face_to_face", "tandem"] = "back_to_back"
    axial_interference: SignedLength = 0.0

    @model_validator(mode="after")
    def _common(self) -> "RollingTable":
        self._check_rows()
        if not 0.0 <= self.contact_angle <= 0.5 * math.pi:
            raise fail(f"must be in [0, 90] deg, got {math.degrees(self.contact_angle):.6g} "
                       "deg", ".contact_angle")
        if self.exponent is not None and self.exponent < 1.0:
            raise fail(f"must be >= 1 (3/2 points, 10/9 lines), got {self.exponent}",
                       ".exponent")
        if self.Kn is not None:
            default = 1.5 if self.type == "ball" else 10.0 / 9.0
            exponent = default if self.exponent is None else self.exponent
            object.__setattr__(self, "Kn", load_deflection_constant(self.Kn, exponent, ".Kn"))
        return self

    def _check_rows(self) -> None:
        """Double-row keys (rotorsim.elements.rolling.double_row) only with ``rows = 2``."""
        if self.rows == 2:
            if self.row_spacing is None:
                raise fail("field required with rows = 2", ".row_spacing")
            return
        for key, default in (("row_spacing", None), ("arrangement", "back_to_back"),
                             ("axial_interference", 0.0)):
            if getattr(self, key) != default:
                raise fail("is a key of double-row bearings (rows = 2)", f".{key}")

    def _check_interference(self, diameter: float, element: str) -> None:
        """Refuse an absurd interference (negative clearance) on the key given."""
        key = "radial_clearance" if self.radial_clearance is not None else "diametral_clearance"
        value = getattr(self, key)
        if value is None:
            return
        radial = value if key == "radial_clearance" else 0.5 * value
        problem = interference_problem(radial, diameter, element)
        if problem is not None:
            raise fail(problem, f".{key}")


class BallTable(RollingTable):
    type: Literal["ball"]
    n_balls: Annotated[int, Field(ge=1, le=10_000)]
    ball_diameter: Length
    f_i: PositiveRatio | None = None
    f_o: PositiveRatio | None = None
    A0: Length | None = None
    groove_center_radius: Length | Literal["pitch"] | None = None
    spring_constant: Literal["hertz", "iso16281"] | None = None

    @model_validator(mode="after")
    def _kn_source(self) -> "BallTable":
        if self.Kn is None and (self.f_i is None or self.f_o is None):
            raise fail("field required (or give f_i and f_o: Kn from Hertz theory)", ".Kn")
        if self.Kn is not None and self.spring_constant is not None:
            raise fail("Kn is given: spring_constant chooses how Kn is computed from f_i, "
                       "f_o; give one of the two", ".spring_constant")
        self._check_interference(self.ball_diameter, "ball")
        return self


class RollerTable(RollingTable):
    type: Literal["roller"]
    n_rollers: Annotated[int, Field(ge=1, le=10_000)]
    roller_diameter: Length | None = None
    effective_length: Length
    profile: ProfileTable | None = None
    model: Literal["tilt_integral", "slices", "influence"] = "tilt_integral"
    n_slices: Annotated[int, Field(ge=1, le=10_000)] = 20
    slice_model: Literal["independent", "influence"] = "independent"
    influence_pressure: Modulus | None = None

    @model_validator(mode="after")
    def _interference(self) -> "RollerTable":
        if self.roller_diameter is not None:  # the bounds scale with the diameter
            self._check_interference(self.roller_diameter, "roller")
        return self


ROLLING_TABLES: dict[str, type[RollingTable]] = {"ball": BallTable, "roller": RollerTable}
"""Rolling-bearing ``type`` names of model files and their tables."""


def validate_rolling_bearings(raw: list[Any]) -> list[RollingTable]:
    """Validate the ``[[rolling_bearings]]`` tables (dispatched on ``type``)."""
    out = []
    for i, body in enumerate(raw):
        where = f"rolling_bearings[{i}]"
        if not isinstance(body, dict):
            raise ModelError(f"expected a table, got {show(body)}", where)
        kind = body.get("type")
        if kind is None:
            raise ModelError("field required (ball or roller)", f"{where}.type")
        if not isinstance(kind, str) or kind not in ROLLING_TABLES:
            hint = suggest(kind, tuple(ROLLING_TABLES)) if isinstance(kind, str) else ""
            raise ModelError(f"unknown bearing type {show(kind)}{hint}; use ball or roller",
                             f"{where}.type")
        out.append(validate_table(ROLLING_TABLES[kind], body, ("rolling_bearings", i)))
    return out
