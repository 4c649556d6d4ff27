"""Checkpoint files of the model-file analyses: where the command line keeps them and the
``checkpoint``/``resume`` keywords an analysis call gets from its spec."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rotorsim.io.long_specs import RestartableSpec


def checkpoint_path(folder: str | os.PathLike[str], name: str) -> Path:
    """Where the command line keeps the checkpoint of analysis ``name``."""
    return Path(folder) / f"{name}.checkpoint.h5"


def restart_options(spec: RestartableSpec, path: Path) -> dict[str, Any]:
    """``checkpoint``, ``checkpoint_every`` and ``resume`` keywords of the analysis call:
    resume only from a checkpoint that exists."""
    out: dict[str, Any] = {}
    if spec.checkpoint or spec.resume:
        out["checkpoint"] = path
        if spec.checkpoint_every is not None:
            out["checkpoint_every"] = spec.checkpoint_every
    if spec.resume and path.is_file():
        out["resume"] = path
    return out
