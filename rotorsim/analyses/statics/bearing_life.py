"""Bearing life and contact pressures at a static load and over a duty cycle.

:func:`bearing_life` rates one equilibrium (solved here, or given): ISO 281 ``L10`` from
``P = X F_r + Y F_a`` of the applied load, ISO/TS 16281 ``L10r`` and ``P_ref`` from the
internal load distribution (tilt and misalignment included, since the element loads are
the model's), ``a_ISO`` when its inputs are given, and the Hertz pressure of every contact.
:func:`duty_cycle_life` combines load cases by Palmgren-Miner on the ring material
(:mod:`rotorsim.elements.rolling.rating.load_history`). The formulas and their
conventions are in :mod:`rotorsim.elements.rolling.rating`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium
from rotorsim.analyses.statics.double_row_life import (
    combine_rows,
    double_row_of,
    double_row_rating,
    split_rows,
    take_sample,
    unit_equivalent_load,
)
from rotorsim.elements.rolling.rating.hertz_pressure import BallContactPressure
from rotorsim.elements.rolling.rating.iso16281 import ReferenceLife
from rotorsim.elements.rolling.rating.life_factor import (
    life_modification_factor,
    reliability_factor,
)
from rotorsim.elements.rolling.rating.load_history import (
    RingDamage,
    combine_histories,
    history_life,
    ring_damage,
)
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing, rated
from rotorsim.errors import ModelError
from rotorsim.results.bearing import BearingEquilibriumResult
from rotorsim.results.bearing_life import BearingLifeResult

FloatArray = Any


def bearing_life(bearing: Any, load: ArrayLike | None = None, *,
                 equilibrium: BearingEquilibriumResult | None = None,
                 options: RatingOptions | None = None, phi: float = 0.0) -> BearingLifeResult:
    """Lives (ISO 281, ISO/TS 16281) and contact pressures of a bearing under a load.

    Parameters
    ----------
    bearing : BallBearing, RollerBearing, DoubleRowBearing, ReversedBearing or RollingBearing
        A double-row bearing is rated row by row and the rows combined
        (:mod:`~rotorsim.analyses.statics.double_row_life`).
    load : array (5,), optional
        ``[Fx, Fy, Fz, Mx, My]`` on the inner ring [N, N m]; the equilibrium is solved
        (:func:`~rotorsim.analyses.statics.bearing_statics.bearing_equilibrium`).
    equilibrium : BearingEquilibriumResult, optional
        An equilibrium already solved for this bearing (instead of ``load``).
    options : RatingOptions, optional
        ``C`` from a catalogue or geometry, rotating ring, ``a_ISO`` inputs, shoulders.
    phi : float
        Shaft angle [rad] placing the elements (with ``load``).

    Returns
    -------
    BearingLifeResult

    Examples
    --------
    >>> import rotorsim as rs
    >>> b = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
    ...                                  ball_diameter=7.938e-3, f_i=0.52, f_o=0.53)
    >>> r = bearing_life(b, [2000.0, 0.0, 0.0, 0.0, 0.0])
    >>> round(r.L10), round(r.L10r / r.L10, 2)
    (344, 0.99)
    """
    t0 = time.perf_counter()
    opts = RatingOptions() if options is None else options
    double = double_row_of(bearing) is not None
    rating = None if double else rated(bearing, opts)  # refuses unknown models first
    if (load is None) == (equilibrium is None):
        raise ModelError("give exactly one of load and equilibrium", "bearing_life")
    if equilibrium is None:
        assert load is not None
        equilibrium = bearing_equilibrium(bearing.bearing if hasattr(bearing, "relative")
                                          else bearing, load, phi=phi)
    if rating is None:
        return _double_row_life(bearing, equilibrium, opts, t0)
    # the equilibrium's element loads and angles are the base model's (also reversed)
    life, pressures = rating.steady(
        equilibrium.displacement[None], equilibrium.element_angles[None],
        equilibrium.element_load[None], equilibrium.contact_angle[None])
    applied = np.asarray(equilibrium.load, dtype=float)
    P = _iso281_load(rating, applied)
    return life_result(rating, life, pressures, source="equilibrium", load=applied, P=P,
                       angles=equilibrium.element_angles,
                       loads=np.asarray(equilibrium.element_load, dtype=float),
                       stats={"wall_time": time.perf_counter() - t0})


def _double_row_life(bearing: Any, eq: BearingEquilibriumResult, opts: RatingOptions,
                     t0: float) -> BearingLifeResult:
    """:func:`bearing_life` of a double-row bearing: each row rated at its own ring
    displacement, the rows combined (:mod:`.double_row_life`)."""
    found = double_row_of(bearing)
    assert found is not None
    unit, factor = found
    rating = double_row_rating(unit, opts)
    own, psi = split_rows(unit, factor, eq.displacement, eq.element_angles)
    n = int(unit.row.n_elements)
    loads = np.asarray(eq.element_load, dtype=float).reshape(2, n)
    angles = np.asarray(eq.contact_angle, dtype=float).reshape(2, n)
    # both rows as two samples of the row model: one evaluation
    life, pressures = rating.row.steady(own[:, 0], psi[:, 0], loads, angles)
    rows = [life_result(rating.row, take_sample(life, k), take_sample(pressures, k),
                        source="equilibrium", load=np.full(5, np.nan), P=math.nan,
                        angles=psi[k, 0], loads=loads[k], stats={}) for k in range(2)]
    applied = np.asarray(eq.load, dtype=float)
    return combine_rows(rating, (rows[0], rows[1]), P=unit_equivalent_load(rating, applied),
                        load=applied, stats={"wall_time": time.perf_counter() - t0},
                        tag=getattr(bearing, "tag", "") or "")


def _iso281_load(rated: RatedBearing, load: FloatArray) -> float:
    """``P`` of ISO 281 from the radial and axial components of ``load`` (moments are not
    part of ISO 281's ``P``; NaN where no ``X, Y`` table applies)."""
    radial, axial = math.hypot(load[0], load[1]), abs(float(load[2]))
    try:
        x, y, e = rated.rating._factors(np.asarray(axial), "bearing_life")
    except ModelError:
        return math.nan
    above = axial > float(e) * radial
    return float(x) * radial + float(y) * axial if above else radial


def life_result(rated: RatedBearing, life: ReferenceLife, pressures: Any, *, source: str,
                load: FloatArray, P: float, angles: FloatArray, loads: FloatArray,
                stats: dict[str, float], options: dict[str, Any] | None = None
                ) -> BearingLifeResult:
    """:class:`BearingLifeResult` from a life (``S = 1``) and pressures (first sample)."""
    o, rating = rated.options, rated.rating
    a1 = reliability_factor(o.reliability)
    l10r, p_ref = float(life.L10r[0]), float(life.P_ref[0])
    l10 = float(rating.basic_life(P)) if math.isfinite(P) and P > 0 else math.nan
    a_iso_r = a_iso = 1.0
    if o.life_factor:
        a_iso_r, a_iso = _a_iso(rated, p_ref), _a_iso(rated, P)
    n = rated.base.n_elements
    nan2 = np.full((n, 2), np.nan)
    if isinstance(pressures, BallContactPressure):
        fields = {"max_pressure": pressures.max_pressure[0],
                  "semi_major": pressures.semi_major[0], "semi_minor": pressures.semi_minor[0],
                  "shoulder_margin": nan2 if pressures.shoulder_margin is None
                  else pressures.shoulder_margin[0],
                  "slice_pressure": np.zeros((0, 0, 2)), "slice_xi": np.zeros(0)}
    else:
        fields = {"max_pressure": pressures.max_pressure[0].max(axis=1),
                  "semi_major": nan2, "semi_minor": pressures.half_width[0].max(axis=1),
                  "shoulder_margin": nan2, "slice_pressure": pressures.max_pressure[0],
                  "slice_xi": pressures.xi}
    return BearingLifeResult(
        kind=rating.kind, source=source, C=rating.C,
        C0=math.nan if rating.C0 is None else rating.C0, rating_source=rating.source,
        load=load, P=P, L10=l10, L10r=l10r, P_ref=p_ref, ring_life=life.ring_life[0],
        equivalent_load=life.equivalent_load[0], reference_load=life.reference_load,
        a1=a1, a_iso=a_iso_r, Lnmr=a1 * a_iso_r * l10r, Lnm=a1 * a_iso * l10,
        element_angles=np.asarray(angles, dtype=float), element_load=loads,
        options={**_options_record(o), **(options or {})}, stats=stats,
        summary={"bearing": type(rated.base).__name__, "n_elements": n,
                 "tag": getattr(rated.base, "tag", "") or ""}, **fields)


def _a_iso(rated: RatedBearing, load: float) -> float:
    """ISO 281 ``a_ISO`` at the equivalent load ``load`` [N] (NaN without a load)."""
    o = rated.options
    if not (math.isfinite(load) and load > 0):
        return math.nan
    return float(life_modification_factor(rated.kind, float(o.viscosity_ratio or 0.0),
                                          float(o.contamination or 0.0),
                                          float(o.fatigue_load_limit or 0.0), load))


def _options_record(o: RatingOptions) -> dict[str, Any]:
    record = {k: getattr(o, k) for k in ("C", "C0", "bm", "rotating_ring", "n_laminae",
                                        "reliability", "viscosity_ratio", "contamination",
                                        "fatigue_load_limit", "n_cells")}
    record["shoulder_heights"] = None if o.shoulder_heights is None else list(
        o.shoulder_heights)
    return record


def steady_damage(rated: RatedBearing, delta: FloatArray, positions: int = 16
                  ) -> RingDamage:
    """Cell damage of one cage revolution at a fixed ring displacement ``delta`` (5,),
    with the ``rotating_ring`` of the options turning (elements at ``positions`` steps
    per pitch)."""
    z = rated.base.n_elements
    kappa = rated.geometric_cage_ratio
    inner = rated.options.rotating_ring == "inner"
    cage = kappa if inner else 1.0 - kappa
    phi = np.linspace(0.0, 2.0 * math.pi / cage, z * positions + 1)
    psi = rated.base.element_angles(0.0)[0] + cage * phi[:, None]
    u = rated.normalized(np.broadcast_to(delta, (phi.size, 5)), psi)
    rings = np.stack([phi, np.zeros_like(phi)] if inner else [np.zeros_like(phi), phi],
                     axis=1)
    return ring_damage(rated.reference, u, psi, rings, kappa, rated.options.n_cells)


def duty_cycle_life(bearing: Any, cases: Sequence[tuple[float, ArrayLike, float | None]],
                    *, basis: str = "revolutions", options: RatingOptions | None = None
                    ) -> BearingLifeResult:
    """Life under a load spectrum: ``cases = [(share, load, speed_rpm), ...]``.

    Each case's equilibrium is solved and one cage revolution of it is rated on the ring
    cells (:func:`steady_damage`); the cases combine by Palmgren-Miner with their shares
    of the revolutions (``basis="revolutions"``; ``speed_rpm`` may be None) or of the
    time (``basis="time"``: share x speed gives the revolutions). ISO 281's ``L10``
    uses ``P = (sum w_i P_i^p)^(1/p)`` over the revolution shares ``w_i``.

    Examples
    --------
    >>> import rotorsim as rs
    >>> b = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
    ...                                  ball_diameter=7.938e-3, f_i=0.52, f_o=0.53)
    >>> r = duty_cycle_life(b, [(0.5, [2000.0, 0, 0, 0, 0], None),
    ...                         (0.5, [2000.0, 0, 0, 0, 0], None)])
    >>> round(r.L10r / r.L10, 2)
    0.99
    """
    t0 = time.perf_counter()
    where = "duty_cycle_life"
    if basis not in ("revolutions", "time"):
        raise ModelError(f"unknown basis {basis!r}; valid: revolutions, time", where)
    if not cases:
        raise ModelError("no load cases", where)
    opts = RatingOptions() if options is None else options
    model = bearing.bearing if hasattr(bearing, "relative") else bearing
    found = double_row_of(bearing)
    shares, loads, equilibria = [], [], []
    for i, case in enumerate(cases):
        if len(case) != 3:
            raise ModelError(f"case {i}: expected (share, load, speed_rpm), got {case!r}",
                             where)
        share, load, speed = case
        if not (math.isfinite(share) and share >= 0):
            raise ModelError(f"case {i}: share must be >= 0, got {share!r}", where)
        if basis == "time":
            if speed is None or not (math.isfinite(speed) and speed > 0):
                raise ModelError(f"case {i}: basis='time' needs a positive speed [rpm]",
                                 where)
            share = share * speed
        eq = bearing_equilibrium(model, load)
        equilibria.append(eq)
        shares.append(share)
        loads.append(np.asarray(eq.load, dtype=float))
    w = np.asarray(shares) / np.sum(shares)
    record = {"basis": basis, "cases": len(cases)}
    if found is not None:
        unit, factor = found
        dr = double_row_rating(unit, opts)
        own = [split_rows(unit, factor, e.displacement, e.element_angles) for e in equilibria]
        n = int(unit.row.n_elements)
        last_loads = np.asarray(eq.element_load, dtype=float)
        rows = tuple(_cycle_result(dr.row, [o[0][k, 0] for o in own], shares,
                                   own[-1][0][k], own[-1][1][k],
                                   last_loads[k * n:(k + 1) * n], math.nan, record)
                     for k in range(2))
        p_values = np.array([unit_equivalent_load(dr, x) for x in loads])
        expo = dr.rating.exponent
        return combine_rows(dr, (rows[0], rows[1]),
                            P=float(np.sum(w * p_values ** expo) ** (1 / expo)),
                            load=np.full(5, np.nan),
                            stats={"wall_time": time.perf_counter() - t0},
                            tag=getattr(bearing, "tag", "") or "")
    rating = rated(bearing, opts)
    p_values = np.array([_iso281_load(rating, x) for x in loads])
    p_exp = rating.rating.exponent
    result = _cycle_result(rating, [e.displacement for e in equilibria], shares,
                           eq.displacement[None], eq.element_angles[None],
                           np.asarray(eq.element_load, dtype=float),
                           float(np.sum(w * p_values ** p_exp) ** (1 / p_exp)), record)
    return dataclasses.replace(result, stats={"wall_time": time.perf_counter() - t0})


def _cycle_result(rating: RatedBearing, displacements: list[FloatArray], shares: list[float],
                  last: FloatArray, last_angles: FloatArray, loads: FloatArray, P: float,
                  record: dict[str, Any]) -> BearingLifeResult:
    """Palmgren-Miner life of the steady cases at ring ``displacements`` (5,) of one row
    (:func:`steady_damage`), with the pressures and element ``loads`` of the last case at
    ``last`` (1, 5); ``P`` the ISO 281 load of the spectrum."""
    parts = [steady_damage(rating, d) for d in displacements]
    life = history_life(rating.reference, combine_histories(parts, shares))
    return life_result(rating, life, rating.pressures(last, last_angles), source="duty_cycle",
                       load=np.full(5, np.nan), P=P, angles=last_angles[0],
                       loads=loads, stats={}, options=record)
