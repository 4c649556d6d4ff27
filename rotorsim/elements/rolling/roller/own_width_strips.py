"""Slice loads of one roller at a given load by strips of each slice's own Hertz width.

A refinement of the 1-D slice model of seed 002 eq 2.29
(:mod:`~rotorsim.elements.rolling.roller.slice_influence`), whose strips all have the Hertz
half-width ``b`` of the roller's mean line load and whose displacement is read on the
centre line ``x = 0``. Here, for a roller carrying a given load ``Q`` with slice deflections
``d_k + s`` (``d_k`` the tilt and profile part, ``s`` the unknown approach):

* **own widths**: strip ``k`` has the Hertz half-width of its own line load,
  ``b_k = sqrt(4 (q_k K/L) R / (pi E*))`` (Johnson 1985 eq 4.45), per race; the widths are
  iterated to a fixed point (``b`` from the loads of the previous iterate);
* **strip averages**: the contact condition of slice ``i`` holds on average across its
  strip ``|x| <= b_i`` (uniform weight), not at ``x = 0``::

      sum_k C_ik(b_i, b_k) q_k >= d_i + s - sum_races b_i^2 / (6 R),   q >= 0,
      q.(C q - d - s + g) = 0,       sum_k q_k = Q,

  with ``C_ik`` the mean over ``|x| <= b_i`` at ``y_i`` of the displacement of a unit load
  spread uniformly on strip ``k`` (``2 b_k x L/K``; Love's rectangle,
  :func:`~rotorsim.elements.rolling.contact.influence.rectangle_influence`, Gauss-Legendre
  in ``x``) and ``b_i^2/(6R)`` the mean of the gap ``x^2/(2R)`` over the strip. With equal
  widths ``C`` is symmetric and Toeplitz; with own widths it is neither.

Measured against the 2-D half-space (:class:`~rotorsim.elements.rolling.roller.half_space.
HalfSpaceLineContact`, slices x strips) at 10 kN on a 20 mm roller (docs/validation.md case
35b): load centre of a tilted roller 1.2-2.1 % above the 2-D one for straight, Lundberg and
circular crowns at K = 20, 40, 80 (mean-width strips: 0-5 % below strip-averaged, as in
``model="influence"``, 4-9 % below on the centre line, as eq 2.29), slice loads within
2.2 % of the largest. Cost: ``K^2`` coefficients (times the Gauss points) per
fixed-point step instead of ``K`` once, so it is not the bearing's slice model; the force
model ``"influence"`` needs a compliance that does not depend on the loads (an energy).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from rotorsim.elements.rolling.contact.influence import (
    check_positive,
    rectangle_influence,
    solve_contact,
)
from rotorsim.errors import ConvergenceError, ModelError

FloatArray = NDArray[np.float64]

_GAUSS = np.polynomial.legendre.leggauss(8)  # 8 points: the centre load to 1e-4 of 32


def strip_average_compliance(y: FloatArray, slice_width: float, half_width: ArrayLike,
                             e_star: float, averaged: bool = True) -> FloatArray:
    """Compliance (K, K) [m/N]: ``C_ik`` the mean over ``|x| <= b_i`` (at ``y_i`` [m]) of
    the displacement of a unit load spread on strip ``k`` (half-width ``b_k``, length
    ``slice_width`` [m]); ``half_width`` (K,) or scalar [m] (module docstring).
    ``averaged=False``: read at ``x = 0`` instead (eq 2.29's centre line). A scalar
    ``half_width`` assumes equal slices at ``y`` (Toeplitz: one row is computed).

    Examples
    --------
    >>> c = strip_average_compliance(np.array([0.0, 1e-3]), 1e-3, 2e-4, 1.13e11)
    >>> bool(abs(c[0, 1] - c[1, 0]) < 1e-12 * c[0, 0]), bool(c[0, 0] > c[0, 1])
    (True, True)
    """
    y = np.asarray(y, dtype=float)
    points, weights = _GAUSS if averaged else (np.zeros(1), np.full(1, 2.0))
    if np.ndim(half_width) == 0:  # one width: Toeplitz in |i - k| (equal slices)
        a = float(np.asarray(half_width, dtype=float))
        d = rectangle_influence((points * a)[None, :], (y - y[0])[:, None], a,
                                0.5 * slice_width)
        row = 0.5 * (d @ weights) / (math.pi * e_star * 2.0 * a * slice_width)
        k = np.arange(y.size)
        return np.asarray(row[np.abs(k[:, None] - k[None, :])])
    b = np.broadcast_to(np.asarray(half_width, dtype=float), y.shape)
    x = points[None, :] * b[:, None]                         # (K, G) receiver points
    d = rectangle_influence(x[:, None, :], (y[:, None] - y[None, :])[:, :, None],
                            b[None, :, None], 0.5 * slice_width)
    mean = 0.5 * np.einsum("ikg,g->ik", d, weights)
    return np.asarray(mean / (math.pi * e_star * 2.0 * b[None, :] * slice_width))


def own_width_slice_loads(deflection: ArrayLike, load: float, length: float,
                          radii: tuple[float, ...], e_star: float, tol: float = 1e-10,
                          max_iter: int = 100, own_width: bool = True,
                          averaged: bool = True) -> tuple[FloatArray, int]:
    """Slice loads (K,) [N] of one roller carrying ``load`` [N] (module docstring).

    Parameters
    ----------
    deflection : array (K,)
        Tilt and profile part ``d_k`` of the slice deflections [m] (e.g.
        ``theta y_k - c(y_k)``); its constant part is irrelevant (the approach ``s`` is
        solved for).
    load : float
        Roller load ``Q`` [N].
    length : float
        Effective length ``L`` [m] (``K`` equal slices).
    radii : tuple of float
        Reduced radii of the race contacts in series [m].
    e_star : float
        Contact modulus ``E*`` [Pa].
    tol : float
        Fixed point of the widths: largest change below ``tol`` times the mean width.
    max_iter : int
        Fixed-point steps before :class:`~rotorsim.errors.ConvergenceError`.
    own_width, averaged : bool
        The two refinements, for comparison: ``own_width=False`` keeps every strip at the
        Hertz half-width of the mean line load ``Q/L`` (no iteration); ``averaged=False``
        reads the displacement at ``x = 0`` without the gap term (eq 2.29). Both ``False``
        is the load-controlled form of the fixed-width centre-line model.

    Returns
    -------
    (q, iterations) : (array (K,), int)

    Examples
    --------
    >>> q, it = own_width_slice_loads(np.zeros(20), 1e4, 0.02, (0.005,), 1.13e11)
    >>> round(float(q.sum()), 6), bool(q[0] > 1.2 * q[10])
    (10000.0, True)
    """
    where = "own_width_slice_loads"
    d = np.asarray(deflection, dtype=float)
    if d.ndim != 1 or d.size < 2 or not np.isfinite(d).all():
        raise ModelError("deflection must be a finite (K,) array, K >= 2 [m]", where)
    q_total = check_positive(load, "load", where)
    length = check_positive(length, "length", where)
    e_star = check_positive(e_star, "e_star", where)
    k = d.size
    w = length / k
    y = (-0.5 + (np.arange(k) + 0.5) / k) * length
    r = np.array([check_positive(x, "radius", where) for x in radii])
    mean = np.sqrt(4.0 * q_total / length * r / (math.pi * e_star))  # (races,)
    b = np.repeat(mean[:, None], k, axis=1)
    q = np.full(k, q_total / k)
    for it in range(1, max_iter + 1):
        c = sum(strip_average_compliance(y, w, b[j], e_star, averaged)
                for j in range(r.size))
        rhs = d - (b**2 / (6.0 * r[:, None])).sum(axis=0) if averaged else d
        q = _at_load(np.asarray(c), rhs, q_total)
        if not own_width:
            return q, it
        new = np.maximum(np.sqrt(4.0 * (q / w) * r[:, None] / (math.pi * e_star)),
                         0.05 * mean[:, None])  # unloaded slices: narrow strips
        change = float(np.max(np.abs(new - b) / mean[:, None]))
        b = new
        if change < tol:
            return q, it
    raise ConvergenceError(f"strip widths did not settle in {max_iter} steps "
                           f"(last change {change:.1e} of the mean width)", where)


def _at_load(c: FloatArray, rhs: FloatArray, load: float) -> FloatArray:
    """Non-negative loads of ``C q >= rhs + s`` at the approach ``s`` where they sum to
    ``load`` (the sum rises monotonically with ``s``)."""
    scale = float(np.abs(c).max())

    def excess(s: float) -> float:
        return float(solve_contact(c, rhs + s)[0].sum() - load)
    lo = float(-rhs.max())                      # nothing in contact at or below
    hi = lo + 2.0 * load * scale                # every slice at least the full load
    while excess(hi) < 0.0:
        hi += 2.0 * load * scale
    s = brentq(excess, lo, hi, xtol=1e-15 * max(abs(hi), scale * load), rtol=1e-15)
    q = solve_contact(c, rhs + s)[0]
    return np.asarray(q * (load / q.sum()))
