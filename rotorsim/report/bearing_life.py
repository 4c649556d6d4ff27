"""Rolling-bearing lives in the report: at the static linearisation point
(:func:`rotorsim.bearing_life`), over the second half of each transient
(:func:`rotorsim.transient_life`) and along the last point of each periodic branch
(:func:`rotorsim.periodic_life`), each with the rating options of the model file
(``[rolling_bearings.rating]``). Every life is stored in ``report.h5`` under its own group,
named in the page beside its table."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rotorsim.report import page

LIFE_HEADER = ("bearing", "source", "C [kN]", "P [N]", "L10 [Mrev]", "L10r [Mrev]",
               "P_ref [N]", "Lnmr [Mrev]", "max p [MPa]", "HDF5 group")


def life_row(life: Any, tag: str, key: str) -> tuple[str, ...]:
    """One table row of a :class:`~rotorsim.results.bearing_life.BearingLifeResult`: the
    numbers as :func:`fmt` writes them (the test reads them back against the HDF5)."""
    return (tag, life.source, fmt(life.C / 1e3), fmt(life.P), fmt(life.L10), fmt(life.L10r),
            fmt(life.P_ref), fmt(life.Lnmr), fmt(life.peak_pressure / 1e6),
            f"/results/{key}")


def fmt(value: float) -> str:
    """A number with 4 significant digits; ``-`` for an undefined one (no load)."""
    import math

    return f"{value:.4g}" if math.isfinite(value) else "-"


def static_lives(model: Any, linear: Any, results: dict[str, Any]) -> str:
    """Table of the lives at the linearisation point of every rolling bearing."""
    from rotorsim.analyses.statics.bearing_life import bearing_life

    def rate(i: int) -> Any:
        return bearing_life(model.rolling_bearings[i], equilibrium=linear.equilibria[i],
                            options=_rating(model, i))

    return _table(model, "life at the static load (ISO 281, ISO/TS 16281)", "life",
                  rate, results)


def history_lives(model: Any, name: str, result: Any, results: dict[str, Any]) -> str:
    """Lives of every rolling bearing along a transient (second half of the run) or the last
    point of a periodic branch over speed; empty for other results (a branch over a model
    parameter changes the bearings themselves, so the model's elements do not rate it)."""
    kind = model.analyses[name].type
    if not model.rolling_bearings or kind not in ("transient", "periodic"):
        return ""
    if kind == "transient":
        from rotorsim.analyses.transient.bearing_life import transient_life

        t_min = 0.5 * float(result.t[-1]) if len(result.t) else None
        title = f"life over the transient from t = {fmt(t_min or 0.0)} s (Palmgren-Miner)"

        def rate(i: int) -> Any:
            return transient_life(result, model.rolling_bearings[i],
                                  options=_rating(model, i), t_min=t_min)
    else:
        from rotorsim.analyses.periodic.bearing_life import periodic_life

        last = len(result) - 1
        along = "torus" if hasattr(result, "vc_order") else "orbit"   # quasi-periodic or not
        title = f"life along the {along} of branch point {last} (Palmgren-Miner)"

        def rate(i: int) -> Any:
            return periodic_life(result, model.rolling_bearings[i], last,
                                 options=_rating(model, i))
    return _table(model, title, f"{name}_life", rate, results)


def _rating(model: Any, i: int) -> Any:
    return model.ratings[i] if model.ratings else None


def _table(model: Any, title: str, prefix: str, rate: Callable[[int], Any],
           results: dict[str, Any]) -> str:
    """Rate every bearing with ``rate(i)``; a bearing that cannot be rated gets a note."""
    from rotorsim.errors import RotorsimError

    rows, notes = [], []
    for i, rolling in enumerate(model.rolling_bearings):
        tag = rolling.tag or str(i)
        key = f"{prefix}_{tag}"
        try:
            life = rate(i)
        except RotorsimError as err:
            notes.append(page.paragraph(f"bearing {tag}: not rated ({err})", "warn"))
            continue
        results[key] = life
        rows.append(life_row(life, tag, key))
    table = page.table(rows, LIFE_HEADER) if rows else ""
    return page.heading(3, title) + table + "".join(notes)
