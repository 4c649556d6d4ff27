"""Standard figures of every result type; matplotlib is imported only here, lazily.

``plot(result, ax=None, **options)`` dispatches on the result type and returns the
matplotlib ``Figure``.
"""

from __future__ import annotations

from typing import Any


def plot(result: Any, ax: Any = None, **options: Any) -> Any:
    """Draw the standard figure of ``result`` and return the matplotlib Figure.

    Parameters
    ----------
    result : ModalResult, CampbellResult, CriticalSpeedMapResult, FrequencyResponseResult,
        StaticResult, TransientResult, Spectrum, Waterfall, OrderTrack or Rotor
        The result to draw (a Rotor gives its layout drawing; a TransientResult its time
        history, orbit, spectrum and bearing loads, see
        :mod:`rotorsim.plotting.transient_figures`).
    ax : matplotlib Axes, optional
        Axes to draw into (single-panel figures only); a new figure otherwise.
    **options
        Passed to the figure function (e.g. ``mode=0`` for a mode shape,
        ``node=2, dof="uy"`` for a Bode plot, ``units="rpm"``).
    """
    from rotorsim.plotting import figures

    name = type(result).__name__
    drawer = figures.DRAWERS.get(name)
    if drawer is None:
        raise TypeError(f"no standard figure for {name}; known: {sorted(figures.DRAWERS)}")
    return drawer(result, ax=ax, **options)
