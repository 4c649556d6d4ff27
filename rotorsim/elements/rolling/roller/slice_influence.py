"""Slice loads of rollers with half-space interaction between the slices (edge effect).

Independent slices (seed 002 eqs 2.7, 2.12) give slice ``k`` of a roller the load
``q_k = (Kn/K) max(delta_k, 0)^n``: a straight roller with a uniform deflection carries a
uniform load up to its ends. On an elastic half-space the slices interact, and the
pressure rises at the roller ends (edge stress). This module gives the slice loads of the
rollers of a bearing from the half-space influence coefficients (seed 002 section 2.3.3,
"simplified model" eq 2.29: each slice a uniform pressure strip of the Hertz half-width
``b``, the displacement read on the centre line ``x = 0``)::

    C_ik = D(0, y_i - y_k; b, L/(2K)) / (pi E* 2 b L/K)     [m/N],  both races summed,

with ``D`` of :func:`~rotorsim.elements.rolling.contact.influence.rectangle_influence`
and ``b`` the Hertz half-width of each race at the roller's mean line load. The slice
loads ``q^hs >= 0`` solve ``C q >= delta``, ``q.(C q - delta) = 0``
(:func:`~rotorsim.elements.rolling.contact.influence.solve_contact`, batched over all
loaded rollers), and are then **normalised** to the roller load of the bearing's own
load-deflection law (seed 002 section 2.3.2: "load normalization", ``q_correct =
q_predict / sum q_predict Q``)::

    q_k = q^hs_k  Q_j / sum_k q^hs_k,      Q_j = (Kn/K) sum_k max(delta_k, 0)^n,

so that the roller loads, and the bearing's stiffness calibrated by ``Kn`` (Palmgren, ISO
10/9), are kept and only their distribution along the roller (the edge peak, the moment)
comes from the half-space.

Cost: per loaded roller, ``K`` influence coefficients per race (the matrix is Toeplitz)
and a few dense ``K x K`` solves, batched over the rollers.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.rolling.contact.influence import rectangle_influence, solve_contact

FloatArray = NDArray[np.float64]


def slice_compliance(y: FloatArray, slice_width: float, half_width: FloatArray,
                     e_star: float) -> FloatArray:
    """Compliance (..., K, K) [m/N] of ``K`` equal slices at ``y`` (K,) [m] of width
    ``slice_width`` [m], each a uniform strip of half-width ``half_width`` (...,) [m]
    (module docstring). Equal slices: ``C_ik`` depends on ``|i - k|`` only (Toeplitz), so
    ``K`` coefficients per roller are computed and gathered."""
    a = np.asarray(half_width, dtype=float)[..., None]
    d = rectangle_influence(0.0, y - y[0], a, 0.5 * slice_width)  # (..., K) by |i - k|
    d = d / (math.pi * e_star * 2.0 * a * slice_width)
    k = np.arange(y.size)
    return np.asarray(d[..., np.abs(k[:, None] - k[None, :])])


def influence_slice_loads(deflection: FloatArray, kn: float, exponent: float, length: float,
                          radii: tuple[float, ...], e_star: float) -> FloatArray:
    """Slice loads (..., K) [N] of rollers with slice deflections ``deflection`` (..., K)
    [m] (module docstring).

    Parameters
    ----------
    deflection : array (..., K)
        ``V + xi_k L omega - c(xi_k)`` of every roller at its slice centres [m].
    kn, exponent : float
        Whole-roller constant ``Kn`` [N/m^n] and exponent ``n`` of the bearing.
    length : float
        Effective length ``L`` [m].
    radii : tuple of float
        Reduced radii of the contacts in series across the rolling direction [m] (inner
        and outer race; one for a single contact).
    e_star : float
        Contact modulus ``E*`` [Pa].

    Examples
    --------
    >>> q = influence_slice_loads(np.full((1, 10), 10e-6), 3e8, 10 / 9, 0.01,
    ...                           (0.004, 0.006), 1.13e11)
    >>> bool(q[0, 0] > q[0, 5]), round(float(q.sum()) / (3e8 * 10e-6 ** (10 / 9)), 12)
    (True, 1.0)
    """
    d = np.asarray(deflection, dtype=float)
    k = d.shape[-1]
    independent = (kn / k) * np.maximum(d, 0.0) ** exponent
    out = np.zeros(d.shape)
    flat_d, flat_q = d.reshape(-1, k), independent.reshape(-1, k)
    total = flat_q.sum(axis=-1)
    rows = np.flatnonzero(total > 0.0)
    if rows.size == 0:
        return out
    y = (-0.5 + (np.arange(k) + 0.5) / k) * length
    mean_line = total[rows] / length
    c = np.zeros((rows.size, k, k))
    for r in radii:  # the two races in series
        b = np.sqrt(4.0 * mean_line * r / (math.pi * e_star))
        c += slice_compliance(y, length / k, b, e_star)
    q_hs, _ = solve_contact(c, flat_d[rows])
    scale = total[rows] / np.maximum(q_hs.sum(axis=-1), np.finfo(float).tiny)
    out.reshape(-1, k)[rows] = q_hs * scale[:, None]
    return out
