"""HDF5 results files: exact round trip of every result type, layout, errors, atomic writes."""

from __future__ import annotations

import dataclasses
import json
import math
from datetime import datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import rotorsim
from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.linear.critical_speed_map import critical_speed_map
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.frequency_response import frequency_response, unbalance_response
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.statics.static import static
from rotorsim.assembly.dof_map import DofMap
from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError, Status
from rotorsim.io import serialize
from rotorsim.io.hdf5 import FORMAT, FORMAT_VERSION, ResultsFileError, load, save
from rotorsim.io.serialize import (
    RESULT_TYPES,
    from_jsonable,
    register_result_type,
    to_jsonable,
)
from rotorsim.model.material import steel
from rotorsim.model.rotor import Rotor
from rotorsim.results.critical_speeds import MapIntersections
from rotorsim.results.orbits import ellipse


# ---------------------------------------------------------------------------- helpers
def _bits(x: Any) -> bytes:
    return np.asarray(x).tobytes()


def assert_results_equal(a: Any, b: Any, path: str = "result") -> None:
    """Exact equality: same types everywhere, arrays with equal dtype, shape and bytes
    (so NaN positions, NaN payloads and signed zeros count), dict keys in the same order."""
    assert type(a) is type(b), f"{path}: {type(a).__name__} != {type(b).__name__}"
    if dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            assert_results_equal(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype, f"{path}: dtype {a.dtype} != {b.dtype}"
        assert a.shape == b.shape, f"{path}: shape {a.shape} != {b.shape}"
        if a.dtype.kind in "US":
            assert np.array_equal(a, b), f"{path}: strings differ"
        else:
            assert _bits(a) == _bits(b), f"{path}: values differ"
    elif isinstance(a, list | tuple):
        assert len(a) == len(b), f"{path}: length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_results_equal(x, y, f"{path}[{i}]")
    elif isinstance(a, dict):
        assert_results_equal(list(a), list(b), f"{path}.keys()")
        for key in a:
            assert_results_equal(a[key], b[key], f"{path}[{key!r}]")
    elif isinstance(a, float | complex | np.inexact):
        assert _bits(a) == _bits(b), f"{path}: {a!r} != {b!r}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def _round_trip(result: Any, tmp_path: Path) -> Any:
    path = save(result, tmp_path / "r.h5")
    return load(path)


# ---------------------------------------------------------------------------- results
def _rotor(speed_dependent: bool = False) -> Rotor:
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [DiskElement.from_geometry(2, steel, width=0.05, i_d=0.05, o_d=0.25),
             DiskElement.from_geometry(4, steel, width=0.05, i_d=0.05, o_d=0.3)]
    right = BearingElement(n=6, kxx=[1e6, 3e6, 9e6], cxx=[200.0, 200.0, 200.0],
                           frequency=[0.0, 500.0, 1000.0]) if speed_dependent else \
        BearingElement(n=6, kxx=2e6, kyy=1.5e6, cxx=300.0)
    bearings = [BearingElement(n=0, kxx=2e6, kyy=1.5e6, cxx=300.0), right]
    return Rotor(shaft, disks, bearings, tag="io_test")


@pytest.fixture(scope="module")
def results() -> dict[str, Any]:
    rotor = _rotor()
    camp = campbell(rotor, np.linspace(0.0, 600.0, 7), num_modes=4)
    wd = camp.wd.copy()
    wd[2, 1] = np.nan  # a failed point, and a signed zero: both must survive bitwise
    wd[0, 0] = -0.0
    with_nan = dataclasses.replace(camp, wd=wd)
    unb = unbalance_response(rotor, np.linspace(10.0, 600.0, 6),
                             unbalance=[(2, 1e-4, 0.0), (4, 5e-5, math.pi / 2)])
    return {
        "modal": modal(rotor, speed=300.0, num_modes=6),
        "campbell": with_nan,
        "critical_exact": critical_speeds(rotor, num_modes=3),
        "critical_campbell": camp.critical_speeds(harmonic=1),
        "map": critical_speed_map(_rotor(speed_dependent=True), (1e5, 1e8), num_points=6,
                                  num_modes=2, speeds=np.linspace(0.0, 1000.0, 21)),
        "unbalance": unb,
        "receptance": frequency_response(rotor, np.linspace(10.0, 500.0, 4),
                                         inputs=[(2, "ux"), (4, "uy")], speed=200.0),
        "static": static(rotor, loads=[(3, "ux", 50.0)]),
        "static_system": static(assemble(rotor)),
        "deflected_shape": unb.deflected_shape(2),
        "ellipse": ellipse(np.array([1.0, 2.0j, np.nan]), np.array([-1j, 0.5, 1.0])),
        "intersections": MapIntersections.empty(),
        **_bearing_results(),
        **_api_results(rotor),
        **_transient_results(),
        **_periodic_results(),
    }


def _api_results(rotor: Rotor) -> dict[str, Any]:
    import rotorsim as rs

    level1 = rs.api_level1(rotor, 600.0, [rs.ApiStage(2, 2e4, 0.3, 0.02, 1.1, "s1")],
                           num=4)  # no density: NaN fields
    unbalance = rs.api_unbalance(rotor, np.linspace(10.0, 1500.0, 60), min_speed=900.0,
                                 mcs=1000.0, num_modes=2,
                                 clearances=[rs.Clearance(2, 3e-4, "seal")])
    return {"api_level1": level1, "api_unbalance": unbalance}


def _bearing_results() -> dict[str, Any]:
    from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium, stiffness_over_pass
    from rotorsim.elements.rolling import BallBearing

    bearing = BallBearing(n_balls=10, pitch_diameter=0.05, ball_diameter=0.008, Kn=8e9,
                          A0=0.1e-3, contact_angle=0.3, radial_clearance=5e-6)
    load = [800.0, -200.0, 300.0, 0.0, 0.0]
    found = bearing_equilibrium(bearing, load, method="global")
    from rotorsim.analyses.statics.bearing_life import bearing_life
    from rotorsim.elements.rolling import RollerBearing
    from rotorsim.elements.rolling.rating.options import RatingOptions

    rated = BallBearing.from_geometry(n_balls=10, pitch_diameter=0.05, ball_diameter=0.008,
                                      f_i=0.52, f_o=0.53, contact_angle=0.3)
    roller = RollerBearing(14, 0.065, 0.01, 0.0096, model="slices", n_slices=6)
    return {"bearing_equilibrium": found, "energy_minimum": found.minima[0],
            "stiffness_over_pass": stiffness_over_pass(bearing, load, 6),
            "bearing_life": bearing_life(rated, load, options=RatingOptions(
                shoulder_heights=(1e-3, 1e-3), viscosity_ratio=2.0, contamination=0.3,
                fatigue_load_limit=400.0)),
            "roller_life": bearing_life(roller, [5000.0, 0.0, 0.0, 0.0, 3.0])}


def _transient_results() -> dict[str, Any]:
    from rotorsim.results.order_tracking import order_track, waterfall
    from rotorsim.results.spectra import amplitude_spectrum, harmonic_fit
    from rotorsim.results.transient import TransientResult

    t = np.arange(400) * 1e-3
    angle = 100.0 * t + 25.0 * t**2
    x = 1e-5 * np.cos(angle)
    run = TransientResult(
        t=t, q=x[:, None], v=None, dofs=np.array([7]), speed=100.0 + 50.0 * t, angle=angle,
        acceleration=np.full(t.size, 50.0), bearing_loads=np.zeros((t.size, 0, 5)),
        bearing_tags=(), bearing_elements=np.zeros(0, dtype=np.int64),
        bearing_kappa=np.zeros(0), reduced={}, dof_map=DofMap(2),
        nodes_pos=np.array([0.0, 1.0]))
    return {"transient": run, "transient_continuable": _continuable(run),
            "transient_state": _continuable(run).final,
            "stepper_state": _continuable(run).final.stepper,
            "counters": _continuable(run).final.stepper.counters,
            "spectrum": amplitude_spectrum(t, x),
            "harmonic_fit": harmonic_fit(t, x, 100.0),
            "waterfall": waterfall(t, x, run.speed, segment=0.05),
            "order_track": order_track(t, x, angle, [1.0], revolutions_per_block=2)}


def _continuable(run: Any) -> Any:
    """A transient with reductions and a final state (stepper state with a history)."""
    from rotorsim.results.transient_state import TransientState
    from rotorsim.time_integration.base import Counters, State

    rng = np.random.default_rng(3)
    n = 6
    stepper = State(0.399, rng.random(n), rng.random(n), rng.random(n), rng.random(n),
                    step=399, dt=1e-3, peak=np.zeros(0), counters=Counters(iterations=7),
                    history=rng.random((2, n)), history_dt=1e-3)
    final = TransientState(t=0.399, q=rng.random(n), v=rng.random(n), a=rng.random(n),
                           angle=43.9, speed=119.95, method="adams4", dt=1e-3,
                           problem="0123abcd", reduction=0, reduction_speed=100.0,
                           stepper=stepper)
    reduced = {"max_abs": rng.random(1), "peak_to_peak": rng.random((7, 1)),
               "peak_to_peak_revolution": np.arange(7.0)}
    return dataclasses.replace(run, reduced=reduced, final=final,
                               options={"stopped": {"reason": "steady", "t": 0.399}})


def _periodic_results() -> dict[str, Any]:
    from rotorsim.results.periodic import PeriodicBifurcation, PeriodicPeak, PeriodicResult

    rng = np.random.default_rng(7)
    fold = PeriodicBifurcation("fold", 1250.0, 1, True, "extended_system",
                               complex(np.nan, np.nan), rng.random(3), rng.random(3))
    doubling = PeriodicBifurcation("period_doubling", 1300.5, 2, False, "test_function",
                                   -1.00001 + 0j, rng.random(3), rng.random(3))
    mu = rng.random((4, 6)) + 1j * rng.random((4, 6))
    mu[3] = np.nan
    run = PeriodicResult(
        parameter=np.array([1200.0, 1250.0, 1240.0, 1310.0]), parameter_name="speed",
        speed=np.array([1200.0, 1250.0, 1240.0, 1310.0]),
        fundamental=np.array([1200.0, 1250.0, 1240.0, 1310.0]), order=1.0, harmonics=2,
        samples=16, dofs=np.array([6, 7, 8]), coefficients=rng.random((4, 5, 3)),
        max_abs=rng.random((4, 3)), peak_to_peak=rng.random((4, 3)), multipliers=mu,
        stability_method="hsu", stability_tol=1e-5, bifurcations=(fold, doubling),
        iterations=np.array([0, 3, 4, 2]), residuals=rng.random(4) * 1e-10,
        approximation="rolling elements frozen", held_dofs=np.array([5]), dof_map=DofMap(3),
        nodes_pos=np.array([0.0, 0.1, 0.2]), options={"unbalance": [[1, 3e-5, 0.0]],
                                                      "stability_modes": "auto"},
        stats={"points": 4.0}, reason="lam_max = 1310 reached")
    peak = PeriodicPeak(1, "orbit", "max", 1276.25, 3.5e-5, 2, True)
    return {**_torus_results(), "periodic": run, "periodic_bifurcation": fold,
            "periodic_peak": peak,
            "periodic_with_peaks": dataclasses.replace(run, peaks=(peak,)),
            "periodic_without_stability": dataclasses.replace(
                run, bifurcations=(), multipliers=np.zeros((4, 0), complex))}


def _torus_results() -> dict[str, Any]:
    from rotorsim.results.quasi_periodic import QuasiPeriodicResult, TorusEvent
    from rotorsim.results.torus_motion import MotionBeyond

    rng = np.random.default_rng(11)
    motion = MotionBeyond(1272.0, "doubled torus", 2, np.array([0.84, 3.7e-5, np.nan, np.nan]),
                          2020.5, -45.4, 45.7, 1.06, (40, 60))
    event = TorusEvent("loss_of_stability", 1270.5, 1, (-0.3, 2.5), 410.25, 2.1, "doubling",
                       motion)
    tori = QuasiPeriodicResult(
        speed=np.array([1200.0, 1250.0, 1300.0]), vc_frequency=np.array([4.09, 4.09, 4.09])
        * np.array([1200.0, 1250.0, 1300.0]), vc_order=4.09,
        tones=np.array([[1, 0], [0, 1], [1, -1]]), dofs=np.array([6, 7, 8]),
        coefficients=rng.random((3, 7, 3)), max_abs=rng.random((3, 3)),
        peak_to_peak=rng.random((3, 3)), exponents=np.array([-0.3, 2.5, np.nan]),
        exponents_converged=np.array([True, True, False]), stability_method="hill",
        events=(event,), iterations=np.array([0, 3, 4]), residuals=rng.random(3) * 1e-10,
        held_dofs=np.array([5]), dof_map=DofMap(3), nodes_pos=np.array([0.0, 0.1, 0.2]),
        options={"box": [6, 2]}, stats={"points": 3.0}, reason="",
        exponents_checked=np.array([True, False, True]))
    return {"quasi_periodic": tori, "torus_event": event, "torus_motion": motion,
            "torus_event_without_motion": dataclasses.replace(event, motion=None)}


RESULT_NAMES = ["quasi_periodic", "torus_event", "torus_motion", "torus_event_without_motion",
                "modal", "campbell", "critical_exact",
                "critical_campbell", "map",
                "unbalance", "receptance", "static", "static_system", "deflected_shape",
                "ellipse", "intersections", "bearing_equilibrium", "energy_minimum",
                "stiffness_over_pass", "transient", "transient_continuable",
                "transient_state", "stepper_state", "counters", "spectrum", "harmonic_fit",
                "waterfall",
                "order_track", "periodic", "periodic_bifurcation", "api_level1",
                "api_unbalance",
                "periodic_without_stability", "periodic_peak", "periodic_with_peaks"]


@pytest.mark.parametrize("name", RESULT_NAMES)
def test_every_result_type_round_trips_exactly(results, name, tmp_path):
    result = results[name]
    assert_results_equal(result, _round_trip(result, tmp_path))


def test_results_cover_every_registered_type_and_interesting_cases(results):
    covered = {type(r).__name__ for r in results.values()}
    assert covered == set(RESULT_TYPES)
    assert len(results["map"].intersections) > 0  # a non-empty nested dataclass
    assert results["critical_campbell"].mode_shapes is None  # None fields
    assert results["static_system"].bearing_forces is None
    assert isinstance(results["modal"].options["rigid_tol"], np.float64)  # numpy scalar
    assert isinstance(results["unbalance"].options["unbalance"][0], tuple)  # tuples in lists


def test_helper_detects_differences(results):
    camp = results["campbell"]
    cases = {
        "NaN moved": camp.wd[[1, 0, 2, 3, 4, 5, 6]],
        "signed zero": np.where(camp.wd == 0.0, 0.0, camp.wd),
        "dtype": camp.wd.astype(np.float32).astype(np.float64).astype(np.longdouble),
    }
    for label, wd in cases.items():
        with pytest.raises(AssertionError):
            assert_results_equal(camp, dataclasses.replace(camp, wd=wd))
            pytest.fail(f"not detected: {label}")
    with pytest.raises(AssertionError):
        assert_results_equal({"a": (1, 2)}, {"a": [1, 2]})
    with pytest.raises(AssertionError):
        assert_results_equal({"a": 1.0}, {"a": np.float64(1.0)})


# ---------------------------------------------------------------------------- edge cases
@dataclasses.dataclass(frozen=True, eq=False)
class Exotic:
    """Every kind of field the layout knows, plus a derived (init=False) one."""

    values: np.ndarray
    labels: tuple[str, ...]
    nothing: Any
    status: Status
    count: int
    huge: int
    scale: float
    gain: complex
    name: str
    flag: bool
    tol: np.float32
    dofs: DofMap
    nested: Any
    options: dict[str, Any]
    items: list[Any]
    pair: tuple[float, int]
    label_nul: tuple[str, ...]
    name_nul: str
    derived: float = dataclasses.field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "derived", float(self.values.size) * self.scale)


@pytest.fixture
def exotic_type():
    register_result_type(Exotic, {"values": "m", "scale": "N"})
    yield Exotic
    del RESULT_TYPES["Exotic"]


def _exotic() -> Exotic:
    options = {
        "nested": [[1, [2.5, None]], {"deep": (True, False)}],
        "nan": float("nan"), "neg_nan": -math.nan, "inf": -math.inf, "neg_zero": -0.0,
        "big": 2**80,
        "complex": 1.5 - 2j, "np_int": np.int32(-7), "np_bool": np.bool_(True),
        "np_complex": np.complex64(1 + 2j), "np_str": np.str_("ab"),
        "array": np.array([[1.0, np.nan], [3.0, 4.0]]), "empty": np.zeros((0, 3), np.int16),
        "strings": np.array(["a", "bcd"]), "status": Status.FAILED,
        3: "int key", (1, "a"): "tuple key", "__tuple__": "looks like a tag", "": "",
        "unicode": "Ω µm", "nul": "a\0b",
    }
    return Exotic(
        values=np.array([[1.0, np.nan, -0.0]]), labels=("forward", "", "Ω"), nothing=None,
        status=Status.NOT_CONVERGED, count=-3, huge=2**70, scale=2.5, gain=1 - 1j, name="",
        flag=False, tol=np.float32(1e-3), dofs=DofMap(3, fixed=[2, 5, 17]),
        nested=ellipse(1.0, -1j), options=options, items=[1, "x", None],
        pair=(0.1, 2), label_nul=("a\0b",), name_nul="x\0",
    )


def test_exotic_fields_round_trip_exactly(exotic_type, tmp_path):
    original = _exotic()
    back = _round_trip(original, tmp_path)
    assert_results_equal(original, back)
    assert back.derived == 3 * 2.5


@pytest.mark.parametrize("array", [
    np.zeros((0, 4)), np.array(5.0), np.array([True, False]), np.arange(6, dtype=np.int32),
    np.array([1 + 2j, np.nan], dtype=np.complex64), np.array([1.5], dtype=np.float16),
    np.array([["x", "ÿÿ"], ["", "abc"]]), np.zeros((2, 0), dtype="<U3"),
    np.asfortranarray(np.arange(6.0).reshape(2, 3)), np.array([b"ab", b""]),
    np.array([1.0, 2.0], dtype=">f8"), np.array([7], dtype=np.uint64),
])
def test_array_dtypes_and_shapes_survive(exotic_type, tmp_path, array):
    original = dataclasses.replace(_exotic(), values=array)
    assert_results_equal(original, _round_trip(original, tmp_path))


_json_leaves = (st.none() | st.booleans() | st.integers() | st.floats()
                | st.complex_numbers() | st.text(max_size=5))
_json_values = st.recursive(
    _json_leaves,
    lambda inner: st.lists(inner, max_size=4) | st.tuples(inner, inner)
    | st.dictionaries(st.text(max_size=4) | st.integers(), inner, max_size=4),
    max_leaves=20,
)


@settings(max_examples=150, deadline=None)
@given(_json_values)
def test_tagged_json_round_trips_any_nesting(value):
    text = json.dumps(to_jsonable(value), allow_nan=False)  # standard JSON
    assert_results_equal(value, from_jsonable(json.loads(text)))


def test_unstorable_values_are_rejected_with_their_path(exotic_type, tmp_path):
    bad = dataclasses.replace(_exotic(), options={"a": [1, {"b": object()}]})
    with pytest.raises(ResultsFileError, match=r"options\['a'\]\[1\]\['b'\].*object"):
        save(bad, tmp_path / "bad.h5")
    with pytest.raises(ResultsFileError, match="dtype object"):
        save(dataclasses.replace(_exotic(), values=np.array([None])), tmp_path / "bad.h5")
    with pytest.raises(ResultsFileError, match="NUL"):
        save(dataclasses.replace(_exotic(), values=np.array(["a\0b"])), tmp_path / "bad.h5")
    with pytest.raises(ResultsFileError, match="cannot store a dict"):
        save({"x": {"not": "a result"}}, tmp_path / "bad.h5")
    assert list(tmp_path.iterdir()) == []


def test_registration_guards_layout_names():
    @dataclasses.dataclass(frozen=True)
    class Clash:
        type: str

    with pytest.raises(ModelError, match="reserved"):
        register_result_type(Clash)
    with pytest.raises(ModelError, match="unknown fields"):
        register_result_type(Exotic, {"nope": "m"})
    assert "Clash" not in RESULT_TYPES and "Exotic" not in RESULT_TYPES


# ---------------------------------------------------------------------------- layout
def test_layout_is_readable_with_plain_h5py(results, tmp_path):
    m = results["modal"]
    path = save(m, tmp_path / "modal.h5")
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == FORMAT and f.attrs["format_version"] == FORMAT_VERSION
        assert f.attrs["rotorsim_version"] == rotorsim.__version__
        assert f.attrs["layout"] == "single"
        assert datetime.fromisoformat(f.attrs["created"]).tzinfo is not None
        g = f["result"]
        assert g.attrs["type"] == "ModalResult"
        kinds = json.loads(g.attrs["fields"])
        assert kinds["wn"] == "array" and kinds["whirl"] == "str_tuple"
        assert kinds["status"] == "status" and kinds["dof_map"] == "dofmap"
        assert kinds["options"] == "json"
        np.testing.assert_array_equal(g["wn"][()], m.wn)
        np.testing.assert_array_equal(g["mode_shapes"][()], m.mode_shapes)  # native complex
        assert g["wn"].attrs["units"] == "rad/s"
        assert list(g["whirl"].asstr()[()]) == list(m.whirl)
        assert g["dof_map"].attrs["n_nodes"] == m.dof_map.n_nodes
        assert json.loads(g.attrs["attr_units"]) == {"speed": "rad/s"}
        assert g.attrs["speed"] == 300.0
        assert json.loads(g.attrs["summary"])["shaft_elements"] == 6


EXPECTED_UNITS = {
    "modal": {"wd": "rad/s", "log_dec": "1", "nodes_pos": "m"},
    "campbell": {"speeds": "rad/s", "wn": "rad/s"},
    "map": {"stiffness": "N/m", "critical_speeds": "rad/s", "bearing_kxx": "N/m",
            "intersections/speed": "rad/s", "intersections/stiffness": "N/m"},
    "unbalance": {"frequencies": "rad/s", "response": "m, rad (per unit input)"},
    "static": {"displacement": "m, rad", "bending_moment": "N m", "shear_force": "N",
               "bearing_forces": "N", "load": "N, N m"},
    "deflected_shape": {"ux": "m", "orbit/major": "m", "orbit/inclination": "rad"},
}


@pytest.mark.parametrize("name", list(EXPECTED_UNITS))
def test_units_are_attributes_of_every_physical_dataset(results, name, tmp_path):
    path = save(results[name], tmp_path / "r.h5")
    with h5py.File(path, "r") as f:
        for key, units in EXPECTED_UNITS[name].items():
            assert f["result"][key].attrs["units"] == units
        unitless = []

        def visit(key: str, obj: Any) -> None:
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fc" \
                    and "units" not in obj.attrs:
                unitless.append(key)

        f["result"].visititems(visit)
        assert unitless == []


def test_collection_round_trips_in_order(results, tmp_path):
    items = {"static": results["static"], "modal": results["modal"],
             "campbell": results["campbell"]}
    path = save(items, tmp_path / "all.h5")
    back = load(path)
    assert list(back) == ["static", "modal", "campbell"]
    for key in items:
        assert_results_equal(items[key], back[key])
    with h5py.File(path, "r") as f:
        assert f.attrs["layout"] == "collection" and "result" not in f
        assert f["results/modal"].attrs["type"] == "ModalResult"


@pytest.mark.parametrize("items", [{}, {"a/b": None}, {"": None}, {3: None}])
def test_bad_collections_are_rejected(results, tmp_path, items):
    items = {k: results["modal"] if v is None else v for k, v in items.items()}
    with pytest.raises(ResultsFileError):
        save(items, tmp_path / "x.h5")
    assert not (tmp_path / "x.h5").exists()


# ---------------------------------------------------------------------------- bad files
def _edit(path: Path, action) -> Path:
    with h5py.File(path, "r+") as f:
        action(f)
    return path


BAD_FILES = {
    "format": (lambda f: f.attrs.__setitem__("format", "something-else"),
               "not a rotorsim results file"),
    "no format": (lambda f: f.attrs.__delitem__("format"), "not a rotorsim results file"),
    "newer version": (lambda f: f.attrs.__setitem__("format_version", 2),
                      "format_version 2 is not supported; this rotorsim reads version 1"),
    "text version": (lambda f: f.attrs.__setitem__("format_version", "one"),
                     "format_version"),
    "layout": (lambda f: f.attrs.__setitem__("layout", "weird"), "unknown layout"),
    "no group": (lambda f: f.__delitem__("result"), "group '/result' missing"),
    "type": (lambda f: f["result"].attrs.__setitem__("type", "Nope"),
             "unknown result type 'Nope'"),
    "missing dataset": (lambda f: f["result"].__delitem__("wn"), "malformed"),
    "fields": (lambda f: f["result"].attrs.__setitem__("fields", json.dumps({"wn": "array"})),
               r"missing \['speed'"),
    "kind": (lambda f: f["result"].attrs.__setitem__(
        "fields", f["result"].attrs["fields"].replace('"speed": "float"', '"speed": "odd"')),
             "unknown field kind 'odd'"),
    "status": (lambda f: f["result"].attrs.__setitem__("status", 99), "malformed"),
    "nested": (lambda f: f["result/dof_map"].attrs.__delitem__("n_nodes"), "malformed"),
}


@pytest.mark.parametrize("case", list(BAD_FILES))
def test_bad_files_raise_a_clear_error(results, tmp_path, case):
    action, message = BAD_FILES[case]
    path = _edit(save(results["modal"], tmp_path / "m.h5"), action)
    with pytest.raises(ResultsFileError, match=message) as info:
        load(path)
    assert str(path) in str(info.value)
    assert isinstance(info.value, ModelError)


def _drop_notes(f: h5py.File) -> None:
    """Make the file look as written before ModalResult had ``notes``."""
    kinds = json.loads(f["result"].attrs["fields"])
    kinds.pop("notes")
    f["result"].attrs["fields"] = json.dumps(kinds)
    if "notes" in f["result"]:
        del f["result"]["notes"]


def test_a_file_without_a_later_defaulted_field_still_loads(results, tmp_path):
    m = results["modal"]
    path = _edit(save(dataclasses.replace(m, notes=("a note",)), tmp_path / "m.h5"),
                 _drop_notes)
    old = load(path)
    assert old.notes == () and np.array_equal(old.wn, m.wn)


def test_non_hdf5_and_missing_files(tmp_path):
    text = tmp_path / "notes.h5"
    text.write_text("hello")
    with pytest.raises(ResultsFileError, match="not an HDF5 file"):
        load(text)
    with pytest.raises(FileNotFoundError):
        load(tmp_path / "missing.h5")
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = np.zeros(3)
    with pytest.raises(ResultsFileError, match="not a rotorsim results file"):
        load(other)


# ---------------------------------------------------------------------------- atomicity
def test_crash_mid_write_keeps_previous_file_and_leaves_no_temp(results, tmp_path,
                                                                monkeypatch):
    target = save(results["static"], tmp_path / "out.h5")
    before = target.read_bytes()
    real = serialize._write_array
    calls = {"n": 0}

    def crashing(*args: Any, **kwargs: Any) -> None:
        calls["n"] += 1
        if calls["n"] == 5:  # after four datasets were written
            raise KeyboardInterrupt("simulated crash")
        real(*args, **kwargs)

    monkeypatch.setattr(serialize, "_write_array", crashing)
    with pytest.raises(KeyboardInterrupt):
        save(results["modal"], target)
    assert calls["n"] == 5
    assert target.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["out.h5"]
    monkeypatch.undo()
    assert_results_equal(results["static"], load(target))


def test_overwrite_replaces_and_missing_folder_is_created(results, tmp_path):
    target = tmp_path / "out.h5"
    save(results["static"], target)
    save(results["modal"], target)
    assert type(load(target)).__name__ == "ModalResult"
    assert [p.name for p in tmp_path.iterdir()] == ["out.h5"]
    nested = save(results["modal"], tmp_path / "no" / "such" / "x.h5")
    assert type(load(nested)).__name__ == "ModalResult"
    (tmp_path / "blocker").write_text("a file where a folder is needed")
    with pytest.raises(ModelError, match=r"^save: cannot create the folder .*blocker.*: a "
                       "file of that name is in the way"):
        save(results["modal"], tmp_path / "blocker" / "x.h5")
