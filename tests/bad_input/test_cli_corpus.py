"""Bad command lines: exit code 2 and exactly one line on stderr, never a traceback."""

from __future__ import annotations

import re

import pytest
from corpus_checks import MODELS

from rotorsim.cli.main import EXIT_BAD_INPUT, main

FRISWELL = str(MODELS / "friswell_5_9_1.toml")
BALL = str(MODELS / "rolling_ball.toml")

WRITERS = {"run", "modal", "campbell", "critical-speeds", "map", "unbalance", "static",
           "transient", "periodic", "periodic-parameter", "bearing"}
"""Subcommands that write results: the cases send them to a temporary folder."""

CASES = [
    pytest.param(["info", "no/such/model.toml"], r"no/such/model\.toml: cannot read the file",
                 id="missing-file"),
    pytest.param(["info", str(MODELS)], r"models: cannot read the file",
                 id="directory-instead-of-file"),
    pytest.param(["simulate", FRISWELL], r"invalid choice: 'simulate'", id="unknown-subcommand"),
    pytest.param(["run", FRISWELL, "campbel"], r"no analysis 'campbel'; the model has",
                 id="unknown-analysis-name"),
    pytest.param(["modal", FRISWELL, "--speed", "50 kg"],
                 r"--speed: \"50 kg\" is a mass, expected a rotational speed",
                 id="speed-wrong-unit"),
    pytest.param(["modal", FRISWELL, "--speed", "fast"], r"--speed: cannot read \"fast\"",
                 id="speed-not-a-number"),
    pytest.param(["modal", FRISWELL, "--num-modes", "four"],
                 r"argument --num-modes: invalid int value: 'four'", id="num-modes-not-an-int"),
    pytest.param(["modal", FRISWELL, "--units", "rps"], r"argument --units: invalid choice",
                 id="units-choice"),
    pytest.param(["modal", FRISWELL, "--spead", "10"], r"unrecognized arguments: --spead",
                 id="unknown-option"),
    pytest.param(["campbell", FRISWELL, "--speeds", "0", "3000 rpm", "ten"],
                 r"NUM must be an integer", id="speeds-num"),
    pytest.param(["campbell", FRISWELL, "--speeds", "0", "3000 kg", "5"],
                 r"\"3000 kg\" is a mass", id="speeds-unit"),
    pytest.param(["transient", BALL, "--t-end", "10 ms", "--dt", "-5 us"],
                 r"transient\.dt: dt must be a positive number \[s\], got -5e-06",
                 id="transient-dt-negative"),
    pytest.param(["transient", BALL, "--t-end", "10 kg", "--dt", "5 us"],
                 r"--t-end: \"10 kg\" is a mass, expected a time", id="transient-t-end-unit"),
    pytest.param(["transient", BALL, "--t-end", "10 ms", "--dt", "1 s"],
                 r"transient\.dt: dt 1\.0 s exceeds the duration 0\.01 s",
                 id="transient-dt-above-t-end"),
    pytest.param(["transient", BALL, "--t-end", "10 ms", "--rtol", "0"],
                 r"transient\.rtol: rtol must be a number in \[1e-10, 0\.1\]",
                 id="transient-rtol-zero"),
    pytest.param(["transient", BALL, "--t-end", "10 ms", "--dt", "5 us", "--rtol", "1e-4"],
                 r"transient: give --dt \(a fixed step\) or --rtol \(error-controlled\), "
                 r"not both", id="transient-dt-and-rtol"),
    pytest.param(["periodic", BALL, "--start", "1000 rpm", "--stop", "nan rpm"],
                 r"--stop: must be finite, got \"nan rpm\"", id="periodic-stop-nan"),
    pytest.param(["unbalance", FRISWELL, "--speeds", "0", "100", "0"],
                 r"command line: NUM must be >= 1, got 0", id="speeds-num-zero"),
    pytest.param(["bearing", BALL, "--tag", "XX"],
                 r"--tag: no rolling bearing tagged 'XX'; the model has DE, NDE", id="bearing-tag"),
    pytest.param(["bearing", FRISWELL], r"friswell_5_9_1: the model has no \[\[rolling_bearings",
                 id="bearing-without-rolling-bearings"),
    pytest.param(["periodic-parameter", BALL, "--vary", "rolling_bearings.XX.Kn", "--speed",
                  "3000 rpm", "--start", "1", "--stop", "2"],
                 r"no entry 'XX' in \[\[rolling_bearings\]\]", id="vary-unknown-entry"),
    pytest.param([], r"the following arguments are required: COMMAND", id="no-command"),
    pytest.param(["map", FRISWELL, "--stiffness", "1 MN/m", "1 kg", "5"],
                 r"\"1 kg\" is a mass, expected a stiffness", id="map-stiffness-unit"),
]


@pytest.mark.parametrize(("argv", "pattern"), CASES)
def test_bad_command_line_is_one_line_with_exit_code_2(argv, pattern, capsys, tmp_path):
    if argv and argv[0] in WRITERS:
        argv = [*argv, "--out", str(tmp_path), "--no-plots"]
    try:
        code = main(argv)
    except SystemExit as stop:  # argparse usage errors
        code = stop.code
    captured = capsys.readouterr()
    err = captured.err
    assert code == EXIT_BAD_INPUT, (code, err)
    assert err.count("\n") == 1 and err.endswith("\n"), err
    assert err.startswith("rotorsim: error: ") and "Traceback" not in err, err
    assert re.search(pattern, err), (pattern, err)
