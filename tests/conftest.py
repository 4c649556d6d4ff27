"""Test-wide settings: figures render off-screen, and figures a test leaves open are closed
after it (on an xdist worker the modules of many tests share one process, and pyplot keeps
every open figure)."""

import os
import sys

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    if "matplotlib.pyplot" in sys.modules:   # only when a test drew something
        sys.modules["matplotlib.pyplot"].close("all")
