"""Maximum Hertz pressure and contact size of every rolling-element contact (batched).

**Ball on a raceway** (point contact): with the radii of relative curvature ``Rx``
(rolling direction) and ``Ry`` (across the groove) of
:func:`~rotorsim.elements.rolling.contact.hertz_point.race_curvature_radii` at each
ball's loaded contact angle, the ellipticity ``k = a / b`` solves exactly (no curve fit)::

    Ry / Rx = (k^2 E(m) - K(m)) / (K(m) - E(m)),    m = 1 - 1/k^2

(complete elliptic integrals ``K``, ``E`` of :mod:`scipy.special`, by Newton's method in
``log k`` from the Brewe-Hamrock estimate, batched over all contacts), and for the load
``Q`` (Hamrock & Dowson 1981 ch. 3; Harris & Kotzalas 2007 ch. 6)::

    a = (3 k^2 E Q R / (pi E*))^(1/3),  b = a / k,  p_max = 3 Q / (2 pi a b),
    1/R = 1/Rx + 1/Ry.

``a`` lies across the groove. **Truncation** at a groove shoulder: the contact ellipse
spans the groove angles ``alpha_j -+ a / r`` (groove radius ``r = f D``); the shoulder
of height ``h`` above the groove bottom ends the groove at ``theta_s = arccos(1 - h/r)``
from the radial direction. The ellipse is truncated when ``|alpha_j| + a / r > theta_s``
(Harris & Kotzalas 2007, ch. 6 and 7, "contact ellipse truncation"); the margin
``theta_s - |alpha_j| - a / r`` [rad] is reported.

**Roller slice on a raceway** (line contact): a slice of a roller carrying the line load
``q`` [N/m] on a raceway of relative radius ``R`` (``D (1 -+ gamma) / 2``, inner/outer,
``gamma = D cos(a) / d_m``) has (Hertz; Johnson 1985, *Contact Mechanics*, eq 4.45)::

    b = sqrt(4 q R / (pi E*)),   p_max = 2 q / (pi b) = sqrt(q E* / (pi R)).

The line load of slice ``k`` is ``q_k = Kn delta_k^n / L`` (the roller model's line load,
:mod:`~rotorsim.elements.rolling.roller.line_load`); the end slices carry the edge load
of independent slices; with ``slice_model="influence"`` the slice loads of the half-space
influence coefficients (seed 002 ch. 2; :mod:`~rotorsim.elements.rolling.roller.
slice_influence`), whose end slices carry the edge stress.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_point import (
    BEARING_STEEL_E,
    BEARING_STEEL_NU,
    effective_modulus,
)
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

RACES = ("inner", "outer")
"""Order of the last axis of the per-race arrays."""


def ellipticity(ratio: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(k, E, K)``: ellipticity and complete elliptic integrals for ``Ry/Rx >= 1``.

    Exact to ~1e-12 relative (Newton in ``log k`` on the Hertz relation of the module
    docstring), batched over any array of ratios.

    Examples
    --------
    >>> k, e, f = ellipticity([1.0, 30.0])
    >>> k.round(4).tolist()
    [1.0, 8.8762]
    """
    from scipy.special import ellipe, ellipkm1

    r = np.asarray(ratio, dtype=float)
    if not np.isfinite(r).all() or (r < 1.0 - 1e-12).any():
        raise ModelError("curvature ratio Ry/Rx must be finite and >= 1", "ellipticity")
    log_r = np.log(np.maximum(r, 1.0))
    circular = log_r < 1e-9

    x = np.log(1.0339) + 0.6360 * log_r  # Brewe-Hamrock estimate of log k
    x = np.where(circular, 1e-3, np.maximum(x, 1e-4))
    for _ in range(30):
        # g(x) = log(k^2 E - K) - log(K - E) - log(Ry/Rx), k = e^x, m = 1 - 1/k^2, with
        # dE/dx = (E - K)(1 - m)/m and dK/dx = (E - (1 - m) K)/m (Byrd & Friedman 710.00)
        p = np.exp(-2.0 * x)  # 1 - m
        m = 1.0 - p
        big_k, big_e = ellipkm1(p), ellipe(m)
        num, den = big_e / p - big_k, big_k - big_e
        d_e = (big_e - big_k) * p / m
        d_k = (big_e - p * big_k) / m
        slope = (2.0 * big_e / p + d_e / p - d_k) / num - (d_k - d_e) / den
        step = np.where(circular, 0.0, (np.log(num / den) - log_r) / slope)
        x = np.maximum(x - step, 0.5 * x)
        if np.all(np.abs(step) < 1e-7):  # quadratic convergence: the error is now ~1e-14
            break
    k = np.where(circular, 1.0, np.exp(x))
    inv = 1.0 / k**2
    half_pi = 0.5 * math.pi
    return (k, np.where(circular, half_pi, ellipe(1.0 - inv)),
            np.where(circular, half_pi, ellipkm1(inv)))


@dataclass(frozen=True, eq=False)
class BallContactPressure:
    """Hertz contact of every ball with the inner and outer race.

    Arrays have shape ``(S, N, 2)``: samples, balls, race (``RACES``: inner, outer).

    Attributes
    ----------
    load : array (S, N, 2)
        Normal contact load ``Q`` [N].
    contact_angle : array (S, N, 2)
        Loaded contact angle [rad].
    max_pressure : array (S, N, 2)
        ``p_max`` [Pa] (0 when unloaded).
    semi_major, semi_minor : arrays (S, N, 2)
        ``a`` (across the groove) and ``b`` (rolling direction) [m].
    shoulder_margin : array (S, N, 2) or None
        ``theta_s - |alpha| - a / r`` [rad] (negative: truncated); None without shoulder
        heights.
    """

    load: FloatArray
    contact_angle: FloatArray
    max_pressure: FloatArray
    semi_major: FloatArray
    semi_minor: FloatArray
    shoulder_margin: FloatArray | None = None

    @property
    def truncated(self) -> NDArray[np.bool_]:
        """Loaded contacts whose ellipse crosses a shoulder (S, N, 2)."""
        if self.shoulder_margin is None:
            return np.zeros(self.load.shape, dtype=bool)
        return np.asarray((self.shoulder_margin < 0.0) & (self.load > 0.0))


@dataclass(frozen=True, eq=False)
class RollerContactPressure:
    """Line contact of every roller slice with the inner and outer race.

    Attributes
    ----------
    xi : array (K,)
        Slice centres along the roller, ``-1/2 .. 1/2`` of the effective length.
    line_load : array (S, Z, K)
        Load per unit length ``q`` [N/m] (the same on both races).
    max_pressure, half_width : arrays (S, Z, K, 2)
        ``p_max`` [Pa] and contact half-width ``b`` [m] on the inner and outer race.
    """

    xi: FloatArray
    line_load: FloatArray
    max_pressure: FloatArray
    half_width: FloatArray

    @property
    def edge_pressure(self) -> FloatArray:
        """Largest pressure of the two end slices (S, Z, 2) [Pa]."""
        return np.asarray(np.maximum(self.max_pressure[..., 0, :],
                                     self.max_pressure[..., -1, :]))


def _modulus(E: float, nu: float, E_ring: float | None, nu_ring: float | None) -> float:
    return effective_modulus(E, nu, E if E_ring is None else E_ring,
                             nu if nu_ring is None else nu_ring)


def ball_pressures(ball_diameter: float, pitch_diameter: float, f_i: float, f_o: float,
                   load: ArrayLike, contact_angle: ArrayLike, *,
                   outer_load: ArrayLike | None = None,
                   outer_contact_angle: ArrayLike | None = None,
                   shoulder_heights: tuple[float, float] | None = None,
                   E: float = BEARING_STEEL_E, nu: float = BEARING_STEEL_NU,
                   E_ring: float | None = None, nu_ring: float | None = None
                   ) -> BallContactPressure:
    """Pressure and ellipse of each ball contact (module docstring), batched.

    Parameters
    ----------
    ball_diameter, pitch_diameter : float
        ``D``, ``d_m`` [m].
    f_i, f_o : float
        Groove curvature factors ``r / D`` (> 0.5).
    load, contact_angle : array (S, N)
        Ball loads [N] (>= 0) and loaded contact angles [rad] (inner contact; also the
        outer one unless given).
    outer_load, outer_contact_angle : array (S, N), optional
        Outer-contact load and angle when they differ (centrifugal force).
    shoulder_heights : (float, float), optional
        Heights [m] of the loaded-side shoulders above the groove bottom, inner and outer
        ring: enables the truncation check.
    E, nu, E_ring, nu_ring : float
        Elastic constants of balls and rings [Pa, -] (bearing steel by default).

    Examples
    --------
    >>> c = ball_pressures(12.7e-3, 65e-3, 0.52, 0.52, [[1000.0]], [[0.0]])
    >>> (c.max_pressure[0, 0] / 1e9).round(3).tolist()
    [1.875, 1.567]
    """
    where = "ball_pressures"
    for name, f in (("f_i", f_i), ("f_o", f_o)):
        if not f > 0.5:
            raise ModelError(f"{name} = {f!r} must be > 0.5", where)
    if not 0.0 < ball_diameter < pitch_diameter:
        raise ModelError(f"ball diameter {ball_diameter} m must be in (0, pitch diameter "
                         f"{pitch_diameter} m)", where)
    q_in = np.atleast_2d(np.asarray(load, dtype=float))
    a_in = np.broadcast_to(np.atleast_2d(np.asarray(contact_angle, dtype=float)), q_in.shape)
    q_out = q_in if outer_load is None else np.atleast_2d(np.asarray(outer_load, float))
    a_out = a_in if outer_contact_angle is None else np.broadcast_to(
        np.atleast_2d(np.asarray(outer_contact_angle, dtype=float)), q_out.shape)
    q = np.stack(np.broadcast_arrays(q_in, q_out), axis=-1)
    alpha = np.stack(np.broadcast_arrays(a_in, a_out), axis=-1)
    if not (np.isfinite(q).all() and np.isfinite(alpha).all()):
        raise ModelError("loads and contact angles must be finite", where)
    if (q < 0).any():
        raise ModelError("contact loads must be >= 0 [N]", where)
    e_star = _modulus(E, nu, E_ring, nu_ring)
    gamma = ball_diameter * np.cos(alpha) / pitch_diameter
    sign = np.array([1.0, -1.0])  # inner race: convex, outer: concave in rolling direction
    curv_x = 2.0 / ball_diameter * (1.0 + sign * gamma / (1.0 - sign * gamma))
    grooves = np.array([f_i, f_o]) * ball_diameter
    curv_y = 2.0 / ball_diameter - 1.0 / grooves
    rx, ry = 1.0 / curv_x, np.broadcast_to(1.0 / curv_y, curv_x.shape)
    k, big_e, _ = ellipticity(np.maximum(rx, ry) / np.minimum(rx, ry))
    r_eff = 1.0 / (curv_x + curv_y)
    a1 = (3.0 * k**2 * big_e * r_eff / (math.pi * e_star)) ** (1.0 / 3.0)
    cube = np.cbrt(q)
    a, b = a1 * cube, a1 / k * cube
    p0 = np.divide(3.0 * q, 2.0 * math.pi * a * b, out=np.zeros(q.shape), where=q > 0)
    margin = None
    if shoulder_heights is not None:
        heights = np.asarray(shoulder_heights, dtype=float)
        if heights.shape != (2,) or not np.isfinite(heights).all() or (heights <= 0).any():
            raise ModelError("shoulder_heights must be two positive heights [m] (inner, "
                             f"outer), got {shoulder_heights!r}", where)
        theta_s = np.arccos(np.clip(1.0 - heights / grooves, -1.0, 1.0))
        half = np.arcsin(np.clip(a / grooves, 0.0, 1.0))
        margin = theta_s - np.abs(alpha) - half
    return BallContactPressure(load=q, contact_angle=alpha, max_pressure=p0, semi_major=a,
                               semi_minor=b, shoulder_margin=margin)


def roller_pressures(roller_diameter: float, pitch_diameter: float, contact_angle: float,
                     line_load: ArrayLike, xi: ArrayLike, *, E: float = BEARING_STEEL_E,
                     nu: float = BEARING_STEEL_NU, E_ring: float | None = None,
                     nu_ring: float | None = None) -> RollerContactPressure:
    """Line-contact pressure of each slice (module docstring).

    Parameters
    ----------
    roller_diameter, pitch_diameter : float
        Mean roller diameter ``D`` and pitch diameter [m].
    contact_angle : float
        Nominal contact angle [rad].
    line_load : array (S, Z, K)
        Load per unit length of each slice [N/m], >= 0.
    xi : array (K,)
        Slice centres (fractions of the effective length).

    Examples
    --------
    >>> c = roller_pressures(10e-3, 65e-3, 0.0, [[[1e6]]], [0.0])
    >>> (c.max_pressure[0, 0, 0] / 1e9).round(4).tolist()
    [2.9323, 2.5111]
    """
    where = "roller_pressures"
    if not 0.0 < roller_diameter < pitch_diameter:
        raise ModelError(f"roller diameter {roller_diameter} m must be in (0, pitch "
                         f"diameter {pitch_diameter} m)", where)
    q = np.asarray(line_load, dtype=float)
    if not np.isfinite(q).all() or (q < 0).any():
        raise ModelError("line loads must be finite and >= 0 [N/m]", where)
    e_star = _modulus(E, nu, E_ring, nu_ring)
    gamma = roller_diameter * math.cos(contact_angle) / pitch_diameter
    radii = 0.5 * roller_diameter * np.array([1.0 - gamma, 1.0 + gamma])
    qq = q[..., None]
    return RollerContactPressure(
        xi=np.asarray(xi, dtype=float), line_load=q,
        max_pressure=np.sqrt(qq * e_star / (math.pi * radii)),
        half_width=np.sqrt(4.0 * qq * radii / (math.pi * e_star)))


def contact_pressures(bearing: Any, delta: ArrayLike, psi: ArrayLike | None = None, *,
                      shoulder_heights: tuple[float, float] | None = None,
                      **materials: float) -> BallContactPressure | RollerContactPressure:
    """Pressures of a ``BallBearing`` or ``RollerBearing`` at ring displacements.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
    delta : array (S, 5)
        Relative displacements ``[x, y, z, rx, ry]`` [m, rad].
    psi : array (S, N), optional
        Element angles [rad]; default ``bearing.element_angles(0)``.
    shoulder_heights : (float, float), optional
        Balls: inner and outer shoulder heights [m] for the truncation check.
    **materials
        ``E``, ``nu``, ``E_ring``, ``nu_ring``.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> b = BallBearing.from_geometry(n_balls=9, pitch_diameter=65e-3,
    ...                               ball_diameter=12.7e-3, f_i=0.52, f_o=0.52)
    >>> c = contact_pressures(b, [[20e-6, 0, 0, 0, 0]])
    >>> bool(c.max_pressure[0, 0, 0] > c.max_pressure[0, 0, 1] > 0)
    True
    """
    psi_arr = bearing.element_angles(0.0) if psi is None else psi
    if hasattr(bearing, "n_balls"):
        if bearing.f_i is None or bearing.f_o is None:
            raise ModelError("contact pressures need the groove curvature factors f_i and "
                             "f_o (the bearing has only A0)", bearing.label)
        st = bearing.state(delta, psi_arr)
        return ball_pressures(bearing.ball_diameter, bearing.pitch_diameter, bearing.f_i,
                              bearing.f_o, st.element_load, st.contact_angle,
                              outer_load=st.outer_load,
                              outer_contact_angle=st.outer_contact_angle,
                              shoulder_heights=shoulder_heights, **materials)
    if hasattr(bearing, "slice_deflections"):
        if getattr(bearing, "slice_model", "independent") == "influence":
            line = bearing.slice_loads(delta, psi_arr) * (bearing.n_slices
                                                          / bearing.effective_length)
        else:
            deflection = np.maximum(bearing.slice_deflections(delta, psi_arr), 0.0)
            line = bearing.kn * deflection**bearing.exponent / bearing.effective_length
        return roller_pressures(bearing.diameter_for("contact pressures"), bearing.pitch_diameter,
                                bearing.contact_angle, line, bearing._line.xi, **materials)
    raise ModelError(f"contact pressures are implemented for BallBearing and RollerBearing, "
                     f"not {type(bearing).__name__}", "contact_pressures")
