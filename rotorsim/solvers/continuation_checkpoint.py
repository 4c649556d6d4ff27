"""Continuation checkpoints: the stepper state and the branch so far.

Layout (``format_version`` 1)::

    /                 attrs: format = "rotorsim-continuation-checkpoint", format_version,
                             created (ISO 8601, UTC), config (JSON: options, size, start)
    /state            attrs: scalar ContinuationState fields; datasets: its arrays
    /state/counters   attrs: the ContinuationCounters fields
    /branch           datasets: one array per branch quantity (points so far)

Floats are stored as float64, so a resumed run continues bit for bit. This module turns a
state into that content and back; the file itself is written and read by a
:class:`~rotorsim.io.checkpoint_file.CheckpointFiles` (by default the atomic HDF5 files of
:mod:`rotorsim.io.checkpoint_file`, imported when a checkpoint is first written or read), so
the continuation never imports h5py.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import CheckpointError
from rotorsim.solvers.continuation_state import ContinuationCounters, ContinuationState

if TYPE_CHECKING:
    from rotorsim.io.checkpoint_file import CheckpointFiles, GroupContent

FORMAT = "rotorsim-continuation-checkpoint"
FORMAT_VERSION = 1
_ARRAYS = ("x", "tangent", "predictor", "x_scale", "r_scale", "origin", "origin_tangent")
_KINDS: dict[str, type] = {"point": int, "iterations": int, "det_sign": int, "status": int,
                           "smooth": bool, "finished": bool, "reason": str, "shrinks": int}


def save_continuation_checkpoint(path: str | os.PathLike[str], state: ContinuationState, *,
                                 branch: Mapping[str, NDArray[Any]],
                                 config: Mapping[str, Any],
                                 files: CheckpointFiles | None = None) -> Path:
    """Write ``state`` and the branch arrays atomically to ``path`` (replaced if present).

    Parameters
    ----------
    path : path-like
        Target file; missing folders are created.
    state : ContinuationState
    branch : mapping of str to array
        Branch quantities so far, one row per point.
    config : mapping
        JSON-able identity of the run, compared by :func:`load_continuation_checkpoint`.
    files : CheckpointFiles, optional
        Where the checkpoint goes (default: HDF5 files, :mod:`rotorsim.io.checkpoint_file`).
    """
    content: dict[str, GroupContent] = {
        "state": _state_content(state),
        "branch": {"datasets": {name: np.asarray(value) for name, value in branch.items()}}}
    return _files(files).write(path, FORMAT, FORMAT_VERSION, config, content)


def load_continuation_checkpoint(
    path: str | os.PathLike[str], *, config: Mapping[str, Any] | None = None,
    files: CheckpointFiles | None = None,
) -> tuple[ContinuationState, dict[str, NDArray[Any]], dict[str, Any]]:
    """Read ``(state, branch arrays, stored config)``.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    CheckpointError
        If the file is not a continuation checkpoint of this version, is damaged, or was
        written by a run with another configuration (the differing entries are listed).
    """
    (state, branch), stored = _files(files).read(path, FORMAT, FORMAT_VERSION, _decode,
                                                 config)
    return state, branch, stored


def _files(files: CheckpointFiles | None) -> CheckpointFiles:
    if files is not None:
        return files
    from rotorsim.io.checkpoint_file import HDF5_CHECKPOINTS

    return HDF5_CHECKPOINTS


def _state_content(state: ContinuationState) -> GroupContent:
    attrs: dict[str, Any] = {}
    datasets: dict[str, NDArray[Any]] = {}
    groups: dict[str, GroupContent] = {}
    for field in dataclasses.fields(state):
        value = getattr(state, field.name)
        if field.name in _ARRAYS:
            datasets[field.name] = np.asarray(value, dtype=float)
        elif field.name == "counters":
            groups[field.name] = {"attrs": {c.name: int(getattr(value, c.name))
                                            for c in dataclasses.fields(value)}}
        else:
            attrs[field.name] = value
    return {"attrs": attrs, "datasets": datasets, "groups": groups}


def _decode(content: Mapping[str, Any], stored: dict[str, Any],
            ) -> tuple[ContinuationState, dict[str, NDArray[Any]]]:
    branch = content["branch"]
    return _read_state(content["state"]), {name: branch[name] for name in branch}


def _read_state(group: Mapping[str, Any]) -> ContinuationState:
    values: dict[str, Any] = {}
    for field in dataclasses.fields(ContinuationState):
        if field.name in _ARRAYS:
            values[field.name] = np.asarray(group[field.name], dtype=float)
        elif field.name == "counters":
            counters = group["counters"]
            values[field.name] = ContinuationCounters(  # counters added later read as 0
                **{c.name: int(counters[c.name]) if c.name in counters else 0
                   for c in dataclasses.fields(ContinuationCounters)})
        elif field.name in group:
            values[field.name] = _KINDS.get(field.name, float)(group[field.name])
        elif field.default is dataclasses.MISSING:      # fields added later keep defaults
            raise CheckpointError(f"the state has no {field.name!r}")
    m = values["x"].size
    if values["tangent"].shape != (m + 1,) or values["x_scale"].shape != (m,):
        raise CheckpointError(f"state arrays have inconsistent shapes for m = {m}")
    return ContinuationState(**values)
