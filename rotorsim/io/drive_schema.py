"""Pydantic schema of the ``drive`` table of a transient analysis (a torque drive).

.. code-block:: toml

    [analyses.start]
    type = "transient"
    t_end = "1 s"
    dt = "0.2 ms"
    speed = 0                 # the initial speed
    [analyses.start.drive]
    node = 0                  # or z = "0 mm": where the motor acts
    motor = { type = "induction", breakdown_torque = "60 N m", breakdown_slip = 0.2,
              synchronous_speed = "1500 rpm" }
    loads = [{ node = 4, type = "quadratic", coefficient = 1e-3 }]
    friction = [{ node = 0, type = "constant", torque = "0.2 N m" }]

Laws (:data:`~rotorsim.io.long_specs.LAW_KEYS`): ``constant`` (``torque``, ``reactive``),
``quadratic`` and ``viscous`` (``coefficient`` in SI), ``curve`` (``speeds``, ``torques``)
and ``induction`` (Kloss); a motor may add ``ripple = {amplitude, order, phase}``.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, PlainValidator, model_validator

from rotorsim.io.long_specs import LAW_KEYS, DriveSpec, Law
from rotorsim.io.schema_types import Angle, Located, Table, fail, number

Moment = Annotated[float, PlainValidator(lambda v: number(v, "moment", None))]
PositiveMoment = Annotated[float, PlainValidator(lambda v: number(v, "moment", "positive"))]
Speed = Annotated[float, PlainValidator(lambda v: number(v, "speed", "nonnegative"))]
PositiveSpeed = Annotated[float, PlainValidator(lambda v: number(v, "speed", "positive"))]
Coefficient = Annotated[float, Field(ge=0.0, allow_inf_nan=False)]
PolarInertia = Annotated[float, PlainValidator(lambda v: number(v, "inertia", "positive"))]


class RippleTable(Table):
    amplitude: Moment
    order: Annotated[float, Field(gt=0.0, allow_inf_nan=False)]
    phase: Angle = 0.0


class LawTable(Table):
    """One torque law: ``type`` and the keys of that type."""

    type: Literal["constant", "quadratic", "viscous", "curve", "induction"]
    torque: Moment | None = None
    reactive: bool | None = None
    coefficient: Coefficient | None = None
    speeds: Annotated[list[Speed], Field(min_length=2)] | None = None
    torques: Annotated[list[Moment], Field(min_length=2)] | None = None
    breakdown_torque: PositiveMoment | None = None
    breakdown_slip: Annotated[float, Field(gt=0.0, le=1.0)] | None = None
    synchronous_speed: PositiveSpeed | None = None

    @model_validator(mode="after")
    def _keys_of_type(self) -> LawTable:
        keys = LAW_KEYS[self.type]
        given = {k for k in LawTable.model_fields if k != "type" and getattr(self, k) is not None}
        extra = sorted(given - set(keys))
        if extra:
            raise fail(f"'{extra[0]}' is not a key of a {self.type} law (keys: "
                       f"{', '.join(keys)})", f".{extra[0]}")
        missing = [k for k in keys if k != "reactive" and getattr(self, k) is None]
        if missing:
            raise fail(f"a {self.type} law needs '{missing[0]}'", f".{missing[0]}")
        if self.type == "curve" and len(self.speeds or ()) != len(self.torques or ()):
            raise fail("give as many torques as speeds", ".torques")
        return self

    def law(self) -> Law:
        """The SI dict of the law (:class:`~rotorsim.io.long_specs.DriveSpec`)."""
        out: Law = {"type": self.type}
        for key in LAW_KEYS[self.type]:
            value = getattr(self, key)
            if value is not None:
                out[key] = list(value) if isinstance(value, list) else value
        return out


class MotorTable(LawTable):
    ripple: RippleTable | None = None

    def law(self) -> Law:
        out = super().law()
        if self.ripple is not None:
            out["ripple"] = {"amplitude": self.ripple.amplitude, "order": self.ripple.order,
                             "phase": self.ripple.phase}
        return out


class PlacedLawTable(LawTable, Located):
    """A load or friction torque at a shaft node (``node`` or ``z``)."""


class DriveTable(Located):
    """A torque drive: the motor at ``node`` (or ``z``), loads and friction torques, the
    polar inertia (default the model's) and ``torque_damping``."""

    motor: MotorTable
    loads: list[PlacedLawTable] = Field(default_factory=list)
    friction: list[PlacedLawTable] = Field(default_factory=list)
    inertia: PolarInertia | None = None
    torque_damping: bool = True


def drive_spec(table: DriveTable, nodes: Any, where: str) -> DriveSpec:
    """The :class:`DriveSpec` of a validated drive table (``nodes`` resolves node or z on
    the shaft, :class:`~rotorsim.io.model_nodes.Nodes`)."""
    placed = {key: tuple((nodes.shaft_node(item, f"{where}.{key}[{i}]"), item.law())
                         for i, item in enumerate(getattr(table, key)))
              for key in ("loads", "friction")}
    return DriveSpec(node=nodes.shaft_node(table, where), motor=table.motor.law(),
                     inertia=table.inertia, torque_damping=table.torque_damping, **placed)
