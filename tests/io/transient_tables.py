"""A model-file dictionary with one transient analysis, shared by the model-file tests of
transients (``test_transient_accuracy_io.py``, ``test_transient_run_control_io.py``)."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

MODELS = Path(__file__).resolve().parents[2] / "models"


def rolling_ball_with_transient(**table: Any) -> dict[str, Any]:
    """``models/rolling_ball.toml`` as a dictionary whose only analysis is ``run``: a
    transient at 6000 rpm that keeps node 5, with the keys of ``table``."""
    with open(MODELS / "rolling_ball.toml", "rb") as stream:
        raw = tomllib.load(stream)
    raw["analyses"] = {"run": {"type": "transient", "speed": "6000 rpm", "nodes": [5],
                               **table}}
    return raw
