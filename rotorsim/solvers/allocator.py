"""Keep freed work arrays in the process: no page faults from re-mapping them each iteration.

A harmonic-balance corrector iteration allocates and frees a dozen dense arrays of a few
MB (the Jacobian of 715 condensed unknowns is 4.1 MB; its AFT blocks, the scaled and
bordered copies, the LU). With glibc's default, *dynamic* thresholds, a freed array above
128 kB goes back to the operating system: at first as an unmapped ``mmap`` chunk, later
by trimming the top of the heap once more than twice the (raised) threshold is free. The
next iteration faults every page of its arrays in again, zero-filled by the kernel.
Measured on the default model's quasi-periodic branch up to 1000 rpm (22 points, one
thread): 526,877 minor page faults and 6.5 s of CPU, against 28,984 and 5.1 s with the
thresholds below; the periodic branch's iterations do the same on a smaller scale.

:func:`keep_freed_memory` raises glibc's ``M_MMAP_THRESHOLD`` to :data:`MMAP_THRESHOLD`
and ``M_TRIM_THRESHOLD`` to :data:`TRIM_THRESHOLD` (``mallopt``), once per process, at
the start of a continuation. Freed arrays below 32 MB then stay in the heap and the next
iteration reuses their pages. The peak memory does not change: up to
:data:`TRIM_THRESHOLD` of freed memory is held for reuse instead of being returned to
the system at once. glibc has no way to read the settings back or to return to its
dynamic mode, so the setting is process-wide and stays, as the BLAS thread limit of
:mod:`~rotorsim.solvers.threads` is for the duration of an analysis.

It does nothing when the C library is not glibc, when the user set either threshold in
the environment (``MALLOC_MMAP_THRESHOLD_``, ``MALLOC_TRIM_THRESHOLD_``: theirs win), or
when the environment variable :data:`SWITCH` is ``off``.
"""

from __future__ import annotations

import ctypes
import os
import threading

SWITCH = "ROTORSIM_KEEP_FREED_MEMORY"
"""Environment variable: ``off`` (or ``0``, ``no``, ``false``) leaves malloc alone."""
MMAP_THRESHOLD = 32 * 1024 * 1024
"""Bytes [B]: requests below it come from the heap (glibc's dynamic maximum on 64 bit)."""
TRIM_THRESHOLD = 128 * 1024 * 1024
"""Bytes [B] of free heap top held before glibc returns it to the system."""
M_TRIM_THRESHOLD = -1
"""glibc's ``mallopt`` parameter numbers (``malloc.h``)."""
M_MMAP_THRESHOLD = -3
USER_VARIABLES = ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_")

_LOCK = threading.Lock()
_STATE: dict[str, bool | None] = {"applied": None}


def enabled() -> bool:
    """False when :data:`SWITCH` says ``off`` or the user tuned glibc's thresholds."""
    if os.environ.get(SWITCH, "").strip().lower() in ("off", "0", "no", "false"):
        return False
    return not any(name in os.environ for name in USER_VARIABLES)


def keep_freed_memory() -> bool:
    """Set the thresholds (module docstring) once per process.

    Returns
    -------
    bool
        True when they are set (now or by an earlier call), False when this process keeps
        malloc's own behaviour (not glibc, the user's settings, or :data:`SWITCH` off).
    """
    with _LOCK:
        if _STATE["applied"] is None:
            _STATE["applied"] = enabled() and _set_glibc_thresholds()
        return bool(_STATE["applied"])


def _set_glibc_thresholds() -> bool:
    """``mallopt`` both thresholds; False where there is no glibc (musl, macOS,
    Windows) or it refuses."""
    try:
        libc = ctypes.CDLL(None)
        if not hasattr(libc, "gnu_get_libc_version"):     # glibc only: musl and others
            return False
        mallopt = libc.mallopt
    except (OSError, AttributeError, TypeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    # mallopt returns 1 on success, 0 on error
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
        mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD))
