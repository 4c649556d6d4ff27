"""Per-roller line integrals and their assembly into the bearing force and tangent.

A roller ``j`` at ``psi_j`` with the centre approach ``V_j`` and tilt ``L omega_j`` has the
deflection ``delta(xi) = V_j + xi L omega_j - c(xi)`` along its length; the bearing needs
the integrals of :class:`LineIntegrals` (seed 000 eqs 7-9, 22-23). With
``g(xi) = d delta / d(x, y, z, rx, ry) = (ca cos psi, ca sin psi, sa, arm sin psi,
-arm cos psi)``, ``arm = r_p sin a0 - xi L`` (seed 000 eq 10), a per-roller quadratic form
``int w(xi) g g^T dxi`` needs only the weights ``int w arm^p dxi`` (``p = 0, 1, 2``):
:func:`assemble_tangent` sums them over the rollers (seed 000 Appendix A2). The rigid-ring
model (:mod:`~rotorsim.elements.rolling.roller.bearing`) and the centrifugal model
(:mod:`~rotorsim.elements.rolling.roller.centrifugal`) share these helpers.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rotorsim.elements.base import frozen_scalar
from rotorsim.elements.rolling.state import FloatArray


class LineIntegrals(NamedTuple):
    """Integrals along each roller, arrays ``(S, N)``; ``delta^+`` the positive deflection.

    ``energy = int delta^(n+1)/(n+1)``, ``load = int delta^n``, ``load_moment =
    int xi delta^n``, ``tangent0..2 = int xi^p delta^(n-1)`` (all over ``dxi``), ``peak``
    the largest deflection along the roller.
    """

    energy: FloatArray
    load: FloatArray
    load_moment: FloatArray
    tangent0: FloatArray
    tangent1: FloatArray
    tangent2: FloatArray
    peak: FloatArray


@dataclass(frozen=True, eq=False)
class RollerLoads:
    """Per-roller load distribution, arrays ``(S, N)`` (``slice_load``: ``(S, N, K)``).

    Attributes
    ----------
    load : Contact load ``Q_j`` [N] (seed 000 eq 7b).
    eccentricity : Load eccentricity ``e_j`` [m] from the roller centre along ``t_j``
        (seed 000 eq 9); 0 for unloaded rollers.
    contact_limits : ``(S, N, 2)`` dimensionless ends ``xi_1, xi_2`` of the loaded zone
        (seed 000 eq 8; for slices the outer edges of the loaded slices); NaN if unloaded.
    slice_load : Load of each slice [N] (``model="slices"``), else ``None``.
    """

    load: FloatArray
    eccentricity: FloatArray
    contact_limits: FloatArray
    slice_load: FloatArray | None = None


class RollerConstants(NamedTuple):
    """Constants of the rigid-ring roller evaluation: floats, then the same values as
    read-only 0-d arrays (cheaper operands of array operations than Python floats)."""

    ca: float  # cos(alpha0)
    sa: float  # sin(alpha0)
    r_sa: float  # r_p sin(alpha0) [m]
    ca0: FloatArray
    sa0: FloatArray
    r_sa0: FloatArray
    clearance: FloatArray  # r_L [m]
    length: FloatArray  # L [m]
    kn: FloatArray  # Kn
    kn_length: FloatArray  # Kn L
    r_sa2: FloatArray  # (r_p sin a0)^2
    two_r_sa_length: FloatArray  # 2 r_p sin(a0) L
    length2: FloatArray  # L^2
    n_kn: FloatArray  # n Kn


def roller_constants(contact_angle: float, pitch_diameter: float, clearance: float,
                     length: float, kn: float, exponent: float) -> RollerConstants:
    """:class:`RollerConstants` of a bearing (angle [rad], lengths [m], ``Kn``, ``n``)."""
    ca, sa = math.cos(contact_angle), math.sin(contact_angle)
    r_sa = 0.5 * pitch_diameter * sa
    values = (ca, sa, r_sa, clearance, length, kn, kn * length, r_sa**2,
              2.0 * r_sa * length, length**2, exponent * kn)
    return RollerConstants(ca, sa, r_sa, *(frozen_scalar(x) for x in values))


def roller_rows(h: RollerConstants, load: FloatArray, load_moment: FloatArray,
                t0: FloatArray, t1: FloatArray, t2: FloatArray) -> FloatArray:
    """Per-roller ``(w0, w1, w2, Q_j, Q_j a_j)`` (5, ..., N) from the line integrals of
    :class:`LineIntegrals`: the tangent weights of ``1, arm, arm^2`` (without ``n Kn``),
    the load and its moment about the pitch circle, ``a_j = r_p sin a0 - e_j``
    (seed 000 eqs 9-10)."""
    rows = np.empty((5, *load.shape))
    q = np.multiply(h.kn, load, out=rows[3])
    np.subtract(h.r_sa0 * q, h.kn_length * load_moment, out=rows[4])
    rows[0] = t0
    np.subtract(h.r_sa0 * t0, h.length * t1, out=rows[1])
    np.add(h.r_sa2 * t0 - h.two_r_sa_length * t1, h.length2 * t2, out=rows[2])
    return rows


def tilt_limits(v: FloatArray, lw: FloatArray) -> FloatArray:
    """Loaded zone ``(xi_1, xi_2)`` of straight rollers (seed 000 eq 8), NaN if unloaded."""
    with np.errstate(divide="ignore", invalid="ignore"):
        xi0 = np.where(lw != 0.0, -v / np.where(lw != 0.0, lw, 1.0), np.nan)
    lo = np.where(lw > 0.0, np.maximum(xi0, -0.5), -0.5)
    hi = np.where(lw < 0.0, np.minimum(xi0, 0.5), 0.5)
    loaded = (v + 0.5 * np.abs(lw)) > 0.0
    return np.where(loaded[..., None], np.stack([lo, hi], axis=-1), np.nan)


# The sums over the rollers: (row of (w0, w1, w2, Q, Q a), angle function c^2, cs, s^2, c,
# s, 1). The first 14 give the tangent, the last 5 the force (seed 000 eq 10).
_PRODUCTS = ((0, 0), (0, 1), (0, 2), (0, 3), (0, 4), (0, 5), (1, 0), (1, 1), (1, 2),
             (1, 3), (1, 4), (2, 0), (2, 1), (2, 2), (3, 3), (3, 4), (3, 5), (4, 4), (4, 3))
_ROWS = np.array([p[0] for p in _PRODUCTS])
_BASIS = np.array([p[1] for p in _PRODUCTS])
_N_TANGENT = 14
_GATHER_LIMIT = 8192  # rows.size below which the products are formed in one operation
# tangent entries (row, column) <- (sum, factor kind) of g = (ca u, sa, arm J u)
_K_ENTRIES = (
    ((0, 0), (0, 0), "ca2"), ((0, 1), (0, 1), "ca2"), ((1, 1), (0, 2), "ca2"),
    ((0, 2), (0, 3), "casa"), ((1, 2), (0, 4), "casa"), ((2, 2), (0, 5), "sa2"),
    ((0, 3), (1, 1), "ca"), ((0, 4), (1, 0), "-ca"), ((1, 3), (1, 2), "ca"),
    ((1, 4), (1, 1), "-ca"), ((2, 3), (1, 4), "sa"), ((2, 4), (1, 3), "-sa"),
    ((3, 3), (2, 2), "1"), ((3, 4), (2, 1), "-1"), ((4, 4), (2, 0), "1"),
)


@functools.lru_cache(maxsize=64)
def sums_transform(ca: float, sa: float) -> FloatArray:
    """``(19, 30)`` matrix ``T``: ``sums @ T`` is ``[force | tangent]`` (..., 5 + 25).

    ``sums`` (..., 19) are the sums over the rollers of the products ``_PRODUCTS`` of the
    rows ``(w0, w1, w2, Q_j, Q_j a_j)`` (the weights of ``1, arm, arm^2`` of
    :func:`assemble_tangent`, the roller load and its moment arm ``a_j = r_p sin a0 - e_j``)
    with the angle functions ``c^2, c s, s^2, c, s, 1``. The force is
    ``(ca sum Q c, ca sum Q s, sa sum Q, sum Q a s, -sum Q a c)`` (seed 000 eq 10), the
    tangent the row-major ``sum_j w g g^T`` of :func:`assemble_tangent`. One non-zero per
    column: each output is one rounded product. Cached, read-only.
    """
    kinds = {"ca2": ca * ca, "casa": ca * sa, "sa2": sa * sa, "ca": ca, "-ca": -ca,
             "sa": sa, "-sa": -sa, "1": 1.0, "-1": -1.0}
    t = np.zeros((len(_PRODUCTS), 30))
    for i, (product, scale) in enumerate((((3, 3), ca), ((3, 4), ca), ((3, 5), sa),
                                          ((4, 4), 1.0), ((4, 3), -1.0))):
        t[_PRODUCTS.index(product), i] = scale
    for (row, col), product, kind in _K_ENTRIES:
        t[_PRODUCTS.index(product), 5 + 5 * row + col] = kinds[kind]
        t[_PRODUCTS.index(product), 5 + 5 * col + row] = kinds[kind]
    t.flags.writeable = False
    return t


def roller_sums(rows: FloatArray, c: FloatArray, s: FloatArray) -> FloatArray:
    """The sums over the rollers ``(19, ...)`` of ``rows`` (5, ..., N) (or of only the
    tangent weights, (3, ..., N): the first 14 sums) times the angle functions of
    ``c, s`` (..., N) ``= cos, sin(psi_j)``, which may omit leading axes of ``rows``.
    Component-major layout: every product is one contiguous array."""
    count = len(_PRODUCTS) if rows.shape[0] == 5 else _N_TANGENT
    cc, cs, ss = c * c, c * s, s * s
    basis = (cc, cs, ss, c, s, None)  # None: 1
    if rows[0].size * count < _GATHER_LIMIT:  # small batches: few operations
        stacked = np.stack((cc, cs, ss, c, s, np.ones_like(c)))
        factors = stacked[_BASIS[:count]]
        factors = factors.reshape(count, *(1,) * (rows.ndim - factors.ndim), *c.shape)
        products = rows[_ROWS[:count]] * factors
        return np.asarray(products.sum(axis=-1))
    sums = np.empty((count, *rows.shape[1:-1]))  # large batches: little memory traffic
    for i, (row, col) in enumerate(_PRODUCTS[:count]):
        factor = basis[col]
        np.add.reduce(rows[row] if factor is None else rows[row] * factor, axis=-1,
                      out=sums[i])
    return sums


def force_stiffness(rows: FloatArray, c: FloatArray, s: FloatArray, ca: float, sa: float
                    ) -> tuple[FloatArray, FloatArray]:
    """Force (..., 5) and tangent ``sum_j w g g^T`` (..., 5, 5) from the per-roller rows
    ``(w0, w1, w2, Q_j, Q_j a_j)`` (5, ..., N) (:func:`sums_transform`)."""
    sums = roller_sums(rows, c, s)
    lead = sums.shape[1:]
    flat = sums.reshape(len(_PRODUCTS), -1).T @ sums_transform(float(ca), float(sa))
    return flat[:, :5].reshape(*lead, 5), flat[:, 5:].reshape(*lead, 5, 5)


def assemble_tangent(c: FloatArray, s: FloatArray, w0: FloatArray, w1: FloatArray,
                     w2: FloatArray, ca: float, sa: float) -> FloatArray:
    """``sum_j int delta^(n-1) g g^T`` from the weights of ``1, arm, arm^2`` (S, N).

    ``g = (ca u, sa, arm J u)`` with ``u = (cos psi, sin psi)``, ``J u = (sin, -cos)`` and
    ``arm = r_p sin a0 - xi L``; ``w0, w1, w2`` are the integrals of
    ``delta^(n-1) arm^p``.
    """
    sums = roller_sums(np.stack(np.broadcast_arrays(w0, w1, w2)), c, s)
    lead = sums.shape[1:]
    transform = sums_transform(float(ca), float(sa))[:_N_TANGENT, 5:]
    return np.asarray(sums.reshape(_N_TANGENT, -1).T @ transform).reshape(*lead, 5, 5)


def unit_load_directions(c: FloatArray, s: FloatArray, unit_arm: FloatArray, ca: float,
                         sa: float) -> FloatArray:
    """Unit-load directions ``g_j = dF/dQ_j`` (S, Z, 5) of the rollers (seed 000 eq 10).

    ``(ca cos psi, ca sin psi, sa, a_j sin psi, -a_j cos psi)`` with the moment arm
    ``a_j = r_p sin a0 - e_j`` [m] (``unit_arm``, (S, Z)).
    """
    direction = np.empty((*c.shape, 5))
    np.multiply(c, ca, out=direction[..., 0])
    np.multiply(s, ca, out=direction[..., 1])
    direction[..., 2] = sa
    np.multiply(unit_arm, s, out=direction[..., 3])
    np.multiply(unit_arm, -c, out=direction[..., 4])
    return direction
