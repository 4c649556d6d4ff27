"""``L10r`` over a sampled load history: Palmgren-Miner on the material points of each ring.

A point of a raceway is over-rolled whenever a rolling element passes it. Each ring is cut
into ``M`` angular cells (in the ring's own frame: the element angle ``psi_j(t)`` minus the
ring angle, ``phi(t)`` for the ring turning with the shaft, 0 for a fixed ring) and, for
rollers, into the ``K`` laminae. Along the history every element adds to the cell it
crosses the damage ``u^p`` (``u = Q / Q_c``, :mod:`.iso16281`) times the fraction of the
cell it sweeps (Palmgren-Miner): a cell's sum ``D_b`` is its ``sum u^p`` over its
over-rollings. One over-rolling of a point counts ``1 / (Z kappa_r)`` revolution, with
``kappa_r = kappa`` for the outer and ``1 - kappa`` for the inner ring (over-rollings of a
point per revolution of the inner ring relative to the outer, cage ratio ``kappa``). Then,
as in :mod:`.iso16281` with the mean over the ring's cells in place of the mean over the
elements (Weibull weakest link over the ring's material)::

    F_ring^e = sum_k mean_b (D_bk / (Z kappa_r))^e,    F^e = F_i^e + F_e^e,
    L10r = R / F   [million revolutions],

``R`` the revolutions of the inner ring relative to the outer in the history. For a steady
load this is exactly the rotating-ring / stationary-ring rule of :mod:`.iso16281` (a fixed
load zone on the fixed ring, every load on each point of the turning one), and a load that
turns with the shaft (unbalance) makes the inner ring the "stationary" one, by itself.

A duty cycle (load spectrum) is the same sum with ``D_bk`` of each case weighted by its
share of the revolutions (:func:`combine_histories`).

The time step must resolve the passage of the elements (a sweep per step below one cell,
``2 pi / M``; otherwise the damage lands on fewer cells than it should).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.rating.iso16281 import ReferenceLife, ReferenceRating
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class RingDamage:
    """Over-rolling damage of the cells of both rings over one history.

    Attributes
    ----------
    damage : array (K, M, 2)
        ``D_bk / (Z kappa_r)``: ``sum u^p`` per cell in revolution units (laminae ``K``,
        cells ``M``, ring inner/outer).
    revolutions : float
        Revolutions ``R`` of the inner ring relative to the outer in the history.
    """

    damage: FloatArray
    revolutions: float

    def scaled(self, factor: float) -> RingDamage:
        return RingDamage(self.damage * factor, self.revolutions * factor)

    def plus(self, other: RingDamage) -> RingDamage:
        """The damage of this history followed by ``other``."""
        return RingDamage(self.damage + other.damage, self.revolutions + other.revolutions)


def ring_damage(ref: ReferenceRating, u: ArrayLike, psi: ArrayLike, ring_angles: ArrayLike,
                kappa: float, n_cells: int = 360) -> RingDamage:
    """Cell damage of a history (module docstring).

    Parameters
    ----------
    ref : ReferenceRating
    u : array (T, N, 2) or (T, Z, K, 2)
        ``Q / Q_c`` of each contact at each sample (:meth:`ReferenceRating.normalized`).
    psi : array (T, N)
        Element angles [rad], unwrapped (continuous in time).
    ring_angles : array (T, 2)
        Angles of the inner and outer ring [rad] (unwrapped).
    kappa : float
        Cage ratio of the geometry (``(1 - D cos a / d_m) / 2``), > 0.
    n_cells : int
        Cells ``M`` per ring.
    """
    uu = np.asarray(u, dtype=float)
    uu = uu[:, :, None, :] if uu.ndim == 3 else uu  # (T, N, K, 2)
    p = ref.exponents[0]
    return ring_damage_density(ref, uu**p, psi, ring_angles, kappa, n_cells)


def ring_damage_density(ref: ReferenceRating, density: ArrayLike, psi: ArrayLike,
                        ring_angles: ArrayLike, kappa: float, n_cells: int = 360,
                        ring_scale: tuple[float, float] = (1.0, 1.0),
                        score: ArrayLike | None = None) -> RingDamage:
    """:func:`ring_damage` from the damage density ``u^p``: (T, N, K, 2) per ring, or
    (T, N, K) shared by both rings times ``ring_scale`` (rollers: the same lamina loads
    on both races, whose ``u^p`` differ by ``(q_ci / q_ce)^p`` only). ``score`` (T, N),
    optional: zero exactly where an element's density is zero (e.g. its summed density),
    so that only the steps of loaded elements are spread on the cells."""
    where = "ring_damage"
    dens = np.asarray(density, dtype=float)
    p_arr = np.asarray(psi, dtype=float)
    rings = np.asarray(ring_angles, dtype=float)
    n_t, n_el, n_k = dens.shape[0], dens.shape[1], dens.shape[2]
    if p_arr.shape != (n_t, n_el) or rings.shape != (n_t, 2):
        raise ModelError(f"psi must be (T, N) = ({n_t}, {n_el}) and ring_angles (T, 2), got "
                         f"{p_arr.shape} and {rings.shape}", where)
    if n_t < 2:
        raise ModelError("a load history needs at least 2 samples", where)
    if not 0.0 < kappa < 1.0:
        raise ModelError(f"cage ratio {kappa!r} must be in (0, 1): the history life needs "
                         "rolling elements that orbit", where)
    mid = dens[1:] + dens[:-1]  # twice the trapezoid mean in time (T-1, N, K[, 2])
    active: NDArray[np.intp] | None = None
    if score is not None:
        sc = np.asarray(score, dtype=float)
        active = np.flatnonzero((sc[1:] + sc[:-1]).ravel() > 0.0)  # loaded steps
    out = np.empty((n_k, n_cells, 2))
    width = 2.0 * math.pi / n_cells
    per_rev = (ref.n_elements * (1.0 - kappa), ref.n_elements * kappa)
    for ring in range(2):
        rel = p_arr - rings[:, ring, None]  # (T, N) element angle on the ring
        start = np.minimum(rel[1:], rel[:-1]) / width  # arcs swept, in cells (T-1, N)
        stop = np.maximum(rel[1:], rel[:-1]) / width
        ring_mid = mid if mid.ndim == 3 else mid[..., ring]
        out[..., ring] = (_swept_cells(start, stop, ring_mid, n_cells, active)
                          * (0.5 * ring_scale[ring] / per_rev[ring]))
    relative = np.abs(np.diff(rings[:, 0] - rings[:, 1])).sum() / (2.0 * math.pi)
    return RingDamage(out, float(relative))


def _swept_cells(start: FloatArray, stop: FloatArray, density: FloatArray, n_cells: int,
                 active: NDArray[np.intp] | None = None) -> FloatArray:
    """``sum density x (overlap of the arc [start, stop] with each cell)`` (K, M): arcs
    (T, N) in cell units on a periodic ring of ``n_cells``, ``density`` (T, N, K) uniform
    along each arc (the midpoint rule of each step).

    The overlaps form a sparse (M, T N) matrix, one entry per cell an arc touches (two or
    one for a step shorter than a cell), applied to the (T N, K) densities at once; only
    the arcs ``active`` (flat indices into (T, N); default: those with a density) enter.
    """
    from scipy.sparse import csr_matrix

    values = density.reshape(start.size, -1)
    if active is None:
        active = np.flatnonzero(values.any(axis=1))  # arcs with damage: the loaded zone
    if active.size == 0:
        return np.zeros((values.shape[1], n_cells))
    lo, hi, values = start.ravel()[active], stop.ravel()[active], values[active]
    i_lo, i_hi = np.floor(lo).astype(np.int64), np.floor(hi).astype(np.int64)
    count = i_hi - i_lo + 1  # cells each arc touches
    arc = np.repeat(np.arange(lo.size), count)
    first = np.cumsum(count) - count
    offset = np.arange(arc.size) - np.repeat(first, count)
    cell = np.repeat(i_lo, count) + offset
    # overlap of [lo, hi] with [cell, cell + 1]
    overlap = np.minimum(np.repeat(hi, count), cell + 1.0) - np.maximum(np.repeat(lo, count),
                                                                        cell)
    matrix = csr_matrix((np.maximum(overlap, 0.0), (np.mod(cell, n_cells), arc)),
                        shape=(n_cells, lo.size))
    cells = matrix @ values  # (M, K)
    return np.asarray(cells.T)


def combine_histories(parts: list[RingDamage], shares: ArrayLike) -> RingDamage:
    """Duty cycle: the damage of each case scaled to its share of the revolutions.

    ``shares`` (n,) > 0 are fractions of the revolutions (normalised to sum 1); case ``i``
    contributes ``shares[i] / R_i`` times its damage per revolution.
    """
    w = np.asarray(shares, dtype=float)
    if len(parts) != w.size or w.size == 0:
        raise ModelError(f"{len(parts)} load cases but {w.size} shares", "combine_histories")
    if not np.isfinite(w).all() or (w < 0).any() or w.sum() <= 0:
        raise ModelError("shares must be >= 0 with a positive sum", "combine_histories")
    w = w / w.sum()
    damage = sum((share / part.revolutions) * part.damage
                 for share, part in zip(w, parts, strict=True) if share > 0)
    return RingDamage(np.asarray(damage), 1.0)


def history_life(ref: ReferenceRating, damage: RingDamage) -> ReferenceLife:
    """:class:`ReferenceLife` (``S = 1``) of the cell damage of a history.

    Examples
    --------
    >>> from rotorsim.elements.rolling.rating.iso281 import BearingRating
    >>> ref = ReferenceRating(BearingRating("ball", C=1e4), 8, 8e-3, 40e-3)
    >>> d = RingDamage(np.full((1, 36, 2), 1e-3), 1.0)
    >>> round(float(history_life(ref, d).L10r[0]), 1)   # 2^(-9/10) / 1e-3
    535.9
    """
    e = ref.exponents[1]
    if damage.revolutions <= 0.0:
        raise ModelError("the history has no relative rotation of the rings: no life",
                         "history_life")
    per_rev = damage.damage / damage.revolutions  # (K, M, 2)
    lamina = np.mean(per_rev**e, axis=1) ** (1.0 / e)  # (K, 2): per-lamina 1/L
    return ref._combine(lamina[None])


def history_from_arrays(ref: ReferenceRating, loads: Any, psi: ArrayLike,
                        ring_angles: ArrayLike, kappa: float, n_cells: int = 360
                        ) -> ReferenceLife:
    """``L10r`` of a history from element (or lamina) loads (T, ...) and angles (T, N)."""
    loads_t = loads if isinstance(loads, tuple) else (loads,)
    u = ref.normalized(*loads_t)
    return history_life(ref, ring_damage(ref, u, psi, ring_angles, kappa, n_cells))
