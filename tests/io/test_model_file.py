"""Model files: loading, the bad-input corpus (one-line errors naming the key path), and
save/load round trips with identical assembled matrices."""

from __future__ import annotations

import itertools
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import Grid
from rotorsim.io.linear_specs import (
    CampbellSpec,
    CriticalSpeedMapSpec,
    FrequencyResponseSpec,
    UnbalanceSpec,
)
from rotorsim.io.model_file import Model, load_model, model_from_dict, run_analysis, save_model
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

MODELS = Path(__file__).resolve().parents[2] / "models"
RPM = math.pi / 30.0  # rad/s per rpm


def base() -> dict:
    """The Friswell 5.9.5 model file as a dict (6 elements, nodes every 0.25 m)."""
    with open(MODELS / "friswell_5_9_5.toml", "rb") as stream:
        return tomllib.load(stream)


def assert_same_matrices(a: Rotor, b: Rotor, speeds=(0.0, 150.0, 1500.0)) -> None:
    sa, sb = assemble(a), assemble(b)
    assert sa.dof_map.n_free == sb.dof_map.n_free
    for w in speeds:
        ma, mb = sa.matrices(w), sb.matrices(w)
        for key in "MCGK":
            diff = getattr(ma, key) - getattr(mb, key)
            assert diff.count_nonzero() == 0, (key, w)


# ---------------------------------------------------------------- loading
def test_units_and_positions_are_resolved():
    model = load_model(MODELS / "friswell_5_9_5.toml")
    rotor = model.rotor
    assert model.name == "friswell_5_9_5" and model.source == MODELS / "friswell_5_9_5.toml"
    assert [d.n for d in rotor.disk_elements] == [2, 4]
    assert [b.n for b in rotor.bearing_elements] == [0, 6]
    b = rotor.bearing_elements[0]
    assert (b.kxx, b.kyy, b.cxx, b.cyy) == (1e6, 1e6, 3e3, 3e3)
    assert model.loads.unbalance == ((4, 1e-4, 0.0),)
    camp = model.analyses["campbell"]
    assert isinstance(camp, CampbellSpec)
    assert camp.speeds == Grid(0.0, 4000 * RPM, 41, "linear")
    assert isinstance(model.analyses["unbalance"], UnbalanceSpec)
    assert model.analyses["unbalance"].unbalance is None  # uses [[loads.unbalance]]


def test_model_from_dict_matches_load_model():
    a = load_model(MODELS / "friswell_5_9_5.toml")
    b = model_from_dict(base(), source=MODELS / "friswell_5_9_5.toml")
    assert_same_matrices(a.rotor, b.rotor)
    assert a.analyses == b.analyses and a.loads == b.loads


def test_analyses_as_an_array_of_tables_with_default_names():
    data = base()
    data["analyses"] = [{"type": "modal", "num_modes": 4},
                        {"type": "campbell", "name": "run_up",
                         "speeds": [0, "1000 rpm", "2000 rpm"]}]
    model = model_from_dict(data)
    assert list(model.analyses) == ["modal", "run_up"]
    assert model.analyses["run_up"].speeds.values == (0.0, 1000 * RPM, 2000 * RPM)
    data["analyses"].append({"type": "modal"})
    with pytest.raises(ModelError, match=r"^analyses\[2\]\.name: duplicate analysis name "):
        model_from_dict(data)


def test_bearing_tables_with_units_and_references():
    data = base()
    data["bearings"][1] = {"z": "1.5 m", "tag": "soft",
                           "frequency": {"values": [0, 3000], "unit": "rpm"},
                           "kxx": {"values": [1, 2], "unit": "MN/m"}, "kxy": ["0.1 MN/m", 0]}
    data["analyses"] = {
        "map": {"type": "critical_speed_map", "bearings": ["soft", 0],
                "stiffness": {"start": "1 MN/m", "stop": "1 GN/m", "num": 5}},
        "frf": {"type": "frequency_response", "inputs": [{"z": "0.5 m", "dof": "uy"}],
                "frequencies": {"start": 1, "stop": 100, "num": 3, "unit": "Hz"}},
    }
    model = model_from_dict(data)
    b = model.rotor.bearing_elements[1]
    assert b.speed_dependent and float(b.coefficient("kxx", 50 * math.pi)) == 1.5e6
    assert float(b.coefficient("kxy", 0.0)) == 1e5 and float(b.coefficient("kyy", 0.0)) == 1e6
    cmap = model.analyses["map"]
    assert isinstance(cmap, CriticalSpeedMapSpec) and cmap.bearings == (1, 0)
    assert cmap.stiffness == Grid(1e6, 1e9, 5, "log")
    frf = model.analyses["frf"]
    assert isinstance(frf, FrequencyResponseSpec) and frf.inputs == ((2, "uy"),)
    assert frf.frequencies.array()[-1] == pytest.approx(200 * math.pi, rel=1e-15)


def test_housing_nodes_point_masses_and_fixed_dofs():
    data = base()
    data["point_masses"] = [{"node": 7, "m": "50 kg", "tag": "pedestal"}]
    data["bearings"][0] = {"node": 0, "n_link": 7, "kxx": "1 MN/m"}
    data["bearings"].append({"node": 7, "kxx": "50 MN/m"})
    data["fixed"] = [{"node": 7, "dofs": ["uz", "rz"]}]
    model = model_from_dict(data)
    assert model.rotor.n_nodes == 8 and model.rotor.bearing_elements[0].nodes == (0, 7)
    assert model.rotor.fixed == ((7, "uz"), (7, "rz"))
    data["point_masses"][0]["node"] = 8
    with pytest.raises(ModelError, match=r"^point_masses\[0\]\.node: housing node 8: "):
        model_from_dict(data)


def test_z_must_be_within_a_nanometre_of_a_node():
    data = base()
    data["disks"][0]["z"] = 0.5 + 5e-10
    assert model_from_dict(data).rotor.disk_elements[0].n == 2
    data["disks"][0]["z"] = 0.5 + 5e-9
    with pytest.raises(ModelError, match=r"^disks\[0\]\.z: 0\.5 m is not a node position"):
        model_from_dict(data)


def test_tapered_segment_interpolates_diameters():
    data = base()
    data["shaft"] = [{"length": 1.5, "n_elements": 6, "id": "10 mm", "odl": "60 mm",
                      "odr": "40 mm", "material": "steel"}]
    shaft = model_from_dict(data).rotor.shaft_elements
    assert shaft[0].odl == 0.06 and shaft[-1].odr == 0.04
    assert all(a.odr == b.odl for a, b in itertools.pairwise(shaft))
    np.testing.assert_allclose([el.odl for el in shaft], 0.06 - 0.02 * np.arange(6) / 6,
                               rtol=1e-15)


def test_run_analysis_rejects_unknown_names():
    model = load_model(MODELS / "friswell_5_9_5.toml")
    with pytest.raises(ModelError, match=r"^friswell_5_9_5: no analysis 'nope'"):
        run_analysis(model, "nope")


# ---------------------------------------------------------------- bad-input corpus
def _set(path, value):
    def mutate(d):
        *parents, last = path
        for key in parents:
            d = d[key]
        d[last] = value
    return mutate


def _delete(path):
    def mutate(d):
        *parents, last = path
        for key in parents:
            d = d[key]
        del d[last]
    return mutate


def _append(path, value):
    def mutate(d):
        for key in path:
            d = d[key]
        d.append(value)
    return mutate


def _node_instead_of_z(index, node):
    def mutate(d):
        del d["disks"][index]["z"]
        d["disks"][index]["node"] = node
    return mutate


CORPUS = [
    # (mutation, exact key path, start of the reason)
    (_set(("bearings", 1, "kxz"), 1e6), "bearings[1]", "unknown key 'kxz'"),
    (_set(("shaft", 0, "lenght"), 1.0), "shaft[0]", "unknown key 'lenght' (did you mean"),
    (_set(("foo",), 1), "top level", "unknown key 'foo'"),
    (_set(("analyses", "campbell", "num_mode"), 4), "analyses.campbell",
     "unknown key 'num_mode'"),
    (_set(("analyses", "campbell", "speeds", "step"), 4), "analyses.campbell.speeds",
     "unknown key 'step'"),
    (_delete(("materials", 0, "E")), "materials[0].E", "field required"),
    (_delete(("shaft", 0, "material")), "shaft[0].material", "field required"),
    (_delete(("analyses", "campbell", "speeds")), "analyses.campbell.speeds", "field required"),
    (_delete(("analyses", "campbell", "speeds", "num")), "analyses.campbell.speeds.num",
     "field required"),
    # no [[shaft]] is a rigid rotor at node 0 (z = 0): items elsewhere are refused
    (_delete(("shaft",)), "disks[0].z", "0.5 m is not a node position; nearest nodes: 0 at"),
    (_set(("shaft",), []), "disks[0].z", "0.5 m is not a node position; nearest nodes: 0 at"),
    (_set(("shaft", 0, "n_elements"), "six"), "shaft[0].n_elements", "expected an integer"),
    (_set(("shaft", 0, "n_elements"), 6.0), "shaft[0].n_elements", "expected an integer"),
    (_set(("shaft", 0, "gyroscopic"), "yes"), "shaft[0].gyroscopic", "expected true or false"),
    (_set(("bearings", 0, "tag"), 5), "bearings[0].tag", "expected a string"),
    (_set(("materials",), "steel"), "materials", "expected an array"),
    (_set(("shaft", 0), 5), "shaft[0]", "expected a table"),
    (_set(("bearings", 0, "kxx"), True), "bearings[0].kxx", "expected a number"),
    (_set(("shaft", 0, "od"), "50 kg"), "shaft[0].od", '"50 kg" is a mass, expected a length'),
    (_set(("bearings", 0, "cxx"), "3 kN/m"), "bearings[0].cxx",
     '"3 kN/m" is a stiffness, expected a damping coefficient'),
    (_set(("analyses", "campbell", "speeds", "stop"), "4000 m"),
     "analyses.campbell.speeds.stop", '"4000 m" is a length, expected a rotational speed'),
    (_set(("loads", "unbalance", 0, "magnitude"), "0.1 g"), "loads.unbalance[0].magnitude",
     '"0.1 g" is a mass, expected an unbalance'),
    (_set(("shaft", 0, "od"), "5 foo"), "shaft[0].od", 'cannot read the unit of "5 foo"'),
    (_set(("shaft", 0, "od"), -0.05), "shaft[0].od", "must be > 0, got -0.05"),
    (_set(("shaft", 0, "length"), "-1.5 m"), "shaft[0].length", 'must be > 0, got "-1.5 m"'),
    (_set(("disks", 0, "width"), 0), "disks[0].width", "must be > 0"),
    (_set(("bearings", 0, "kxx"), "-1 MN/m"), "bearings[0].kxx", "must be >= 0"),
    (_set(("shaft", 0, "n_elements"), 0), "shaft[0].n_elements", "must be >= 1"),
    (_set(("shaft", 0, "od"), math.nan), "shaft[0].od", "must be finite, got nan"),
    (_set(("bearings", 1, "kxx"), math.inf), "bearings[1].kxx", "must be finite"),
    (_set(("materials", 0, "rho"), "nan kg/m^3"), "materials[0].rho", "must be finite"),
    (_set(("shaft", 0, "id"), "60 mm"), "shaft[0].od", "must be > id (0.06 m)"),
    (_set(("disks", 0, "i_d"), "300 mm"), "disks[0].o_d", "must be > i_d (0.3 m)"),
    (_node_instead_of_z(0, 40), "disks[0].node", "node 40 is not a shaft node (0..6)"),
    (_set(("bearings", 0, "n_link"), 9), "bearings[0].n_link", "node 9 is neither"),
    (_set(("analyses", "unbalance", "nodes"), [99]), "analyses.unbalance.nodes[0]",
     "node 99 is neither"),
    (_set(("shaft", 0, "material"), "stel"), "shaft[0].material",
     "unknown material 'stel' (defined: steel)"),
    (_set(("disks", 1, "z"), "0.512 m"), "disks[1].z",
     "0.512 m is not a node position; nearest nodes: 2 at 0.5 m, 3 at 0.75 m"),
    (_set(("loads", "unbalance", 0, "z"), 2.0), "loads.unbalance[0].z",
     "2 m is not a node position"),
    (_set(("shaft",), {}), "shaft", "expected an array"),
    (_set(("bearings", 0, "kxx"), [1e6, 2e6]), "bearings[0].kxx",
     "is an array but no frequency is given"),
    (_set(("bearings", 0, "frequency"), [0.0, 10.0, 5.0]), "bearings[0].frequency",
     "values must be strictly increasing"),
    (_set(("disks", 0, "node"), 2), "disks[0].z", "give node or z, not both"),
    (_delete(("disks", 0, "z")), "disks[0]", "give node or z"),
    (_set(("disks", 0, "m"), 3.0), "disks[0].width", "give m, Id, Ip or width"),
    (_set(("materials", 0, "nu"), 0.2), "materials[0].nu", "disagrees with G_s"),
    # issue 12: E = "1 Pa" ran for minutes (ARPACK far from every mode) with no hint
    (_set(("materials", 0, "E"), "1 Pa"), "materials[0].E",
     "1 Pa is outside the range of solid materials, 1e+06 Pa (soft rubber) to 1.2e+12 Pa"),
    (_set(("materials", 0, "E"), "5 TPa"), "materials[0].E",
     "5e+12 Pa is outside the range of solid materials"),
    (_append(("materials",), {"name": "steel", "E": 1e9, "rho": 1e3, "nu": 0.3}),
     "materials[1].name", "duplicate material 'steel'"),
    (_set(("analyses", "campbell", "type"), "campbel"), "analyses.campbell.type",
     "unknown analysis type \"campbel\" (did you mean 'campbell'?)"),
    (_set(("analyses", "unbalance", "units"), "rps"), "analyses.unbalance.units",
     "must be one of 'rpm', 'Hz' or 'rad/s'"),
    (_set(("analyses", "campbell", "speeds", "num"), -3), "analyses.campbell.speeds.num",
     "must be an integer in 1..100000"),
    (_set(("analyses", "campbell", "speeds", "stop"), 0), "analyses.campbell.speeds.stop",
     "must be > start (0 rad/s)"),
    (_set(("analyses",), "campbell"), "analyses", "expected named tables"),
    (_set(("loads", "unbalance"), []), "analyses.unbalance", "no unbalance given"),
    (_set(("loads", "gravity_direction"), [0, 0, 0]), "loads.gravity_direction",
     "must not be zero"),
]


@pytest.mark.parametrize(("mutate", "path", "reason"), CORPUS,
                         ids=[f"{i}-{c[1]}" for i, c in enumerate(CORPUS)])
def test_bad_input_gives_one_line_error_with_key_path(mutate, path, reason):
    data = base()
    mutate(data)
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    message = str(info.value)
    assert info.value.where == path
    assert message.startswith(f"{path}: {reason}"), message
    assert "\n" not in message


def test_several_errors_are_counted_in_one_line():
    data = base()
    data["shaft"][0]["od"] = "5 kg"
    data["bearings"][0]["kxx"] = "1 kg"
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert str(info.value).startswith("shaft[0].od: ")
    assert str(info.value).endswith("(and 1 more error)")


def test_toml_syntax_errors_give_line_and_column(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('[model]\nname = "x"\n[[shaft]]\nlength = \n')
    with pytest.raises(ModelError) as info:
        load_model(path)
    assert str(info.value).startswith(f"{path}: invalid TOML: ")
    assert "line 4, column" in str(info.value)


def test_missing_and_binary_files_are_model_errors(tmp_path):
    with pytest.raises(ModelError, match="cannot read the file"):
        load_model(tmp_path / "nothing.toml")
    (tmp_path / "bin.toml").write_bytes(b"\xff\xfe\x00")
    with pytest.raises(ModelError, match="not a UTF-8 text file"):
        load_model(tmp_path / "bin.toml")


# ---------------------------------------------------------------- round trips
@pytest.mark.parametrize("name", sorted(p.stem for p in MODELS.glob("*.toml")))
def test_every_model_file_round_trips(tmp_path, name):
    model = load_model(MODELS / f"{name}.toml")
    again = load_model(save_model(model, tmp_path / f"{name}.toml"))
    assert_same_matrices(model.rotor, again.rotor)
    assert again.name == model.name and again.description == model.description
    assert again.loads == model.loads
    assert again.analyses == model.analyses
    assert list(again.analyses) == list(model.analyses)


def feature_rotor() -> Rotor:
    """A rotor using every feature the writer must reproduce exactly."""
    steel = Material(name="steel", E=210e9, rho=7850.0, nu=0.3)
    alloy = Material(name="steel", E=110e9, rho=4430.0, G_s=42e9)  # same name, other values
    shaft = [ShaftElement(L=0.1, idl=0.01, odl=0.05, material=steel) for _ in range(3)]
    shaft += [ShaftElement(L=0.07, idl=0.0, odl=0.05, idr=0.01, odr=0.04, material=alloy,
                           shear_effects=False, tag="cone"),
              ShaftElement(L=0.07, idl=0.01, odl=0.04, idr=0.0, odr=0.03, material=alloy,
                           tag="cone")]
    shaft += [ShaftElement(L=0.2, idl=0.0, odl=0.03, material=steel, rotary_inertia=False,
                           gyroscopic=False, axial_force=-500.0, shear_coefficient=0.8,
                           alpha=0.5, beta=1e-5, tag="tail") for _ in range(2)]
    disks = [DiskElement(n=2, m=3.1, Id=0.011, Ip=0.02, tag="d"),
             DiskElement.from_geometry(5, steel, 0.03, 0.03, 0.2)]
    freq = np.array([0.0, 100.0, 400.0])
    bearings = [
        BearingElement(n=0, kxx=[1e7, 2e7, 3e7], kyy=[1e7, 2e7, 3e7], kxy=[1e5, 0.0, -1e5],
                       cxx=500.0, cyy=0.0, mxx=0.2, krr=1e3, crr=2.0, czz=3.0,
                       frequency=freq, n_link=8, tag="B0"),
        BearingElement(n=7, kxx=5e6, kyy=4e6, kzz=1e8, cxy=-10.0, cyx=10.0, myx=0.1),
        BearingElement(n=8, kxx=1e9, cxx=1e3, tag="pedestal"),
    ]
    masses = [PointMass(n=8, m=20.0, mz=0.0, tag="housing"), PointMass(n=3, m=0.5)]
    fixed = [(8, "uz"), (8, "rz"), (0, "uz"), (0, "rz")]
    return Rotor(shaft, disks, bearings, masses, fixed=fixed, tag="features")


def test_rotor_round_trip_keeps_every_feature(tmp_path):
    rotor = feature_rotor()
    path = save_model(rotor, tmp_path / "features.toml")
    model = load_model(path)
    assert_same_matrices(rotor, model.rotor, speeds=(0.0, 50.0, 250.0, 1000.0))
    assert model.rotor.fixed == rotor.fixed and model.rotor.n_nodes == rotor.n_nodes
    assert [el.tag for el in model.rotor.shaft_elements] == [el.tag for el in rotor.shaft_elements]
    text = tomllib.loads(path.read_text())
    # identical runs collapse to one segment; 0.3 / 3 != 0.1 in floating point, so that run
    # is written with its element length; tapered elements stay one per segment
    assert [s["n_elements"] for s in text["shaft"]] == [3, 1, 1, 2]
    assert "element_length" in text["shaft"][0] and "length" in text["shaft"][3]
    assert [m["name"] for m in text["materials"]] == ["steel", "steel_2"]
    assert text["bearings"][1]["kyy"] == 4e6 and "kyy" not in text["bearings"][2]
    assert text["bearings"][0]["cyy"] == 0.0  # differs from the default cyy = cxx


def test_saved_model_is_readable_toml(tmp_path):
    model = load_model(MODELS / "compressor.toml")
    text = save_model(model, tmp_path / "c.toml").read_text()
    assert text.startswith("[model]\nname = \"compressor\"")
    assert "\n[[bearings]]\n" in text and "\n[analyses.campbell]\n" in text
    assert "speeds = { start = 0.0, stop = " in text
    assert not list(tmp_path.glob(".*.tmp"))  # the temporary file was renamed


def test_save_model_rejects_other_objects(tmp_path):
    with pytest.raises(ModelError, match="expected a Model or Rotor"):
        save_model("rotor", tmp_path / "x.toml")  # type: ignore[arg-type]
    assert isinstance(load_model(MODELS / "tapered.toml"), Model)


def test_the_example_in_the_reference_loads_and_runs(tmp_path):
    import re

    doc = (MODELS.parent / "docs" / "model_files.md").read_text()
    first = re.findall(r"```toml\n(.*?)```", doc, re.S)[0]
    path = tmp_path / "first.toml"
    path.write_text(first)
    model = load_model(path)
    assert [d.n for d in model.rotor.disk_elements] == [2, 4]
    for name in model.analyses:
        run_analysis(model, name, fast=True)


def test_full_bearing_matrices_round_trip(tmp_path):
    """A bearing with a full (5, 5) stiffness and damping (e.g. a linearised rolling
    bearing) is written and read back exactly."""
    import numpy as np

    import rotorsim as rs

    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
    K5 = np.diag([1e8, 2e8, 5e7, 1e4, 1e4])
    K5[0, 4] = K5[4, 0] = 3.5e5
    rotor = rs.Rotor([rs.ShaftElement(L=0.2, idl=0.0, odl=0.04, material=steel)] * 3, [],
                     [rs.BearingElement(n=0, stiffness_matrix=K5, damping_matrix=K5 * 1e-5),
                      rs.BearingElement(n=3, kxx=1e7)])
    path = rs.save_model(rotor, tmp_path / "full.toml")
    back = rs.load_model(path).rotor
    np.testing.assert_array_equal(back.bearing_elements[0].stiffness_matrix, K5)
    a, b = rs.assemble(rotor).matrices(0.0), rs.assemble(back).matrices(0.0)
    assert (a.K != b.K).nnz == 0 and (a.C != b.C).nnz == 0


def test_messages_stay_on_one_line_with_control_characters_in_values():
    """A value with a newline is shown escaped (found by the property test)."""
    with pytest.raises(ModelError) as err:
        model_from_dict({"model": "\n"})
    assert "\n" not in str(err.value) and '"\\n"' in str(err.value)
