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
    where = "ring_damage"
    uu = np.asarray(u, dtype=float)
    uu = uu[:, :, None, :] if uu.ndim == 3 else uu  # (T, N, K, 2)
    p_arr = np.asarray(psi, dtype=float)
    rings = np.asarray(ring_angles, dtype=float)
    n_t, n_el, n_k = uu.shape[0], uu.shape[1], uu.shape[2]
    if p_arr.shape != (n_t, n_el) or rings.shape != (n_t, 2):
        raise ModelError(f"psi must be (T, N) = ({n_t}, {n_el}) and ring_angles (T, 2), got "
                         f"{p_arr.shape} and {rings.shape}", where)
    if n_t < 2:
        raise ModelError("a load history needs at least 2 samples", where)
    if not 0.0 < kappa < 1.0:
        raise ModelError(f"cage ratio {kappa!r} must be in (0, 1): the history life needs "
                         "rolling elements that orbit", where)
    p = ref.exponents[0]
    power = uu**p
    mid = 0.5 * (power[1:] + power[:-1])  # (T-1, N, K, 2) trapezoid in time
    out = np.empty((n_k, n_cells, 2))
    width = 2.0 * math.pi / n_cells
    per_rev = (ref.n_elements * (1.0 - kappa), ref.n_elements * kappa)
    for ring in range(2):
        rel = p_arr - rings[:, ring, None]  # (T, N) element angle on the ring
        start = np.minimum(rel[1:], rel[:-1]) / width  # arcs swept, in cells (T-1, N)
        stop = np.maximum(rel[1:], rel[:-1]) / width
        out[..., ring] = _swept_cells(start, stop, mid[..., ring], n_cells) / per_rev[ring]
    relative = np.abs(np.diff(rings[:, 0] - rings[:, 1])).sum() / (2.0 * math.pi)
    return RingDamage(out, float(relative))


def _swept_cells(start: FloatArray, stop: FloatArray, density: FloatArray, n_cells: int
                 ) -> FloatArray:
    """``sum density x (overlap of the arc [start, stop] with each cell)`` (K, M): arcs
    (T, N) in cell units on a periodic ring of ``n_cells``, ``density`` (T, N, K) uniform
    along each arc (the midpoint rule of each step)."""
    n_k = density.shape[-1]
    shift = np.floor(start / n_cells) * n_cells
    lo, hi = start - shift, stop - shift  # lo in [0, M)
    i_lo, i_hi = np.floor(lo).astype(np.int64), np.floor(hi).astype(np.int64)
    span = int(i_hi.max(initial=0)) + 2
    extended = span + (-span) % n_cells  # a multiple of M, folded back at the end
    lamina = extended * np.arange(n_k)
    d = density
    same = (i_lo == i_hi)[..., None]
    # partial first and last cells; full cells in between by a difference array
    first = np.where(same, (hi - lo)[..., None], (i_lo + 1 - lo)[..., None]) * d
    last = np.where(same, 0.0, (hi - i_hi)[..., None] * d)
    total = np.bincount((i_lo[..., None] + lamina).ravel(), first.ravel(),
                        minlength=n_k * extended)
    total += np.bincount((i_hi[..., None] + lamina).ravel(), last.ravel(),
                         minlength=n_k * extended)
    full = np.where(same, 0.0, d)
    steps = np.bincount((i_lo[..., None] + 1 + lamina).ravel(), full.ravel(),
                        minlength=n_k * extended + 1)[:n_k * extended]
    steps -= np.bincount((i_hi[..., None] + lamina).ravel(), full.ravel(),
                         minlength=n_k * extended + 1)[:n_k * extended]
    runs = np.cumsum(steps.reshape(n_k, extended), axis=1)
    cells = total.reshape(n_k, extended) + runs
    folded = cells.reshape(n_k, extended // n_cells, n_cells).sum(axis=1)
    return np.asarray(np.maximum(folded, 0.0))  # round-off of the running sums


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
