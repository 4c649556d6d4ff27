"""Bad input to the analyses: one-line ModelError naming the argument, or a TypeError listing
the valid keywords. Every case fails before any solve, so the module runs in about a second."""

from __future__ import annotations

import math

import pytest
from corpus_checks import assert_one_line_error, small_rotor

import rotorsim as rs
from rotorsim.errors import ModelError

NAN, INF = math.nan, math.inf
ROTOR = small_rotor()
UNB = [(2, 1e-4, 0.0)]
ZERO = {"initial": "zero"}  # the small rotor turns freely about z: start at rest


def transient(t_end=0.01, dt=1e-3, **kw):
    return lambda: rs.transient(ROTOR, t_end, dt, **{**ZERO, **kw})


MODEL_ERRORS = [
    # Campbell
    pytest.param(lambda: rs.campbell(ROTOR, [], num_modes=4),
                 r"^campbell: speeds must be a non-empty 1-D array", id="campbell-speeds-empty"),
    pytest.param(lambda: rs.campbell(ROTOR, [0.0, NAN], num_modes=4),
                 r"^campbell: speeds must be finite; got \[nan\]", id="campbell-speeds-nan"),
    pytest.param(lambda: rs.campbell(ROTOR, [0.0, INF], num_modes=4),
                 r"^campbell: speeds must be finite; got \[inf\]", id="campbell-speeds-inf"),
    pytest.param(lambda: rs.campbell(ROTOR, [100.0, 50.0, 200.0], num_modes=4),
                 r"^campbell: speeds must be strictly increasing", id="campbell-non-monotonic"),
    pytest.param(lambda: rs.campbell(ROTOR, "0 rpm", num_modes=4),
                 r"^campbell: speeds must be numbers, got '0 rpm'", id="campbell-unit-string"),
    pytest.param(lambda: rs.campbell(ROTOR, [1.0, 2.0], num_modes=4, on_failure="skip"),
                 r"^campbell: on_failure must be 'raise' or 'record', got 'skip'",
                 id="campbell-on-failure"),
    # unbalance and frequency response
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0, NAN], UNB),
                 r"^speeds: value nan at index 1 is not finite and >= 0", id="unbalance-speed-nan"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [], UNB),
                 r"^speeds: must be a non-empty 1-D array", id="unbalance-speeds-empty"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, ["1000 rpm", "2000 rpm"], UNB),
                 r"^speeds: values must be a number in SI units, got \['1000 rpm'",
                 id="unbalance-speeds-unit-strings"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(40, 1e-4, 0.0)]),
                 r"^unbalance\[0\]: node 40 is not a node of the rotor \(0\.\.4\)",
                 id="unbalance-missing-node"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(2.5, 1e-4, 0.0)]),
                 r"^unbalance\[0\]: node 2\.5 is not a node", id="unbalance-fractional-node"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(2, NAN, 0.0)]),
                 r"^unbalance\[0\]: magnitude at node 2 must be finite and >= 0 \[kg m\], got nan",
                 id="unbalance-magnitude-nan"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(2, -1e-4, 0.0)]),
                 r"^unbalance\[0\]: magnitude at node 2 must be finite and >= 0",
                 id="unbalance-magnitude-negative"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(2, 1e-4, INF)]),
                 r"^unbalance\[0\]: phase at node 2 must be finite \[rad\], got inf",
                 id="unbalance-phase-inf"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], [(2, 1e-4)]),
                 r"^unbalance\[0\]: expected \(node, magnitude_kg_m, phase_rad\), "
                 r"got \(2, 0\.0001\)",
                 id="unbalance-tuple-short"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [10.0], []),
                 r"^unbalance: give a non-empty list", id="unbalance-empty"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0, 2.0], [(2, "uq")]),
                 r"^inputs\[0\]: unknown DOF 'uq' at node 2, use one of", id="frf-dof-name"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0, 2.0], [(9, "ux")]),
                 r"^inputs\[0\]: node 9 is not a node of the rotor", id="frf-node"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0, NAN], [(2, "ux")]),
                 r"^frequencies: value nan at index 1", id="frf-frequency-nan"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0, 2.0], [(2, "ux")], speed=NAN),
                 r"^frequency_response: speed must be finite, got nan", id="frf-speed-nan"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0, 2.0], [2]),
                 r"^inputs\[0\]: expected \(node, dof\), got 2", id="frf-input-not-a-pair"),
    # modal and critical speeds
    pytest.param(lambda: rs.modal(ROTOR, speed="3000 rpm", num_modes=4),
                 r"^modal: speed must be a number in SI units, got '3000 rpm'",
                 id="modal-speed-unit-string"),
    pytest.param(lambda: rs.modal(ROTOR, num_modes=4, sigma=NAN),
                 r"^modal: sigma must be finite, got nan", id="modal-sigma-nan"),
    pytest.param(lambda: rs.critical_speeds(ROTOR, harmonic=0),
                 r"^critical_speeds: harmonic must be finite and > 0, got 0",
                 id="critical-harmonic"),
    pytest.param(lambda: rs.critical_speeds(ROTOR, whirl="sideways"),
                 r"^critical_speeds: whirl must be one of .*got 'sideways'", id="critical-whirl"),
    pytest.param(lambda: rs.critical_speed_map(ROTOR, (1e8, 1e6)),
                 r"^critical_speed_map: need 0 < stiffness_range\[0\] < stiffness_range\[1\]",
                 id="map-range-reversed"),
    pytest.param(lambda: rs.critical_speed_map(ROTOR, ("1 MN/m", "1 GN/m")),
                 r"^critical_speed_map: stiffness_range must be a number in SI units",
                 id="map-range-unit-strings"),
    pytest.param(lambda: rs.critical_speed_map(ROTOR, (1e5, 1e7, 1e9)),
                 r"^critical_speed_map: need 0 < stiffness_range\[0\] < stiffness_range\[1\]",
                 id="map-range-three-values"),
    pytest.param(lambda: rs.critical_speed_map(ROTOR, bearings=[5]),
                 r"^critical_speed_map: bearing indices must be in 0\.\.1, got \[5\]",
                 id="map-bearing-index"),
    # statics
    pytest.param(lambda: rs.static(ROTOR, loads=[(2, "uq", 100.0)]),
                 r"^loads\[0\]: unknown DOF 'uq' at node 2", id="static-load-dof"),
    pytest.param(lambda: rs.static(ROTOR, loads=[(9, "uy", 100.0)]),
                 r"^loads\[0\]: node 9 is not a node of the rotor", id="static-load-node"),
    pytest.param(lambda: rs.static(ROTOR, loads=[(2, "uy", NAN)]),
                 r"^loads\[0\]: value on uy of node 2 must be finite, got nan",
                 id="static-load-nan"),
    pytest.param(lambda: rs.static(ROTOR, method="bisect"),
                 r"^static: method must be 'newton' or 'energy', got 'bisect'", id="static-method"),
    pytest.param(lambda: rs.static(ROTOR, gravity=NAN),
                 r"^gravity: must be finite or None, got nan", id="static-gravity-nan"),
    pytest.param(lambda: rs.static(ROTOR, gravity="9.81 m/s^2"),
                 r"^gravity: value must be a number in SI units, got '9\.81 m/s\^2'",
                 id="static-gravity-unit-string"),
    pytest.param(lambda: rs.static(ROTOR, gravity=True),  # was read as 1 m/s^2
                 r"^gravity: value must be a number, got True", id="static-gravity-bool"),
    pytest.param(lambda: rs.static(ROTOR, direction=(0, 0, 0)),
                 r"^direction: must be 3 finite components, not all zero", id="static-direction"),
    pytest.param(lambda: rs.static(ROTOR, direction="down"),
                 r"^direction: value must be a number in SI units, got 'down'",
                 id="static-direction-word"),
    pytest.param(lambda: rs.static(ROTOR, speed=NAN),
                 r"^static: speed must be finite, got nan", id="static-speed-nan"),
    # transients
    pytest.param(transient(dt=0.0), r"^transient\.dt: dt must be a positive number \[s\], got 0",
                 id="transient-dt-zero"),
    pytest.param(transient(dt=-1e-3), r"^transient\.dt: dt must be a positive number",
                 id="transient-dt-negative"),
    pytest.param(transient(dt=NAN), r"^transient\.dt: dt must be a positive number .*nan",
                 id="transient-dt-nan"),
    pytest.param(transient(t_end=0.0), r"^transient\.t_end: t_end must be finite and after t0",
                 id="transient-t-end-zero"),
    pytest.param(transient(t_end=-1.0), r"^transient\.t_end: t_end must be finite and after t0",
                 id="transient-t-end-negative"),
    pytest.param(transient(t_end=INF), r"^transient\.t_end: .*got inf", id="transient-t-end-inf"),
    pytest.param(transient(t_end=0.01, dt=0.1),
                 r"^transient\.dt: dt 0\.1 s exceeds the duration 0\.01 s: check the units",
                 id="transient-dt-above-t-end"),
    pytest.param(transient(t_end=1.0, dt=1e-12),
                 r"^transient\.dt: dt 1e-12 s gives 1e\+12 steps over 1\.0 s, more than 1e\+09",
                 id="transient-dt-would-never-end"),
    pytest.param(transient(t_end="10 ms"), r"^transient: t_end must be a time or \(t0, t_end\), "
                 r"got '10 ms'", id="transient-t-end-unit-string"),
    pytest.param(transient(method="euler"), r"^transient\.method: unknown Newmark method 'euler'; "
                 r"valid: average_acceleration", id="transient-method"),
    pytest.param(transient(initial="rest"), r"^transient\.initial: initial must be 'static', "
                 r"'zero' or \(q0, v0\), got 'rest'", id="transient-initial"),
    pytest.param(transient(initial=([0.0] * 3, [0.0] * 3)),
                 r"^transient\.initial: q0 and v0 must have 30 entries", id="transient-q0-size"),
    pytest.param(transient(unbalance=[(40, 1e-4, 0.0)]),
                 r"^unbalance\[0\]: node 40 is not a node", id="transient-unbalance-node"),
    pytest.param(transient(unbalance=[(2, NAN, 0.0)]),
                 r"^unbalance\[0\]: magnitude at node 2 must be finite",
                 id="transient-unbalance-nan"),
    pytest.param(transient(nodes=[40]), r"^transient\.nodes: node 40 outside 0\.\.4",
                 id="transient-output-node"),
    pytest.param(transient(output=rs.Output(times=[0.0, 0.5])),
                 r"^OutputSpec\.times: times must lie in \[0\.0, 0\.01\]",
                 id="transient-times-outside"),
    pytest.param(transient(excitation=rs.Excitation(forces=lambda t: [1.0, 2.0])),
                 r"^transient\.forces: forces\(0\.0\) must be 30 finite numbers .*got shape \(2,\)",
                 id="transient-forces-shape"),
    pytest.param(transient(speed=NAN), r"^speed: give a number \[rad/s\], a callable",
                 id="transient-speed-nan"),
    pytest.param(transient(speed=lambda t: NAN),
                 r"^SpeedFunction\.function: returned nan at t = \d",
                 id="transient-speed-function-nan"),
    pytest.param(transient(excitation=rs.Excitation(gravity="9.81")),
                 r"^gravity: value must be a number in SI units",
                 id="transient-gravity-string"),
    pytest.param(lambda: rs.LinearSpeed(0.0, NAN, 0.0, 1.0),
                 r"^LinearSpeed\.stop: must be a finite number, got nan", id="speed-profile-nan"),
    pytest.param(lambda: rs.LinearSpeed(0.0, 100.0, 1.0, 0.5),
                 r"^LinearSpeed: t_stop \(0\.5\) must exceed t_start \(1\.0\)",
                 id="speed-profile-times"),
    pytest.param(lambda: rs.ConstantSpeed(NAN), r"^ConstantSpeed\.value: must be a finite number",
                 id="constant-speed-nan"),
    pytest.param(lambda: rs.SpeedFunction(5),
                 r"^SpeedFunction\.function: must be callable, got int",
                 id="speed-function-not-callable"),
    pytest.param(lambda: rs.BaseExcitation(lambda t: 0.0, direction=(0, 0, 0)),
                 r"^BaseExcitation\.direction: must be 3 finite components, not all zero",
                 id="base-excitation-direction"),
    pytest.param(lambda: rs.Newmark(beta=-1.0), r"^Newmark\(average_acceleration\): need gamma > 0 "
                 r"and beta > 0, got 0\.5, -1\.0", id="newmark-beta-negative"),
    pytest.param(lambda: rs.Newmark(max_iter=0), r"^Newmark\(average_acceleration\): need "
                 r".*max_iter >= 1", id="newmark-max-iter"),
    pytest.param(lambda: rs.Adaptive(dt_min=1.0, dt_max=0.1),
                 r"^Adaptive\(average_acceleration\): need 0 <= dt_min < dt_max",
                 id="adaptive-step-bounds"),
    pytest.param(transient(method=5), r"^transient\.method: not a time stepper: 5",
                 id="transient-method-object"),
    # periodic (start/stop only: harmonics are checked elsewhere)
    pytest.param(lambda: rs.periodic(ROTOR, start=NAN, stop=100.0, unbalance=UNB),
                 r"^periodic\.start: must be a positive number \[rad/s\], got nan",
                 id="periodic-start-nan"),
    pytest.param(lambda: rs.periodic(ROTOR, start=100.0, stop=500.0, unbalance=[(40, 1e-4, 0)]),
                 r"^unbalance\[0\]: node 40 is not a node", id="periodic-unbalance-node"),
    # wrong objects
    pytest.param(lambda: rs.assemble("rotor"), r"^assemble: expected a Rotor, got str",
                 id="assemble-not-a-rotor"),
    pytest.param(lambda: rs.modal("rotor"), r"^model: expected a Rotor or RotorSystem, got str",
                 id="modal-not-a-rotor"),
    pytest.param(lambda: rs.linearize_rolling_bearings("rotor"),
                 r"^linearize_rolling_bearings: needs a Rotor, got str",
                 id="linearize-not-a-rotor"),
]


@pytest.mark.parametrize(("call", "pattern"), MODEL_ERRORS)
def test_analysis_input_is_refused_by_name(call, pattern):
    assert_one_line_error(call, ModelError, pattern)


def _valid(name):
    return rf"( \(did you mean .*\))?; valid: .*\b{name}\b"


KEYWORD_ERRORS = [
    pytest.param(lambda: rs.modal(ROTOR, num_mode=4),
                 r"^modal: unknown keyword 'num_mode' \(did you mean 'num_modes'\?\)"
                 + _valid("sigma"), id="modal"),
    pytest.param(lambda: rs.campbell(ROTOR, [1.0, 2.0], nmodes=4),
                 r"^campbell: unknown keyword 'nmodes'" + _valid("num_modes"), id="campbell"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [1.0], UNB, on_fail="record"),
                 r"^unbalance_response: unknown keyword 'on_fail'" + _valid("on_failure"),
                 id="unbalance_response"),
    pytest.param(lambda: rs.frequency_response(ROTOR, [1.0], [(2, "ux")], spin=10.0),
                 r"^frequency_response: unknown keyword 'spin'" + _valid("speed"),
                 id="frequency_response"),
    pytest.param(lambda: rs.critical_speeds(ROTOR, harmonics=2),
                 r"^critical_speeds: unknown keyword 'harmonics' \(did you mean 'harmonic'\?\)",
                 id="critical_speeds"),
    pytest.param(lambda: rs.critical_speed_map(ROTOR, n_points=5),
                 r"^critical_speed_map: unknown keyword 'n_points'" + _valid("num_points"),
                 id="critical_speed_map"),
    pytest.param(lambda: rs.static(ROTOR, gravty=9.81),
                 r"^static: unknown keyword 'gravty' \(did you mean 'gravity'\?\)", id="static"),
    pytest.param(lambda: rs.transient(ROTOR, 0.01, 1e-3, t_stop=1.0),
                 r"^transient: unknown keyword 't_stop'" + _valid("t_end"), id="transient"),
    pytest.param(lambda: rs.periodic(ROTOR, start=100, stop=500, unbalanse=UNB),
                 r"^periodic: unknown keyword 'unbalanse' \(did you mean 'unbalance'\?\)",
                 id="periodic"),
    pytest.param(lambda: rs.Newmark.from_name("euler"),
                 r"^unknown Newmark method 'euler'; valid: average_acceleration",
                 id="newmark-method"),
    pytest.param(lambda: rs.Adams(startup="euler"), r"^unknown Adams startup 'euler'; valid: rk4",
                 id="adams-startup"),
    pytest.param(lambda: rs.unbalance_response(ROTOR, [1.0], UNB, on_failure="skip"),
                 r"^on_failure must be one of \('raise', 'record'\), got 'skip'",
                 id="unbalance-on-failure-value"),
]


@pytest.mark.parametrize(("call", "pattern"), KEYWORD_ERRORS)
def test_unknown_keywords_list_the_valid_ones(call, pattern):
    assert_one_line_error(call, TypeError, pattern)
