"""Checkpoint files of long runs: :class:`Checkpointing`."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import ClassVar

from rotorsim.options.group import OptionGroup, about, check_count, check_path


@dataclass(frozen=True)
class Checkpointing(OptionGroup):
    """Checkpoints and resume of :func:`~rotorsim.transient`, :func:`~rotorsim.periodic`
    and :func:`~rotorsim.periodic_parameter` (``checkpoint="run.h5"`` or
    ``checkpoint=rs.Checkpointing(...)``).

    Parameters
    ----------
    path : str or os.PathLike, optional
        HDF5 checkpoint file, written every ``every`` steps or points and at the end
        (atomically: a crash never leaves a half-written file).
    every : int, optional
        Time steps (transient, default 1000) or branch points (periodic branches,
        default 25) between checkpoints.
    resume : str or os.PathLike, optional
        Continue from this checkpoint (same model and options, else a
        ``CheckpointError``); the result equals that of an uninterrupted run. A finished
        periodic run also resumes from its results file (``rs.save(result, path)``).

    Examples
    --------
    >>> Checkpointing("run.h5", every=100).every
    100
    >>> Checkpointing(every=2.5)
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: Checkpointing.every: must be a positive integer, got 2.5
    """

    FROM_VERB: ClassVar[tuple[str, ...]] = ("every",)
    SHORTCUT: ClassVar[str | None] = "path"

    path: str | os.PathLike[str] | None = field(
        default=None, metadata=about("checkpoint file (HDF5)"))
    every: int | None = field(
        default=None, metadata=about("steps (transient) or branch points (periodic) "
                                     "between checkpoints", key="checkpoint_every",
                                     file=int, ge=1))
    resume: str | os.PathLike[str] | None = field(
        default=None, metadata=about("checkpoint to continue from"))

    def __post_init__(self) -> None:
        for name in ("path", "resume"):
            if not check_path(getattr(self, name)):
                raise self._fail(name, f"expected a file path, got "
                                       f"{type(getattr(self, name)).__name__}")
        if self.every is not None and not check_count(self.every, 1):
            raise self._fail("every", f"must be a positive integer, got {self.every!r}")
