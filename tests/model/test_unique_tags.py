"""Tags select elements (critical-speed maps over ``bearings=["DE"]``, ``--tag``, key
paths), so a tag used twice is refused, naming the tag and both positions (issue 12)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import rotorsim as rs
from rotorsim.io.model_file import model_from_dict

MODELS = Path(__file__).resolve().parents[2] / "models"
steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _shaft(n: int = 4) -> list[rs.ShaftElement]:
    return [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel, tag="S")
            for _ in range(n)]  # one segment's elements share their tag: allowed


def _model(name: str) -> dict:
    with open(MODELS / f"{name}.toml", "rb") as stream:
        return tomllib.load(stream)


def test_two_bearings_with_one_tag_are_refused():
    bearings = [rs.BearingElement(n=0, kxx=1e7, tag="DE"), rs.BearingElement(n=4, kxx=1e7,
                                                                             tag="DE")]
    with pytest.raises(rs.ModelError, match=r"^Rotor 'rotor': duplicate tag 'DE': "
                       r"bearing_elements\[0\] and bearing_elements\[1\]"):
        rs.Rotor(_shaft(), bearing_elements=bearings)


def test_a_linear_and_a_rolling_bearing_share_one_namespace():
    ball = rs.BallBearing(n_balls=8, ball_diameter=0.008, pitch_diameter=0.04, Kn=1e10,
                          A0=3e-4)
    rolling = rs.RollingBearing(ball, n=4, tag="DE")
    with pytest.raises(rs.ModelError, match=r"duplicate tag 'DE': bearing_elements\[0\] and "
                       r"nonlinear_elements\[0\]"):
        rs.Rotor(_shaft(), bearing_elements=[rs.BearingElement(n=0, kxx=1e7, tag="DE")],
                 nonlinear_elements=[rolling])


@pytest.mark.parametrize(("kind", "make"), [
    ("disk_elements", lambda n, tag: rs.DiskElement(n=n, m=1.0, Id=0.01, Ip=0.02, tag=tag)),
    ("point_mass_elements", lambda n, tag: rs.PointMass(n=n, m=1.0, tag=tag)),
])
def test_disks_and_point_masses_with_one_tag_are_refused(kind, make):
    elements = [make(1, "X"), make(3, "X")]
    with pytest.raises(rs.ModelError, match=rf"duplicate tag 'X': {kind}\[0\] and "
                       rf"{kind}\[1\]"):
        rs.Rotor(_shaft(), bearing_elements=[rs.BearingElement(n=0, kxx=1e7)],
                 **{kind: elements})


def test_untagged_and_distinct_tags_are_fine():
    rotor = rs.Rotor(_shaft(), [rs.DiskElement(n=2, m=1.0, Id=0.01, Ip=0.02, tag="B0")],
                     [rs.BearingElement(n=0, kxx=1e7), rs.BearingElement(n=4, kxx=1e7),
                      rs.BearingElement(n=2, kxx=1e5, tag="B0")])  # a disk's tag is its own
    assert len(rotor.bearing_elements) == 3


@pytest.mark.parametrize(("model", "section", "other"), [
    ("friswell_5_9_5", "bearings", "bearings"),
    ("friswell_5_9_1", "disks", "disks"),
    ("rolling_ball", "rolling_bearings", "rolling_bearings"),
])
def test_model_file_with_a_repeated_tag_is_refused(model, section, other):
    data = _model(model)
    data[section][1]["tag"] = data[other][0]["tag"]
    tag = data[other][0]["tag"]
    with pytest.raises(rs.ModelError) as info:
        model_from_dict(data)
    assert str(info.value) == (f"{section}[1].tag: duplicate tag {tag!r} (also {other}[0].tag);"
                               " tags select elements, so each must be unique")


def test_model_file_bearing_and_rolling_bearing_with_one_tag_are_refused():
    data = _model("rolling_ball")
    data["bearings"] = [{"tag": "DE", "z": "250 mm", "kxx": "1 MN/m"}]
    with pytest.raises(rs.ModelError, match=r"^rolling_bearings\[0\]\.tag: duplicate tag 'DE' "
                       r"\(also bearings\[0\]\.tag\)"):
        model_from_dict(data)


def test_critical_speed_map_by_tag_varies_the_tagged_bearing():
    data = _model("friswell_5_9_5")
    data["analyses"] = {"map": {"type": "critical_speed_map", "bearings": ["B1"],
                                "stiffness": {"start": "1 MN/m", "stop": "10 MN/m", "num": 2}}}
    model = model_from_dict(data)
    assert model.analyses["map"].bearings == (1,)
