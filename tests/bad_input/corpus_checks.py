"""Shared checks and small models of the bad-input corpus.

The bad-input corpus (issue 12): every case is an input that must be refused with a
one-line, named error that says what is wrong and where, never a traceback from numpy or
scipy, a hang or a silently wrong number.

- ``test_element_corpus.py``: materials, shaft elements, disks, point masses, linear bearings
  and the rotor's node bookkeeping (``ModelError`` naming element and field).
- ``test_rolling_corpus.py``: ball, roller and flexible-ring bearings and bearing statics.
- ``test_analysis_corpus.py``: arguments of the analyses (``ModelError`` naming the argument)
  and unknown keywords (``TypeError`` listing the valid ones).
- ``test_model_file_corpus.py``: model files (``ModelError.where`` is the key path).
- ``test_cli_corpus.py``: command lines (exit code 2, one line on stderr).

Every case of the corpus is ``(call, expected exception class, regex)``: the call must raise
exactly that class (or a subclass), its message must match the regex, which names the
culprit (key path, element, argument) and the reason, and it must fit on one line.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import rotorsim as rs
from rotorsim.model.material import steel

MODELS = Path(__file__).resolve().parents[2] / "models"


def assert_one_line_error(call: Callable[[], Any], kind: type[BaseException],
                          pattern: str) -> BaseException:
    """Run ``call``; it must raise ``kind`` with a one-line message matching ``pattern``."""
    with pytest.raises(Exception) as info:  # the class is checked below
        call()
    error = info.value
    message = str(error)
    assert isinstance(error, kind), f"{type(error).__name__} instead of {kind.__name__}: {message}"
    assert "\n" not in message and "\r" not in message, f"message spans lines: {message!r}"
    assert re.search(pattern, message), f"{pattern!r} not in {message!r}"
    return error


def shaft(n: int = 4, **kw: Any) -> list[rs.ShaftElement]:
    """``n`` steel elements of 0.25 m, 50 mm outer diameter."""
    return [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel, **kw) for _ in range(n)]


def small_rotor() -> rs.Rotor:
    """A 4-element steel shaft with a disk at node 2 on two 1 MN/m bearings (nodes 0, 4)."""
    return rs.Rotor(shaft(), [rs.DiskElement(n=2, m=10.0, Id=0.05, Ip=0.1)],
                    [rs.BearingElement(n=0, kxx=1e6, cxx=100.0, kzz=1e6),
                     rs.BearingElement(n=4, kxx=1e6, cxx=100.0)])


def model_dict(name: str = "friswell_5_9_5") -> dict[str, Any]:
    """A shipped model file as a dict, to be mutated by a case."""
    with open(MODELS / f"{name}.toml", "rb") as stream:
        return tomllib.load(stream)
