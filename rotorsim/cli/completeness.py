"""Whether an analysis result is complete: the source of exit code 3 (``EXIT_INCOMPLETE``).

A result is incomplete when its ``status`` is not OK (a periodic branch that stopped short
of its bound, a transient whose step failed) or when some of its points failed (Campbell
speeds, map stiffnesses, response frequencies, sweep points). Its partial results are
still written; the reason is printed on stderr.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorsim.errors import Status


def incomplete_reason(result: Any) -> str | None:
    """Why ``result`` is incomplete, or None when every status is OK.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> incomplete_reason(SimpleNamespace(status=Status.OK)) is None
    True
    >>> incomplete_reason(SimpleNamespace(status=Status.NOT_CONVERGED, reason="step too small"))
    'status NOT_CONVERGED: step too small'
    >>> incomplete_reason(SimpleNamespace(status=np.array([0, 1, 0, 2])))
    '2 of 4 points failed'
    """
    status = getattr(result, "status", Status.OK)
    points = status if np.ndim(status) else getattr(result, "point_status", None)
    failed = _failed_points(points)
    if np.ndim(status) == 0 and int(status) != Status.OK:
        return f"status {Status(int(status)).name}" + _why(result, failed)
    return failed or None


def _failed_points(points: Any) -> str:
    if points is None or np.ndim(points) == 0:
        return ""
    points = np.asarray(points)
    failed = int(np.count_nonzero(points != int(Status.OK)))
    return f"{failed} of {points.size} points failed" if failed else ""


def _why(result: Any, failed: str) -> str:
    options = getattr(result, "options", None) or {}
    text = getattr(result, "reason", "") or (options.get("failure", "")
                                             if isinstance(options, dict) else "") or failed
    return f": {text}" if text else ""
