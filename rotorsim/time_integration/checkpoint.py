"""Checkpoints: a stepper :class:`~.base.State` and the output so far, in HDF5.

Layout (``format_version`` 2; version 2 added the multistep ``history``)::

    /                 attrs: format = "rotorsim-checkpoint", format_version = 2, created
                             (ISO 8601, UTC), config (JSON: stepper options, time span, dt,
                             output spec, problem fingerprint)
    /state            attrs: the scalar State fields (t, step, dt, error, status, factor_*)
                      datasets: q, v, a, force (n,), peak (n,) or (0,), history (k, n)
    /state/counters   attrs: the Counters fields
    /output           datasets: t, q, v, next_time, reduced/<name> (the OutputRecorder)

Floats are stored as float64, so a resumed run continues bit for bit. A file is written to
a temporary name beside the target and renamed when complete: an interruption never leaves
a half-written checkpoint. h5py is imported when a checkpoint is read or written.
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

from rotorsim.errors import RotorsimError
from rotorsim.time_integration.base import Counters, FloatArray, State

FORMAT = "rotorsim-checkpoint"
FORMAT_VERSION = 2
_ARRAYS = ("q", "v", "a", "force", "peak", "history")


class CheckpointError(RotorsimError, ValueError):
    """A checkpoint cannot be read or belongs to another run.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The checkpoint file.
    """

    def __init__(self, message: str, path: str | None = None) -> None:
        self.path = path
        super().__init__(f"checkpoint {path}: {message}" if path else message)


def save_checkpoint(path: str | os.PathLike[str], state: State, *,
                    config: Mapping[str, Any], output: Mapping[str, FloatArray]) -> Path:
    """Write ``state`` and the recorder arrays ``output`` atomically to ``path``.

    Parameters
    ----------
    path : path-like
        Target file; its folder must exist. Replaced if present.
    state : State
        Stepper state (its runtime ``cache`` is not stored).
    config : mapping
        JSON-able description of the run; :func:`load_checkpoint` compares it.
    output : mapping of str to array
        Samples and reductions so far (``OutputRecorder.snapshot()``).

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
    import h5py

    from rotorsim.io.output_folder import prepare_folder

    target = Path(path)
    prepare_folder(target, "checkpoint")
    temp = target.with_name(f".{target.name}.{uuid.uuid4().hex}.tmp")
    try:
        with h5py.File(temp, "x") as f:
            f.attrs["format"] = FORMAT
            f.attrs["format_version"] = FORMAT_VERSION
            f.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
            f.attrs["config"] = json.dumps(config, sort_keys=True)
            _write_state(f.create_group("state"), state)
            group = f.create_group("output")
            for name, value in output.items():
                group.create_dataset(name, data=np.asarray(value, dtype=float))
        with open(temp, "rb+") as raw:  # on disk before the rename
            os.fsync(raw.fileno())
        os.replace(temp, target)
    except BaseException:
        temp.unlink(missing_ok=True)
        raise
    return target


def load_checkpoint(path: str | os.PathLike[str], *, config: Mapping[str, Any] | None = None,
                    ) -> tuple[State, dict[str, FloatArray], dict[str, Any]]:
    """Read a checkpoint: ``(state, output arrays, stored config)``.

    Parameters
    ----------
    path : path-like
        File written by :func:`save_checkpoint`.
    config : mapping, optional
        Description of the run about to continue; must equal the stored one.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    CheckpointError
        If the file is not a readable rotorsim checkpoint of this version, is incomplete or
        corrupted, or was written by a run with another configuration (the message lists
        the entries that differ).
    """
    import h5py

    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no such checkpoint: {source}")
    try:
        handle = h5py.File(source, "r")
    except OSError as exc:
        raise CheckpointError(f"not a readable HDF5 file ({exc})", str(source)) from exc
    try:
        with handle as f:
            stored = read_header(f)
            if config is not None:
                compare_config(stored, json.loads(json.dumps(config, sort_keys=True)))
            state = _read_state(f["state"], int(stored.get("n", len(f["state"]["q"]))))
            output: dict[str, FloatArray] = {}
            f["output"].visititems(lambda name, obj: output.__setitem__(name, obj[()])
                                   if isinstance(obj, h5py.Dataset) else None)
    except CheckpointError as exc:
        raise CheckpointError(str(exc), str(source)) from exc
    except (KeyError, OSError, TypeError, ValueError) as exc:
        raise CheckpointError(f"corrupted or incomplete ({type(exc).__name__}: {exc})",
                              str(source)) from exc
    return state, output, stored


def _write_state(group: Any, state: State) -> None:
    for f in dataclasses.fields(state):
        value = getattr(state, f.name)
        if f.name in State.RUNTIME_FIELDS:
            continue
        if f.name in _ARRAYS:
            group.create_dataset(f.name, data=np.asarray(value, dtype=float))
        elif f.name == "counters":
            sub = group.create_group("counters")
            for c in dataclasses.fields(value):
                sub.attrs[c.name] = int(getattr(value, c.name))
        else:
            group.attrs[f.name] = value


def _read_state(group: Any, n: int) -> State:
    values: dict[str, Any] = {}
    for f in dataclasses.fields(State):
        if f.name in State.RUNTIME_FIELDS:
            continue
        if f.name == "history":
            arr = np.asarray(group[f.name][()], dtype=float)
            if arr.ndim != 2 or (arr.size and arr.shape[1] != n) \
                    or not np.all(np.isfinite(arr)):
                raise CheckpointError(f"state/history has shape {arr.shape} or non-finite "
                                      f"values; expected (k, {n})")
            values[f.name] = arr
        elif f.name in _ARRAYS:
            arr = np.asarray(group[f.name][()], dtype=float)
            shapes = [(n,), (0,)] if f.name == "peak" else [(n,)]
            if arr.shape not in shapes or not np.all(np.isfinite(arr)):
                raise CheckpointError(f"state/{f.name} has shape {arr.shape} or non-finite "
                                      f"values; expected {n} finite numbers")
            values[f.name] = arr
        elif f.name == "counters":
            attrs = group["counters"].attrs
            values[f.name] = Counters(**{c.name: int(attrs[c.name])
                                         for c in dataclasses.fields(Counters)})
        else:
            kind = int if f.name in ("step", "status", "factor_tangent") else float
            values[f.name] = kind(group.attrs[f.name])
    return State(**values)


def read_header(f: Any, fmt_expected: str = FORMAT,
                version_expected: int = FORMAT_VERSION) -> dict[str, Any]:
    """The stored run configuration of an open checkpoint file, after checking its format
    name and version (shared by the time-integration and continuation checkpoints)."""
    fmt = f.attrs.get("format")
    fmt = fmt.decode() if isinstance(fmt, bytes) else fmt
    if fmt != fmt_expected:
        raise CheckpointError(f"not a {fmt_expected} file (format {fmt!r})")
    version = f.attrs.get("format_version")
    version = version.item() if hasattr(version, "item") else version  # numpy scalar
    if version is None or int(version) != version_expected:
        raise CheckpointError(f"format_version {version!r} is not supported; this rotorsim "
                              f"reads version {version_expected}")
    stored = json.loads(f.attrs["config"])
    if not isinstance(stored, dict):
        raise CheckpointError("config attribute is not a JSON object")
    return stored


def compare_config(stored: dict[str, Any], current: dict[str, Any]) -> None:
    """Refuse a checkpoint written by another run (the differing keys in the message)."""
    differ = sorted(k for k in set(stored) | set(current) if stored.get(k) != current.get(k))
    if differ:
        details = "; ".join(f"{k}: checkpoint {_short(stored.get(k))}, this run "
                            f"{_short(current.get(k))}" for k in differ)
        raise CheckpointError(f"written by a different run ({details})")


def _short(value: Any) -> str:
    text = json.dumps(value, sort_keys=True)
    return text if len(text) <= 120 else text[:117] + "..."
