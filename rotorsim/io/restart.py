"""Checkpoint files of the model-file analyses: where the command line keeps them and the
``checkpoint=`` group (:class:`~rotorsim.options.Checkpointing`) an analysis call gets
from its spec."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from rotorsim.options import Checkpointing

if TYPE_CHECKING:
    from rotorsim.io.long_specs import RestartableSpec


def checkpoint_path(folder: str | os.PathLike[str], name: str) -> Path:
    """Where the command line keeps the checkpoint of analysis ``name``."""
    return Path(folder) / f"{name}.checkpoint.h5"


def restart_options(spec: RestartableSpec, path: Path) -> Checkpointing:
    """The checkpoints of the analysis call: the file ``path`` and the spec's interval when
    ``checkpoint`` or ``resume`` is set; resume only from a checkpoint that exists."""
    on = spec.checkpoint or spec.resume
    return Checkpointing(path=path if on else None,
                         every=spec.checkpointing.every if on else None,
                         resume=path if spec.resume and path.is_file() else None)
