"""An interrupted checkpointed transient, resumed: the shared steps of the resume tests."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import rotorsim as rs
import rotorsim.analyses.transient.transient as module


class Stop(Exception):
    """Raised by the step callback to interrupt a run."""


def resumed_run(monkeypatch: pytest.MonkeyPatch, path: Path, stop_step: int, every: int,
                *args: Any, **kwargs: Any) -> rs.TransientResult:
    """Run ``rs.transient(*args, **kwargs)`` with checkpoints every ``every`` steps, stop it
    after step ``stop_step`` and resume it from the checkpoint; the resumed result."""
    original = module.integrate

    def interrupted(*a: Any, **kw: Any) -> Any:
        def callback(state: Any) -> None:
            if state.step == stop_step:
                raise Stop

        return original(*a, **kw, callback=callback)

    monkeypatch.setattr(module, "integrate", interrupted)
    with pytest.raises(Stop):
        module.transient(*args, checkpoint=rs.Checkpointing(path, every=every), **kwargs)
    monkeypatch.setattr(module, "integrate", original)
    return module.transient(*args, checkpoint=rs.Checkpointing(resume=path), **kwargs)
