"""Unit strings -> SI (rotorsim.units): conversions, errors naming the key, output units."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.units import (
    DIMENSIONS,
    convert,
    format_speed,
    speed_from_si,
    to_si,
    to_si_array,
)

# Expected values follow from the unit definitions (SI prefixes; 1 rev = 2 pi rad;
# 1 deg = pi/180 rad; 1 in = 25.4 mm; standard gravity 9.80665 m/s^2).
CONVERSIONS = [
    ("50 mm", "length", 0.05),
    ("350 mm", "length", 0.35),
    ("2 in", "length", 0.0508),
    ("32.6 kg", "mass", 32.6),
    ("0.27 kg m^2", "inertia", 0.27),
    ("2.2 kg cm^2", "inertia", 2.2e-4),
    ("1 MN/m", "stiffness", 1e6),
    ("0.8 MN/m", "stiffness", 0.8e6),
    ("3 kN s/m", "damping", 3e3),
    ("1 kN m/rad", "angular_stiffness", 1e3),
    ("5 N m s/rad", "angular_damping", 5.0),
    ("3000 rpm", "speed", 100.0 * math.pi),
    ("50 Hz", "speed", 100.0 * math.pi),
    ("2 kHz", "frequency", 4000.0 * math.pi),
    ("100 rad/s", "speed", 100.0),
    ("5 kN", "force", 5e3),
    ("20 N m", "moment", 20.0),
    ("211 GPa", "modulus", 211e9),
    ("81.2 GPa", "pressure", 81.2e9),
    ("7810 kg/m^3", "density", 7810.0),
    ("0.1 g m", "unbalance", 1e-4),
    ("76 g mm", "unbalance", 7.6e-5),
    ("90 deg", "angle", math.pi / 2),
    ("1 g0", "acceleration", 9.80665),
    ("2 ms", "time", 2e-3),
    ("0.3", "dimensionless", 0.3),
]


@pytest.mark.parametrize(("text", "dimension", "expected"), CONVERSIONS)
def test_unit_strings_convert_to_si(text, dimension, expected):
    # relative 1e-15: the conversion is one multiplication or division by an exact factor
    assert to_si(text, dimension, "key") == pytest.approx(expected, rel=1e-15)


def test_decimal_prefixes_give_the_nearest_double():
    # "350 mm" must be the same double as the literal 0.35, so that model files that give
    # diameters in mm build bit-identical elements to SI builders
    for text, dimension, literal in (("350 mm", "length", 0.35), ("70 mm", "length", 0.07),
                                     ("12 g mm", "unbalance", 12e-6),
                                     ("3 um", "length", 3e-6),
                                     ("0.8 MN/m", "stiffness", 0.8e6)):
        assert convert(text, dimension) == literal


def test_plain_numbers_are_si():
    assert to_si(0.05, "length", "k") == 0.05
    assert to_si(3, "speed", "k") == 3.0
    assert to_si(np.float64(2.5), "mass", "k") == 2.5
    assert to_si("0.05", "length", "k") == 0.05


def test_hz_and_rpm_count_revolutions():
    assert to_si("1 Hz", "speed", "k") == pytest.approx(2 * math.pi, rel=1e-15)
    assert to_si("60 rpm", "speed", "k") == pytest.approx(to_si("1 Hz", "speed", "k"),
                                                          rel=1e-15)
    assert to_si("1 1/s", "speed", "k") == 1.0


@pytest.mark.parametrize(("value", "dimension", "message"), [
    ("50 kg", "length", 'shaft[2].odl: "50 kg" is a mass, expected a length'),
    ("3000 rpm", "length", 'shaft[2].odl: "3000 rpm" is a rotational speed, expected a length'),
    ("1 MN/m", "damping", 'shaft[2].odl: "1 MN/m" is a stiffness, expected a damping '
                          "coefficient"),
    ("1 m/s", "length", 'shaft[2].odl: "1 m/s" is a velocity, expected a length'),
    ("5 degC", "length", 'shaft[2].odl: "5 degC" has units of degree_Celsius ([temperature]),'
                         " expected a length"),
    ("nan m", "length", 'shaft[2].odl: must be finite, got "nan m"'),
    (math.inf, "length", "shaft[2].odl: must be finite, got inf"),
    (True, "length", "shaft[2].odl: expected a number or a string with units, got True"),
    ([1.0], "length", "shaft[2].odl: expected a number or a string with units, got [1.0]"),
    ("mm", "length", "shaft[2].odl: cannot read \"mm\": expected '<number> <unit>', e.g. "
                     "'1 m'"),
])
def test_bad_values_name_the_key(value, dimension, message):
    with pytest.raises(ModelError) as info:
        to_si(value, dimension, "shaft[2].odl")
    assert str(info.value) == message
    assert info.value.where == "shaft[2].odl"


@pytest.mark.parametrize("text", ["5 foo", "5 m m m /", "5 (", "5 2**2**2**2", "x" * 300])
def test_unreadable_units_are_one_line_model_errors(text):
    with pytest.raises(ModelError) as info:
        to_si(text, "length", "disks[0].width")
    assert str(info.value).startswith("disks[0].width: ")
    assert "\n" not in str(info.value)


def test_unknown_dimension_is_a_programming_error():
    with pytest.raises(ValueError, match="unknown dimension"):
        convert(1.0, "lenght")


def test_every_dimension_has_a_parseable_si_unit():
    for name, (unit, _) in DIMENSIONS.items():
        assert convert(f"1 {unit}" if unit else "1", name) == pytest.approx(1.0, rel=1e-15)


def test_arrays_name_the_failing_item():
    assert to_si_array(["1 MN/m", 2e6], "stiffness", "kxx").tolist() == [1e6, 2e6]
    with pytest.raises(ModelError, match=r"^bearings\[0\]\.kxx\[1\]: "):
        to_si_array([1e6, "2 kg"], "stiffness", "bearings[0].kxx")


def test_output_speed_units():
    assert float(speed_from_si(math.pi, "rpm")) == pytest.approx(30.0, rel=1e-15)
    assert float(speed_from_si(2 * math.pi, "Hz")) == pytest.approx(1.0, rel=1e-15)
    assert format_speed(100 * math.pi, "rpm") == "3000 rpm"
    assert format_speed(100.0, "rad/s", digits=3) == "100 rad/s"
    with pytest.raises(ModelError, match="unknown speed unit 'rps'"):
        speed_from_si(1.0, "rps")


def test_pint_is_imported_only_when_a_unit_string_is_parsed():
    code = ("import sys, rotorsim, rotorsim.units, rotorsim.io.model_file; "
            "from rotorsim.units import to_si; to_si(1.0, 'length', 'k'); "
            "a = [m for m in ('pint', 'pydantic') if m in sys.modules]; "
            "to_si('1 mm', 'length', 'k'); print(a, 'pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[] True"
