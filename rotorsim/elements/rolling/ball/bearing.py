"""Rigid-ring ball bearing with 5 relative DOFs (Lim & Singh; seed 000 eqs 1-5, 12-18, 27).

Ball ``j`` at angle ``psi_j`` (from +x towards +y) sees the inner groove curvature centre
displaced relative to the outer one by (seed 000 eq 2, ``delta = [x, y, z, rx, ry]`` of the
inner ring relative to the outer ring)::

    Z_j = A0 sin(alpha0) + z + r_j (rx sin(psi_j) - ry cos(psi_j))     (axial)
    R_j = A0 cos(alpha0) + x cos(psi_j) + y sin(psi_j) - r_L           (radial)
    A_j = sqrt(Z_j^2 + R_j^2),     delta_j = max(A_j - A0, 0)          (eq 1)
    Q_j = Kn delta_j^n,            tan(alpha_j) = Z_j / R_j            (eqs 3, 4)

The strain energy is ``U = Kn / (n + 1) sum delta_j^(n+1)`` (eqs 14-16) and
``F = dU/d delta = sum Q_j g_j`` with ``g_j = dA_j/d delta =
[cos a cos psi, cos a sin psi, sin a, r_j sin a sin psi, -r_j sin a cos psi]`` (eq 4).
Since ``Z_j`` and ``R_j`` are linear in ``delta``, the Hessian of ``A_j`` is
``t_j t_j^T / A_j`` with ``t_j = [-sin a cos psi, -sin a sin psi, cos a, r_j cos a sin psi,
-r_j cos a cos psi]``, so the exact tangent (eq 27, Appendix A1) is::

    K = sum_j  n Kn delta_j^(n-1) g_j g_j^T + (Q_j / A_j) t_j t_j^T

Both terms vanish continuously at first contact for ``n > 1`` (the load law is C1).
A ball is also unloaded when its groove-centre line has turned by more than 90 deg from the
unloaded direction (``Z_j sin(alpha0) + R_j cos(alpha0) <= 0``), where ``A_j > A0`` would
otherwise describe a spurious contact on the far side of the groove.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.elements.base import frozen_scalar
from rotorsim.elements.rolling import geometry
from rotorsim.elements.rolling.ball.checks import CAGES, ResolvedGeometry, resolve_geometry
from rotorsim.elements.rolling.ball.tangent import assemble, ball_sums, directions
from rotorsim.elements.rolling.contact.hertz_point import ball_bearing_constant
from rotorsim.elements.rolling.state import BearingState, FloatArray
from rotorsim.errors import ModelError

__all__ = ["CAGES", "BallBearing"]


class _Constants(NamedTuple):
    """Hot-path constants as read-only 0-d arrays (same values as the floats)."""

    axial0: FloatArray
    radial0: FloatArray
    arm: FloatArray
    a0: FloatArray
    kn: FloatArray  # Kn
    n_kn: FloatArray  # n Kn
    n_minus_1: FloatArray  # n - 1


_ZERO, _ONE = frozen_scalar(0.0), frozen_scalar(1.0)


@dataclass(frozen=True, eq=False)
class BallBearing:
    """Ball bearing with rigid rings (Lim & Singh model, seed 000 eqs 1-5).

    Parameters
    ----------
    n_balls : int
        Number of balls ``N`` (>= 1).
    pitch_diameter : float
        ``d_m`` [m].
    ball_diameter : float
        ``d`` [m], ``0 < d < d_m``.
    Kn : float
        Load-deflection constant of one ball (inner and outer contact in series)
        [N/m^exponent]; :meth:`from_geometry` computes it from Hertz theory.
    contact_angle : float
        Unloaded contact angle ``alpha0`` [rad] in ``[0, pi/2]``: 0 is a deep-groove
        (radial) bearing, ``pi/2`` a thrust bearing.
    f_i, f_o : float, optional
        Groove curvature factors ``r / d`` (> 0.5) of the inner and outer race; they give
        ``A0 = (f_i + f_o - 1) d``.
    A0 : float, optional
        Distance of the groove curvature centres [m], instead of (or consistent with)
        ``f_i`` and ``f_o``.
    radial_clearance : float, optional
        ``r_L`` [m] of seed 000 eq 2b: the radial play *per side*, i.e. the radial
        displacement of the inner ring before a ball at that angle is touched (for
        ``alpha0 = 0``). Negative values are an interference (preload). Default 0.
    diametral_clearance : float, optional
        ``P_d = 2 r_L`` [m] (catalogue "radial internal clearance"); give one of the two
        (or both, consistent).
    exponent : float
        Load-deflection exponent ``n`` (3/2 for point contact; >= 1 so that the tangent
        is finite at first contact).
    psi0 : float
        Angle of ball 0 at shaft angle 0 [rad].
    cage : {"rotating", "fixed"}
        Balls orbit with the cage ratio ``(1 - d cos(alpha0)/d_m)/2`` of the shaft angle
        (inner ring turning, outer fixed), or stay at ``psi0 + 2 pi j / N``.
    groove_center_radius : float or "pitch", optional
        ``r_j`` [m], radius of the locus of the inner groove curvature centres, the arm of
        the tilt terms in eq 2a. Default ``d_m/2 + (f_i - 1/2) d cos(alpha0)`` (Harris &
        Kotzalas); with only ``A0`` given, ``f_i = f_o`` is assumed:
        ``d_m/2 + A0 cos(alpha0)/2``. ``"pitch"``: the pitch radius ``d_m/2``, the tilt
        lever arm of ISO/TS 16281 (and of seed 000 Table 1; bearing tools such as MASTA
        follow it).
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> b = BallBearing(n_balls=12, pitch_diameter=39.3e-3, ball_diameter=7.9e-3,
    ...                 Kn=8.5e9, A0=0.05e-3)
    >>> s = b.state([[10e-6, 0.0, 0.0, 0.0, 0.0]], b.element_angles())
    >>> round(float(s.force[0, 0]), 1), int(s.loaded.sum())
    (739.0, 5)
    """

    n_balls: int
    pitch_diameter: float
    ball_diameter: float
    Kn: float
    contact_angle: float = 0.0
    f_i: float | None = None
    f_o: float | None = None
    A0: float | None = None
    radial_clearance: float | None = None
    diametral_clearance: float | None = None
    exponent: float = 1.5
    psi0: float = 0.0
    cage: str = "rotating"
    groove_center_radius: float | str | None = None
    tag: str | None = None
    _geo: ResolvedGeometry = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_geo", resolve_geometry(self))

    @classmethod
    def from_geometry(cls, *, n_balls: int, pitch_diameter: float, ball_diameter: float,
                      f_i: float, f_o: float, contact_angle: float = 0.0,
                      E_ball: float = 2.08e11, nu_ball: float = 0.3,
                      E_ring: float | None = None, nu_ring: float | None = None,
                      method: str = "exact", **kwargs: Any) -> BallBearing:
        """Bearing whose ``Kn`` follows from Hertz theory (:mod:`.hertz_point`).

        The inner and outer point contacts are evaluated at ``alpha0`` and combined in
        series, ``Kn = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)``; other keyword arguments go to
        the constructor. Materials default to bearing steel (208 GPa, 0.3).
        ``method``: ``"exact"`` (elliptic integrals), ``"hamrock_brewe"`` (curve fits) or
        ``"iso16281"``, the ISO/TS 16281 spring constant
        (:func:`~rotorsim.elements.rolling.contact.iso_spring.iso16281_ball_constant`,
        0.99935 times the exact one; balls and rings of one material, ``E_ball``,
        ``nu_ball``).

        Examples
        --------
        >>> b = BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3,
        ...                               ball_diameter=9.525e-3, f_i=0.515, f_o=0.525)
        >>> round(b.Kn / 1e9, 2)
        10.32
        """
        if method == "iso16281":
            from rotorsim.elements.rolling.contact.iso_spring import (
                iso16281_ball_constant,
            )

            if (E_ring not in (None, E_ball)) or (nu_ring not in (None, nu_ball)):
                raise ModelError("the ISO/TS 16281 spring constant takes balls and rings of "
                                 "one material (give E_ball, nu_ball only)",
                                 "BallBearing.from_geometry")
            kn = iso16281_ball_constant(ball_diameter, pitch_diameter, contact_angle, f_i,
                                        f_o, E=E_ball, nu=nu_ball)
        else:
            kn, _, _ = ball_bearing_constant(ball_diameter, pitch_diameter, contact_angle,
                                             f_i, f_o, E_ball=E_ball, nu_ball=nu_ball,
                                             E_ring=E_ring, nu_ring=nu_ring, method=method)
        return cls(n_balls=n_balls, pitch_diameter=pitch_diameter,
                   ball_diameter=ball_diameter, Kn=kn, contact_angle=contact_angle, f_i=f_i,
                   f_o=f_o, **kwargs)

    @property
    def label(self) -> str:
        return f"BallBearing '{self.tag}'" if self.tag else "BallBearing"

    @property
    def n_elements(self) -> int:
        return int(self.n_balls)

    @property
    def center_distance(self) -> float:
        """Unloaded distance ``A0`` of the groove curvature centres [m]."""
        return self._geo.a0

    @property
    def clearance(self) -> float:
        """Radial clearance ``r_L`` [m] (half the diametral clearance)."""
        return self._geo.clearance

    @property
    def moment_arm(self) -> float:
        """Radius ``r_j`` of the inner groove curvature centres [m] (seed 000 eq 2a)."""
        return self._geo.arm

    @property
    def kappa(self) -> float:
        """Cage ratio: cage angle per shaft angle (0 for ``cage="fixed"``)."""
        return self._geo.kappa

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Ball angles ``psi`` [rad], shape ``(S, N)``, at shaft angles ``phi`` (S,)."""
        return geometry.element_angles(self.n_balls, phi, self._geo.kappa, self.psi0)

    def _inputs(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Check shapes; return ``delta (S, 5)`` and ``psi (S, N)``."""
        return geometry.checked_state(delta, psi, self.n_balls, self.label)

    def _contacts(self, d: FloatArray, c: FloatArray, s: FloatArray
                  ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Groove-centre components ``Z, R``, distance ``A`` and deflection, (..., N), of
        checked ``d`` (..., 5) and ``c, s = cos, sin(psi)`` broadcastable to (..., N)."""
        g, h = self._geo, self._hot
        x, y, z, rx, ry = (d[..., k, None] for k in range(5))
        axial = (h.axial0 + z) + h.arm * (rx * s - ry * c)
        radial = (h.radial0 + x * c) + y * s
        dist = np.sqrt(axial * axial + radial * radial)
        # contact needs A > A0 and the centre line within 90 deg of its unloaded direction:
        # beyond, |A| would describe a ball on the far side of the groove (not physical);
        # for alpha0 = 0 the second test is R > 0 exactly
        front = radial > _ZERO if g.sin0 == 0.0 else axial * g.sin0 + radial * g.cos0 > 0.0
        deflection = np.maximum(dist - h.a0, _ZERO)
        deflection *= front
        return axial, radial, dist, deflection

    @cached_property
    def _hot(self) -> _Constants:
        """Constants of the evaluation as 0-d arrays (cheaper operands than floats)."""
        g, n = self._geo, self.exponent
        values = (g.axial0, g.radial0, g.arm, g.a0, self.Kn, n * self.Kn, n - 1.0)
        return _Constants(*(frozen_scalar(v) for v in values))

    def _load(self, deflection: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``Q = Kn delta^n`` and ``n Kn delta^(n-1)``."""
        n, h = self.exponent, self._hot
        if n == 1.5:
            root = np.sqrt(deflection)
            return h.kn * deflection * root, h.n_kn * root
        if n == 1.0:
            return h.kn * deflection, np.where(deflection > _ZERO, h.kn, _ZERO)
        power = np.power(deflection, h.n_minus_1)
        return h.kn * deflection * power, h.n_kn * power

    def energy(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Strain energy ``U`` [J] of all ball contacts, shape ``(S,)`` (seed 000 eq 16)."""
        d, p = self._inputs(delta, psi)
        deflection = self._contacts(d, np.cos(p), np.sin(p))[3]
        load, _ = self._load(deflection)
        return np.asarray((load * deflection).sum(axis=1) / (self.exponent + 1.0))

    def state(self, delta: ArrayLike, psi: ArrayLike) -> BearingState:
        """Force, exact tangent, energy and ball loads at ``S`` relative displacements.

        Parameters
        ----------
        delta : array (S, 5)
            ``[x, y, z, rx, ry]`` of the inner ring relative to the outer ring [m, rad].
        psi : array (S, N) or (N,)
            Ball angles [rad] (:meth:`element_angles`).

        Returns
        -------
        BearingState
            ``force`` (S, 5) = dU/d delta [N, N m] (seed 000 eq 4), ``stiffness``
            (S, 5, 5) (eq 27), ``energy`` (S,), ball loads ``Q_j`` (S, N), loaded contact
            angles ``atan2(Z_j, R_j)`` (S, N; for unloaded balls the angle of the
            groove-centre line), deflections (S, N), the unit-load directions ``g_j``
            (S, N, 5; ``force = sum_j Q_j g_j``) and the contact stiffnesses
            ``n Kn delta_j^(n-1)`` (S, N).
        """
        d, p = self._inputs(delta, psi)
        c, s = np.cos(p), np.sin(p)
        axial, radial, dist, deflection = self._contacts(d, c, s)
        load, slope = self._load(deflection)
        rows, sin_a, cos_a = _rows(axial, radial, dist, load, slope)
        force, stiffness = assemble(ball_sums(rows, c, s), self._geo.arm)
        return BearingState(force=force, stiffness=stiffness,
                            energy=(load * deflection).sum(axis=1) / (self.exponent + 1.0),
                            element_load=load, contact_angle=np.arctan2(axial, radial),
                            deflection=deflection,
                            contact_direction=directions(sin_a, cos_a, c, s,
                                                          self._geo.arm),
                            element_stiffness=slope)

    def _force_stiffness(self, d: FloatArray, c: FloatArray, s: FloatArray
                         ) -> tuple[FloatArray, FloatArray]:
        """Force (..., 5) and exact tangent (..., 5, 5) only, as :meth:`state`, without
        checks (the hot path of :class:`~rotorsim.elements.rolling.element.RollingBearing`).

        ``d`` (..., 5) checked relative displacements, ``c, s`` (..., N) ``cos, sin(psi)``;
        ``c, s`` may omit leading axes of ``d`` (shared ball angles, e.g. ``d`` (3, S, 5)
        and ``c`` (S, N)).
        """
        axial, radial, dist, deflection = self._contacts(d, c, s)
        load, slope = self._load(deflection)
        rows = _rows(axial, radial, dist, load, slope)[0]
        return assemble(np.matmul(rows, np.swapaxes(geometry.angle_basis(c, s), -1, -2)),
                        self._geo.arm)


def _rows(axial: FloatArray, radial: FloatArray, dist: FloatArray, load: FloatArray,
          slope: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Per-ball ``(P, U, V, F_R, F_Z)`` (..., 5, N) of eq 27 and ``sin, cos`` of the
    contact angles (..., N) (module docstring)."""
    inv = _ONE / np.where(dist > _ZERO, dist, _ONE)  # unloaded balls: load and slope are 0
    sin_a, cos_a = axial * inv, radial * inv
    w_geo = load * inv  # Q / A: the curvature term of the distance A
    sin2, cos2 = sin_a * sin_a, cos_a * cos_a
    rows = np.empty((*dist.shape[:-1], 5, dist.shape[-1]))
    np.add(slope * cos2, w_geo * sin2, out=rows[..., 0, :])  # P: radial-radial
    np.multiply(slope - w_geo, sin_a * cos_a, out=rows[..., 1, :])  # U: radial-axial
    np.add(slope * sin2, w_geo * cos2, out=rows[..., 2, :])  # V: axial-axial
    np.multiply(load, cos_a, out=rows[..., 3, :])  # radial force
    np.multiply(load, sin_a, out=rows[..., 4, :])  # axial force
    return rows, sin_a, cos_a
