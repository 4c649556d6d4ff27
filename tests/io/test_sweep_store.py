"""The incremental HDF5 store of sweep points: layout, reading back, identity, errors."""

from __future__ import annotations

import functools
import json

import h5py
import numpy as np
import pytest

from rotorsim.analyses.sweep.sweep import Grid, Normal, Sample, set_bearing_stiffness, sweep
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError, Status
from rotorsim.io.sweep_store import FORMAT, VERSION, content_hash, describe_callable, load_sweep
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)


def rotor(k: float = 1e6) -> Rotor:
    shaft = [ShaftElement(L=0.25, idl=0.0, odl=0.05, material=STEEL) for _ in range(2)]
    return Rotor(shaft, [], [BearingElement(n=0, kxx=k), BearingElement(n=2, kxx=k)])


def outputs(rotor: Rotor, params) -> dict:
    """Synthetic outputs of several shapes and kinds; fails for negative ``k``."""
    k = params["k"]
    if k < 0:
        raise ModelError("negative stiffness", "outputs")
    return {"scalar": k, "vector": np.array([k, 2 * k, 3 * k]), "flag": k > 1.5,
            "matrix": np.full((2, 2), k + 1j * k)}


def test_store_layout_is_the_documented_one(tmp_path):
    path = tmp_path / "s.h5"
    res = sweep(rotor(), Grid({"k": [1.0, -1.0, 2.0], "c": [0.0, 5.0]}), None, outputs,
                store=path)
    assert not (tmp_path / "s.h5.tmp").exists()
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == FORMAT and f.attrs["version"] == VERSION
        assert f.attrs["kind"] == "grid" and json.loads(f.attrs["shape"]) == [3, 2]
        assert f.attrs["fingerprint"] == res.fingerprint
        definition = json.loads(f.attrs["definition"])
        assert definition["space"]["names"] == ["k", "c"]
        assert definition["rotor_summary"]["nodes"] == 3
        assert f["parameters/names"].asstr()[...].tolist() == ["k", "c"]
        assert f["parameters/values"].shape == (6, 2)
        assert f["points/done"][...].all()
        assert f["points/status"].dtype == np.int8
        assert f["points/status"][...].tolist() == [0, 0, 2, 2, 0, 0]
        assert "negative stiffness" in f["points/message"].asstr()[2]
        assert f["outputs/vector"].shape == (6, 3) and f["outputs/vector"].dtype == np.float64
        assert f["outputs/matrix"].dtype == np.complex128
        np.testing.assert_array_equal(f["outputs/flag"][...], [0, 0, np.nan, np.nan, 1, 1])
        last = json.loads(f.attrs["last_run"])
        assert last["options"]["executor"] == "serial" and last["stats"]["evaluated"] == 6
    assert np.isnan(res.outputs["matrix"][3]).all()
    np.testing.assert_array_equal(res.outputs["vector"][5], [2.0, 4.0, 6.0])


def test_load_gives_back_the_result_of_the_sweep(tmp_path):
    path = tmp_path / "s.h5"
    space = Sample(5, {"k": Normal(1.0, 2.0)}, seed=3)
    res = sweep(rotor(), space, None, outputs, store=path)
    memory = sweep(rotor(), space, None, outputs)
    loaded = load_sweep(path)
    for r in (loaded, memory):
        assert r.kind == "sample" and r.shape is None and r.names == ("k",)
        np.testing.assert_array_equal(r.values, res.values)
        np.testing.assert_array_equal(r.point_status, res.point_status)
        assert r.messages == res.messages and r.fingerprint == res.fingerprint
        for key in res.outputs:
            np.testing.assert_array_equal(r.outputs[key], res.outputs[key])
    assert loaded.options["store"] == str(path) and memory.options["store"] is None
    assert loaded.summary == res.summary and res.summary["nodes"] == 3


def test_outputs_must_keep_their_names_and_shapes(tmp_path):
    def varying(rotor, params):
        return {"y": np.zeros(int(params["n"]))}

    with pytest.raises(ModelError, match="fixed shapes"):
        sweep(rotor(), Grid({"n": [2, 3]}), None, varying, store=tmp_path / "v.h5")
    with pytest.raises(ModelError, match="fixed shapes"):
        sweep(rotor(), Grid({"n": [2, 3]}), None, varying)
    with pytest.raises(ModelError, match="not numeric"):
        sweep(rotor(), Grid({"n": [2]}), None, lambda r, p: {"y": "text"})
    with pytest.raises(ModelError, match="non-empty dict"):
        sweep(rotor(), Grid({"n": [2]}), None, lambda r, p: {})


def test_load_rejects_other_files(tmp_path):
    text = tmp_path / "x.h5"
    text.write_text("not hdf5")
    with pytest.raises(ModelError, match="cannot read as HDF5"):
        load_sweep(text)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f.attrs["format"] = "something else"
    with pytest.raises(ModelError, match="not a rotorsim sweep store"):
        load_sweep(other)
    future = tmp_path / "future.h5"
    sweep(rotor(), Grid({"k": [1.0]}), None, outputs, store=future)
    with h5py.File(future, "r+") as f:
        f.attrs["version"] = VERSION + 1
    with pytest.raises(ModelError, match="version"):
        load_sweep(future)
    with pytest.raises(ModelError, match="version"):  # resume reads it too
        sweep(rotor(), Grid({"k": [1.0]}), None, outputs, store=future)


def test_content_hash_sees_every_model_number():
    assert content_hash(rotor()) == content_hash(rotor())
    assert content_hash(rotor(1e6)) != content_hash(rotor(np.nextafter(1e6, 2e6)))
    tabulated = rotor().with_bearings([BearingElement(n=0, kxx=[1e6, 2e6], frequency=[0, 9]),
                                       BearingElement(n=2, kxx=1e6)])
    retabulated = rotor().with_bearings([BearingElement(n=0, kxx=[1e6, 2e6],
                                                        frequency=[0, 10]),
                                         BearingElement(n=2, kxx=1e6)])
    assert content_hash(tabulated) != content_hash(retabulated)


def test_describe_callable_names_functions_and_bound_arguments():
    apply = set_bearing_stiffness([0, 1], "k")
    text = describe_callable(apply)
    assert text.startswith("rotorsim.analyses.sweep.functions._change_bearings(")
    assert "indices=(0, 1)" in text and "parameter='k'" in text
    assert describe_callable(None) == "none"
    assert describe_callable(functools.partial(outputs)) == f"{__name__}.outputs()"
    assert describe_callable(set_bearing_stiffness([0], "k")) != text
    assert Status.SKIPPED == 3  # the fill value of points/status documented in the layout
