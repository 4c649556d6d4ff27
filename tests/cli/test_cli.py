"""The rotorsim command line: subcommands, outputs, one-line errors and exit codes."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import h5py
import pytest

import rotorsim as rs
from rotorsim.cli.main import EXIT_BAD_INPUT, main

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_info_prints_summary_table(capsys):
    assert main(["info", str(MODELS / "friswell_5_9_1.toml")]) == 0
    out = capsys.readouterr().out
    assert "shaft_elements" in out and "| " not in out
    assert "7" in out  # nodes


def test_run_writes_results_and_figures(tmp_path, capsys):
    code = main(["run", str(MODELS / "default.toml"), "campbell", "unbalance", "static",
                 "--out", str(tmp_path), "--fast"])
    assert code == 0
    folder = tmp_path / "default"
    assert (folder / "layout.png").stat().st_size > 5000
    for name in ("campbell", "unbalance", "static"):
        assert (folder / f"{name}.h5").is_file()
        assert (folder / f"{name}.png").stat().st_size > 5000
    campbell = rs.load(folder / "campbell.h5")
    assert type(campbell).__name__ == "CampbellResult"
    with h5py.File(folder / "unbalance.h5") as f:
        assert f.attrs["format"] == "rotorsim-results"
    out = capsys.readouterr().out
    assert "1X critical speeds" in out and "peaks at the requested nodes" in out


def test_subcommand_overrides_with_units(tmp_path, capsys):
    code = main(["modal", str(MODELS / "friswell_5_9_1.toml"), "--speed", "4000 rpm",
                 "--num-modes", "4", "--out", str(tmp_path), "--no-plots", "--units", "Hz"])
    assert code == 0
    [h5] = list((tmp_path / "friswell_5_9_1").glob("*.h5"))
    modes = rs.load(h5)
    assert modes.speed == pytest.approx(4000 * 3.141592653589793 / 30)
    assert modes.num_modes == 4
    assert "wd [Hz]" in capsys.readouterr().out


def test_campbell_speed_range_from_command_line(tmp_path):
    code = main(["campbell", str(MODELS / "friswell_5_9_1.toml"), "--speeds", "0",
                 "3000 rpm", "11", "--num-modes", "4", "--out", str(tmp_path), "--no-plots"])
    assert code == 0
    [h5] = list((tmp_path / "friswell_5_9_1").glob("*.h5"))
    result = rs.load(h5)
    assert len(result.speeds) == 11 and result.speeds[-1] == pytest.approx(100 * 3.141592653589793)


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["info", "no/such/model.toml"], "no/such/model.toml"),
        (["run", "{models}/friswell_5_9_1.toml", "nonexistent"], "no analysis 'nonexistent'"),
        (["modal", "{models}/friswell_5_9_1.toml", "--speed", "50 kg"], "--speed"),
        (["campbell", "{models}/friswell_5_9_1.toml", "--speeds", "0", "100", "x"],
         "NUM must be an integer"),
    ],
)
def test_bad_input_is_one_line_on_stderr_with_exit_code_2(argv, fragment, capsys, tmp_path):
    argv = [a.format(models=MODELS) for a in argv] + (
        ["--out", str(tmp_path)] if argv[0] != "info" else [])
    assert main(argv) == EXIT_BAD_INPUT
    err = capsys.readouterr().err.strip()
    assert err.startswith("rotorsim: error:") and fragment in err
    assert "\n" not in err and "Traceback" not in err


def test_bad_model_file_via_subprocess(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[model]\nname = "x"\n[[shaft]]\nlength = "-1 m"\nod = "50 mm"\n')
    proc = subprocess.run([sys.executable, "-m", "rotorsim", "info", str(bad)],
                          capture_output=True, text=True)
    assert proc.returncode == EXIT_BAD_INPUT
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    debug = subprocess.run([sys.executable, "-m", "rotorsim", "--debug", "info", str(bad)],
                           capture_output=True, text=True)
    assert debug.returncode != 0 and "Traceback" in debug.stderr


def test_help_lists_subcommands():
    proc = subprocess.run([sys.executable, "-m", "rotorsim", "--help"], capture_output=True,
                          text=True, check=True)
    for name in ("info", "run", "modal", "campbell", "map", "unbalance", "static"):
        assert name in proc.stdout


def test_transient_subcommand_runs_a_run_up_on_rolling_bearings(tmp_path, capsys):
    code = main(["transient", str(MODELS / "rolling_ball.toml"), "--t-end", "10 ms",
                 "--dt", "50 us", "--speed", "0", "--speed-stop", "3000 rpm",
                 "--out", str(tmp_path)])
    assert code == 0
    folder = tmp_path / "rolling_ball"
    result = rs.load(folder / "transient.h5")
    assert type(result).__name__ == "TransientResult"
    assert result.speed[-1] == pytest.approx(100 * 3.141592653589793)
    assert result.bearing_loads.shape == (201, 2, 5)
    assert (folder / "transient.png").stat().st_size > 5000
    out = capsys.readouterr().out
    assert "200 steps" in out and "max |Fr| [N]" in out


def test_transient_subcommand_needs_a_duration(tmp_path, capsys):
    code = main(["transient", str(MODELS / "rolling_ball.toml"), "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "--t-end and --dt" in capsys.readouterr().err


def test_periodic_subcommand_traces_a_branch(tmp_path, capsys):
    code = main(["periodic", str(MODELS / "rolling_ball.toml"), "--start", "1000 rpm",
                 "--stop", "3000 rpm", "--harmonics", "3", "--max-points", "8",
                 "--out", str(tmp_path)])
    result = rs.load(tmp_path / "rolling_ball" / "periodic.h5")
    # the file's unbalance with the balls' varying compliance: the branch of tori (issue 17)
    assert code == (0 if result.status == rs.Status.OK else 3)
    assert type(result).__name__ == "QuasiPeriodicResult" and 2 <= len(result) <= 8
    assert result.options["box"] == [3, 1] and result.has_stability
    out = capsys.readouterr().out
    assert "quasi-periodic branch" in out and "stable tori" in out


def test_periodic_subcommand_needs_a_speed_range(tmp_path, capsys):
    code = main(["periodic", str(MODELS / "rolling_ball.toml"), "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "--start and --stop" in capsys.readouterr().err
