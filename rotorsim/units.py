"""Unit strings at the edges of rotorsim (model files, CLI); the core works in SI.

A value is either a plain number, taken as SI, or a string ``"<number> <unit>"`` such as
``"50 mm"``, ``"1 MN/m"``, ``"3 kN s/m"``, ``"0.1 g m"`` or ``"3000 rpm"``. Strings are
parsed with pint (imported on first use, so ``import rotorsim`` stays light) and converted
to the SI unit of the dimension the caller expects; a string of another dimension is an
error that names the key (``shaft[2].odl: "50 kg" is a mass, expected a length``).

Rotational speeds and frequencies are angular inside rotorsim (rad/s). ``Hz`` (and its
prefixed forms), ``rps`` and ``rpm`` count revolutions, so ``"1 Hz"`` is ``2 pi rad/s``;
``rad/s`` and ``1/s`` are angular.

Examples
--------
>>> to_si("50 mm", "length", "shaft[0].od")
0.05
>>> round(to_si("3000 rpm", "speed", "speeds.stop"), 4)
314.1593
>>> to_si(2.5, "length", "shaft[0].length")
2.5
>>> to_si("50 kg", "length", "shaft[2].odl")
Traceback (most recent call last):
...
rotorsim.errors.ModelError: shaft[2].odl: "50 kg" is a mass, expected a length
>>> format_speed(314.159265, "rpm")
'3000 rpm'
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Sequence
from functools import cache
from typing import Any

import numpy as np

from rotorsim.errors import ModelError

DIMENSIONS: dict[str, tuple[str, str]] = {
    "length": ("m", "a length"),
    "mass": ("kg", "a mass"),
    "time": ("s", "a time"),
    "inertia": ("kg m^2", "a moment of inertia"),
    "stiffness": ("N/m", "a stiffness"),
    "damping": ("N s/m", "a damping coefficient"),
    "angular_stiffness": ("N m/rad", "an angular stiffness"),
    "angular_damping": ("N m s/rad", "an angular damping coefficient"),
    "speed": ("rad/s", "a rotational speed"),
    "frequency": ("rad/s", "a frequency"),
    "rate": ("1/s", "a rate"),
    "force": ("N", "a force"),
    "moment": ("N m", "a moment"),
    "pressure": ("Pa", "a pressure"),
    "power": ("W", "a power"),
    "modulus": ("Pa", "a modulus"),
    "density": ("kg/m^3", "a density"),
    "unbalance": ("kg m", "an unbalance (mass times eccentricity)"),
    "angle": ("rad", "an angle"),
    "acceleration": ("m/s^2", "an acceleration"),
    "dimensionless": ("", "a plain number"),
}
"""Dimensions understood by :func:`to_si`: name -> (SI unit, description)."""

_NAMING_ORDER = ("length", "mass", "time", "speed", "force", "moment", "stiffness",
                 "damping", "pressure", "power", "density", "unbalance", "inertia",
                 "acceleration", "dimensionless")
_EXTRA_NAMES = (("m/s", "a velocity"), ("m^2", "an area"), ("m^3", "a volume"),
                ("kg/s", "a mass flow"), ("N s", "an impulse"))

SPEED_UNITS: dict[str, float] = {"rad/s": 1.0, "rpm": 30.0 / math.pi, "Hz": 0.5 / math.pi}
"""Output units of speeds and frequencies: factor from rad/s to the unit."""

_NUMBER = re.compile(
    r"^\s*([+-]?(?:(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?|(?:nan|inf(?:inity)?)(?![a-z])))"
    r"\s*(.*?)\s*$", re.IGNORECASE)
_MAX_TEXT = 200


class UnitParseError(ValueError):
    """A value could not be converted; the message does not name the key."""


@cache
def _registry() -> Any:
    """The shared pint registry, with Hz counting revolutions per second."""
    import pint

    ureg: Any = pint.UnitRegistry(on_redefinition="ignore")
    ureg.define("hertz = revolution / second = Hz")
    return ureg


@cache
def _dimensionality(unit: str) -> Any:
    return _registry().parse_units(unit).dimensionality


def _describe(dimensionality: Any, units: Any) -> str:
    for name in _NAMING_ORDER:
        if _dimensionality(DIMENSIONS[name][0]) == dimensionality:
            return "is " + DIMENSIONS[name][1]
    for unit, noun in _EXTRA_NAMES:
        if _dimensionality(unit) == dimensionality:
            return "is " + noun
    return f"has units of {units} ({dimensionality})"


def convert(value: Any, dimension: str) -> float:
    """Convert ``value`` to SI of ``dimension``; raise :class:`UnitParseError` if impossible.

    The validators of the model-file schema use this; user code should call :func:`to_si`,
    which names the key in the error.

    Parameters
    ----------
    value : float, int or str
        A plain number (SI) or ``"<number> <unit>"``.
    dimension : str
        One of :data:`DIMENSIONS`.

    Returns
    -------
    float
        The finite value in the SI unit of ``dimension``.
    """
    if dimension not in DIMENSIONS:
        raise ValueError(f"unknown dimension {dimension!r}; use one of {sorted(DIMENSIONS)}")
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating
                                                 | str):
        raise UnitParseError(f"expected a number or a string with units, got {_show(value)}")
    number = _parse(value, dimension) if isinstance(value, str) else float(value)
    if not math.isfinite(number):
        raise UnitParseError(f"must be finite, got {_show(value)}")
    return number


def _parse(text: str, dimension: str) -> float:
    if len(text) > _MAX_TEXT:
        raise UnitParseError(f"string too long ({len(text)} characters)")
    match = _NUMBER.match(text)
    if match is None:
        raise UnitParseError(f"cannot read {_show(text)}: expected '<number> <unit>', e.g. "
                             f"'{_example(dimension)}'")
    magnitude, unit_text = float(match.group(1)), match.group(2)
    if not unit_text:
        return magnitude
    if unit_text.startswith("/"):
        unit_text = "1" + unit_text
    try:
        units = _registry().parse_units(unit_text)
    except Exception as err:  # pint raises many types on malformed unit text
        detail = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        raise UnitParseError(f"cannot read the unit of {_show(text)}: {detail}") from None
    target = DIMENSIONS[dimension][0]
    if units.dimensionality != _dimensionality(target):
        raise UnitParseError(
            f"{_show(text)} {_describe(units.dimensionality, units)}, expected "
            f"{DIMENSIONS[dimension][1]}"
        )
    try:
        factor = float(_registry().Quantity(1.0, units).to(target or "dimensionless").magnitude)
    except Exception as err:  # offset units (degC) and similar
        raise UnitParseError(f"cannot convert {_show(text)} to {target}: {err}") from None
    return _scale(magnitude, factor)


def _scale(magnitude: float, factor: float) -> float:
    """``magnitude * factor``, dividing instead when ``factor`` is ``1 / integer`` (decimal
    prefixes) so that ``"350 mm"`` gives exactly ``0.35``."""
    if 0.0 < factor < 1.0:
        inverse = round(1.0 / factor)
        if abs(1.0 / factor - inverse) <= 1e-9 * inverse:
            return magnitude / inverse
    return magnitude * factor


def _show(value: Any) -> str:
    """Short one-line text of a user value for messages (control characters escaped)."""
    text = json.dumps(value, ensure_ascii=False) if isinstance(value, str) else repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _example(dimension: str) -> str:
    unit = DIMENSIONS[dimension][0]
    return f"1 {unit}" if unit else "1"


def to_si(value: Any, dimension: str, where: str) -> float:
    """Convert a number (SI) or a string with units to SI.

    Parameters
    ----------
    value : float, int or str
        ``0.05`` or ``"50 mm"``.
    dimension : str
        Expected dimension, one of :data:`DIMENSIONS` (``"length"``, ``"stiffness"``,
        ``"speed"``, ...).
    where : str
        Key path of the value, used in the error message.

    Returns
    -------
    float
        The value in the SI unit of ``dimension`` (m, kg, N/m, rad/s, ...).

    Raises
    ------
    ModelError
        Unreadable string, wrong dimension or a non-finite value.
    """
    try:
        return convert(value, dimension)
    except UnitParseError as err:
        raise ModelError(str(err), where) from None


def to_si_array(values: Sequence[Any], dimension: str, where: str) -> np.ndarray:
    """Convert numbers or unit strings with :func:`to_si`; errors name ``where[i]``.

    Examples
    --------
    >>> to_si_array([0.1, "200 mm"], "length", "z").tolist()
    [0.1, 0.2]
    """
    if isinstance(values, str) or not isinstance(values, Sequence | np.ndarray):
        raise ModelError(f"expected a list of values, got {_show(values)}", where)
    return np.array([to_si(v, dimension, f"{where}[{i}]") for i, v in enumerate(values)],
                    dtype=float)


def speed_from_si(value: float | np.ndarray, unit: str) -> Any:
    """Convert speeds or frequencies from rad/s to ``unit`` (``rad/s``, ``rpm`` or ``Hz``).

    Examples
    --------
    >>> float(speed_from_si(2 * math.pi, "Hz"))
    1.0
    """
    if unit not in SPEED_UNITS:
        raise ModelError(f"unknown speed unit {unit!r}; use one of {list(SPEED_UNITS)}", "units")
    return np.asarray(value, dtype=float) * SPEED_UNITS[unit]


def format_speed(value: float, unit: str = "rpm", digits: int = 4) -> str:
    """Text of a speed given in rad/s, in ``unit`` with ``digits`` significant digits.

    Examples
    --------
    >>> format_speed(100.0, "rad/s")
    '100 rad/s'
    >>> format_speed(100.0, "Hz")
    '15.92 Hz'
    """
    return f"{float(speed_from_si(value, unit)):.{digits}g} {unit}"
