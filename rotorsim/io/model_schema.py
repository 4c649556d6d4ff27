"""Pydantic schema of rotorsim model files (TOML): model, materials, shaft, disks,
bearings, point masses, fixed DOFs and loads (rolling bearings: :mod:`rotorsim.io.rolling_schema`).

Every table forbids unknown keys; quantities take SI numbers or unit strings.
:func:`validate_model` raises one :class:`~rotorsim.errors.ModelError` whose message starts
with the key path, e.g. ``shaft[3].od: must be > id (0.06 m)`` or
``bearings[1]: unknown key 'kxz'``. Cross references (materials, nodes, positions) are
resolved by :mod:`rotorsim.io.model_build`; analyses are validated by
:mod:`rotorsim.io.analysis_schema`. pydantic is imported only when a model file is read.
"""

import math
from typing import Annotated, Any

from pydantic import Field, PlainValidator, model_validator

from rotorsim.errors import ModelError
from rotorsim.io.schema_types import (
    MAX_ELEMENTS,
    AddedMass,
    Angle,
    AngularDamping,
    AngularStiffness,
    Damping,
    Density,
    DirectAddedMass,
    DirectDamping,
    DirectStiffness,
    Dof,
    Force,
    FrequencyGrid,
    Inertia,
    Length,
    Linked,
    Located,
    Mass,
    Modulus,
    Name,
    NonNegLength,
    NonNegMass,
    PositiveRatio,
    PositiveSpeed,
    Rate,
    Ratio,
    Stiffness,
    Table,
    Time,
    UnbalanceMagnitude,
    fail,
    fmt,
    number,
    show,
    validate_table,
)


class ModelInfo(Table):
    name: str | None = None
    description: str = ""


PLAUSIBLE_MODULUS = (1e6, 1.2e12)
"""Young's moduli [Pa] a model file accepts: soft rubber (about 1 MPa) to diamond (about
1.2 TPa). Outside it is a unit slip (``"1 Pa"`` for ``"1 GPa"``), which would give natural
frequencies near 0 and a useless run; placeholder materials of the API (e.g. a ghost shaft
with ``E = 1``) are not affected."""


class MaterialTable(Table):
    name: Name
    E: Modulus
    rho: Density
    G_s: Modulus | None = None
    nu: Ratio | None = None

    @model_validator(mode="after")
    def _g_or_nu(self) -> "MaterialTable":
        lo, hi = PLAUSIBLE_MODULUS
        if not lo <= self.E <= hi:
            raise fail(f"{fmt(self.E, 'modulus')} is outside the range of solid materials, "
                       f"{fmt(lo, 'modulus')} (soft rubber) to {fmt(hi, 'modulus')} "
                       "(diamond): check the unit, e.g. E = \"211 GPa\"", ".E")
        if self.G_s is None and self.nu is None:
            raise fail("give G_s or nu")
        if self.nu is not None and not -1.0 < self.nu < 0.5:
            raise fail(f"must be in (-1, 0.5), got {self.nu}", ".nu")
        if self.G_s is not None and self.nu is not None:
            implied = self.E / (2.0 * (1.0 + self.nu))
            if not math.isclose(self.G_s, implied, rel_tol=1e-6):
                raise fail(f"disagrees with G_s: E / (2 (1 + nu)) = {fmt(implied, 'modulus')}"
                           f" but G_s = {fmt(self.G_s, 'modulus')}; give one of them", ".nu")
        return self


class ShaftSegment(Table):
    """A run of ``n_elements`` equal-length shaft elements, uniform or linearly tapered."""

    length: Length | None = None
    element_length: Length | None = None
    n_elements: Annotated[int, Field(ge=1, le=MAX_ELEMENTS)] = 1
    id: NonNegLength | None = None
    od: Length | None = None
    idl: NonNegLength | None = None
    idr: NonNegLength | None = None
    odl: Length | None = None
    odr: Length | None = None
    material: Name
    shear_effects: bool = True
    rotary_inertia: bool = True
    gyroscopic: bool = True
    axial_force: Force = 0.0
    shear_coefficient: PositiveRatio | None = None
    alpha: Rate = 0.0
    beta: Time = 0.0
    tag: str | None = None

    @model_validator(mode="after")
    def _geometry(self) -> "ShaftSegment":
        if (self.length is None) == (self.element_length is None):
            raise fail("give length or element_length" if self.length is None
                       else "give length or element_length, not both",
                       "" if self.length is None else ".element_length")
        outer = self._end("od", "odl", "odr", required=True)
        inner = self._end("id", "idl", "idr", required=False)
        for side, (di, do) in enumerate(zip(inner, outer, strict=True)):
            if di >= do:
                ikey, okey = self._key("id", side), self._key("od", side)
                raise fail(f"must be > {ikey} ({fmt(di, 'length')})", f".{okey}")
        return self

    def _key(self, both: str, side: int) -> str:
        """The key the user gave for the inner/outer diameter at one end."""
        if getattr(self, both) is not None:
            return both
        right = f"{both[0]}{both[1]}r"
        return right if side == 1 and getattr(self, right) is not None else f"{both}l"

    def _end(self, both: str, left: str, right: str, required: bool) -> tuple[float, float]:
        b, lv, rv = getattr(self, both), getattr(self, left), getattr(self, right)
        if b is not None and (lv is not None or rv is not None):
            raise fail(f"give {both} or {left}/{right}, not both", f".{both}")
        if b is not None:
            return b, b
        if lv is None:
            if rv is not None or required:
                raise fail(f"field required (or give {both})", f".{left}")
            return 0.0, 0.0
        return lv, lv if rv is None else rv

    @property
    def diameters(self) -> tuple[float, float, float, float]:
        """``(idl, odl, idr, odr)`` at the two ends of the segment [m]."""
        do = self._end("od", "odl", "odr", required=True)
        di = self._end("id", "idl", "idr", required=False)
        return di[0], do[0], di[1], do[1]

    @property
    def element_size(self) -> float:
        if self.element_length is not None:
            return self.element_length
        assert self.length is not None
        return self.length / self.n_elements


class DiskTable(Located):
    m: Mass | None = None
    Id: Inertia | None = None
    Ip: Inertia | None = None
    width: Length | None = None
    i_d: NonNegLength = 0.0
    o_d: Length | None = None
    material: Name | None = None
    tag: str | None = None

    @model_validator(mode="after")
    def _inertia_or_geometry(self) -> "DiskTable":
        explicit = ("m", "Id", "Ip")
        geometry = ("width", "o_d", "material")
        given_e = [k for k in explicit if getattr(self, k) is not None]
        given_g = [k for k in geometry if getattr(self, k) is not None]
        if given_e and (given_g or self.i_d):
            raise fail("give m, Id, Ip or width, i_d, o_d, material, not both",
                       f".{(given_g or ['i_d'])[0]}")
        keys = explicit if given_e or not given_g else geometry
        for key in keys:
            if getattr(self, key) is None:
                raise fail("field required" + ("" if given_e or given_g else
                                               " (give m, Id, Ip or width, o_d, material)"),
                           f".{key}")
        if given_g and self.o_d is not None and self.i_d >= self.o_d:
            raise fail(f"must be > i_d ({fmt(self.i_d, 'length')})", ".o_d")
        return self


class BearingTable(Linked):
    kxx: DirectStiffness = 0.0
    kyy: DirectStiffness = None
    kxy: Stiffness = 0.0
    kyx: Stiffness = 0.0
    kzz: DirectStiffness = 0.0
    krr: AngularStiffness = 0.0
    ktt: AngularStiffness = 0.0
    cxx: DirectDamping = 0.0
    cyy: DirectDamping = None
    cxy: Damping = 0.0
    cyx: Damping = 0.0
    czz: DirectDamping = 0.0
    crr: AngularDamping = 0.0
    ctt: AngularDamping = 0.0
    mxx: DirectAddedMass = 0.0
    myy: DirectAddedMass = None
    mxy: AddedMass = 0.0
    myx: AddedMass = 0.0
    stiffness_matrix: list[list[float]] | None = None
    damping_matrix: list[list[float]] | None = None
    frequency: FrequencyGrid | None = None
    tag: str | None = None

    @model_validator(mode="after")
    def _tables(self) -> "BearingTable":
        n_freq = None if self.frequency is None else self.frequency.array().size
        for key in self.coefficient_names():
            value = getattr(self, key)
            if isinstance(value, tuple) and len(value) > 1:
                if n_freq is None:
                    raise fail("is an array but no frequency is given", f".{key}")
                if len(value) != n_freq:
                    raise fail(f"has {len(value)} values but frequency has {n_freq}",
                               f".{key}")
        return self

    @staticmethod
    def coefficient_names() -> tuple[str, ...]:
        return tuple(k for k in BearingTable.model_fields if k[0] in "kcm" and len(k) == 3
                     and k[1:] in ("xx", "yy", "xy", "yx", "zz", "rr", "tt"))


class PointMassTable(Located):
    m: NonNegMass = 0.0
    mx: NonNegMass | None = None
    my: NonNegMass | None = None
    mz: NonNegMass | None = None
    tag: str | None = None


class FixedTable(Located):
    dofs: Annotated[list[Dof], Field(min_length=1)]


class UnbalanceTable(Located):
    magnitude: UnbalanceMagnitude
    phase: Angle = 0.0
    tag: str | None = None


class PointLoadTable(Located):
    dof: Dof
    value: Any

    @model_validator(mode="after")
    def _value(self) -> "PointLoadTable":
        dimension = "force" if self.dof.startswith("u") else "moment"
        object.__setattr__(self, "value", number(self.value, dimension, None, ".value"))
        return self


def _gravity(value: Any) -> float | None:
    if value is True:
        return 9.80665
    if value is False:
        return None
    return number(value, "acceleration", "nonnegative") or None


class LoadsTable(Table):
    gravity: Annotated[Any, PlainValidator(_gravity)] = 9.80665
    gravity_direction: Annotated[list[Ratio], Field(min_length=3, max_length=3)] = Field(
        default_factory=lambda: [0.0, -1.0, 0.0])
    unbalance: list[UnbalanceTable] = Field(default_factory=list)
    point_loads: list[PointLoadTable] = Field(default_factory=list)

    @model_validator(mode="after")
    def _direction(self) -> "LoadsTable":
        if not any(self.gravity_direction):
            raise fail("must not be zero", ".gravity_direction")
        return self


class CouplingTable(Linked):
    """A flexible coupling between two shaft ends (:meth:`BearingElement.coupling`)."""

    lateral: DirectStiffness = 0.0
    angular: AngularStiffness = 0.0
    torsional: AngularStiffness = 0.0
    axial: DirectStiffness = 0.0
    lateral_damping: DirectDamping = 0.0
    angular_damping: AngularDamping = 0.0
    torsional_damping: AngularDamping = 0.0
    axial_damping: DirectDamping = 0.0
    tag: str | None = None

    @model_validator(mode="after")
    def _linked(self) -> "CouplingTable":
        if self.n_link is None and self.link_line is None:
            raise fail("a coupling joins two shaft ends: give link_line (with link_z or "
                       "n_link) or n_link", ".link_line")
        return self


class FoundationTable(Table):
    """``[[foundations]]``: a support structure on connection DOFs
    (:class:`~rotorsim.elements.foundation.Foundation`), by its matrices in files (``mass``,
    ``stiffness``, optional ``damping``: ``.npy`` or Matrix Market ``.mtx``, paths relative
    to the model file) or by its modal data (``frequencies``, ``damping_ratios`` and the
    mass-normalised ``shapes`` file). Rows follow ``connections`` then ``dofs``: every DOF of
    the first connection, then of the next."""

    tag: str | None = None
    connections: Annotated[list[Located], Field(min_length=1)]
    dofs: Annotated[list[Dof], Field(min_length=1)]
    mass: str | None = None
    stiffness: str | None = None
    damping: str | None = None
    frequencies: list[PositiveSpeed] | None = None
    damping_ratios: list[Annotated[float, Field(ge=0.0, lt=1.0)]] | None = None
    shapes: str | None = None

    @model_validator(mode="after")
    def _one_form(self) -> "FoundationTable":
        matrices = self.mass is not None or self.stiffness is not None
        modal = any(v is not None for v in (self.frequencies, self.damping_ratios,
                                            self.shapes))
        if matrices == modal:
            raise fail("give mass and stiffness files, or frequencies, damping_ratios and "
                       "shapes (modal data), not both")
        if matrices and (self.mass is None or self.stiffness is None):
            raise fail("give both mass and stiffness", ".stiffness" if self.mass else ".mass")
        if modal and (self.frequencies is None or self.damping_ratios is None
                      or self.shapes is None):
            raise fail("modal data need frequencies, damping_ratios and shapes")
        if modal and self.damping is not None:
            raise fail("modal data carry their damping in damping_ratios", ".damping")
        return self


class DampingTable(Table):
    """``[damping]``: Rayleigh and modal damping of the whole system
    (:class:`~rotorsim.model.damping.SystemDamping`)."""

    alpha: Rate = 0.0
    beta: Time = 0.0
    modal_ratios: list[Annotated[float, Field(ge=0.0, lt=1.0)]] = Field(default_factory=list)


class LineTable(Table):
    """One shaft line of a machine: ``[lines.NAME]`` with its ``[[lines.NAME.shaft]]``."""

    speed_ratio: Ratio = 1.0
    z0: NonNegLength = 0.0
    shaft: list[ShaftSegment] = Field(default_factory=list)  # none: a single node


class ModelTable(Table):
    """The whole model file (analyses are validated separately)."""

    model: ModelInfo = ModelInfo()
    materials: list[MaterialTable] = Field(default_factory=list)
    shaft: list[ShaftSegment] = Field(default_factory=list)  # none: a rigid rotor at node 0
    lines: dict[Annotated[str, Field(min_length=1, pattern=r"^[^:]+$")], LineTable] = Field(
        default_factory=dict)
    disks: list[DiskTable] = Field(default_factory=list)
    bearings: list[BearingTable] = Field(default_factory=list)
    couplings: list[CouplingTable] = Field(default_factory=list)
    damping: DampingTable | None = None
    foundations: list[FoundationTable] = Field(default_factory=list)
    rolling_bearings: list[Any] = Field(default_factory=list)
    point_masses: list[PointMassTable] = Field(default_factory=list)
    fixed: list[FixedTable] = Field(default_factory=list)
    loads: LoadsTable = LoadsTable()
    analyses: Any = None


def validate_model(data: Any) -> ModelTable:
    """Validate a whole parsed model file (a dict) except its analyses."""
    if not isinstance(data, dict):
        raise ModelError(f"expected a table of model sections, got {show(data)}", "top level")
    table = validate_table(ModelTable, data)
    if table.lines and table.shaft:
        raise ModelError("give [[shaft]] (one line) or [lines.NAME] tables, not both",
                         "shaft")
    return table
