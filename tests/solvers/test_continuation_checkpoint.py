"""Continuation checkpoints: an interrupted and resumed branch equals an uninterrupted one
bit for bit; foreign or damaged checkpoints are refused."""

from __future__ import annotations

import dataclasses

import h5py
import numpy as np
import pytest

from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_checkpoint import load_continuation_checkpoint
from rotorsim.time_integration.checkpoint import CheckpointError


class Interrupted(Exception):
    pass


def two_dof(x, lam):
    """A 2-unknown S-shaped branch with two folds (cubic spring, coupled)."""
    r = np.array([x[0] ** 3 - x[0] + 0.3 * x[1] + lam, x[1] - 0.5 * x[0] ** 2])
    J = np.array([[3 * x[0] ** 2 - 1.0, 0.3], [-x[0], 1.0]])
    return r, J, np.array([1.0, 0.0])


OPTS = Continuation(initial_step=0.02, max_step=0.1, direction=-1, lam_min=-1.5, lam_max=1.5)
ARRAYS = ("lam", "x", "tangents", "step_sizes", "iterations", "det_sign", "log_det", "smooth",
          "residuals")


def stop_at(point):
    def monitor(state):
        if state.point == point:
            raise Interrupted

    return monitor


def test_resumed_branch_is_bitwise_identical(tmp_path):
    whole = continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS)
    assert whole.reason == "lam_min = -1.5 reached" and len(whole) > 60
    path = tmp_path / "branch.h5"
    with pytest.raises(Interrupted):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=path, checkpoint_every=10,
                        monitor=stop_at(47))
    state, saved, _ = load_continuation_checkpoint(path)
    assert state.point == 40 and saved["lam"].shape == (41,)
    assert [p.name for p in tmp_path.iterdir()] == ["branch.h5"]  # no temporary file left
    seen: list[int] = []
    resumed = continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=path,
                              checkpoint_every=10, resume=path,
                              monitor=lambda s: seen.append(s.point))
    assert seen[0] == 41 and seen[-1] == len(whole) - 1  # continued, not redone
    for name in ARRAYS:
        np.testing.assert_array_equal(getattr(resumed, name), getattr(whole, name), name)
    assert resumed.reason == whole.reason and resumed.status == whole.status
    counted = ("residual_evaluations", "factorizations", "iterations", "rejected_steps")
    assert all(resumed.stats[k] == whole.stats[k] for k in counted)
    final, _, _ = load_continuation_checkpoint(path)  # the final checkpoint is complete
    assert final.finished and final.point == len(whole) - 1


def test_resume_refuses_other_run_and_damaged_file(tmp_path):
    path = tmp_path / "branch.h5"
    continue_branch(two_dof, [-1.5, 1.1], 1.5, dataclasses.replace(OPTS, max_points=12),
                    checkpoint=path, checkpoint_every=5)
    with pytest.raises(CheckpointError, match="options"):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, dataclasses.replace(OPTS, max_step=0.2),
                        resume=path)
    with pytest.raises(CheckpointError, match="start"):
        continue_branch(two_dof, [-1.4, 1.1], 1.5, dataclasses.replace(OPTS, max_points=12),
                        resume=path)
    with h5py.File(path, "r+") as f:
        del f["state"]["tangent"]
    with pytest.raises(CheckpointError, match="corrupted"):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, dataclasses.replace(OPTS, max_points=12),
                        resume=path)
    with pytest.raises(FileNotFoundError):
        load_continuation_checkpoint(tmp_path / "missing.h5")


def test_checkpoint_folder_is_created_and_a_folder_path_is_refused(tmp_path):
    """Issue 12: a missing folder used to raise FileNotFoundError at the first checkpoint,
    after the work; now it is created before the run, and impossible paths are refused
    before any work with a named error."""
    from rotorsim.errors import ModelError

    path = tmp_path / "new" / "deeper" / "branch.h5"
    b = continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=path, checkpoint_every=5)
    assert path.is_file() and len(b) > 1
    with pytest.raises(ModelError, match=r"continue_branch\.checkpoint: .* is a folder"):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=tmp_path)
    (tmp_path / "file").write_text("")
    with pytest.raises(ModelError, match=r"continue_branch\.checkpoint: cannot create"):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=tmp_path / "file" / "b.h5")


def test_a_checkpoint_written_before_the_shrinks_counter_still_resumes(tmp_path):
    """``ContinuationState.shrinks`` (issue 16) came after the checkpoint format: a state
    without it resumes with the count at 0 (a missing required field is still refused)."""
    path = tmp_path / "branch.h5"
    with pytest.raises(Interrupted):
        continue_branch(two_dof, [-1.5, 1.1], 1.5, OPTS, checkpoint=path, checkpoint_every=10,
                        monitor=stop_at(25))
    with h5py.File(path, "r+") as f:
        group = f["state"]
        assert "shrinks" in group.attrs
        del group.attrs["shrinks"]
    state, _, _ = load_continuation_checkpoint(path)
    assert state.point == 20 and state.shrinks == 0
    with h5py.File(path, "r+") as f:
        del f["state"].attrs["point"]
    with pytest.raises(CheckpointError, match="'point'"):
        load_continuation_checkpoint(path)
