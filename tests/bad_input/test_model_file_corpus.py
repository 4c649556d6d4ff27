"""Bad model files: one-line ModelError whose ``where`` is the key path of the culprit.

Complements the corpus of ``tests/io/test_model_file.py`` (schema keys, types and grids) with
materials, rolling bearings, loads and analysis options, TOML syntax and file errors.
"""

from __future__ import annotations

import math
import re

import pytest
from corpus_checks import MODELS, assert_one_line_error, model_dict

from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model, model_from_dict


def edit(path, value, base="friswell_5_9_5"):
    """A case: ``model_from_dict`` of ``base`` with the value at key ``path`` replaced
    (``None`` deletes the key)."""
    def call():
        data = model_dict(base)
        *parents, last = path
        node = data
        for key in parents:
            node = node[key]
        if value is None:
            del node[last]
        else:
            node[last] = value
        return model_from_dict(data)
    return call


def _tabulated(kxx, frequency):
    """A case: bearing 0 with ``kxx`` tabulated over ``frequency`` [rad/s]."""
    def call():
        data = model_dict()
        data["bearings"][0].update(kxx=kxx, frequency=frequency)
        return model_from_dict(data)
    return call


BALL = ("rolling_bearings", 0)
TRANSIENT = {"type": "transient", "t_end": "10 ms", "dt": "50 us"}


def analysis(**kw):
    """A case adding analysis ``run`` of the rolling-bearing model."""
    return edit(("analyses", "run"), kw, base="rolling_ball")


CASES = [
    # materials
    pytest.param(edit(("materials", 0, "E"), "50 kg"), "materials[0].E",
                 r'"50 kg" is a mass, expected a (modulus|pressure)', id="E-wrong-unit"),
    pytest.param(edit(("materials", 0, "E"), "stiff"), "materials[0].E",
                 r"cannot read \"stiff\"", id="E-no-number"),
    pytest.param(edit(("materials", 0, "E"), "-211 GPa"), "materials[0].E", r"must be > 0",
                 id="E-negative"),
    pytest.param(edit(("materials", 0, "E"), 0), "materials[0].E", r"must be > 0", id="E-zero"),
    pytest.param(edit(("materials", 0, "G_s"), "inf GPa"), "materials[0].G_s",
                 r"must be finite", id="G-inf"),
    pytest.param(edit(("materials", 0, "rho"), "7810 kg/m"), "materials[0].rho",
                 r"expected a density", id="rho-wrong-unit"),
    pytest.param(edit(("materials", 0, "name"), None), "materials[0].name", r"field required",
                 id="material-name-missing"),
    # shaft, disks, bearings, point loads
    pytest.param(edit(("shaft", 0, "length"), "1.5 rpm"), "shaft[0].length",
                 r'"1\.5 rpm" is a rotational speed, expected a length', id="length-in-rpm"),
    pytest.param(edit(("shaft", 0, "id"), "50 mm"), "shaft[0].od", r"must be > id \(0\.05 m\)",
                 id="bore-equals-od"),
    pytest.param(edit(("shaft", 0, "odr"), "nan mm"), "shaft[0].odr", r"must be finite",
                 id="taper-odr-nan"),
    pytest.param(edit(("disks", 0, "o_d"), "-280 mm"), "disks[0].o_d", r"must be > 0",
                 id="disk-od-negative"),
    pytest.param(_tabulated([1e6, 2e6], [0, 100, 200]), "bearings[0].kxx",
                 r"has 2 values but frequency has 3", id="bearing-table-lengths"),
    pytest.param(_tabulated([1e6, 2e6, 3e6], [0, 200, 100]), "bearings[0].frequency",
                 r"values must be strictly increasing", id="bearing-frequency-non-monotonic"),
    pytest.param(edit(("bearings", 0, "kxx"), ["1 MN/m", "2 MN/m", "3 MN/m"]), "bearings[0].kxx",
                 r"is an array but no frequency is given", id="bearing-array-no-frequency"),
    pytest.param(edit(("bearings", 0, "cxx"), "-3 kN s/m"), "bearings[0].cxx", r"must be >= 0",
                 id="bearing-damping-negative"),
    pytest.param(edit(("bearings", 1, "z"), "1.6 m"), "bearings[1].z",
                 r"1\.6 m is not a node position", id="bearing-off-the-shaft"),
    pytest.param(edit(("loads", "unbalance", 0, "magnitude"), "nan g m"),
                 "loads.unbalance[0].magnitude", r"must be finite", id="unbalance-nan"),
    pytest.param(edit(("loads", "unbalance", 0, "node"), 9), "loads.unbalance[0].z",
                 r"give node or z, not both", id="unbalance-node-and-z"),
    pytest.param(edit(("loads", "point_loads", 0, "dof"), "uw", base="rolling_ball"),
                 "loads.point_loads[0].dof", r"must be one of 'ux', .*got \"uw\"",
                 id="point-load-dof"),
    pytest.param(edit(("loads", "point_loads", 0, "value"), "300 kg", base="rolling_ball"),
                 "loads.point_loads[0].value", r'"300 kg" is a mass, expected a force',
                 id="point-load-unit"),
    # rolling bearings
    pytest.param(edit((*BALL, "n_balls"), 0, base="rolling_ball"), "rolling_bearings[0].n_balls",
                 r"must be >= 1, got 0", id="ball-zero-balls"),
    pytest.param(edit((*BALL, "type"), "needle", base="rolling_ball"), "rolling_bearings[0].type",
                 r"needle", id="rolling-type"),
    pytest.param(edit((*BALL, "contact_angle"), "120 deg", base="rolling_ball"),
                 "rolling_bearings[0].contact_angle", r"must be in \[0, 90\] deg, got 120 deg",
                 id="ball-angle-out-of-range"),
    pytest.param(edit((*BALL, "ball_diameter"), "nan mm", base="rolling_ball"),
                 "rolling_bearings[0].ball_diameter", r"must be finite", id="ball-diameter-nan"),
    pytest.param(edit((*BALL, "pitch_diameter"), "5 mm", base="rolling_ball"),
                 "rolling_bearings[0]", r"ball_diameter 0\.00794\d* m must be in \(0, pitch",
                 id="ball-pitch-below-ball"),
    pytest.param(edit((*BALL, "f_i"), 0.4, base="rolling_ball"), "rolling_bearings[0]",
                 r"f_i = 0\.4 must be > 0\.5", id="ball-groove-factor"),
    pytest.param(edit((*BALL, "n_rollers"), 12, base="rolling_ball"), "rolling_bearings[0]",
                 r"unknown key 'n_rollers'", id="ball-with-roller-key"),
    pytest.param(edit((*BALL, "damping_factor"), "20 kg", base="rolling_ball"),
                 "rolling_bearings[0].damping_factor", r"expected a time",
                 id="rolling-damping-unit"),
    pytest.param(edit((*BALL, "Kn"), "9.3e9 N/m", base="rolling_ball"), "rolling_bearings[0].Kn",
                 r'"9\.3e9 N/m" is not a load-deflection constant in N/m\^1\.5', id="ball-Kn-unit"),
    pytest.param(edit((*BALL, "cage"), "free", base="rolling_ball"), "rolling_bearings[0].cage",
                 r"must be one of 'rotating' or 'fixed', got \"free\"", id="ball-cage"),
    pytest.param(edit((*BALL, "z"), "600 mm", base="rolling_ball"), "rolling_bearings[0].z",
                 r"0\.6 m is not a node position; nearest nodes", id="ball-off-the-shaft"),
    pytest.param(edit((*BALL, "linearize"), "dynamic", base="rolling_ball"),
                 "rolling_bearings[0].linearize", r'expected "static", .*got "dynamic"',
                 id="ball-linearize"),
    pytest.param(edit((*BALL, "n_rollers"), 0, base="rolling_tapered"),
                 "rolling_bearings[0].n_rollers", r"must be >= 1, got 0", id="roller-zero-rollers"),
    pytest.param(edit((*BALL, "model"), "hertz", base="rolling_tapered"),
                 "rolling_bearings[0].model",
                 r"must be one of 'tilt_integral', 'slices' or 'influence'",
                 id="roller-model"),
    pytest.param(edit((*BALL, "roller_diameter"), "60 mm", base="rolling_tapered"),
                 "rolling_bearings[0]", r"roller_diameter 0\.06 m must be smaller than "
                 r"pitch_diameter 0\.046 m", id="roller-pitch-below-roller"),
    pytest.param(edit((*BALL, "profile"), {"type": "parabolic"}, base="rolling_tapered"),
                 "rolling_bearings[0].profile.type", r"must be one of 'straight', 'crowned'",
                 id="roller-profile-type"),
    pytest.param(edit((*BALL, "profile"), {"type": "crowned", "crown_drop": "5 um",
                                           "crown_length": "30 mm"}, base="rolling_tapered"),
                 "rolling_bearings[0]", r"crown length 0\.03 m exceeds half the effective length",
                 id="roller-crown-too-long"),
    # other tables
    pytest.param(edit(("loads", "gravity"), "yes", base="rolling_ball"), "loads.gravity",
                 r'cannot read "yes"', id="gravity-not-a-value"),
    pytest.param(edit(("disks", 0), {"z": "0.5 m", "m": 1.0, "Id": -0.1, "Ip": 0.2}),
                 "disks[0].Id", r"must be >= 0, got -0\.1", id="disk-Id-negative"),
    pytest.param(edit(("fixed",), [{"node": 70, "dofs": ["ux"]}]), "fixed[0].node",
                 r"node 70 is neither a shaft node \(0\.\.6\)", id="fixed-node"),
    pytest.param(edit(("materials",), []), "shaft[0].material",
                 r"unknown material 'steel' \(defined: none", id="no-materials"),
    pytest.param(edit(("shaft", 0, "n_elements"), 10**9), "shaft[0].n_elements",
                 r"must be <= 10000, got 1000000000", id="absurd-element-count"),
    # analyses
    pytest.param(edit(("analyses", "run"), {"type": "critical_speeds", "whirl": "both"}),
                 "analyses.run.whirl", r"must be one of 'forward' or 'backward'",
                 id="critical-speeds-whirl"),
    pytest.param(edit(("analyses", "run"), {"type": "critical_speed_map", "bearings": ["XX"]}),
                 "analyses.run.bearings[0]", r"no bearing tagged 'XX' \(tags: B0, B1\)",
                 id="map-bearing-tag"),
    pytest.param(edit(("analyses", "run"), {"type": "frequency_response", "frequencies": [1.0],
                                           "inputs": [{"node": 2, "dof": "uu"}]}),
                 "analyses.run.inputs[0].dof", r"must be one of 'ux'", id="frf-input-dof"),
    pytest.param(edit(("analyses", "run"), {"type": "static", "speed": "1 m"}),
                 "analyses.run.speed", r'"1 m" is a length, expected a rotational speed',
                 id="static-speed-unit"),
    pytest.param(edit(("analyses", "modes", "speed"), "50 kg"), "analyses.modes.speed",
                 r'"50 kg" is a mass, expected a rotational speed', id="modal-speed-unit"),
    pytest.param(edit(("analyses", "campbell", "speeds"), [0, "nan rpm", 100]),
                 "analyses.campbell.speeds[1]", r"must be finite", id="campbell-speed-nan"),
    pytest.param(edit(("analyses", "campbell", "speeds"), [0, 3000, 1000]),
                 "analyses.campbell.speeds", r"values must be strictly increasing",
                 id="campbell-speeds-non-monotonic"),
    pytest.param(edit(("analyses", "campbell", "speeds"), []), "analyses.campbell.speeds",
                 r"expected a non-empty array", id="campbell-speeds-empty"),
    pytest.param(edit(("analyses", "modes", "type"), "eigen"), "analyses.modes.type",
                 r'unknown analysis type "eigen"', id="analysis-type"),
    pytest.param(analysis(**{**TRANSIENT, "dt": "-50 us"}), "analyses.run.dt", r"must be > 0",
                 id="transient-dt-negative"),
    pytest.param(analysis(**{**TRANSIENT, "t_end": 0}), "analyses.run.t_end", r"must be > 0",
                 id="transient-t-end-zero"),
    pytest.param(analysis(**{**TRANSIENT, "dt": "1 s"}), "analyses.run.dt",
                 r"exceeds t_end", id="transient-dt-above-t-end"),
    pytest.param(analysis(**{**TRANSIENT, "method": "euler"}), "analyses.run.method",
                 r"must be one of 'average_acceleration', .*got \"euler\"", id="transient-method"),
    pytest.param(analysis(**{**TRANSIENT, "dt": "50 Hz"}), "analyses.run.dt",
                 r'"50 Hz" is a rotational speed, expected a time', id="transient-dt-unit"),
    pytest.param(analysis(**{**TRANSIENT, "t_ends": 1}), "analyses.run",
                 r"unknown key 't_ends'", id="transient-unknown-key"),
    pytest.param(analysis(**{**TRANSIENT, "rtol": 0}), "analyses.run.rtol", r"must be > 0",
                 id="transient-rtol-zero"),
    pytest.param(analysis(**{**TRANSIENT, "dt": None, "rtol": 0.5}), "analyses.run.rtol",
                 r"rtol must be a number in \[1e-10, 0\.1\]", id="transient-rtol-too-loose"),
    pytest.param(analysis(**{**TRANSIENT, "rtol": 1e-4}), "analyses.run.rtol",
                 r"give dt .* or rtol .*, not both", id="transient-dt-and-rtol"),
    pytest.param(analysis(type="periodic", start="1000 rpm"), "analyses.run.stop",
                 r"field required", id="periodic-stop-missing"),
    pytest.param(analysis(type="periodic", start="nan rpm", stop="3000 rpm"),
                 "analyses.run.start", r"must be finite", id="periodic-start-nan"),
]


@pytest.mark.parametrize(("call", "where", "reason"), CASES)
def test_bad_model_file_names_the_key_path(call, where, reason):
    error = assert_one_line_error(call, ModelError, rf"^{re.escape(where)}: .*{reason}")
    assert error.where == where


def test_toml_syntax_error_gives_the_line(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('[model]\nname = "x"\n\n[[shaft]]\nlength = "1 m"\nod = 50 mm\n')
    assert_one_line_error(lambda: load_model(path), ModelError,
                          rf"^{re.escape(str(path))}: invalid TOML: .*line 6")


def test_duplicate_toml_table_gives_the_line(tmp_path):
    path = tmp_path / "twice.toml"
    path.write_text('[model]\nname = "x"\n[model]\nname = "y"\n')
    assert_one_line_error(lambda: load_model(path), ModelError,
                          rf"^{re.escape(str(path))}: invalid TOML: .*line 3")


def test_missing_model_file(tmp_path):
    assert_one_line_error(lambda: load_model(tmp_path / "none.toml"), ModelError,
                          r"none\.toml: cannot read the file")


def test_non_finite_toml_number(tmp_path):
    text = (MODELS / "friswell_5_9_5.toml").read_text().replace('kxx = "1 MN/m"', "kxx = nan", 1)
    path = tmp_path / "nan.toml"
    path.write_text(text)
    assert_one_line_error(lambda: load_model(path), ModelError,
                          r"^bearings\[0\]\.kxx: must be finite, got nan")


def test_model_from_dict_needs_a_table():
    assert_one_line_error(lambda: model_from_dict([1, 2]), ModelError, r"expected a table")
    assert math.isfinite(1.0)
