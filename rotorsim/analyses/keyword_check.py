"""Unknown keyword arguments of the public verbs: a ``TypeError`` that lists the valid ones.

Python's own message (``modal() got an unexpected keyword argument 'num_mode'``) names the
culprit but not the alternatives; :func:`checked_keywords` adds them, with the closest match.
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


def checked_keywords(func: Callable[P, R]) -> Callable[P, R]:
    """Wrap ``func`` so that an unknown keyword raises a one-line ``TypeError`` listing the
    valid keywords (and the closest one); everything else is passed through unchanged.

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
    """
    params = inspect.signature(func).parameters
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()):
        return func
    names = tuple(name for name, p in params.items() if p.kind in _NAMED)

    @functools.wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        for key in kwargs:
            if key not in names:
                raise TypeError(unknown_keyword_message(func.__name__, key, names))
        return func(*args, **kwargs)

    return wrapper


def unknown_keyword_message(owner: str, key: str, valid: tuple[str, ...]) -> str:
    """``"<owner>: unknown keyword '<key>' (did you mean '<x>'?); valid: a, b, c"``."""
    close = difflib.get_close_matches(key, valid, n=1, cutoff=0.75)
    hint = f" (did you mean '{close[0]}'?)" if close else ""
    return f"{owner}: unknown keyword {key!r}{hint}; valid: {', '.join(valid)}"
