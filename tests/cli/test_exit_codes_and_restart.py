"""Command-line contract of issue 12: exit code 3 with partial results for an analysis that
stops short, the final transient state always written, options anywhere on the line, and
checkpoint/resume of transients and periodic branches (a resumed run writes the same
result as an uninterrupted one, bit for bit on the same machine)."""

from __future__ import annotations

import importlib
from pathlib import Path

import h5py
import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import (
    EXIT_BAD_INPUT,
    EXIT_INCOMPLETE,
    EXIT_INTERRUPTED,
    EXIT_OK,
    main,
)
from rotorsim.errors import Status

# the modules themselves (the packages export functions of the same names)
integration = importlib.import_module("rotorsim.time_integration.integrate")
continuation = importlib.import_module("rotorsim.solvers.continuation")
MODELS = Path(__file__).resolve().parents[2] / "models"
FRISWELL = (MODELS / "friswell_5_9_1.toml").read_text()
ROLLING = (MODELS / "rolling_ball.toml").read_text()


def model_file(tmp_path: Path, base: str, extra: str, name: str = "m") -> str:
    path = tmp_path / f"{name}.toml"
    path.write_text(base.replace('name = "friswell_5_9_1"', f'name = "{name}"')
                    .replace('name = "rolling_ball"', f'name = "{name}"') + "\n" + extra)
    return str(path)


# ------------------------------------------------------------ the final transient state
def test_transient_with_every_ends_at_t_end(tmp_path, capsys):
    model = model_file(tmp_path, FRISWELL, """
[analyses.short]
type = "transient"
t_end = "1 s"
dt = "0.3 s"
every = 5
initial = "zero"
""")
    assert main(["run", model, "short", "--out", str(tmp_path), "--no-plots"]) == EXIT_OK
    assert "4 steps to t = 1 s" in capsys.readouterr().out
    result = rs.load(tmp_path / "m" / "short.h5")
    assert result.t.tolist() == [0.0, 1.0]


# ------------------------------------------------------------ exit code 3
FAILING = """
[analyses.violent]
type = "transient"
description = "200 kg mm of unbalance at 60000 rpm: Newton fails at the 9th step"
t_end = "20 ms"
dt = "50 us"
speed = "60000 rpm"
unbalance = [{ z = "250 mm", magnitude = "200000 g mm" }]
"""


def test_a_transient_that_fails_midway_writes_its_partial_result_and_exits_3(tmp_path, capsys):
    model = model_file(tmp_path, ROLLING, FAILING)
    code = main(["run", model, "violent", "static", "--out", str(tmp_path), "--no-plots"])
    assert code == EXIT_INCOMPLETE
    captured = capsys.readouterr()
    assert "STOPPED SHORT of t_end = 0.02 s (status NOT_CONVERGED)" in captured.out
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("rotorsim: incomplete: violent: status "
                                               "NOT_CONVERGED: average_acceleration: Newton")
    assert err[0].endswith("(partial results written)")
    result = rs.load(tmp_path / "m" / "violent.h5")
    assert result.status == Status.NOT_CONVERGED and "Newton" in result.options["failure"]
    assert 1 < result.t.size < 401 and result.t[-1] < 0.02  # up to the last accepted step
    assert np.all(np.isfinite(result.q))
    assert (tmp_path / "m" / "static.h5").is_file()  # the other analyses still ran


def test_on_failure_raise_in_the_model_file_keeps_exit_code_1(tmp_path, capsys):
    model = model_file(tmp_path, ROLLING, FAILING + 'on_failure = "raise"\n')
    assert main(["run", model, "violent", "--out", str(tmp_path), "--no-plots"]) == 1
    assert "Newton did not converge" in capsys.readouterr().err
    assert not (tmp_path / "m" / "violent.h5").exists()


def test_exit_code_follows_the_status_of_a_periodic_branch(tmp_path, capsys):
    code = main(["periodic", str(MODELS / "rolling_ball.toml"), "--start", "1000 rpm",
                 "--stop", "3000 rpm", "--harmonics", "3", "--max-points", "3",
                 "--no-stability", "--out", str(tmp_path), "--no-plots"])
    result = rs.load(tmp_path / "rolling_ball" / "periodic.h5")
    # unbalance with the balls' VC: a branch of tori, which may reach its bound in 3 points
    assert result.speed[-1] <= 3000 * np.pi / 30 * (1 + 1e-12)
    err = capsys.readouterr().err
    if result.status == Status.OK:  # a branch ended by max_points counts as complete ...
        assert code == EXIT_OK and err == ""
    else:  # ... until continuation reports it as stopped short: then exit 3
        assert code == EXIT_INCOMPLETE and "rotorsim: incomplete: periodic:" in err


def test_help_documents_the_exit_codes(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    for line in ("2  bad input", "3  incomplete", "130  interrupted"):
        assert line in out


# ------------------------------------------------------------ options after names
def test_options_may_follow_or_precede_the_analysis_names(tmp_path):
    model = str(MODELS / "friswell_5_9_1.toml")
    assert main(["run", model, "modes", "--out", str(tmp_path / "a"), "--no-plots"]) == 0
    assert main(["run", model, "--out", str(tmp_path / "b"), "modes", "--no-plots",
                 "critical_speeds", "--debug"]) == 0
    assert sorted(p.name for p in (tmp_path / "b" / "friswell_5_9_1").iterdir()) == [
        "critical_speeds.h5", "modes.h5"]
    assert [p.name for p in (tmp_path / "a" / "friswell_5_9_1").iterdir()] == ["modes.h5"]


def test_unknown_options_anywhere_are_still_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        main(["run", str(MODELS / "friswell_5_9_1.toml"), "modes", "--bogus"])
    assert info.value.code == EXIT_BAD_INPUT
    assert "unrecognized arguments: --bogus" in capsys.readouterr().err


# ------------------------------------------------------------ checkpoint and resume
def interrupt_after(monkeypatch, module, name, writes):
    """Make the ``writes``-th checkpoint write of ``module.name`` end with Ctrl-C."""
    original, count = getattr(module, name), [0]

    def write_then_interrupt(*args, **kwargs):
        out = original(*args, **kwargs)
        count[0] += 1
        if count[0] == writes:
            raise KeyboardInterrupt
        return out

    monkeypatch.setattr(module, name, write_then_interrupt)


def assert_same_datasets(a: Path, b: Path) -> None:
    """Every numeric dataset of two results files equal bit for bit (same machine), the
    cost counters and timings aside (a resume adds one factorisation)."""
    with h5py.File(a) as fa, h5py.File(b) as fb:
        names: list[str] = []
        fa.visit(lambda n: names.append(n) if isinstance(fa[n], h5py.Dataset) else None)
        compared = 0
        for n in names:
            if "stats" in n or fa[n].dtype.kind not in "fciub":
                continue
            assert np.array_equal(fa[n][()], fb[n][()], equal_nan=True), n
            compared += 1
        assert compared >= 5


RUN_UP = """
[analyses.run_up]
type = "transient"
t_end = "10 ms"
dt = "50 us"
speed = 0
speed_stop = "6000 rpm"
checkpoint_every = 40
"""


def test_interrupted_transient_resumed_from_the_command_line_equals_a_whole_run(
        tmp_path, monkeypatch, capsys):
    model = model_file(tmp_path, ROLLING, RUN_UP)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert main(["run", model, "run_up", "--out", str(whole), "--no-plots"]) == EXIT_OK
    with monkeypatch.context() as patch:
        interrupt_after(patch, integration, "save_checkpoint", writes=3)  # t0, 40, 80
        code = main(["run", model, "run_up", "--out", str(parts), "--no-plots",
                     "--checkpoint"])
    assert code == EXIT_INTERRUPTED and "--resume" in capsys.readouterr().err
    checkpoint = parts / "m" / "run_up.checkpoint.h5"
    with h5py.File(checkpoint) as f:
        assert f["output/t"][-1, 0] == pytest.approx(80 * 50e-6)
    assert not (parts / "m" / "run_up.h5").exists()
    assert main(["run", model, "run_up", "--resume", "--out", str(parts),
                 "--no-plots"]) == EXIT_OK
    assert f"resuming from {checkpoint}" in capsys.readouterr().out
    assert_same_datasets(whole / "m" / "run_up.h5", parts / "m" / "run_up.h5")


BRANCH = """
[analyses.branch]
type = "periodic"
start = "1000 rpm"
stop = "3000 rpm"
harmonics = 3
varying_compliance = false          # the periodic problem: checkpoints (a torus has none)
max_points = 8
checkpoint = true
resume = true
checkpoint_every = 2
"""


def test_interrupted_periodic_branch_resumed_from_its_model_file_equals_a_whole_run(
        tmp_path, monkeypatch, capsys):
    model = model_file(tmp_path, ROLLING, BRANCH)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert main(["run", model, "branch", "--out", str(whole), "--no-plots"]) in (
        EXIT_OK, EXIT_INCOMPLETE)
    with monkeypatch.context() as patch:
        interrupt_after(patch, continuation, "save_continuation_checkpoint", writes=2)
        code = main(["run", model, "branch", "--out", str(parts), "--no-plots"])
    assert code == EXIT_INTERRUPTED
    assert "starting from the beginning" in capsys.readouterr().out
    assert not (parts / "m" / "branch.h5").exists()
    # resume = true in the model file: the second run continues from the checkpoint
    assert main(["run", model, "branch", "--out", str(parts), "--no-plots"]) in (
        EXIT_OK, EXIT_INCOMPLETE)
    assert "resuming from" in capsys.readouterr().out
    assert_same_datasets(whole / "m" / "branch.h5", parts / "m" / "branch.h5")


def test_checkpoint_options_are_checked(tmp_path, capsys):
    model = model_file(tmp_path, ROLLING, RUN_UP)
    assert main(["run", model, "run_up", "--checkpoint-every", "0", "--out",
                 str(tmp_path)]) == EXIT_BAD_INPUT
    assert "--checkpoint-every: must be >= 1, got 0" in capsys.readouterr().err
    bad = model_file(tmp_path, ROLLING, RUN_UP.replace("= 40", "= 0"), name="bad")
    assert main(["info", bad]) == EXIT_BAD_INPUT
    assert "analyses.run_up.checkpoint_every" in capsys.readouterr().err


def test_an_output_folder_blocked_by_a_file_is_bad_input_before_any_work(tmp_path, capsys):
    (tmp_path / "friswell_5_9_1").write_text("a file where the results folder goes")
    code = main(["run", str(MODELS / "friswell_5_9_1.toml"), "modes", "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    captured = capsys.readouterr()
    assert captured.err.startswith("rotorsim: error: --out: cannot create the folder")
    assert "== modes" not in captured.out  # refused before running anything


SWEEP = """
[analyses.stability]
type = "sweep"
stiffness = { start = "1 MN/m", stop = "100 MN/m", num = 3, spacing = "log" }
speeds = { start = 0, stop = "3000 rpm", num = 4 }
bearings = ["B1"]
num_modes = 4
"""


def test_interrupted_sweep_resumed_from_the_command_line_equals_a_whole_run(
        tmp_path, monkeypatch, capsys):
    from rotorsim.io.sweep_store import HDF5Store

    model = model_file(tmp_path, (MODELS / "friswell_5_9_5.toml").read_text().replace(
        'name = "friswell_5_9_5"', 'name = "m"'), SWEEP)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert main(["run", model, "stability", "--out", str(whole), "--no-plots"]) == EXIT_OK
    with monkeypatch.context() as patch:
        interrupt_after(patch, HDF5Store, "write", writes=5)
        assert main(["run", model, "stability", "--out", str(parts),
                     "--no-plots"]) == EXIT_INTERRUPTED
    partial = rs.load(parts / "m" / "stability.h5")  # the store is readable when cut short
    assert int(np.sum(partial.point_status == int(Status.OK))) == 5
    capsys.readouterr()
    assert main(["run", model, "stability", "--resume", "--out", str(parts),
                 "--no-plots"]) == EXIT_OK
    out = capsys.readouterr().out
    assert "resuming the sweep stored in" in out
    assert "12 points (7 evaluated, 5 resumed from the store, 0 failed)" in out
    a, b = rs.load(whole / "m" / "stability.h5"), rs.load(parts / "m" / "stability.h5")
    assert np.array_equal(a.values, b.values) and np.all(b.point_status == int(Status.OK))
    # points 0-4 were read back, 5-11 recomputed: log decrements of the same eigenproblems
    # (eigensolver accuracy ~1e-12 relative; the start vector may differ between runs)
    np.testing.assert_allclose(b.outputs["log_dec_min"], a.outputs["log_dec_min"],
                               rtol=1e-9)
