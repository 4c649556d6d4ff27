"""Bad model input raises ModelError naming the element and the field."""

from __future__ import annotations

import math

import pytest

import rotorsim as rs
from rotorsim.model.material import steel


def _shaft(n=4, **kw):
    return [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel, **kw) for _ in range(n)]


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"L": -0.1}, "L (length) must be > 0"),
        ({"L": 0.0}, "L (length) must be > 0"),
        ({"L": math.nan}, "L (length) must be finite"),
        ({"idl": 0.05}, "inner diameter idl=0.05 m must be < outer diameter odl=0.05 m"),
        ({"idr": 0.06, "odr": 0.04}, "inner diameter idr=0.06 m must be < outer"),
        ({"material": None}, "material is missing"),
        ({"odl": -0.05}, "odl must be > 0"),
        ({"alpha": math.inf}, "alpha must be finite"),
    ],
)
def test_shaft_element_errors_name_field(kwargs, fragment):
    args = {"L": 0.25, "idl": 0.0, "odl": 0.05, "material": steel, "tag": "S3"}
    args.update(kwargs)
    with pytest.raises(rs.ModelError, match="ShaftElement'S3'") as info:
        rs.ShaftElement(**args)
    assert fragment in str(info.value)


def test_material_errors():
    with pytest.raises(rs.ModelError, match="Material 'x': E must be"):
        rs.Material(name="x", E=-1.0, rho=7800.0, nu=0.3)
    with pytest.raises(rs.ModelError, match="exactly one of G_s and nu"):
        rs.Material(name="x", E=2e11, rho=7800.0)
    with pytest.raises(rs.ModelError, match="Poisson"):
        rs.Material(name="x", E=2e11, rho=7800.0, nu=0.7)


def test_node_outside_shaft():
    with pytest.raises(rs.ModelError, match=r"DiskElement\(n=9\): node 9 is not on the shaft"):
        rs.Rotor(_shaft(), [rs.DiskElement(n=9, m=1.0, Id=0.1, Ip=0.1)])
    with pytest.raises(rs.ModelError, match=r"BearingElement 'B2'.*node 12 is not on the shaft"):
        rs.Rotor(_shaft(), [], [rs.BearingElement(n=12, kxx=1e6, tag="B2")])


def test_housing_nodes_need_mass_and_consecutive_numbers():
    bearing = rs.BearingElement(n=0, n_link=6, kxx=1e6)
    with pytest.raises(rs.ModelError, match="without gaps"):
        rs.Rotor(_shaft(), [], [bearing], [rs.PointMass(n=6, m=5.0)])
    rotor = rs.Rotor(_shaft(), [], [rs.BearingElement(n=0, n_link=5, kxx=1e6),
                                     rs.BearingElement(n=5, kxx=1e7)], [rs.PointMass(n=5, m=5.0)])
    assert rotor.n_nodes == 6 and rotor.nodes_pos[5] == 0.0


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"kxx": math.nan}, "kxx must be finite"),
        ({"cyy": math.inf}, "cyy must be finite"),
        ({"kxx": -1.0}, "direct coefficient kxx must be >= 0"),
        ({"kxx": [1.0, 2.0]}, "kxx is an array but no frequency is given"),
        ({"kxx": [1.0, 2.0], "frequency": [0.0, 1.0, 2.0]}, "kxx has 2 values but frequency has 3"),
        ({"kxx": [1.0, 2.0], "frequency": [1.0, 0.0]}, "frequency must be strictly increasing"),
        ({"n_link": 0}, "n_link must differ from n"),
    ],
)
def test_bearing_errors(kwargs, fragment):
    with pytest.raises(rs.ModelError, match="BearingElement 'B1'") as info:
        rs.BearingElement(n=0, tag="B1", **kwargs)
    assert fragment in str(info.value)


def test_disk_errors():
    with pytest.raises(rs.ModelError, match=r"DiskElement\(n=2\): m must be > 0"):
        rs.DiskElement(n=2, m=0.0, Id=1.0, Ip=1.0)
    with pytest.raises(rs.ModelError, match=r"bore i_d=0\.3 m must be < outer diameter"):
        rs.DiskElement.from_geometry(2, steel, width=0.05, i_d=0.3, o_d=0.2)


def test_fixed_dof_names_checked():
    with pytest.raises(rs.ModelError, match="unknown DOF 'uw'"):
        rs.Rotor(_shaft(), fixed=[(0, "uw")])
    with pytest.raises(rs.ModelError, match="node 7 outside"):
        rs.Rotor(_shaft(), fixed=[(7, "ux")])


def test_unconnected_housing_rotations_are_inactive_not_errors():
    rotor = rs.Rotor(_shaft(), [], [rs.BearingElement(n=0, n_link=5, kxx=1e6, kzz=1e6),
                                     rs.BearingElement(n=5, kxx=1e7, kzz=1e7)],
                     [rs.PointMass(n=5, m=5.0)])
    system = rs.assemble(rotor)
    assert system.summary["inactive_dofs"] == ["5:rx", "5:ry", "5:rz"]
    assert rs.modal(system, num_modes=4).wn[0] > 0


def test_massless_dof_in_modal_is_reported():
    rotor = rs.Rotor(_shaft(), [], [rs.BearingElement(n=0, n_link=5, kxx=1e6, kzz=1e6),
                                     rs.BearingElement(n=5, kxx=1e7)],
                     [rs.PointMass(n=5, mx=5.0, my=5.0, mz=0.0)])
    with pytest.raises(rs.ModelError, match="DOF uz of node 5 has no mass"):
        rs.modal(rotor)


def test_modal_arguments_checked():
    rotor = rs.Rotor(_shaft(), [], [rs.BearingElement(n=0, kxx=1e6)])
    with pytest.raises(rs.ModelError, match="num_modes must be a positive integer"):
        rs.modal(rotor, num_modes=0)
    with pytest.raises(rs.ModelError, match="speed must be finite"):
        rs.modal(rotor, speed=math.nan)
