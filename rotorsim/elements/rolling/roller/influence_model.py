"""Roller contact model ``"influence"``: slices coupled by the half-space, driving the force.

Independent slices (seed 002 eqs 2.7, 2.12) give slice ``k`` of a roller the load
``(Kn/K) max(delta_k, 0)^n``. Here the ``K`` slices of a roller press on one another through
the half-space influence coefficients of seed 002 section 2.3.3 (the "simplified model" of
eq 2.29: each slice a uniform strip; the displacement averaged across the receiving strip,
where eq 2.29 reads it on the centre line), and the roller's energy, force and exact
tangent follow from that coupled problem.

**Geometry-only compliance.** ``C`` (K, K) of both races in series
(:func:`~rotorsim.elements.rolling.roller.own_width_strips.strip_average_compliance`, all
strips of one width: symmetric, Toeplitz), with strips of the Hertz half-width of each race
at a fixed reference line load: the one that gives the inner race the Hertz pressure
``p_ref`` (default 1500 MPa, the contact pressure at which ISO 281 defines the fatigue load
limit). ``C`` is built, inverted and its sums formed once per bearing; only its shape
matters (its scale cancels in the calibration below). The strip average brings the load
centre of a tilted roller to 0.95-1.01 of the 2-D half-space's, from 0.91-0.96 read on the
centre line (docs/validation.md, case 35b).

**The roller's problem.** For slice deflections ``d`` (K,) (``V + xi_k L omega - c(xi_k)``),
the half-space slice loads ``u >= 0`` solve ``C u >= d``, ``u.(C u - d) = 0`` (a linear
complementarity problem; Kalker's active set). Its value
``Phi(d) = max_{u >= 0} (u.d - u.C u / 2) = u.d / 2`` is convex with ``dPhi/dd = u`` and,
on the contact set ``A``, ``d^2 Phi/dd^2 = M = P_A C_AA^-1 P_A``. The roller energy is

    U(d) = Kn beta Phi^(m+1) / (m+1),     m = (n - 1)/2,
    q = dU/dd = Kn beta Phi^m u                      (slice loads, shape of the half-space)
    dq/dd = Kn beta (m Phi^(m-1) u u^T + Phi^m M)    (symmetric: the exact tangent),

with ``beta = 2^m S^-(m+1)``, ``S = 1.C^-1 1``, so that a straight roller under a uniform
deflection ``d`` carries ``Q = Kn d^n``: the bearing's ``Kn`` (ISO/TS 16281 or Palmgren,
10/9) and its stiffness are kept for that case, and ``U`` is homogeneous of degree
``n + 1`` like the independent law. With ``n = 1`` the model *is* the linear half-space
(1-D, eq 2.29) with its modulus calibrated to ``Kn``. The load calibration of a uniform
roller follows seed 002 section 2.3.2 ("load normalization"); unlike the seed, the load of a
tilted, crowned or partly loaded roller is the half-space's (not re-normalised to the
independent slices), so that force and tangent derive from one energy.

**Cost** (``benchmarks/bench_roller_edge.py``, docs/benchmarks.md): per loaded roller a
``K x K`` problem. Rollers loaded along their whole length whose unconstrained solution
``C^-1 d`` is positive (the usual case of a straight roller under moderate tilt) take one
product with the precomputed ``C^-1``; the others a few batched ``K x K`` solves of their
contact set.

References
----------
Seed 002 sections 2.3.2-2.3.3, eqs 2.26-2.29; Johnson (1985) *Contact Mechanics* eq 3.25
and section 5.9 (the complementarity conditions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.rolling.contact.influence import solve_contact
from rotorsim.elements.rolling.roller.integrals import LineIntegrals
from rotorsim.elements.rolling.roller.own_width_strips import strip_average_compliance
from rotorsim.elements.rolling.roller.profile import slice_centres
from rotorsim.elements.rolling.roller.slice_outputs import STEEL_E_STAR, race_radii
from rotorsim.elements.rolling.state import FloatArray

BoolArray = NDArray[np.bool_]

REFERENCE_PRESSURE = 1.5e9
"""Default ``p_ref`` [Pa] of the strip half-width (ISO 281's fatigue-load-limit pressure)."""

_MAX_ITER = 40
_CACHE_SLICES = 64  # largest K whose interval inverses are cached (memory ~ K^4 / 12 floats)


def influence_compliance(length: float, n_slices: int, radii: tuple[float, ...],
                         e_star: float, pressure: float = REFERENCE_PRESSURE) -> FloatArray:
    """Slice compliance ``C`` (K, K), normalised to ``C_00 = 1``, of both races in series.

    Parameters
    ----------
    length : float
        Effective length ``L`` [m].
    n_slices : int
        Number of equal slices ``K``.
    radii : tuple of float
        Reduced radii of the race contacts [m] (inner first).
    e_star : float
        Contact modulus ``E*`` [Pa].
    pressure : float
        Reference Hertz pressure of the inner race [Pa]; the reference line load is
        ``w = pi R_i p^2 / E*`` and each race's strip half-width ``sqrt(4 w R/(pi E*))``.

    Examples
    --------
    >>> c = influence_compliance(0.01, 10, (0.003, 0.004), 1.14e11)
    >>> c.shape, float(c[0, 0]), bool(c[0, 1] < 1.0)
    ((10, 10), 1.0, True)
    """
    k = int(n_slices)
    y = (-0.5 + (np.arange(k) + 0.5) / k) * length
    line = math.pi * radii[0] * pressure**2 / e_star
    c = sum(strip_average_compliance(y, length / k, math.sqrt(4.0 * line * r
                                                               / (math.pi * e_star)),
                                     e_star) for r in radii)
    c = 0.5 * (c + np.asarray(c).T)  # symmetric up to rounding (equal widths)
    return np.asarray(c / c[0, 0])


@dataclass(frozen=True, eq=False)
class InfluenceSlices:
    """Energy, loads and tangent weights of rollers of coupled slices (module docstring).

    Parameters
    ----------
    compliance : array (K, K)
        Symmetric positive definite slice compliance (any scale).
    exponent : float
        Load-deflection exponent ``n``.
    xi : array (K,)
        Slice centres ``xi_k`` in ``[-1/2, 1/2]``.
    """

    compliance: FloatArray
    exponent: float
    xi: FloatArray

    @cached_property
    def inverse(self) -> FloatArray:
        """``C^-1`` (K, K), read-only."""
        inv = np.linalg.inv(self.compliance)
        inv = 0.5 * (inv + inv.T)
        inv.flags.writeable = False
        return inv

    @cached_property
    def _full_sums(self) -> tuple[float, float, float]:
        """``1.C^-1 1``, ``1.C^-1 xi``, ``xi.C^-1 xi`` of the whole roller."""
        inv, xi = self.inverse, self.xi
        return float(inv.sum()), float(inv.sum(axis=0) @ xi), float(xi @ inv @ xi)

    @cached_property
    def beta(self) -> float:
        """``2^m S^-(m+1)``: a uniform deflection ``d`` gives ``Q = Kn d^n``."""
        m = 0.5 * (float(self.exponent) - 1.0)
        return float(2.0**m * self._full_sums[0] ** -(m + 1.0))

    def solve(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Half-space slice loads ``u`` (R, K) [per unit compliance] of the deflections
        ``d`` (R, K) [m] and the sums ``(1.M 1, 1.M xi, xi.M xi)`` (R, 3) of
        ``M = P_A C_AA^-1 P_A`` on their contact sets."""
        inv = self.inverse
        u = d @ inv
        sums = np.broadcast_to(np.asarray(self._full_sums), (d.shape[0], 3)).copy()
        rest = np.flatnonzero(~((d > 0.0).all(axis=-1) & (u > 0.0).all(axis=-1)))
        if rest.size:
            u[rest], sums[rest] = self._active_set(d[rest])
        return u, sums

    @cached_property
    def _interval_inverses(self) -> dict[tuple[int, int], FloatArray]:
        """Inverses of the diagonal blocks ``C[a:b+1, a:b+1]`` met so far (a contact set is
        an interval of slices when the deflection is concave along the roller: straight or
        crowned profiles with a tilt)."""
        return {}

    def _interval_solve(self, first: FloatArray, last: FloatArray, rhs: FloatArray
                        ) -> FloatArray:
        """``C_AA^-1 rhs_A`` (R, K, 3), zero outside, for the contact sets
        ``A = first..last`` (R,) by the cached block inverses (one gather and product)."""
        k = self.xi.size
        cache, c = self._interval_inverses, self.compliance
        keys, which = np.unique(first * k + last, return_inverse=True)
        blocks = np.zeros((keys.size, k, k))
        for i, key in enumerate(keys.tolist()):
            a, b = divmod(key, k)
            if (a, b) not in cache:
                cache[(a, b)] = np.asarray(np.linalg.inv(c[a:b + 1, a:b + 1]), dtype=float)
            blocks[i, a:b + 1, a:b + 1] = cache[(a, b)]
        return np.asarray(np.einsum("rkm,rmj->rkj", blocks[which], rhs))

    def _set_solve(self, act: BoolArray, rhs: FloatArray) -> FloatArray:
        """``C_AA^-1 rhs_A`` (R, K, 3), zero outside the contact sets ``act`` (R, K):
        cached interval inverses where ``act`` is an interval, batched solves elsewhere."""
        k = self.xi.size
        first = np.argmax(act, axis=-1)
        last = k - 1 - np.argmax(act[:, ::-1], axis=-1)
        interval = act.sum(axis=-1) == last - first + 1
        x = np.zeros(rhs.shape)
        if k <= _CACHE_SLICES and interval.any():
            x[interval] = self._interval_solve(first[interval], last[interval],
                                               rhs[interval])
        else:
            interval[:] = False
        rest = ~interval
        if rest.any():
            a = act[rest]
            both = a[:, :, None] & a[:, None, :]
            x[rest] = np.linalg.solve(np.where(both, self.compliance, np.eye(k, dtype=bool)),
                                      np.where(a[..., None], rhs[rest], 0.0))
        return x

    def _active_set(self, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Kalker's active set (drop negative loads, then add penetrating slices), batched,
        with right-hand sides ``d, 1, xi``; unsettled problems go to ``solve_contact``."""
        c, xi = self.compliance, self.xi
        k = xi.size
        rhs = np.stack(np.broadcast_arrays(d, np.ones(k), xi), axis=-1)  # (R, K, 3)
        active = d > 0.0
        u, x = np.zeros(d.shape), np.zeros(rhs.shape)
        todo = np.arange(d.shape[0])
        for _ in range(_MAX_ITER):
            act = active[todo]
            x_t = self._set_solve(act, rhs[todo])
            u_t = np.where(act, x_t[..., 0], 0.0)
            negative = act & (u_t < 0.0)
            gap = np.maximum(u_t, 0.0) @ c
            scale = np.abs(d[todo]).max(axis=-1, keepdims=True)
            adding = ~act & (gap < d[todo] - 1e-12 * scale)
            drop: BoolArray = np.asarray(negative.any(axis=-1))
            add: BoolArray = np.asarray(adding.any(axis=-1))
            done = ~(drop | add)
            u[todo[done]], x[todo[done]] = u_t[done], x_t[done]
            active[todo] = np.where(drop[:, None], act & ~negative, act | adding)
            todo = todo[~done]
            if todo.size == 0:
                break
        if todo.size:  # rare: Kalker's iteration did not settle; NNLS, then its contact set
            u[todo] = solve_contact(c, d[todo])[0]
            active[todo] = u[todo] > 0.0
            x[todo] = self._set_solve(active[todo], rhs[todo])
        x = np.where(active[..., None], x, 0.0)
        sums = np.stack([x[..., 1].sum(axis=-1), x[..., 2].sum(axis=-1), x[..., 2] @ xi],
                        axis=-1)
        return u, sums

    def integrals(self, d: FloatArray, energy_only: bool = False) -> LineIntegrals:
        """:class:`LineIntegrals` (...,) per unit ``Kn`` of rollers with slice deflections
        ``d`` (..., K) [m], in the conventions of the bearing: ``Q = Kn load``,
        ``Q e = Kn L load_moment``, tangent ``n Kn (t0, t1, t2)`` for ``(1, xi, xi^2)``
        (the weights of ``sum dq_k/dd_m``, ``sum xi_m dq_k/dd_m``, ``sum xi_k xi_m
        dq_k/dd_m``), energy ``Kn energy``."""
        lead, k = d.shape[:-1], d.shape[-1]
        flat = d.reshape(-1, k)
        out = np.zeros((7, flat.shape[0]))
        out[6] = flat.max(axis=-1)
        rows = np.flatnonzero(out[6] > 0.0)
        if rows.size:
            out[:6, rows] = self._roller_terms(flat[rows], energy_only)
        return LineIntegrals(*(o.reshape(lead) for o in out))

    def _roller_terms(self, d: FloatArray, energy_only: bool) -> FloatArray:
        """``(energy, load, load_moment, t0, t1, t2)`` (6, R) of loaded rollers (R, K)."""
        n = float(self.exponent)
        m = 0.5 * (n - 1.0)
        u, sums = self.solve(d)
        phi, pm = self._level(u, d)
        total, moment = u.sum(axis=-1), u @ self.xi
        out = np.zeros((6, d.shape[0]))
        out[0] = pm * phi / (m + 1.0)
        if energy_only:
            return out
        out[1], out[2] = pm * total, pm * moment
        rank1 = m * pm / phi / n  # pm = 0 where phi was 0 (set to 1)
        out[3] = rank1 * total**2 + pm / n * sums[:, 0]
        out[4] = rank1 * total * moment + pm / n * sums[:, 1]
        out[5] = rank1 * moment**2 + pm / n * sums[:, 2]
        return out

    def _level(self, u: FloatArray, d: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``Phi = u.d / 2`` (R,) (1 where it is 0: an unloaded roller to rounding) and
        ``beta Phi^m`` (0 there)."""
        phi = 0.5 * np.einsum("rk,rk->r", u, d)
        loaded = phi > 0.0
        phi = np.where(loaded, phi, 1.0)
        m = 0.5 * (float(self.exponent) - 1.0)
        return phi, np.where(loaded, self.beta * phi**m, 0.0)

    def slice_loads(self, d: FloatArray) -> FloatArray:
        """Slice loads per unit ``Kn``, ``beta Phi^m u`` (..., K), of deflections ``d``
        (..., K) [m] (multiply by ``Kn`` for newtons)."""
        lead, k = d.shape[:-1], d.shape[-1]
        flat = d.reshape(-1, k)
        q = np.zeros(flat.shape)
        rows = np.flatnonzero(flat.max(axis=-1) > 0.0)
        if rows.size:
            u, _ = self.solve(flat[rows])
            q[rows] = self._level(u, flat[rows])[1][:, None] * u
        return q.reshape(*lead, k)


def bearing_influence(bearing: Any) -> InfluenceSlices | None:
    """The :class:`InfluenceSlices` of a ``RollerBearing`` with ``model="influence"`` (its
    length, slices, race radii, bearing steel and ``influence_pressure``), else ``None``."""
    if bearing.model != "influence":
        return None
    c = influence_compliance(bearing.effective_length, int(bearing.n_slices),
                             race_radii(bearing), STEEL_E_STAR,
                             float(bearing.influence_pressure))
    return InfluenceSlices(c, float(bearing.exponent), slice_centres(int(bearing.n_slices)))
