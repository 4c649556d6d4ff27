"""One progress-bar helper for every layer: tqdm bars with the caller's label and unit, and
no bar (the run goes on) when tqdm is missing."""

from __future__ import annotations

import sys

import pytest

from rotorsim.progress import progress_bar, with_progress


def test_bars_carry_label_unit_and_resumed_work(capsys):
    pytest.importorskip("tqdm")
    bar = progress_bar(True, total=10, initial=4, desc="sweep", unit="pt")
    assert (bar.desc, bar.unit, bar.total, bar.n) == ("sweep", "pt", 10, 4)
    bar.update(6)
    bar.close()
    assert "sweep: 100%" in capsys.readouterr().err
    timed = progress_bar(True, total=2.0, desc="newmark", unit="s",
                         bar_format="{desc}: t = {n:.4g}/{total:.4g} s")
    timed.update(0.5)
    timed.close()
    assert "newmark: t = 0.5/2 s" in capsys.readouterr().err
    assert list(with_progress(range(3), True, desc="campbell", unit="speed")) == [0, 1, 2]
    assert "campbell: 100%" in capsys.readouterr().err


def test_no_bar_when_not_asked_or_without_tqdm(monkeypatch, capsys):
    items = range(3)
    assert progress_bar(False, total=3, desc="x", unit="pt") is None
    assert with_progress(items, False, desc="x", unit="pt") is items
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # import fails as if not installed
    assert progress_bar(True, total=3, desc="x", unit="pt") is None
    assert with_progress(items, True, desc="x", unit="pt") is items
    assert capsys.readouterr().err == ""
