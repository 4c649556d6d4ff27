"""Bad input to machines of several lines gets a named error (issue 15)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.errors import ModelError
from rotorsim.io.model_file import model_from_dict
from rotorsim.model.lines import ShaftLine

MODELS = Path(__file__).resolve().parents[2] / "models"
STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _shaft(n: int) -> list[rs.ShaftElement]:
    return [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(n)]


def _two_spool() -> dict:
    with open(MODELS / "two_spool.toml", "rb") as stream:
        return tomllib.load(stream)


def test_overlapping_lines_without_a_connection_are_refused() -> None:
    a, b = ShaftLine("A", _shaft(4)), ShaftLine("B", _shaft(4), z0=0.2)
    bearings = [rs.BearingElement(n=0, kxx=1e7), rs.BearingElement(n=4, kxx=1e7, tag="a2"),
                rs.BearingElement(n=5, kxx=1e7, tag="b1"),
                rs.BearingElement(n=9, kxx=1e7, tag="b2")]
    with pytest.raises(ModelError, match=r"lines 'A' and 'B' overlap along z .* no bearing"):
        rs.Rotor([], bearing_elements=bearings, lines=[a, b])
    joined = [*bearings, rs.BearingElement(n=3, n_link=6, kxx=1e6, tag="inter")]
    assert rs.Rotor([], bearing_elements=joined, lines=[a, b]).n_nodes == 10


def test_a_turning_line_without_rotating_parts_is_refused() -> None:
    casing = [rs.ShaftElement(L=0.1, idl=0.3, odl=0.32, material=STEEL, gyroscopic=False)] * 4
    lines = [ShaftLine("rotor", _shaft(4)), ShaftLine("casing", casing)]  # ratio 1 forgotten
    bearings = [rs.BearingElement(n=0, n_link=5, kxx=1e7),
                rs.BearingElement(n=4, n_link=9, kxx=1e7, tag="b"),
                rs.BearingElement(n=5, kxx=1e8, tag="g1"),
                rs.BearingElement(n=9, kxx=1e8, tag="g2")]
    with pytest.raises(ModelError, match="'casing' has speed_ratio 1 but no rotating parts"):
        rs.Rotor([], bearing_elements=bearings, lines=lines)
    lines[1] = ShaftLine("casing", casing, speed_ratio=0.0)
    assert rs.Rotor([], bearing_elements=bearings, lines=lines).multi_line


def test_lines_and_nodes_that_do_not_exist_are_named() -> None:
    rotor = rs.load_model(MODELS / "two_spool.toml").rotor
    with pytest.raises(ModelError, match="no line named 'IP'"):
        rotor.node("IP", 0)
    with pytest.raises(ModelError, match=r"line 'HP' has nodes 0\.\.8"):
        rotor.node("HP", 9)
    with pytest.raises(ModelError, match="no line named 'IP'"):
        rs.critical_speeds(rotor, spool="IP")
    with pytest.raises(ModelError, match="does not rotate"):
        rs.critical_speeds(rotor, spool="casing")
    casing_node = rotor.node("casing", 3)
    with pytest.raises(ModelError, match=r"unbalance\[0\].*does not rotate"):
        rs.unbalance_response(rotor, [100.0], [(casing_node, 1e-4, 0.0)])


@pytest.mark.parametrize(("edit", "where", "message"), [
    (lambda d: d["bearings"][3].update(link_line="IP"), "bearings[3]", "no line named 'IP'"),
    (lambda d: d["bearings"][0].update(n_link=40, link_line="casing"), "bearings[0].n_link",
     "not a node of line 'casing'"),
    (lambda d: d["disks"][0].pop("line"), "disks[0]", "give line = one of LP, HP, casing"),
    (lambda d: d["disks"][2].update(z="1.35 m"), "disks[2].z", "not a node position"),
    (lambda d: d["bearings"][0].update(link_z="0.2 m", link_line=None) or
     d["bearings"][0].pop("link_line"), "bearings[0].link_z", "needs link_line"),
    (lambda d: d.update(shaft=[{"length": "1 m", "od": "50 mm", "material": "steel"}]),
     "shaft", "not both"),
])
def test_model_files_with_bad_line_references_name_the_key(edit, where, message) -> None:
    data = _two_spool()
    edit(data)
    with pytest.raises(ModelError, match=message) as info:
        model_from_dict(data)
    assert info.value.where.startswith(where)


def test_one_line_model_files_refuse_a_line_key() -> None:
    with open(MODELS / "default.toml", "rb") as stream:
        data = tomllib.load(stream)
    data["disks"][0]["line"] = "LP"
    with pytest.raises(ModelError, match="one shaft line"):
        model_from_dict(data)


def test_one_line_rotors_are_unchanged() -> None:
    rotor = rs.load_model(MODELS / "default.toml").rotor
    assert not rotor.multi_line and rotor.lines == ()
    assert [line.name for line in rotor.layout.lines] == ["shaft"]
    assert np.all(rotor.node_speed_ratio[: rotor.n_shaft_nodes] == 1.0)
    assert "line shaft" not in rotor.summary()
