"""The one home of checkpoint files: atomic HDF5 writes of the numerics' plain content,
read back with errors that name the file and the missing entry; the numerics take any
CheckpointFiles."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import h5py
import numpy as np
import pytest

from rotorsim.errors import CheckpointError, ModelError
from rotorsim.io.checkpoint_file import HDF5_CHECKPOINTS, compare_config, file_format
from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_checkpoint import load_continuation_checkpoint
from rotorsim.time_integration.base import State
from rotorsim.time_integration.checkpoint import load_checkpoint, save_checkpoint

CONTENT = {"state": {"attrs": {"t": 1.5, "reason": "bound"},
                     "datasets": {"q": np.arange(3.0), "flags": np.array([True, False])},
                     "groups": {"counters": {"attrs": {"solves": 4}}}},
           "output": {"datasets": {"t": np.ones((2, 1)), "reduced/max": np.zeros(2)}}}


def raw(content, stored):
    return content


def test_content_is_written_as_given_and_read_back(tmp_path):
    path = HDF5_CHECKPOINTS.write(tmp_path / "deep" / "run.h5", "demo", 3, {"b": 1, "a": 2},
                                  CONTENT)
    with h5py.File(path) as f:
        assert f.attrs["format"] == "demo" and f.attrs["format_version"] == 3
        assert f.attrs["config"] == '{"a": 2, "b": 1}'
        assert f["state"].attrs["t"] == 1.5 and f["state/flags"].dtype == bool
        assert f["state/counters"].attrs["solves"] == 4
        assert f["output/reduced/max"].shape == (2,)
    assert [p.name for p in path.parent.iterdir()] == ["run.h5"]  # no temporary left
    content, stored = HDF5_CHECKPOINTS.read(path, "demo", 3, raw, config={"a": 2, "b": 1})
    assert stored == {"a": 2, "b": 1}
    state = content["state"]
    assert state["reason"] == "bound" and state["q"].tolist() == [0.0, 1.0, 2.0]
    assert int(state["counters"]["solves"]) == 4 and "q" in state and "p" not in state
    assert content["output"]["reduced"]["max"].tolist() == [0.0, 0.0]


def test_errors_name_the_file_and_the_missing_entry(tmp_path):
    path = HDF5_CHECKPOINTS.write(tmp_path / "run.h5", "demo", 3, {}, CONTENT)
    with pytest.raises(CheckpointError, match=r"run\.h5: corrupted or incomplete: "
                                              r"'/state/counters/steps' is missing"):
        HDF5_CHECKPOINTS.read(path, "demo", 3, lambda c, s: c["state"]["counters"]["steps"])
    with pytest.raises(CheckpointError, match=r"run\.h5: not a other file"):
        HDF5_CHECKPOINTS.read(path, "other", 3, raw)
    with pytest.raises(CheckpointError, match=r"run\.h5: format_version 3 is not supported"):
        HDF5_CHECKPOINTS.read(path, "demo", 4, raw)
    with pytest.raises(CheckpointError, match=r"run\.h5: written by a different run \(n: "):
        HDF5_CHECKPOINTS.read(path, "demo", 3, raw, config={"n": 1})
    (tmp_path / "text.h5").write_text("not HDF5")
    with pytest.raises(CheckpointError, match=r"text\.h5: not a readable HDF5 file"):
        HDF5_CHECKPOINTS.read(tmp_path / "text.h5", "demo", 3, raw)
    with pytest.raises(FileNotFoundError, match=r"absent\.h5"):
        HDF5_CHECKPOINTS.read(tmp_path / "absent.h5", "demo", 3, raw)
    (tmp_path / "blocker").write_text("a file where a folder goes")
    with pytest.raises(ModelError, match="checkpoint: cannot create the folder"):
        HDF5_CHECKPOINTS.write(tmp_path / "blocker" / "run.h5", "demo", 3, {}, CONTENT)


def test_compare_config_lists_what_differs():
    compare_config({"a": 1}, {"a": 1})
    with pytest.raises(CheckpointError, match=r"\(a: checkpoint 1, this run 2; c: "
                                              r"checkpoint null, this run 3\)"):
        compare_config({"a": 1, "b": 0}, {"a": 2, "b": 0, "c": 3})


def test_file_format_tells_checkpoints_from_results(tmp_path):
    HDF5_CHECKPOINTS.write(tmp_path / "run.h5", "rotorsim-checkpoint", 2, {}, {})
    (tmp_path / "text.h5").write_text("not HDF5")
    assert file_format(tmp_path / "run.h5") == "rotorsim-checkpoint"
    assert file_format(tmp_path / "text.h5") is None
    assert file_format(tmp_path / "absent.h5") is None


@dataclasses.dataclass
class MemoryFiles:
    """Checkpoints kept in a dict: what the numerics need of a CheckpointFiles."""

    files: dict[str, tuple[str, int, dict, dict]] = dataclasses.field(default_factory=dict)

    def write(self, path, fmt, version, config, content):
        self.files[str(path)] = (fmt, version, dict(config), content)
        return Path(path)

    def read(self, path, fmt, version, decode, config=None):
        stored_fmt, stored_version, stored, content = self.files[str(path)]
        assert (stored_fmt, stored_version) == (fmt, version)
        return decode(_unified(content), stored), stored


def _unified(content):
    """GroupContent as read back: attrs, datasets and subgroups under one mapping."""
    if "attrs" not in content and "datasets" not in content and "groups" not in content:
        return {name: _unified(group) for name, group in content.items()}
    out = {**content.get("attrs", {})}
    for name, array in content.get("datasets", {}).items():
        head, _, tail = name.partition("/")
        if tail:
            out.setdefault(head, {})[tail] = array
        else:
            out[name] = array
    out.update({name: _unified(g) for name, g in content.get("groups", {}).items()})
    return out


def test_numerics_write_through_the_files_they_are_given():
    files = MemoryFiles()
    z = np.zeros(2)
    state = State(1.5, np.ones(2), z, z, z, step=3, dt=0.1)
    save_checkpoint("run", state, config={"n": 2}, output={"reduced/max": np.ones(2)},
                    files=files)
    assert files.files["run"][:3] == ("rotorsim-checkpoint", 2, {"n": 2})
    back, output, config = load_checkpoint("run", files=files)
    assert config == {"n": 2}
    assert back.t == 1.5 and back.step == 3 and output["reduced/max"].tolist() == [1.0, 1.0]


def test_continuation_checkpoint_missing_entry_is_named(tmp_path):
    def line(x, lam):
        return x - lam, np.eye(1), -np.ones(1)

    path = tmp_path / "branch.h5"
    continue_branch(line, [0.0], 0.0, Continuation(max_points=3), checkpoint=path)
    with h5py.File(path, "r+") as f:
        del f["state"]["counters"]
    with pytest.raises(CheckpointError, match=r"branch\.h5: corrupted or incomplete: "
                                              r"'/state/counters' is missing"):
        load_continuation_checkpoint(path)
