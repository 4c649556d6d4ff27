"""Checkpoints of a time integration: a stepper :class:`~.base.State` and the output so far.

Layout (``format_version`` 2; version 2 added the multistep ``history``)::

    /                 attrs: format = "rotorsim-checkpoint", format_version = 2, created
                             (ISO 8601, UTC), config (JSON: stepper options, time span, dt,
                             output spec, problem fingerprint)
    /state            attrs: the scalar State fields (t, step, dt, error, status, factor_*)
                      datasets: q, v, a, force (n,), peak (n,) or (0,), history (k, n)
    /state/counters   attrs: the Counters fields
    /output           datasets: t, q, v, next_time, reduced/<name> (the OutputRecorder)

Floats are stored as float64, so a resumed run continues bit for bit. This module turns a
state into that content and back; the file itself is written and read by a
:class:`~rotorsim.io.checkpoint_file.CheckpointFiles` (by default the atomic HDF5 files of
:mod:`rotorsim.io.checkpoint_file`, imported when a checkpoint is first written or read), so
the integrator never imports h5py.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.errors import CheckpointError
from rotorsim.time_integration.base import Counters, FloatArray, State

if TYPE_CHECKING:
    from rotorsim.io.checkpoint_file import CheckpointFiles, GroupContent

__all__ = ["FORMAT", "FORMAT_VERSION", "CheckpointError", "load_checkpoint", "save_checkpoint"]

FORMAT = "rotorsim-checkpoint"
FORMAT_VERSION = 2
_ARRAYS = ("q", "v", "a", "force", "peak", "history")


def save_checkpoint(path: str | os.PathLike[str], state: State, *,
                    config: Mapping[str, Any], output: Mapping[str, FloatArray],
                    files: CheckpointFiles | None = None) -> Path:
    """Write ``state`` and the recorder arrays ``output`` atomically to ``path``.

    Parameters
    ----------
    path : path-like
        Target file, replaced if present; missing folders are created.
    state : State
        Stepper state (its runtime ``cache`` is not stored).
    config : mapping
        JSON-able description of the run; :func:`load_checkpoint` compares it.
    output : mapping of str to array
        Samples and reductions so far (``OutputRecorder.snapshot()``).
    files : CheckpointFiles, optional
        Where the checkpoint goes (default: HDF5 files, :mod:`rotorsim.io.checkpoint_file`).

    Examples
    --------
    >>> import tempfile
    >>> z = np.zeros(2)
    >>> s = State(1.5, np.ones(2), z, z, z, step=3, dt=0.1)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_checkpoint(Path(folder) / "run.h5", s, config={"n": 2}, output={})
    ...     back, _, _ = load_checkpoint(path, config={"n": 2})
    >>> back.t, back.step, back.q.tolist()
    (1.5, 3, [1.0, 1.0])
    """
    content: dict[str, GroupContent] = {
        "state": _state_content(state),
        "output": {"datasets": {name: np.asarray(value, dtype=float)
                                for name, value in output.items()}}}
    return _files(files).write(path, FORMAT, FORMAT_VERSION, config, content)


def load_checkpoint(path: str | os.PathLike[str], *, config: Mapping[str, Any] | None = None,
                    files: CheckpointFiles | None = None,
                    ) -> tuple[State, dict[str, FloatArray], dict[str, Any]]:
    """Read a checkpoint: ``(state, output arrays, stored config)``.

    Parameters
    ----------
    path : path-like
        File written by :func:`save_checkpoint`.
    config : mapping, optional
        Description of the run about to continue; must equal the stored one.
    files : CheckpointFiles, optional
        Where the checkpoint is (default: HDF5 files, :mod:`rotorsim.io.checkpoint_file`).

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    CheckpointError
        If the file is not a readable rotorsim checkpoint of this version, is incomplete or
        corrupted, or was written by a run with another configuration (the message lists
        the entries that differ).
    """
    (state, output), stored = _files(files).read(path, FORMAT, FORMAT_VERSION, _decode,
                                                 config)
    return state, output, stored


def _files(files: CheckpointFiles | None) -> CheckpointFiles:
    if files is not None:
        return files
    from rotorsim.io.checkpoint_file import HDF5_CHECKPOINTS

    return HDF5_CHECKPOINTS


def _state_content(state: State) -> GroupContent:
    attrs: dict[str, Any] = {}
    datasets: dict[str, FloatArray] = {}
    groups: dict[str, GroupContent] = {}
    for f in dataclasses.fields(state):
        value = getattr(state, f.name)
        if f.name in State.RUNTIME_FIELDS:
            continue
        if f.name in _ARRAYS:
            datasets[f.name] = np.asarray(value, dtype=float)
        elif f.name == "counters":
            groups[f.name] = {"attrs": {c.name: int(getattr(value, c.name))
                                        for c in dataclasses.fields(value)}}
        else:
            attrs[f.name] = value
    return {"attrs": attrs, "datasets": datasets, "groups": groups}


def _decode(content: Mapping[str, Any], stored: dict[str, Any],
            ) -> tuple[State, dict[str, FloatArray]]:
    state = _read_state(content["state"], int(stored.get("n", len(content["state"]["q"]))))
    return state, dict(_datasets(content["output"], ""))


def _datasets(group: Mapping[str, Any], prefix: str) -> Iterator[tuple[str, FloatArray]]:
    """The arrays of ``group`` and its subgroups by relative path (``reduced/<name>``)."""
    for name in group:
        value = group[name]
        if isinstance(value, Mapping):
            yield from _datasets(value, f"{prefix}{name}/")
        else:
            yield f"{prefix}{name}", value


def _read_state(group: Mapping[str, Any], n: int) -> State:
    values: dict[str, Any] = {}
    for f in dataclasses.fields(State):
        if f.name in State.RUNTIME_FIELDS:
            continue
        if f.name == "history":
            arr = np.asarray(group[f.name], dtype=float)
            if arr.ndim != 2 or (arr.size and arr.shape[1] != n) \
                    or not np.all(np.isfinite(arr)):
                raise CheckpointError(f"state/history has shape {arr.shape} or non-finite "
                                      f"values; expected (k, {n})")
            values[f.name] = arr
        elif f.name in _ARRAYS:
            arr = np.asarray(group[f.name], dtype=float)
            shapes = [(n,), (0,)] if f.name == "peak" else [(n,)]
            if arr.shape not in shapes or not np.all(np.isfinite(arr)):
                raise CheckpointError(f"state/{f.name} has shape {arr.shape} or non-finite "
                                      f"values; expected {n} finite numbers")
            values[f.name] = arr
        elif f.name == "counters":
            counters = group["counters"]
            values[f.name] = Counters(**{c.name: int(counters[c.name])
                                         for c in dataclasses.fields(Counters)})
        else:
            kind = int if f.name in ("step", "status", "factor_tangent") else float
            if f.name not in group and f.name == "factor_kappa":
                continue  # written before this field existed: its default (NaN) is exact
            values[f.name] = kind(group[f.name])
    return State(**values)
