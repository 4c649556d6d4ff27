"""Unknown keyword arguments of the public verbs: a ``TypeError`` that lists the valid ones.

Python's own message (``modal() got an unexpected keyword argument 'num_mode'``) names the
culprit but not the alternatives; :func:`checked_keywords` adds them, with the closest match.
A keyword that moved into an option group (:mod:`rotorsim.options`) names its new home
instead (:data:`MOVED`).
"""

from __future__ import annotations

import difflib
import functools
import inspect
from collections.abc import Callable
from typing import ParamSpec, TypeVar

P = ParamSpec("P")
R = TypeVar("R")

_NAMED = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)


def _homes(keyword: str, group: str, fields: dict[str, str]) -> dict[str, str]:
    """``{old keyword: "keyword=rs.Group(field=...)"}`` for the ``fields`` (old keyword ->
    field name) of one group."""
    return {old: f"{keyword}=rs.{group}({new}=...)" for old, new in fields.items()}


_EXCITATION = _homes("excitation", "Excitation",
                     {k: k for k in ("gravity", "direction", "loads", "base")})
_CONTINUATION = _homes("continuation", "ContinuationOptions",
                       {k: k for k in ("step", "max_step", "max_points", "tol")})
_CHECKPOINT = _homes("checkpoint", "Checkpointing",
                     {"checkpoint_every": "every", "resume": "resume"})
_STABILITY = _homes("stability", "StabilityOptions",
                    {"stability_modes": "modes", "stability_tol": "tol",
                     "bifurcations": "bifurcations"})
_HARMONICS = _homes("harmonics", "Harmonics", {"samples": "samples"})

MOVED: dict[str, dict[str, str]] = {
    "periodic": {
        **_EXCITATION, **_CONTINUATION, **_CHECKPOINT, **_STABILITY, **_HARMONICS,
        **_homes("harmonics", "Harmonics", {"fundamental": "fundamental",
                                            "condense": "condense"}),
        **_homes("output", "Output", {"progress": "progress"}),
    },
    "periodic_parameter": {
        **{k: v for k, v in _EXCITATION.items() if k != "base"}, **_CONTINUATION,
        **_CHECKPOINT, **_STABILITY, **_HARMONICS,
        **_homes("output", "Output", {"progress": "progress"}),
    },
    "transient": {
        **_EXCITATION, **_homes("excitation", "Excitation", {"forces": "forces"}),
        **_CHECKPOINT,
        **_homes("output", "Output", {k: k for k in ("every", "times", "rolling_elements",
                                                      "progress", "velocities", "reducers")}),
        "keep_velocities": "output=rs.Output(velocities=...)",
        "continue_from": "initial=<the TransientResult to continue>",
        "stop_when_steady": "steady=rs.SteadyStop(...)",
    },
}
"""Keywords of each verb that moved into an option group, and their new home."""


def checked_keywords(func: Callable[P, R]) -> Callable[P, R]:
    """Wrap ``func`` so that an unknown keyword raises a one-line ``TypeError`` listing the
    valid keywords (and the closest one), or naming its new home when it moved into an
    option group (:data:`MOVED`); everything else is passed through unchanged.

    Examples
    --------
    >>> @checked_keywords
    ... def solve(model, *, tol=1e-8, max_iter=50):
    ...     return tol
    >>> solve(None, tol=1e-6)
    1e-06
    >>> solve(None, tolerance=1e-6)
    Traceback (most recent call last):
    ...
    TypeError: solve: unknown keyword 'tolerance'; valid: model, tol, max_iter
    >>> @checked_keywords
    ... def periodic(model, *, continuation=None):
    ...     return continuation
    >>> periodic(None, max_step=0.1)
    Traceback (most recent call last):
    ...
    TypeError: periodic: 'max_step' moved to continuation=rs.ContinuationOptions(max_step=...)
    """
    params = inspect.signature(func).parameters
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()):
        return func
    names = tuple(name for name, p in params.items() if p.kind in _NAMED)
    moved = MOVED.get(func.__name__, {})

    @functools.wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        for key in kwargs:
            if key not in names:
                if key in moved:
                    raise TypeError(moved_keyword_message(func.__name__, key, moved[key]))
                raise TypeError(unknown_keyword_message(func.__name__, key, names))
        return func(*args, **kwargs)

    return wrapper


def moved_keyword_message(owner: str, key: str, home: str) -> str:
    """``"<owner>: '<key>' moved to <home>"``."""
    return f"{owner}: {key!r} moved to {home}"


def unknown_keyword_message(owner: str, key: str, valid: tuple[str, ...]) -> str:
    """``"<owner>: unknown keyword '<key>' (did you mean '<x>'?); valid: a, b, c"``."""
    close = difflib.get_close_matches(key, valid, n=1, cutoff=0.75)
    hint = f" (did you mean '{close[0]}'?)" if close else ""
    return f"{owner}: unknown keyword {key!r}{hint}; valid: {', '.join(valid)}"
