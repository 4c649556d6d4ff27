"""Continuation checkpoints: the stepper state and the branch so far, in HDF5.

Layout (``format_version`` 1)::

    /                 attrs: format = "rotorsim-continuation-checkpoint", format_version,
                             created (ISO 8601, UTC), config (JSON: options, size, start)
    /state            attrs: scalar ContinuationState fields; datasets: its arrays
    /state/counters   attrs: the ContinuationCounters fields
    /branch           datasets: one array per branch quantity (points so far)

Floats are stored as float64, so a resumed run continues bit for bit. The file is written
under a temporary name and renamed when complete; h5py is imported only here, when a
checkpoint is read or written.
"""

from __future__ import annotations

import dataclasses
import json
import os
import uuid
from collections.abc import Mapping
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.solvers.continuation_state import ContinuationCounters, ContinuationState
from rotorsim.time_integration.checkpoint import CheckpointError, compare_config, read_header

FORMAT = "rotorsim-continuation-checkpoint"
FORMAT_VERSION = 1
_ARRAYS = ("x", "tangent", "predictor", "x_scale", "r_scale", "origin", "origin_tangent")
_KINDS: dict[str, type] = {"point": int, "iterations": int, "det_sign": int, "status": int,
                           "smooth": bool, "finished": bool, "reason": str}


def save_continuation_checkpoint(path: str | os.PathLike[str], state: ContinuationState, *,
                                 branch: Mapping[str, NDArray[Any]],
                                 config: Mapping[str, Any]) -> Path:
    """Write ``state`` and the branch arrays atomically to ``path`` (replaced if present).

    Parameters
    ----------
    path : path-like
        Target file; its folder must exist.
    state : ContinuationState
    branch : mapping of str to array
        Branch quantities so far, one row per point.
    config : mapping
        JSON-able identity of the run, compared by :func:`load_continuation_checkpoint`.
    """
    import h5py

    target = Path(path)
    if not target.parent.is_dir():
        raise FileNotFoundError(f"folder of checkpoint {target} does not exist")
    temp = target.with_name(f".{target.name}.{uuid.uuid4().hex}.tmp")
    try:
        with h5py.File(temp, "x") as f:
            f.attrs["format"] = FORMAT
            f.attrs["format_version"] = FORMAT_VERSION
            f.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
            f.attrs["config"] = json.dumps(config, sort_keys=True)
            group = f.create_group("state")
            for field in dataclasses.fields(state):
                value = getattr(state, field.name)
                if field.name in _ARRAYS:
                    group.create_dataset(field.name, data=np.asarray(value, dtype=float))
                elif field.name == "counters":
                    sub = group.create_group("counters")
                    for c in dataclasses.fields(value):
                        sub.attrs[c.name] = int(getattr(value, c.name))
                else:
                    group.attrs[field.name] = value
            out = f.create_group("branch")
            for name, value in branch.items():
                out.create_dataset(name, data=np.asarray(value))
        with open(temp, "rb+") as raw:
            os.fsync(raw.fileno())
        os.replace(temp, target)
    except BaseException:
        temp.unlink(missing_ok=True)
        raise
    return target


def load_continuation_checkpoint(
    path: str | os.PathLike[str], *, config: Mapping[str, Any] | None = None,
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
    import h5py

    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no such checkpoint: {source}")
    try:
        with h5py.File(source, "r") as f:
            stored = read_header(f, FORMAT, FORMAT_VERSION)
            if config is not None:
                compare_config(stored, json.loads(json.dumps(config, sort_keys=True)))
            state = _read_state(f["state"])
            branch = {name: f["branch"][name][()] for name in f["branch"]}
    except CheckpointError as exc:
        raise CheckpointError(str(exc), str(source)) from exc
    except (KeyError, OSError, TypeError, ValueError) as exc:
        raise CheckpointError(f"corrupted or incomplete ({type(exc).__name__}: {exc})",
                              str(source)) from exc
    return state, branch, stored


def _read_state(group: Any) -> ContinuationState:
    values: dict[str, Any] = {}
    for field in dataclasses.fields(ContinuationState):
        if field.name in _ARRAYS:
            values[field.name] = np.asarray(group[field.name][()], dtype=float)
        elif field.name == "counters":
            attrs = group["counters"].attrs
            values[field.name] = ContinuationCounters(
                **{c.name: int(attrs[c.name]) for c in dataclasses.fields(ContinuationCounters)})
        else:
            raw = group.attrs[field.name]
            raw = raw.decode() if isinstance(raw, bytes) else raw
            values[field.name] = _KINDS.get(field.name, float)(raw)
    m = values["x"].size
    if values["tangent"].shape != (m + 1,) or values["x_scale"].shape != (m,):
        raise CheckpointError(f"state arrays have inconsistent shapes for m = {m}")
    return ContinuationState(**values)
