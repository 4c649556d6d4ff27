"""Bad input to materials and linear elements: one-line ModelError naming element and field."""

from __future__ import annotations

import math

import numpy as np
import pytest
from corpus_checks import assert_one_line_error, shaft

import rotorsim as rs
from rotorsim.errors import ModelError
from rotorsim.model.material import steel

NAN, INF = math.nan, math.inf


def material(**kw):
    args = {"name": "M1", "E": 211e9, "rho": 7810.0, "G_s": 81.2e9}
    args.update(kw)
    return lambda: rs.Material(**args)


def shaft_element(**kw):
    args = {"L": 0.25, "idl": 0.0, "odl": 0.05, "material": steel, "tag": "S3"}
    args.update(kw)
    return lambda: rs.ShaftElement(**args)


def bearing(**kw):
    return lambda: rs.BearingElement(n=0, tag="B1", **kw)


CASES = [
    # materials
    pytest.param(material(E=0.0), r"^Material 'M1': E must be a positive", id="E-zero"),
    pytest.param(material(E=-2e11), r"^Material 'M1': E must be a positive", id="E-negative"),
    pytest.param(material(E=NAN), r"^Material 'M1': E must be .*finite.*nan", id="E-nan"),
    pytest.param(material(E=INF), r"^Material 'M1': E must be .*finite.*inf", id="E-inf"),
    pytest.param(material(E="211e9"),
                 r"^Material 'M1': E must be a number in SI units, got '211e9'", id="E-string"),
    pytest.param(material(E="211 GPa"), r"^Material 'M1': E must be a number.*'211 GPa'",
                 id="E-unit-string"),
    pytest.param(material(rho=0.0), r"^Material 'M1': rho must be a positive", id="rho-zero"),
    pytest.param(material(rho=NAN), r"^Material 'M1': rho must be .*finite", id="rho-nan"),
    pytest.param(material(G_s=-1.0), r"^Material 'M1': G_s must be positive", id="G-negative"),
    pytest.param(material(G_s=0.0), r"^Material 'M1': G_s must be positive", id="G-zero"),
    pytest.param(material(G_s=INF), r"^Material 'M1': G_s must be .*finite", id="G-inf"),
    pytest.param(material(G_s="81 GPa"), r"^Material 'M1': G_s must be a number",
                 id="G-string"),
    pytest.param(material(G_s=NAN, nu=0.5), r"^Material 'M1': Poisson ratio 0\.5000 outside",
                 id="nu-half"),
    pytest.param(material(G_s=NAN, nu=-1.0), r"^Material 'M1': Poisson ratio -1\.0000 outside",
                 id="nu-minus-one"),
    pytest.param(material(G_s=NAN, nu=INF), r"^Material 'M1': nu must be .*finite",
                 id="nu-inf"),
    pytest.param(material(G_s=NAN), r"^Material 'M1': give exactly one of G_s and nu",
                 id="neither-G-nor-nu"),
    pytest.param(lambda: rs.Material(name="M\n1", E=-1.0, rho=7810.0, nu=0.3),
                 r"^Material 'M\\n1': E must be a positive", id="name-with-newline"),
    # shaft elements
    pytest.param(shaft_element(L=-0.25), r"^ShaftElement'S3': L \(length\) must be > 0",
                 id="L-negative"),
    pytest.param(shaft_element(L=INF), r"^ShaftElement'S3': L \(length\) must be finite",
                 id="L-inf"),
    pytest.param(shaft_element(L="0.25 m"), r"^ShaftElement'S3': L \(length\) must be a number",
                 id="L-string"),
    pytest.param(shaft_element(L=-1.0, tag="S\r\n3"), r"^ShaftElement'S\\r\\n3': L \(length\)",
                 id="tag-with-newline"),
    pytest.param(shaft_element(L=[0.25, 0.3]),
                 r"^ShaftElement'S3': L \(length\) must be a single number", id="L-list"),
    pytest.param(shaft_element(L=True), r"^ShaftElement'S3': L \(length\) must be a number, got "
                 r"True", id="L-bool"),
    pytest.param(shaft_element(idl=0.06), r"^ShaftElement'S3': inner diameter idl=0\.06 m must "
                 r"be < outer diameter odl=0\.05 m", id="idl-above-odl"),
    pytest.param(shaft_element(idl=-0.01), r"^ShaftElement'S3': idl must be >= 0",
                 id="idl-negative"),
    pytest.param(shaft_element(odl=NAN), r"^ShaftElement'S3': odl must be finite",
                 id="odl-nan"),
    pytest.param(shaft_element(odl=0.0), r"^ShaftElement'S3': odl must be > 0", id="odl-zero"),
    pytest.param(shaft_element(odr=0.0), r"^ShaftElement'S3': odr must be > 0",
                 id="taper-odr-zero"),
    pytest.param(shaft_element(idr=0.05), r"^ShaftElement'S3': inner diameter idr=0\.05 m must "
                 r"be < outer diameter odr=0\.05 m", id="taper-idr-equals-odr"),
    pytest.param(shaft_element(odr=NAN), r"^ShaftElement'S3': odr must be finite",
                 id="taper-odr-nan"),
    pytest.param(shaft_element(shear_coefficient=0.0),
                 r"^ShaftElement'S3': shear_coefficient must be > 0", id="shear-coefficient-zero"),
    pytest.param(shaft_element(beta=-1e-5), r"^ShaftElement'S3': beta must be >= 0",
                 id="rayleigh-beta-negative"),
    pytest.param(shaft_element(axial_force=NAN), r"^ShaftElement'S3': axial_force must be finite",
                 id="axial-force-nan"),
    pytest.param(shaft_element(material="steel"),
                 r"^ShaftElement'S3': material is missing or not a Material", id="material-name"),
    # disks and point masses
    pytest.param(lambda: rs.DiskElement(n=2, m=-1.0, Id=0.1, Ip=0.2),
                 r"^DiskElement\(n=2\): m must be > 0", id="disk-mass-negative"),
    pytest.param(lambda: rs.DiskElement(n=2, m=1.0, Id=NAN, Ip=0.2, tag="D1"),
                 r"^DiskElement 'D1': Id must be finite", id="disk-Id-nan"),
    pytest.param(lambda: rs.DiskElement(n=2, m=1.0, Id=0.1, Ip=-0.2),
                 r"^DiskElement\(n=2\): Ip must be >= 0", id="disk-Ip-negative"),
    pytest.param(lambda: rs.DiskElement(n=-1, m=1.0, Id=0.1, Ip=0.2),
                 r"^DiskElement\(n=-1\): node number must be a non-negative integer",
                 id="disk-node-negative"),
    pytest.param(lambda: rs.DiskElement(n=2.0, m=1.0, Id=0.1, Ip=0.2),
                 r"^DiskElement\(n=2\.0\): node number must be a non-negative integer",
                 id="disk-node-float"),
    pytest.param(lambda: rs.DiskElement(n=True, m=1.0, Id=0.1, Ip=0.2),
                 r"^DiskElement\(n=True\): node number must be a non-negative integer",
                 id="disk-node-bool"),
    pytest.param(lambda: rs.DiskElement.from_geometry(2, steel, width=0.0, i_d=0.05, o_d=0.2),
                 r"^DiskElement\(n=2\): width must be > 0", id="disk-width-zero"),
    pytest.param(lambda: rs.DiskElement.from_geometry(2, steel, width=0.05, i_d=0.05, o_d=NAN),
                 r"^DiskElement\(n=2\): o_d must be finite", id="disk-od-nan"),
    pytest.param(lambda: rs.DiskElement.from_geometry(2, None, width=0.05, i_d=0.05, o_d=0.2),
                 r"^DiskElement\(n=2\): material must be a Material, got NoneType",
                 id="disk-no-material"),
    pytest.param(lambda: rs.PointMass(n=3, m=0.0), r"^PointMass\(n=3\): mass must be > 0 in at",
                 id="point-mass-zero"),
    pytest.param(lambda: rs.PointMass(n=3, m=5.0, mz=-1.0, tag="P"),
                 r"^PointMass 'P': mz must be >= 0", id="point-mass-negative-direction"),
    pytest.param(lambda: rs.PointMass(n=3, m=NAN), r"^PointMass\(n=3\): m must be finite",
                 id="point-mass-nan"),
    # linear bearings
    pytest.param(bearing(cxx=-100.0), r"^BearingElement 'B1': direct coefficient cxx must be >= 0",
                 id="bearing-damping-negative"),
    pytest.param(bearing(kyy=-1e6, kxx=1e6),
                 r"^BearingElement 'B1': direct coefficient kyy must be >= 0",
                 id="bearing-kyy-negative"),
    pytest.param(bearing(kxx=[1e6, 2e6], cxx=[1.0, 2.0, 3.0], frequency=[0.0, 100.0]),
                 r"^BearingElement 'B1': cxx has 3 values but frequency has 2",
                 id="bearing-arrays-mismatched"),
    pytest.param(bearing(kxx=[1e6, 2e6, 3e6], frequency=[0.0, 200.0, 100.0]),
                 r"^BearingElement 'B1': frequency must be strictly increasing",
                 id="bearing-frequency-non-monotonic"),
    pytest.param(bearing(kxx=[1e6, 2e6], frequency=[0.0, NAN]),
                 r"^BearingElement 'B1': frequency must be a 1-D array of finite",
                 id="bearing-frequency-nan"),
    pytest.param(bearing(kxx=[1e6, NAN], frequency=[0.0, 100.0]),
                 r"^BearingElement 'B1': kxx must be finite", id="bearing-table-nan"),
    pytest.param(bearing(kxx=[[1e6, 2e6]], frequency=[0.0, 100.0]),
                 r"^BearingElement 'B1': kxx must be a number or a 1-D array over frequency, "
                 r"got shape \(1, 2\)", id="bearing-table-2d"),
    pytest.param(bearing(kxx="1 MN/m"), r"^BearingElement 'B1': kxx must be a number",
                 id="bearing-unit-string"),
    pytest.param(bearing(stiffness_matrix=np.eye(4)),
                 r"^BearingElement 'B1': stiffness_matrix must be a finite \(5, 5\) array",
                 id="bearing-matrix-shape"),
    pytest.param(lambda: rs.BearingElement(n=-2, kxx=1e6),
                 r"^BearingElement\(n=-2\): n must be a non-negative integer",
                 id="bearing-node-negative"),
]


@pytest.mark.parametrize(("call", "pattern"), CASES)
def test_element_input_is_refused_by_name(call, pattern):
    assert_one_line_error(call, ModelError, pattern)


ROTOR_CASES = [
    pytest.param(lambda: rs.Rotor(shaft(), [rs.DiskElement(n=5, m=1.0, Id=0.1, Ip=0.1)]),
                 r"^DiskElement\(n=5\): node 5 is not on the shaft \(nodes 0\.\.4\)",
                 id="disk-node-out-of-range"),
    pytest.param(lambda: rs.Rotor(shaft(), [], [rs.BearingElement(n=0, kxx=1e6),
                                                rs.BearingElement(n=40, kxx=1e6)]),
                 r"^BearingElement\(n=40\).*node 40 is not on the shaft",
                 id="bearing-node-out-of-range"),
    pytest.param(lambda: rs.Rotor(shaft(), [], [rs.BearingElement(n=0, kxx=1e6)],
                                  [rs.PointMass(n=9, m=1.0)]),
                 r"^Rotor 'rotor': housing nodes must be numbered 5, 6, \.\.\. without gaps; "
                 r"got \[9\]", id="point-mass-unlinked-node"),
    pytest.param(lambda: rs.Rotor(shaft(), fixed=[(2, "uq")]),
                 r"^Rotor\.fixed: unknown DOF 'uq'", id="fixed-dof-name"),
    pytest.param(lambda: rs.Rotor(shaft(), [rs.BearingElement(n=0, kxx=1e6)]),
                 r"^disk_elements\[0\]: expected a DiskElement, got BearingElement",
                 id="bearing-among-disks"),
    pytest.param(lambda: rs.Rotor(shaft(), [], [rs.DiskElement(n=0, m=1.0, Id=0.1, Ip=0.1)]),
                 r"^bearing_elements\[0\]: expected a BearingElement, got DiskElement",
                 id="disk-among-bearings"),
    pytest.param(lambda: rs.Rotor(shaft(), [None]),
                 r"^disk_elements\[0\]: expected a DiskElement, got NoneType", id="disk-none"),
    pytest.param(lambda: rs.Rotor(shaft(), point_mass_elements=[rs.DiskElement(n=1, m=1.0,
                                                                              Id=0.1, Ip=0.1)]),
                 r"^point_mass_elements\[0\]: expected a PointMass, got DiskElement",
                 id="disk-among-point-masses"),
    pytest.param(lambda: rs.Rotor(shaft(), fixed=[(0, "ux", 3)]),
                 r"^Rotor\.fixed\[0\]: expected \(node, dof\) such as \(0, 'uz'\), got "
                 r"\(0, 'ux', 3\)", id="fixed-triple"),
    pytest.param(lambda: rs.Rotor(shaft(), fixed=["ux"]),
                 r"^Rotor\.fixed\[0\]: expected \(node, dof\)", id="fixed-dof-without-node"),
    pytest.param(lambda: rs.Rotor(shaft(), fixed=[(1.5, "ux")]),
                 r"^Rotor\.fixed\[0\]: expected \(node, dof\).*got \(1\.5, 'ux'\)",
                 id="fixed-fractional-node"),
    pytest.param(lambda: rs.Rotor([*shaft(), "S"]), r"^shaft_elements\[4\]: not a ShaftElement",
                 id="shaft-list-holds-a-string"),
]


@pytest.mark.parametrize(("call", "pattern"), ROTOR_CASES)
def test_rotor_assembly_refuses_bad_nodes(call, pattern):
    assert_one_line_error(call, ModelError, pattern)
