"""``keep_freed_memory``: glibc keeps freed work arrays for reuse
(``rotorsim/solvers/allocator.py``).

Measured in a fresh process (the setting is process-wide and stays): three 4 MB arrays
allocated, filled and freed twenty times fault about 20,000 pages in with glibc's dynamic
thresholds (measured 19,880: the freed heap top is trimmed, or the arrays mapped afresh),
and none once the thresholds are set (measured 0). Asserted: more than 5,000 (the churn
does fault by default) and ten times fewer with the setting. Off switches and the user's
own settings leave malloc alone.
"""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import textwrap

import pytest

from rotorsim.solvers import allocator

GLIBC = platform.system() == "Linux" and platform.libc_ver()[0] == "glibc"

CHURN = textwrap.dedent("""
    import resource
    import numpy as np
    from rotorsim.solvers.allocator import keep_freed_memory

    def faults():
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        for _ in range(20):
            arrays = [np.ones(512 * 1024) for _ in range(3)]    # 4 MB each, touched
            del arrays
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before

    faults()                                   # warm up: numpy, the first mappings
    default = faults()
    applied = keep_freed_memory()
    faults()
    print(default, faults(), applied)
""")


def _run(env: dict[str, str]) -> tuple[int, int, bool]:
    out = subprocess.run([sys.executable, "-c", CHURN], capture_output=True, text=True,
                         env=env, check=True, timeout=120)
    default, kept, applied = out.stdout.split()
    return int(default), int(kept), applied == "True"


def _environment(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in (allocator.SWITCH, *allocator.USER_VARIABLES)}
    return {**env, **extra}


@pytest.mark.skipif(not GLIBC, reason="the thresholds are glibc's (mallopt)")
def test_freed_arrays_are_reused_without_page_faults() -> None:
    default, kept, applied = _run(_environment())
    print(f"minor page faults: {default} by default, {kept} with the thresholds set")
    assert applied
    assert default > 5_000 and kept * 10 < default


@pytest.mark.skipif(not GLIBC, reason="the thresholds are glibc's (mallopt)")
def test_the_switch_and_the_users_settings_leave_malloc_alone() -> None:
    for env in (_environment(**{allocator.SWITCH: "off"}),
                _environment(MALLOC_TRIM_THRESHOLD_="1000000")):
        default, kept, applied = _run(env)
        assert not applied and kept * 10 > default       # the faults stay


def test_enabled_reads_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in (allocator.SWITCH, *allocator.USER_VARIABLES):
        monkeypatch.delenv(name, raising=False)
    assert allocator.enabled()
    monkeypatch.setenv(allocator.SWITCH, "No")
    assert not allocator.enabled()
    monkeypatch.setenv(allocator.SWITCH, "on")
    monkeypatch.setenv("MALLOC_MMAP_THRESHOLD_", "65536")
    assert not allocator.enabled()
