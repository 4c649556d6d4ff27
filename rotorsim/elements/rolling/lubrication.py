"""Lubricated (EHL) rolling contacts: film and Hertz stiffness in series, squeeze damping.

Seed 002 section 3.2 (eqs 3.1-3.5) and 3.4 (eqs 3.15-3.16, 3.19-3.20); full statement,
units, interpretation and checks in ``docs/rolling_bearings.md`` ("Lubricated contacts").
Per race of every contact (ball, or roller slice), with the approach
``lambda = delta - h`` (eq 3.12), the Hertz slope ``K_H = n F / delta`` of the bearing's
load law and the film slope ``K_EHL = dF/dh`` of the central film law (Hamrock-Dowson
``h ~ U^0.67 G^0.53 W^-0.067`` for points: ``K_EHL = -F/(0.067 h)``; Dowson-Higginson
``h = (4/3) 1.6 Rx U^0.7 G^0.6 W^-0.13`` for lines: ``-F/(0.13 h)``)::

    k = dF/d lambda = K_H K_EHL / (K_EHL - K_H)                         (eq 3.1)
    c = 6 pi eta0 Rx^1.5 a / (sqrt(2) h^1.5)  (ball),  3 pi eta0 Rx^1.5 (L/K) / h^1.5  (slice)

inner and outer races in series (eq 3.5, ``s = 1``), entrainment speed
``u = |W| d_m (1 - gamma^2)/4`` (pure rolling, outer ring fixed), and bearing matrices
``C = sum_p c_p g_p g_p^T`` (eqs 3.16, 3.20), ``K_EHL = K + sum_p (k_p - K_H,p) g_p g_p^T``
(eqs 3.15, 3.19; linear analyses only) along the unit-load directions ``g_p``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.ehl_contact import (  # re-exported
    LINE_FILM_EXPONENT,
    POINT_FILM_EXPONENT,
    STEEL_REDUCED_MODULUS,
    Lubricant,
    central_film_line,
    central_film_point,
    combine_races,
    entrainment_speed,
    series_stiffness,
)
from rotorsim.elements.rolling.contact.hertz_point import (
    contact_constant,
    point_contact,
    race_curvature_radii,
)
from rotorsim.elements.rolling.roller.bearing import _assemble_tangent  # sum w g g^T, rollers
from rotorsim.elements.rolling.roller.profile import slice_centres
from rotorsim.elements.rolling.state import BearingState
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

__all__ = [
    "LINE_FILM_EXPONENT", "POINT_FILM_EXPONENT", "STEEL_REDUCED_MODULUS", "ContactCoefficients",
    "EHLMatrices", "Lubricant", "LubricatedContacts", "central_film_line", "central_film_point",
    "combine_races", "entrainment_speed", "series_stiffness",
]


class ContactCoefficients(NamedTuple):
    """Per-contact EHL quantities, arrays shaped like the loads (unloaded: 0).

    ``film`` (2, ...) central film at the inner and outer race [m]; ``hertz`` ``K_H`` of
    both races in series [N/m]; ``stiffness`` the lubricated series value ``k`` and
    ``damping`` ``c`` [N s/m] at the requested frequency (eqs 3.1-3.5);
    ``damping_slope`` ``dc/dF`` at zero frequency [s/m].
    """

    film: FloatArray
    hertz: FloatArray
    stiffness: FloatArray
    damping: FloatArray
    damping_slope: FloatArray


class EHLMatrices(NamedTuple):
    """Bearing matrices of the EHL model on the 5 relative DOFs (S samples).

    ``damping`` C (S, 5, 5) [N s/m, ...]; ``stiffness`` the EHL-softened stiffness
    (S, 5, 5), for linear analyses only (not the Jacobian of the force);
    ``damping_force`` ``C delta'`` (S, 5) and ``damping_tangent`` its exact derivative
    with respect to ``delta`` (S, 5, 5) (zero without ``rate``).
    """

    damping: FloatArray
    stiffness: FloatArray
    damping_force: FloatArray
    damping_tangent: FloatArray


class _Races(NamedTuple):
    """Inner and outer race data: radii ``(Rx, Ry)``, deflection shares, Hertz semi-axis
    at unit load (balls), element diameter and slice width (rollers) [m]."""

    point: bool
    radii: tuple[tuple[float, float], ...]
    share: tuple[float, ...]
    axis: tuple[float, ...]
    diameter: float
    width: float = 0.0


def _ball_races(b: Any, lubricant: Lubricant) -> _Races:
    if b.f_i is None or b.f_o is None:
        raise ModelError("EHL film thickness of ball contacts needs the groove curvature "
                         "factors f_i and f_o (transverse radii Ry)", b.label)
    e_star = 0.5 * lubricant.reduced_modulus  # Hertz E* = E'/2
    radii = tuple(race_curvature_radii(b.ball_diameter, b.pitch_diameter, b.contact_angle,
                                       f, race)
                  for race, f in (("inner", b.f_i), ("outer", b.f_o)))
    flex = np.array([contact_constant(rx, ry, e_star) for rx, ry in radii]) ** (
        -1.0 / b.exponent)  # race deflection per F^(1/n)
    axes = tuple(point_contact(rx, ry, e_star, 1.0).semi_major for rx, ry in radii)
    return _Races(True, radii, tuple(flex / flex.sum()), axes, b.ball_diameter)


def _roller_races(b: Any) -> _Races:
    d = b.diameter_for("EHL contact damping")
    gamma = d * math.cos(b.contact_angle) / b.pitch_diameter
    radii = ((0.5 * d * (1.0 - gamma), math.inf), (0.5 * d * (1.0 + gamma), math.inf))
    return _Races(False, radii, (0.5, 0.5), (), d,
                  b.effective_length / b.n_slices)


@dataclass(frozen=True, eq=False)
class LubricatedContacts:
    """EHL stiffness and damping of the contacts of one bearing (module docstring).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Balls need the groove curvature factors ``f_i, f_o`` (``Ry`` of the contacts);
        rollers are evaluated on their ``n_slices`` slices (also for the tilt-integral
        model, whose force it leaves unchanged).
    lubricant : Lubricant

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> b = BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3,
    ...                               ball_diameter=9.525e-3, f_i=0.515, f_o=0.525)
    >>> ehl = LubricatedContacts(b, Lubricant(eta0=0.04, alpha=2e-8))
    >>> out = ehl.matrices([[20e-6, 0, 0, 0, 0]], b.element_angles(), 300.0)
    >>> bool(out.damping[0, 0, 0] > 0), out.damping.shape
    (True, (1, 5, 5))
    """

    bearing: Any
    lubricant: Lubricant
    races: _Races = field(init=False, repr=False)

    def __post_init__(self) -> None:
        b = self.bearing
        if not isinstance(self.lubricant, Lubricant):
            raise ModelError(f"lubricant must be a Lubricant, got {self.lubricant!r}",
                             "LubricatedContacts")
        if hasattr(b, "ball_diameter"):
            races = _ball_races(b, self.lubricant)
        elif hasattr(b, "roller_diameter"):
            races = _roller_races(b)
        else:
            raise ModelError(f"EHL contacts need a BallBearing or RollerBearing, got "
                             f"{type(b).__name__}", "LubricatedContacts")
        object.__setattr__(self, "races", races)

    def coefficients(self, load: ArrayLike, slope: ArrayLike, speed: ArrayLike,
                     frequency: float = 0.0) -> ContactCoefficients:
        """EHL coefficients of contact points with loads ``load`` (S, P) [N].

        ``slope`` (S, P) is the Hertz ``dF/d delta`` of both races [N/m], ``speed`` the
        shaft speed (S,) [rad/s] (outer ring fixed, non-zero), ``frequency`` ``w`` [rad/s]
        of eq 3.5 (0: quasi-static combination). Only loaded points are evaluated.
        """
        f_all = np.asarray(load, dtype=float)
        loaded = f_all > 0.0
        u_s = self._entrainment(speed, f_all.shape[0]).reshape(-1, *[1] * (f_all.ndim - 1))
        u = np.broadcast_to(u_s, f_all.shape)[loaded]
        f, kh = f_all[loaded], np.asarray(slope, dtype=float)[loaded]
        films, k, c, dc = self._loaded_coefficients(f, kh, u, frequency)
        out = [np.zeros(f_all.shape) for _ in range(4)]
        for arr, values in zip(out, (kh, k, c, dc), strict=True):
            arr[loaded] = values
        film = np.full((2, *f_all.shape), np.inf)
        film[:, loaded] = films
        return ContactCoefficients(film, *out)

    def _loaded_coefficients(self, f: FloatArray, kh: FloatArray, u: FloatArray,
                             frequency: float) -> tuple[FloatArray, ...]:
        """Films (2, M), ``k``, ``c`` and ``dc/dF`` (M,) of ``M`` loaded points.

        The film laws are power laws, ``h_race = h_race(F=1, u=1) u^e F^-p``: the common
        factor ``u^e F^-p`` is evaluated once for both races.
        """
        races, lub = self.races, self.lubricant
        p, e = (POINT_FILM_EXPONENT, 0.67) if races.point else (LINE_FILM_EXPONENT, 0.7)
        m = (1.0 / 3.0 if races.point else 0.0) + 1.5 * p  # c ~ F^m (a ~ F^(1/3), balls)
        s_h = (self.bearing.exponent - 1.0) / self.bearing.exponent  # K_H ~ F^((n-1)/n)
        base = u**e * f**-p
        squeeze = (np.cbrt(f) if races.point else 1.0) / (base * np.sqrt(base))
        films, ks, dks, cs = [], [], [], []
        for i, ((rx, ry), share) in enumerate(zip(races.radii, races.share, strict=True)):
            if races.point:
                unit = float(central_film_point(1.0, 1.0, rx, ry, lub))
                c_unit = 6.0 * math.pi / math.sqrt(2.0) * lub.eta0 * races.axis[i]
            else:
                unit = float(central_film_line(1.0 / races.width, 1.0, rx, lub))
                c_unit = 3.0 * math.pi * lub.eta0 * races.width
            c = (c_unit * (rx / unit) ** 1.5) * squeeze  # c = c_unit Rx^1.5 / h^1.5
            k_hertz = kh / share
            k_film = f / ((p * unit) * base)  # |K_EHL| = F / (p h)
            k = k_hertz * k_film / (k_hertz + k_film)  # eq 3.1
            films.append(unit * base)
            ks.append(k)
            dks.append((k_film * s_h + k_hertz * (1.0 + p)) / (k_hertz + k_film) * k / f)
            cs.append(c)
        if frequency == 0.0:
            total = ks[0] + ks[1]
            k_all = ks[0] * ks[1] / total
            c_all = (cs[0] * ks[1] * ks[1] + cs[1] * ks[0] * ks[0]) / (total * total)
        else:
            k_all, c_all = combine_races(ks[0], cs[0], ks[1], cs[1], frequency)
        slope_c = _damping_slope(ks, dks, cs, [m * c / f for c in cs])
        return np.stack(films), k_all, c_all, slope_c

    def _entrainment(self, speed: ArrayLike, n_samples: int) -> FloatArray:
        b = self.bearing
        w = np.broadcast_to(np.asarray(speed, dtype=float).reshape(-1), (n_samples,))
        if not np.all(np.isfinite(w)) or np.any(w == 0.0):
            raise ModelError("EHL contacts need a finite, non-zero shaft speed (the film "
                             "thickness vanishes at rest)", type(b).__name__)
        u = entrainment_speed(w, self.races.diameter, b.pitch_diameter, b.contact_angle)
        return np.asarray(u[:, None])

    def _slices(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, ...]:
        """Slice loads ``(Kn/K) delta_k^n``, Hertz slopes ``n F_k / delta_k`` (S, Z, K)
        and moment arms ``r_p sin a0 - xi_k L`` (K,) [m] (seed 002 eqs 2.7, 2.12)."""
        b = self.bearing
        defl = b.slice_deflections(delta, psi)
        pos = np.maximum(defl, 0.0)
        n, per_slice = b.exponent, b.kn / b.n_slices
        power = pos ** (n - 1.0) if n > 1.0 else (defl > 0.0).astype(float)
        arm = (0.5 * b.pitch_diameter * math.sin(b.contact_angle)
               - slice_centres(b.n_slices) * b.effective_length)
        return per_slice * pos * power, (n * per_slice) * power, arm

    def matrices(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike, *,
                 rate: ArrayLike | None = None, frequency: float = 0.0,
                 state: BearingState | None = None) -> EHLMatrices:
        """Damping, EHL-softened stiffness and damping force at ``delta`` (S, 5) [m, rad].

        ``psi`` (S, N) element angles [rad], ``speed`` (S,) shaft speed [rad/s], ``rate``
        ``delta'`` (S, 5) for ``damping_force = C delta'`` and its exact tangent,
        ``frequency`` ``w`` [rad/s] of eq 3.5 (0 in time-domain use), ``state`` =
        ``bearing.state(delta, psi)`` if already computed.
        """
        st = self.bearing.state(delta, psi) if state is None else state
        n_s = st.force.shape[0]
        v = None if rate is None else np.asarray(rate, dtype=float).reshape(n_s, 5)
        if self.races.point:
            damping, soft, tangent = self._ball_matrices(psi, speed, v, frequency, st)
        else:  # sample blocks of ~32k slices: the temporaries stay in cache
            b = self.bearing
            d = np.asarray(delta, dtype=float).reshape(n_s, 5)
            p = np.broadcast_to(np.asarray(psi, dtype=float), (n_s, b.n_elements))
            w = np.broadcast_to(np.asarray(speed, dtype=float).reshape(-1), (n_s,))
            size = max(1, 32768 // (b.n_elements * b.n_slices))
            parts = [self._roller_matrices(d[i:i + size], p[i:i + size], w[i:i + size],
                                           None if v is None else v[i:i + size], frequency)
                     for i in range(0, n_s, size)]
            damping, soft, tangent = (np.concatenate(x) for x in zip(*parts, strict=True))
        force = np.zeros((n_s, 5)) if v is None else np.einsum("sij,sj->si", damping, v)
        return EHLMatrices(damping, st.stiffness + soft, force, tangent)

    def _ball_matrices(self, psi: ArrayLike, speed: ArrayLike, v: FloatArray | None,
                       frequency: float, st: BearingState) -> tuple[FloatArray, ...]:
        """``C``, ``K_EHL - K`` and ``d(C v)/d delta`` summed over the balls."""
        g, slope = st.contact_direction, st.element_stiffness
        if g is None or slope is None:
            raise ModelError("the bearing state lacks contact directions", "EHL")
        co = self.coefficients(st.element_load, slope, speed, frequency)
        gt = np.swapaxes(g, 1, 2)
        damping = np.matmul(gt * co.damping[:, None, :], g)
        soft = np.matmul(gt * (co.stiffness - co.hertz)[:, None, :], g)
        if v is None:
            return damping, soft, np.zeros_like(damping)
        along = np.matmul(g, v[:, :, None])[..., 0]  # g_j . delta'
        tangent = np.matmul(gt * (co.damping_slope * slope * along)[:, None, :], g)
        # g_j turns with delta: dg/d delta = t t^T / A (seed 000 Appendix A1); tau = t/sqrt(A)
        b, alpha = self.bearing, st.contact_angle
        p = np.broadcast_to(np.asarray(psi, dtype=float), alpha.shape)
        c, s, sa, ca = np.cos(p), np.sin(p), np.sin(alpha), np.cos(alpha)
        tau = np.stack([-sa * c, -sa * s, ca, b.moment_arm * ca * s,
                        -b.moment_arm * ca * c], axis=-1)
        tau /= np.sqrt(b.center_distance + st.deflection)[..., None]
        mixed = (along[..., None] * tau + np.matmul(tau, v[:, :, None]) * g)
        tangent += np.matmul(np.swapaxes(mixed * co.damping[..., None], 1, 2), tau)
        return damping, soft, tangent

    def _roller_matrices(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike,
                         v: FloatArray | None, frequency: float) -> tuple[FloatArray, ...]:
        """As :meth:`_ball_matrices` over the roller slices, whose directions
        ``(ca u, sa, arm_k J u)`` are fixed: sums of ``w, w arm, w arm^2`` per roller."""
        loads, slope, arm = self._slices(delta, psi)
        co = self.coefficients(loads, slope, speed, frequency)
        b = self.bearing
        p = np.broadcast_to(np.asarray(psi, dtype=float), loads.shape[:2])
        c, s = np.cos(p), np.sin(p)
        ca, sa = math.cos(b.contact_angle), math.sin(b.contact_angle)
        basis = np.stack([np.ones_like(arm), arm, arm * arm], axis=1)  # (K, 3)

        def assemble(weight: FloatArray) -> FloatArray:
            w = weight @ basis  # (S, Z, 3)
            return _assemble_tangent(c, s, w[..., 0], w[..., 1], w[..., 2], ca, sa)

        damping = assemble(co.damping)
        soft = assemble(co.stiffness - co.hertz)
        if v is None:
            return damping, soft, np.zeros_like(damping)
        # g_jk . delta' = ca (c vx + s vy) + sa vz + arm_k (s vrx - c vry)
        base = ca * (c * v[:, 0:1] + s * v[:, 1:2]) + sa * v[:, 2:3]
        turn = s * v[:, 3:4] - c * v[:, 4:5]
        along = base[..., None] + turn[..., None] * arm
        return damping, soft, assemble(co.damping_slope * slope * along)


def _damping_slope(k: list[FloatArray], dk: list[FloatArray], c: list[FloatArray],
                   dc: list[FloatArray]) -> FloatArray:
    """``dc/dF`` of the zero-frequency series ``c = (c_i k_o^2 + c_o k_i^2)/(k_i + k_o)^2``."""
    (ki, ko), (dki, dko), (ci, co), (dci, dco) = k, dk, c, dc
    total = ki + ko
    num = ci * ko * ko + co * ki * ki
    dnum = dci * ko * ko + 2.0 * ci * ko * dko + dco * ki * ki + 2.0 * co * ki * dki
    return np.asarray((dnum * total - 2.0 * num * (dki + dko)) / total**3)
