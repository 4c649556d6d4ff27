"""Every file in models/ loads, assembles and runs each of its named analyses (fast grids);
the textbook files build exactly the rotors of examples/textbook_rotors.py."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorsim.assembly.system import assemble
from rotorsim.errors import Status
from rotorsim.io.analysis_spec import FAST_POINTS, SPEC_TYPES, run_analysis
from rotorsim.io.model_file import load_model
from rotorsim.results.campbell import CampbellResult
from rotorsim.results.critical_speeds import CriticalSpeedMapResult, CriticalSpeeds
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.results.modal import ModalResult
from rotorsim.results.periodic import PeriodicResult
from rotorsim.results.static import StaticResult
from rotorsim.results.transient import TransientResult

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import textbook_rotors as textbook  # noqa: E402

RPM = math.pi / 30.0  # rad/s per rpm
RESULT_TYPES = {
    "modal": ModalResult, "campbell": CampbellResult, "critical_speeds": CriticalSpeeds,
    "critical_speed_map": CriticalSpeedMapResult, "unbalance": FrequencyResponseResult,
    "frequency_response": FrequencyResponseResult, "static": StaticResult,
    "transient": TransientResult, "periodic": PeriodicResult,
    "periodic_parameter": PeriodicResult,
}
FILES = sorted(p.stem for p in MODELS.glob("*.toml"))
CASES = [(f, a) for f in FILES for a in load_model(MODELS / f"{f}.toml").analyses]


def test_the_expected_model_files_exist():
    assert set(FILES) >= {"default", "compressor", "large_rotor", "tapered", "friswell_5_9_1",
                          "friswell_5_9_2", "friswell_5_9_5", "friswell_5_9_9"}
    assert set(RESULT_TYPES) == set(SPEC_TYPES)


@pytest.mark.parametrize(("name", "analysis"), CASES, ids=[f"{f}-{a}" for f, a in CASES])
def test_every_named_analysis_runs(name, analysis):
    model = load_model(MODELS / f"{name}.toml")
    spec = model.analyses[analysis]
    result = run_analysis(model, analysis, fast=True)
    assert isinstance(result, RESULT_TYPES[spec.type])
    if isinstance(result, PeriodicResult) and len(result) == min(spec.max_points, 10):
        # fast=True caps a branch at 10 points: short of its end, it says so (issue 12)
        assert result.status in (Status.OK, Status.NOT_CONVERGED)
        assert result.status == Status.OK or "(max_points reached)" in result.reason
    else:
        assert np.all(np.asarray(result.status) == Status.OK)
    if isinstance(result, CampbellResult):
        assert 2 <= result.speeds.size <= FAST_POINTS
    if isinstance(result, FrequencyResponseResult):
        assert 2 <= result.frequencies.size <= FAST_POINTS
        assert np.all(np.isfinite(result.response))
    if isinstance(result, ModalResult):
        assert result.wn.size == spec.num_modes and np.all(np.isfinite(result.wn))
    if isinstance(result, CriticalSpeeds):
        assert len(result) > 0 and np.all(np.isfinite(result.speed))


TEXTBOOK = {
    "friswell_5_9_1": textbook.friswell_5_9_1,
    "friswell_5_9_2": textbook.friswell_5_9_2,
    "friswell_5_9_5": textbook.friswell_5_9_5,
    "friswell_5_9_9": textbook.friswell_5_9_9,
    "tapered": textbook.tapered_rotor,
    "friswell_5_9_5_fine": lambda: textbook.friswell_5_9_5(n_elements=24),
}


@pytest.mark.parametrize("name", sorted(TEXTBOOK))
def test_textbook_files_build_the_builder_rotors_exactly(name):
    # bit-identical: the files give the same numbers (unit strings convert to the nearest
    # double) and segments split into the same elements as the builders
    loaded, built = assemble(load_model(MODELS / f"{name}.toml").rotor), \
        assemble(TEXTBOOK[name]())
    assert loaded.dof_map.n_free == built.dof_map.n_free
    for speed in (0.0, 300.0):
        a, b = loaded.matrices(speed), built.matrices(speed)
        for key in "MCGK":
            assert (getattr(a, key) - getattr(b, key)).count_nonzero() == 0, (key, speed)


def test_default_model_is_the_showcase():
    """The Friswell two-disk rotor (24 elements) on two ball bearings of the seed 000 model,
    with every analysis of the showcase."""
    model = load_model(MODELS / "default.toml")
    assert len(model.rotor.shaft_elements) == 24
    built = textbook.friswell_5_9_5(n_elements=24)
    assert [d.m for d in model.rotor.disk_elements] == [d.m for d in built.disk_elements]
    assert not model.rotor.bearing_elements  # the supports are the rolling bearings
    assert [rb.tag for rb in model.rolling_bearings] == ["DE", "NDE"]
    assert all(type(rb.bearing).__name__ == "BallBearing" for rb in model.rolling_bearings)
    a = model.analyses
    assert {"campbell", "critical_speeds", "unbalance", "static",
            "critical_speed_map", "modes"} <= set(a)
    speeds = a["campbell"].speeds.array()
    assert speeds[0] == 0.0 and speeds[-1] == pytest.approx(4500 * RPM, rel=1e-15)
    # 0.2 g m at the 350 mm disk (z = 1.0 m, node 16 of 24)
    assert model.loads.unbalance == ((16, 2e-4, 0.0),)
    assert model.rotor.disk_elements[1].tag == "disk_350" \
        and model.rotor.disk_elements[1].n == 16


def test_compressor_has_speed_dependent_cross_coupled_bearings():
    model = load_model(MODELS / "compressor.toml")
    rotor = model.rotor
    assert len(rotor.disk_elements) == 2 and rotor.speed_dependent
    assert abs(rotor.length - 1.2) < 1e-12
    for b in rotor.bearing_elements:
        for speed in (150.0, 1000.0):
            kxy, kyx = b.coefficient("kxy", speed), b.coefficient("kyx", speed)
            assert kxy > 0 > kyx and b.coefficient("cxx", speed) > 0
        assert b.coefficient("kxx", 1000.0) < b.coefficient("kxx", 150.0)
    assert {s.type for s in model.analyses.values()} >= {"campbell", "critical_speed_map",
                                                         "unbalance"}
    unbalance = model.loads.unbalance
    assert [u[0] for u in unbalance] == [d.n for d in rotor.disk_elements]


def test_large_rotor_is_large():
    rotor = load_model(MODELS / "large_rotor.toml").rotor
    assert len(rotor.shaft_elements) >= 100
    assert len(rotor.disk_elements) == 3 and len(rotor.bearing_elements) == 2
