"""Critical-speed map: undamped critical speeds against support stiffness, with the
speed-dependent stiffness curves of the real bearings overlaid and intersected."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import NEGATIVE_SPEED_HINT, check_num_modes
from rotorsim.analyses.linear.critical_speeds import solve_critical_speeds
from rotorsim.analyses.system_input import require_linear
from rotorsim.assembly.system import assemble
from rotorsim.elements.base import as_float_array
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.rotor import Rotor
from rotorsim.results.critical_speeds import CriticalSpeedMapResult, MapIntersections
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]


@checked_keywords
@one_blas_thread()
def critical_speed_map(
    rotor: Rotor,
    stiffness_range: tuple[float, float] = (1e5, 1e10),
    *,
    num_points: int = 30,
    stiffness: ArrayLike | None = None,
    num_modes: int = 4,
    harmonic: float = 1,
    bearings: Sequence[int] | None = None,
    gyroscopic: bool = True,
    speeds: ArrayLike | None = None,
    on_failure: Literal["raise", "record"] = "raise",
) -> CriticalSpeedMapResult:
    """Undamped critical speeds against the lateral stiffness of the supports.

    At every stiffness ``k_s`` the mapped bearings get ``kxx = kyy = k_s``, no
    cross-coupling, damping or added mass (their ``kzz`` and ``krr`` are kept at their
    zero-speed values); the ``num_modes`` lowest forward critical speeds follow from
    :func:`critical_speeds`. With ``gyroscopic=False`` they are the lateral natural
    frequencies of the rotor at rest instead (one per x/y pair), divided by ``harmonic``.

    If mapped bearings of ``rotor`` are tabulated against speed, their ``kxx(W)`` and
    ``kyy(W)`` are sampled over ``speeds`` and intersected with every critical-speed
    curve: each intersection estimates a critical speed on the real bearings. The curves
    are interpolated by a cubic spline of ``log W`` against ``log k_s``; crossings are
    bracketed on ``speeds`` and refined by Brent's method.

    Parameters
    ----------
    rotor : Rotor
        The model.
    stiffness_range : (float, float)
        Lowest and highest support stiffness [N/m] (not powers of ten), swept with
        ``num_points`` logarithmically spaced values.
    num_points : int
        Number of stiffness values (>= 2) when ``stiffness`` is not given.
    stiffness : array_like (P,), optional
        Explicit support stiffness values [N/m], positive and increasing; overrides
        ``stiffness_range``.
    num_modes : int
        Number of critical-speed curves.
    harmonic : float
        Excitation order (> 0).
    bearings : sequence of int, optional
        Indices into ``rotor.bearing_elements`` of the bearings to vary; default all.
    gyroscopic : bool
        Include the gyroscopic coupling (forward synchronous critical speeds).
    speeds : array_like (Q,), optional
        Spin speeds [rad/s] for the bearing curves, >= 0; default 201 points from 0 to
        1.5 x the highest critical speed found.
    on_failure : {"raise", "record"}
        Raise on a failed point, or record its status and leave NaN.

    Returns
    -------
    CriticalSpeedMapResult

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e6),
    ...                              rs.BearingElement(n=4, kxx=1e6)])
    >>> res = critical_speed_map(rotor, num_points=5, num_modes=2)
    >>> res.critical_speeds.shape, bool(np.all(np.diff(res.curve(0)) > 0))
    ((5, 2), True)
    """
    where = "critical_speed_map"
    if not isinstance(rotor, Rotor):
        raise ModelError(f"needs a Rotor (its bearings are replaced), got {type(rotor).__name__}",
                         where)
    require_linear(rotor)
    if on_failure not in ("raise", "record"):
        raise ModelError(f"on_failure must be 'raise' or 'record', got {on_failure!r}", where)
    check_num_modes(num_modes, where)
    given_speeds = _check_speeds(speeds)
    grid = _stiffness_grid(stiffness, num_points, stiffness_range)
    mapped = _bearing_indices(rotor, bearings)
    stats = Stats()
    table = np.full((grid.size, num_modes), np.nan)
    status = np.full(grid.size, int(Status.OK), dtype=np.int64)
    for p, k_s in enumerate(grid):
        new = [_support(b, k_s) if i in mapped else b
               for i, b in enumerate(rotor.bearing_elements)]
        try:
            res = solve_critical_speeds(assemble(rotor.with_bearings(new)), harmonic, num_modes,
                                   "forward", gyroscopic, None, None, stats)
        except ConvergenceError:
            if on_failure == "raise":
                raise
            status[p] = int(Status.NOT_CONVERGED)
            continue
        table[p, : len(res)] = res.speed
    curves = [i for i in mapped if rotor.bearing_elements[i].speed_dependent]
    sample = _curve_speeds(given_speeds, table, curves, rotor)
    kxx, kyy = (np.array([rotor.bearing_elements[i].coefficient(c, sample) for i in curves])
                .reshape(len(curves), sample.size) for c in ("kxx", "kyy"))
    crossings = _intersections(rotor, grid, table, curves, sample)
    return CriticalSpeedMapResult(
        stiffness=grid, critical_speeds=table, harmonic=float(harmonic),
        gyroscopic=gyroscopic, bearings=np.array(mapped, dtype=np.int64), speeds=sample,
        curve_bearings=np.array(curves, dtype=np.int64), bearing_kxx=kxx, bearing_kyy=kyy,
        intersections=crossings, status=status,
        options={"num_modes": num_modes, "harmonic": harmonic, "gyroscopic": gyroscopic,
                 "on_failure": on_failure, "interpolation": "cubic spline, log-log"},
        stats=stats.finish(), summary=rotor.summary(),
    )


def _stiffness_grid(stiffness: ArrayLike | None, num_points: int,
                    stiffness_range: tuple[float, float]) -> FloatArray:
    if stiffness is None:
        bounds = as_float_array(stiffness_range, "stiffness_range", "critical_speed_map")
        lo, hi = (float(v) for v in bounds) if bounds.shape == (2,) else (np.nan, np.nan)
        if not (np.isfinite(hi) and 0 < lo < hi) or not isinstance(num_points, int | np.integer) \
                or num_points < 2:
            raise ModelError("need 0 < stiffness_range[0] < stiffness_range[1] and an integer"
                             f" num_points >= 2; got {stiffness_range}, {num_points!r}",
                             "critical_speed_map")
        return np.geomspace(lo, hi, num_points)
    grid = np.atleast_1d(as_float_array(stiffness, "stiffness", "critical_speed_map"))
    if grid.ndim != 1 or grid.size == 0 or not np.all(np.isfinite(grid) & (grid > 0)) \
            or np.any(np.diff(grid) <= 0):
        raise ModelError("stiffness must be a 1-D array of positive, increasing values",
                         "critical_speed_map")
    return grid


def _bearing_indices(rotor: Rotor, bearings: Sequence[int] | None) -> list[int]:
    n = len(rotor.bearing_elements)
    if n == 0:
        raise ModelError("the rotor has no bearings to vary", "critical_speed_map")
    chosen = list(range(n)) if bearings is None else [int(i) for i in bearings]
    bad = [i for i in chosen if not 0 <= i < n]
    if bad or not chosen:
        raise ModelError(f"bearing indices must be in 0..{n - 1}, got {bearings}",
                         "critical_speed_map")
    return sorted(set(chosen))


def _support(bearing: BearingElement, stiffness: float) -> BearingElement:
    """Isotropic undamped support of lateral stiffness ``stiffness`` at ``bearing``'s place;
    its axial and tilt stiffness (``kzz``, ``krr`` and the z/rx/ry part of a full matrix,
    e.g. of a linearised rolling bearing) is kept."""
    full = None
    if bearing.stiffness_matrix is not None:
        full = np.array(bearing.stiffness_matrix, dtype=float)
        full[:2, :] = 0.0
        full[:, :2] = 0.0
    return BearingElement(n=bearing.n, n_link=bearing.n_link, kxx=stiffness, kyy=stiffness,
                          kzz=float(bearing.coefficient("kzz", 0.0)),
                          krr=float(bearing.coefficient("krr", 0.0)),
                          ktt=float(bearing.coefficient("ktt", 0.0)), stiffness_matrix=full,
                          tag=bearing.tag)


def _check_speeds(speeds: ArrayLike | None) -> FloatArray | None:
    """The given curve speeds [rad/s] as an array, checked before any solve."""
    if speeds is None:
        return None
    where = "critical_speed_map"
    try:
        sample = np.atleast_1d(np.asarray(speeds, dtype=float))
    except (TypeError, ValueError) as exc:
        raise ModelError(f"speeds must be numbers [rad/s], got {speeds!r}", where) from exc
    if sample.ndim != 1 or sample.size < 2 or not np.all(np.isfinite(sample)) \
            or np.any(np.diff(sample) <= 0):
        raise ModelError("speeds must be finite, increasing, at least 2 values", where)
    if sample[0] < 0:
        raise ModelError(f"speeds must be >= 0 rad/s, got {sample[0]!r}: "
                         f"{NEGATIVE_SPEED_HINT}", where)
    return sample


def _curve_speeds(sample: FloatArray | None, table: FloatArray, curves: list[int],
                  rotor: Rotor) -> FloatArray:
    if not curves:
        return np.zeros(0)
    if sample is not None:
        return sample
    top = np.nanmax(table) if np.any(np.isfinite(table)) else max(
        float(rotor.bearing_elements[i].frequency[-1]) for i in curves  # type: ignore[index]
    )
    return np.linspace(0.0, 1.5 * top, 201)


def _intersections(rotor: Rotor, grid: FloatArray, table: FloatArray, curves: list[int],
                   sample: FloatArray) -> MapIntersections:
    from scipy.interpolate import CubicSpline  # slow to import: on first use
    from scipy.optimize import brentq

    rows: list[tuple[int, str, int, float, float]] = []
    for j in range(table.shape[1]):
        good = np.isfinite(table[:, j])
        if good.sum() < 2:
            continue
        x, y = np.log(grid[good]), np.log(table[good, j])
        curve = CubicSpline(x, y) if x.size >= 4 else lambda t, x=x, y=y: np.interp(t, x, y)
        for b, name in ((b, name) for b in curves for name in ("kxx", "kyy")):
            stiff = rotor.bearing_elements[b].coefficient

            def gap(w: float, stiff=stiff, name=name, curve=curve, x=x) -> float:
                lk = np.clip(np.log(max(float(stiff(name, w)), 1e-300)), x[0], x[-1])
                return float(w - np.exp(curve(lk)))

            lk = np.log(np.maximum(stiff(name, sample), 1e-300))
            h = np.where((lk >= x[0]) & (lk <= x[-1]),
                         sample - np.exp(curve(np.clip(lk, x[0], x[-1]))), np.nan)
            ok = np.isfinite(h)
            for i in np.flatnonzero(ok[:-1] & ok[1:] & (h[:-1] * h[1:] <= 0)):
                if h[i + 1] == 0 and i + 2 < h.size:
                    continue  # counted as the left end of the next interval
                w = brentq(gap, sample[i], sample[i + 1], xtol=1e-12 * sample[-1])
                rows.append((b, name, j, float(stiff(name, w)), float(w)))
    return MapIntersections.from_rows(rows)
