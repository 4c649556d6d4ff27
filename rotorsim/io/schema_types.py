"""Building blocks of the model-file schema: quantity types with units, swept grids, the
strict base table and the translation of pydantic errors into one path-named
:class:`~rotorsim.errors.ModelError`.

A quantity accepts an SI number or a unit string (:mod:`rotorsim.units`); a coefficient
also accepts an array or a ``{values = [...], unit = "..."}`` table; a grid is a range
table ``{start, stop, num, spacing, unit}`` or explicit values. Validators raise
:func:`fail` errors whose ``subpath`` extends the key path (``speeds.num``).
"""

import difflib
import itertools
from collections.abc import Callable
from typing import Annotated, Any, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, ValidationError, model_validator
from pydantic_core import PydanticCustomError

from rotorsim.elements.base import DOF_NAMES
from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import Grid
from rotorsim.units import DIMENSIONS, UnitParseError, _show, convert

ERROR_TYPE = "rotorsim"
MAX_ELEMENTS = 10_000
MAX_POINTS = 100_000


def fail(reason: str, subpath: str = "") -> PydanticCustomError:
    """A validation error with our own message; ``subpath`` extends the key path."""
    return PydanticCustomError(ERROR_TYPE, "{reason}", {"reason": reason, "subpath": subpath})


def show(value: Any) -> str:
    """Short one-line text of a user value for messages (control characters escaped)."""
    return _show(value)


def fmt(number: float, dimension: str) -> str:
    """``0.06 m``: an SI number with its unit."""
    unit = DIMENSIONS[dimension][0]
    return f"{number:.6g} {unit}" if unit else f"{number:.6g}"


# ---------------------------------------------------------------- quantities
def number(value: Any, dimension: str, sign: str | None, subpath: str = "") -> float:
    """SI value of ``value`` (number or unit string) checked against ``sign``
    (``"positive"``, ``"nonnegative"`` or ``None``); a :func:`fail` error otherwise."""
    try:
        out = convert(value, dimension)
    except UnitParseError as err:
        raise fail(str(err), subpath) from None
    if sign == "positive" and out <= 0:
        raise fail(f"must be > 0, got {show(value)}", subpath)
    if sign == "nonnegative" and out < 0:
        raise fail(f"must be >= 0, got {show(value)}", subpath)
    return out


def _quantity(dimension: str, sign: str | None = None) -> Callable[[Any], float]:
    def validate(value: Any) -> float:
        return number(value, dimension, sign)

    return validate


def _unit_table(value: dict[str, Any], dimension: str, sign: str | None) -> tuple[float, ...]:
    """``{values = [...], unit = "MN/m"}`` -> SI values."""
    for key in value:
        if key not in ("values", "unit"):
            raise fail(f"unknown key '{key}' (expected values, unit)")
    values, unit = value.get("values"), value.get("unit", "")
    if not isinstance(unit, str):
        raise fail(f"expected a unit string, got {show(unit)}", ".unit")
    if not isinstance(values, list) or not values:
        raise fail(f"expected a non-empty array, got {show(values)}", ".values")
    if unit.strip():
        number(f"1 {unit}", dimension, None, ".unit")
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, int | float):
            raise fail(f"expected a number, got {show(v)}", f".values[{i}]")
        out.append(number(f"{v!r} {unit}" if unit.strip() else v, dimension, sign,
                          f".values[{i}]"))
    return tuple(out)


def _coefficient(dimension: str, sign: str | None) -> Callable[[Any], float | tuple[float, ...]]:
    """A scalar, an array, or a ``{values, unit}`` table of ``dimension``."""
    def validate(value: Any) -> float | tuple[float, ...]:
        if isinstance(value, dict):
            return _unit_table(value, dimension, sign)
        if isinstance(value, list):
            if not value:
                raise fail("expected a non-empty array")
            return tuple(number(v, dimension, sign, f"[{i}]") for i, v in enumerate(value))
        return number(value, dimension, sign)

    return validate


# ---------------------------------------------------------------- grids
_GRID_KEYS = ("start", "stop", "num", "spacing", "unit", "values")


def _grid(dimension: str, sign: str, spacing: str) -> Callable[[Any], Grid]:
    """A range table ``{start, stop, num, spacing, unit}`` or increasing explicit values."""
    def validate(value: Any) -> Grid:
        if isinstance(value, list):
            return _explicit_grid(_coefficient(dimension, sign)(value), "")
        if not isinstance(value, dict):
            raise fail(f"expected a table {{start, stop, num}} or an array, got {show(value)}")
        if "values" in value:
            return _explicit_grid(_unit_table(value, dimension, sign), ".values")
        return _range_grid(value, dimension, sign, spacing)

    return validate


def _explicit_grid(values: Any, subpath: str) -> Grid:
    values = values if isinstance(values, tuple) else (values,)
    if any(b <= a for a, b in itertools.pairwise(values)):
        raise fail("values must be strictly increasing", subpath)
    return Grid(values=values)


def _range_grid(value: dict[str, Any], dimension: str, sign: str, spacing: str) -> Grid:
    for key in value:
        if key not in _GRID_KEYS:
            raise fail(f"unknown key '{key}'" + suggest(key, _GRID_KEYS))
    for key in ("start", "stop", "num"):
        if key not in value:
            raise fail("field required", f".{key}")
    unit = value.get("unit", "")
    if not isinstance(unit, str):
        raise fail(f"expected a unit string, got {show(unit)}", ".unit")

    def read(key: str) -> float:
        raw = value[key]
        if unit.strip() and not isinstance(raw, bool) and isinstance(raw, int | float):
            raw = f"{raw!r} {unit}"
        return number(raw, dimension, sign, f".{key}")

    start, stop = read("start"), read("stop")
    num = value["num"]
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_POINTS:
        raise fail(f"must be an integer in 1..{MAX_POINTS}, got {show(num)}", ".num")
    kind = value.get("spacing", spacing)
    if kind not in ("linear", "log"):
        raise fail(f"must be 'linear' or 'log', got {show(kind)}", ".spacing")
    if num > 1 and stop <= start:
        raise fail(f"must be > start ({fmt(start, dimension)})", ".stop")
    if kind == "log" and start <= 0:
        raise fail("must be > 0 for log spacing", ".start")
    return Grid(start=start, stop=stop, num=num, spacing=kind)


# ---------------------------------------------------------------- rolling bearings
_POINT_DIMENSIONS = {"load": ("force",) * 3 + ("moment",) * 2,
                     "displacement": ("length",) * 3 + ("angle",) * 2}


def _linearize(value: Any) -> tuple[str, tuple[float, ...] | None]:
    """``"static"``, ``{load = [5 values]}`` or ``{displacement = [5 values]}``."""
    if value == "static":
        return "static", None
    if not isinstance(value, dict):
        raise fail(f'expected "static", {{load = [...]}} or {{displacement = [...]}}, got '
                   f"{show(value)}")
    if len(value) != 1 or next(iter(value)) not in _POINT_DIMENSIONS:
        key = next((k for k in value if k not in _POINT_DIMENSIONS), "")
        raise fail("give exactly one of load, displacement" + (
            f" (unknown key '{key}'{suggest(key, tuple(_POINT_DIMENSIONS))})" if key else ""))
    (kind, items), = value.items()
    if not isinstance(items, list) or len(items) != 5:
        raise fail(f"expected 5 values [x, y, z, rx, ry], got {show(items)}", f".{kind}")
    dims = _POINT_DIMENSIONS[kind]
    return kind, tuple(number(v, d, None, f".{kind}[{i}]")
                       for i, (v, d) in enumerate(zip(items, dims, strict=True)))


def load_deflection_constant(value: Any, exponent: float, subpath: str = "") -> float:
    """``Kn`` [N/m^exponent] from an SI number or a string such as ``"8.5e9 N/m^1.5"``
    (its unit times ``m^exponent`` must be a force: that is how it is converted)."""
    if isinstance(value, str):
        magnitude, _, unit = value.strip().partition(" ")
        text = f"{magnitude} ({unit}) * m^{exponent!r}" if unit.strip() else magnitude
        try:
            out = convert(text, "force")
        except UnitParseError:
            raise fail(f"{show(value)} is not a load-deflection constant in N/m^{exponent:.6g}"
                       f' (e.g. "8.5e9 N/m^{exponent:.6g}")', subpath) from None
    else:
        out = number(value, "dimensionless", None, subpath)
    if out <= 0:
        raise fail(f"must be > 0, got {show(value)}", subpath)
    return out


# ---------------------------------------------------------------- tables
# Annotated types: a quantity of a dimension (SI number or unit string), with a sign rule.
Length = Annotated[float, PlainValidator(_quantity("length", "positive"))]
NonNegLength = Annotated[float, PlainValidator(_quantity("length", "nonnegative"))]
Mass = Annotated[float, PlainValidator(_quantity("mass", "positive"))]
NonNegMass = Annotated[float, PlainValidator(_quantity("mass", "nonnegative"))]
Inertia = Annotated[float, PlainValidator(_quantity("inertia", "nonnegative"))]
Modulus = Annotated[float, PlainValidator(_quantity("modulus", "positive"))]
Density = Annotated[float, PlainValidator(_quantity("density", "positive"))]
Power = Annotated[float, PlainValidator(_quantity("power", "positive"))]
Ratio = Annotated[float, PlainValidator(_quantity("dimensionless"))]
PositiveRatio = Annotated[float, PlainValidator(_quantity("dimensionless", "positive"))]
Force = Annotated[float, PlainValidator(_quantity("force"))]
Rate = Annotated[float, PlainValidator(_quantity("rate", "nonnegative"))]
Time = Annotated[float, PlainValidator(_quantity("time", "nonnegative"))]
PositiveTime = Annotated[float, PlainValidator(_quantity("time", "positive"))]
UnbalanceMagnitude = Annotated[float, PlainValidator(_quantity("unbalance", "nonnegative"))]
Angle = Annotated[float, PlainValidator(_quantity("angle"))]
Speed = Annotated[float, PlainValidator(_quantity("speed", "nonnegative"))]
PositiveSpeed = Annotated[float, PlainValidator(_quantity("speed", "positive"))]
SignedLength = Annotated[float, PlainValidator(_quantity("length"))]
LinearizationValue = Annotated[Any, PlainValidator(_linearize)]
# constant or tabulated (over frequency) bearing coefficients
Stiffness = Annotated[Any, PlainValidator(_coefficient("stiffness", None))]
DirectStiffness = Annotated[Any, PlainValidator(_coefficient("stiffness", "nonnegative"))]
AngularStiffness = Annotated[Any, PlainValidator(_coefficient("angular_stiffness",
                                                              "nonnegative"))]
Damping = Annotated[Any, PlainValidator(_coefficient("damping", None))]
DirectDamping = Annotated[Any, PlainValidator(_coefficient("damping", "nonnegative"))]
AngularDamping = Annotated[Any, PlainValidator(_coefficient("angular_damping", "nonnegative"))]
AddedMass = Annotated[Any, PlainValidator(_coefficient("mass", None))]
DirectAddedMass = Annotated[Any, PlainValidator(_coefficient("mass", "nonnegative"))]
# swept quantities: a range table or explicit values
SpeedGrid = Annotated[Any, PlainValidator(_grid("speed", "nonnegative", "linear"))]
FrequencyGrid = Annotated[Any, PlainValidator(_grid("frequency", "nonnegative", "linear"))]
StiffnessGrid = Annotated[Any, PlainValidator(_grid("stiffness", "positive", "log"))]
NodeIndex = Annotated[int, Field(ge=0, le=10 * MAX_ELEMENTS)]
Dof = Literal["ux", "uy", "uz", "rx", "ry", "rz"]
Name = Annotated[str, Field(min_length=1)]
assert get_args(Dof) == DOF_NAMES


class Table(BaseModel):
    """Base of all model-file tables: strict types, unknown keys rejected."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)


class Located(Table):
    """An item placed at a node number or at an axial position ``z`` on the shaft; in a
    model of several ``[lines.NAME]``, ``line`` names the line and ``node`` is local to it."""

    node: NodeIndex | None = None
    z: NonNegLength | None = None
    line: Annotated[str, Field(min_length=1)] | None = None

    @model_validator(mode="after")
    def _one_position(self) -> "Located":
        if self.node is None and self.z is None:
            raise fail("give node or z")
        if self.node is not None and self.z is not None:
            raise fail("give node or z, not both", ".z")
        return self


# ---------------------------------------------------------------- errors
class Linked(Located):
    """A connection from its node to ground, to a housing node ``n_link`` or, in a model of
    several lines, to the line ``link_line`` (at ``link_z``, local node ``n_link``, or by
    default at the same axial position as its own node)."""

    n_link: NodeIndex | None = None
    link_line: Annotated[str, Field(min_length=1)] | None = None
    link_z: NonNegLength | None = None

    @model_validator(mode="after")
    def _link(self) -> "Linked":
        if self.link_z is not None and self.link_line is None:
            raise fail("link_z needs link_line (the line it is measured on)", ".link_z")
        if self.link_z is not None and self.n_link is not None:
            raise fail("give n_link or link_z, not both", ".link_z")
        if self.link_line is None and self.n_link is not None and self.line is None \
                and self.n_link == self.node:
            raise fail(f"must differ from node ({self.node})", ".n_link")
        return self


def validate_table(cls: type[Table], data: Any, prefix: tuple[str | int, ...] = ()) -> Any:
    """Validate ``data`` against ``cls``; raise one :class:`ModelError` naming the key path."""
    try:
        return cls.model_validate(data)
    except ValidationError as err:
        raise model_error(err, cls, prefix) from None


def model_error(err: ValidationError, root: type[BaseModel],
                prefix: tuple[str | int, ...] = ()) -> ModelError:
    """One :class:`ModelError` from the first error of ``err``; the count of others is noted."""
    errors = err.errors(include_url=False)
    path, message = describe(errors[0], root, prefix)
    if len(errors) > 1:
        message += f" (and {len(errors) - 1} more error{'s' if len(errors) > 2 else ''})"
    return ModelError(message, path or "top level")


def format_path(loc: tuple[str | int, ...]) -> str:
    """``('shaft', 3, 'od')`` -> ``shaft[3].od``."""
    out = ""
    for item in loc:
        out += f"[{item}]" if isinstance(item, int) else (f".{item}" if out else str(item))
    return out


def describe(error: Any, root: type[BaseModel], prefix: tuple[str | int, ...]) -> tuple[str, str]:
    """Key path and message of one pydantic error."""
    loc = tuple(error["loc"])
    kind, ctx, given = error["type"], error.get("ctx") or {}, error.get("input")
    if kind == ERROR_TYPE:
        return format_path(prefix + loc) + ctx.get("subpath", ""), ctx["reason"]
    if kind == "extra_forbidden":
        key = str(loc[-1])
        valid = tuple(_fields_at(root, loc[:-1]))
        return format_path(prefix + loc[:-1]), f"unknown key '{key}'" + suggest(key, valid)
    path = format_path(prefix + loc)
    messages = {
        "missing": "field required",
        "literal_error": f"must be one of {ctx.get('expected')}, got {show(given)}",
        "greater_than_equal": f"must be >= {ctx.get('ge')}, got {show(given)}",
        "less_than_equal": f"must be <= {ctx.get('le')}, got {show(given)}",
        "too_short": "must not be empty" if ctx.get("min_length") == 1 else
                     f"needs at least {ctx.get('min_length')} entries, got "
                     f"{ctx.get('actual_length')}",
        "too_long": f"takes at most {ctx.get('max_length')} entries",
        "string_too_short": "must not be empty",
    }
    if kind in messages:
        return path, messages[kind]
    expected = next((noun for prefix_, noun in _TYPE_NOUNS if kind.startswith(prefix_)), None)
    if expected:
        return path, f"expected {expected}, got {show(given)}"
    return path, str(error.get("msg", kind))


_TYPE_NOUNS = (("int", "an integer"), ("string", "a string"), ("bool", "true or false"),
               ("list", "an array"), ("tuple", "an array"), ("model", "a table"),
               ("dict", "a table"), ("float", "a number"))


def suggest(key: str, valid: tuple[str, ...] | list[str]) -> str:
    """`` (did you mean 'x'?)`` for the closest valid key, or an empty string."""
    close = difflib.get_close_matches(key, list(valid), n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def _fields_at(root: type[BaseModel], loc: tuple[str | int, ...]) -> list[str]:
    """Field names of the table reached from ``root`` along ``loc``."""
    cls: Any = root
    for item in loc:
        if isinstance(item, int):
            continue
        field = getattr(cls, "model_fields", {}).get(item)
        cls = _table_in(field.annotation) if field is not None else None
        if cls is None:
            return []
    return list(getattr(cls, "model_fields", {}))


def _table_in(annotation: Any) -> type[BaseModel] | None:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in get_args(annotation):
        found = _table_in(arg)
        if found is not None:
            return found
    return None
