"""Progress bars of long runs: one look for every analysis and solver.

A bar is a tqdm bar (``tqdm.auto``: a widget in notebooks, text on stderr elsewhere),
imported only when one is shown. Progress is cosmetic: without tqdm the run goes on without
a bar. Any layer may use this module; it imports nothing of rotorsim.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, TypeVar

T = TypeVar("T")


def progress_bar(enabled: bool, *, total: float, desc: str, unit: str, initial: float = 0,
                 bar_format: str | None = None) -> Any | None:
    """A bar advanced by hand (``bar.update(n)``, ``bar.close()``), or None.

    Parameters
    ----------
    enabled : bool
        False gives None (no bar).
    total : float
        Amount of work (points, steps, or simulated time in ``unit``).
    desc, unit : str
        Label in front of the bar and unit of ``total`` (``"pt"``, ``"s"``, ...).
    initial : float
        Work already done (a resumed run).
    bar_format : str, optional
        tqdm's layout string (default: tqdm's own).

    Returns
    -------
    tqdm or None
        None when not ``enabled`` or when tqdm is not installed.

    Examples
    --------
    >>> progress_bar(False, total=10, desc="sweep", unit="pt") is None
    True
    """
    tqdm = _tqdm() if enabled else None
    if tqdm is None:
        return None
    options: dict[str, Any] = {"bar_format": bar_format} if bar_format is not None else {}
    return tqdm(total=total, initial=initial, desc=desc, unit=unit, **options)


def with_progress(items: Iterable[T], enabled: bool, *, desc: str, unit: str) -> Iterable[T]:
    """``items``, wrapped in a bar that advances by one per item when ``enabled`` (and
    tqdm is installed).

    Examples
    --------
    >>> list(with_progress(range(3), False, desc="campbell", unit="speed"))
    [0, 1, 2]
    """
    tqdm = _tqdm() if enabled else None
    if tqdm is None:
        return items
    bar: Iterable[T] = tqdm(items, desc=desc, unit=unit)
    return bar


def _tqdm() -> Any | None:
    try:
        from tqdm.auto import tqdm
    except ImportError:  # progress is cosmetic: run without the bar
        return None
    return tqdm
