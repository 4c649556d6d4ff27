"""Bearing friction torque by Palmgren's load and viscous terms, ``M = M_0 + M_1``.

Palmgren's model (Harris & Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed.,
ch. 9), with the formulas, factors and load rules as printed in Schaeffler's catalogue HR 1
*Rolling Bearings* (Schaeffler KG, June 2006, "Friction and increases in temperature",
pp. 55-60), in its units inside (N mm, mm, rpm, cSt = mm^2/s) and SI at the interface::

    M_0 = 1e-7 f_0 (nu_0 n)^(2/3) d_m^3     nu_0 n >= 2000     (viscous, speed dependent)
    M_0 = 160e-7 f_0 d_m^3                   nu_0 n <  2000
    M_1 = f_1 P_1 d_m                                           (load dependent)

with ``n`` the speed of the turning ring [rpm], ``nu_0`` the lubricant's kinematic viscosity
at operating temperature (of the base oil for grease), ``d_m`` the pitch diameter.
**Convention for ``f_0``**: a factor of the bearing series and the lubrication (grease or
oil mist, oil bath or recirculating oil) that the user gives from a catalogue; no default
here. **``f_1``**: given, or ``z (P_0 / C_0)^y`` (:data:`F1_FACTORS`, the catalogue's values
for one named series per type), ``P_0`` the static equivalent load, taken here as the load
``P_1`` of the friction formula (a stated simplification: ISO 76's ``P_0 = X_0 F_r + Y_0
F_a`` differs by its factors). ``P_1`` (:data:`P1_RULES`, the catalogue's rules for single
bearings): deep groove ``3.3 F_a - 0.1 F_r``, angular contact ``F_a - 0.1 F_r``, thrust ball
``F_a``, tapered ``0.8 F_a cot a`` (the catalogue's ``2 Y F_a`` with ISO 281's ``Y = 0.4 cot
a``), spherical ``1.6 F_a / e`` for ``F_a / F_r > e``, else ``F_r (1 + 0.6 (F_a / (e
F_r))^3)`` with ``e = 1.5 tan a`` (ISO 281's ``e`` of double-row roller bearings),
cylindrical ``F_r``; never below ``F_r``. The torque opposes the relative rotation of the
rings; it is counted positive (the sign of a friction torque in
:mod:`rotorsim.analyses.transient.torque_laws`).

The loads come from any analysis: a bearing equilibrium (its ``load``), the reactions of a
static rotor, or a transient's bearing-force history; :func:`friction_torque` takes arrays
of samples. :meth:`PalmgrenFriction.torque_law` gives the speed-dependent torque at fixed
loads in the form of the torque laws of torque-driven transients (``torque``, ``slope``,
``reactive``, ``describe``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

F1_FACTORS: dict[str, tuple[float, float]] = {
    "deep_groove": (0.0009, 0.5),
    "angular_contact": (0.001, 0.33),
    "thrust_ball": (0.0012, 0.33),
    "cylindrical": (0.0003, 0.0),
    "tapered": (0.0004, 0.0),
    "spherical": (0.0005, 0.33),
}
"""``(z, y)`` of ``f_1 = z (P_0/C_0)^y`` (``y = 0``: ``f_1 = z``), Schaeffler HR 1 (2006)
pp. 57-59 for the series named: deep groove 62, 63, 64 (the catalogue: 618 ``0.0005``; 160,
60, 619 ``0.0007``; 42, 43 double row ``0.0010``; all ``y = 0.5``); angular contact 70, 72,
73 (and double row); thrust ball 511 to 514 (``P_0 = F_a``); cylindrical with cage 2 (10,
19: ``0.0002``; 3: ``0.00035``; 4, 22, 23, 30: ``0.0004``; full complement ``0.00055``);
tapered all series; spherical 213, 222 (223: ``0.0008, 0.33``; 230, 239: ``0.00075, 0.5``;
231, 240: ``0.0012, 0.5``; 232: ``0.0016, 0.5``; 241: ``0.0022, 0.5``). Give ``f1`` for
another series (docs/validation.md, case 29b)."""
P1_RULES = ("deep_groove", "angular_contact", "thrust_ball", "cylindrical", "tapered",
            "spherical")
"""Bearing types of the ``P_1`` rules (module docstring)."""
_LOW_SPEED = 2000.0  # nu_0 n [cSt rpm] below which M_0 is constant


@dataclass(frozen=True)
class PalmgrenFriction:
    """Palmgren friction of one bearing (module docstring).

    Parameters
    ----------
    bearing_type : str
        One of :data:`P1_RULES`.
    pitch_diameter : float
        ``d_m`` [m].
    f0 : float
        Viscous factor ``f_0`` [-] (type and lubrication; > 0).
    viscosity : float
        Kinematic viscosity ``nu_0`` [m^2/s] at operating temperature (1 cSt = 1e-6).
    C0 : float, optional
        Static load rating [N] (``f_1`` of ball bearings from :data:`F1_FACTORS`).
    contact_angle : float
        Nominal contact angle [rad] (``P_1`` of tapered and spherical rollers).
    f1 : float, optional
        Load factor ``f_1`` [-], instead of the table.

    Examples
    --------
    >>> m = PalmgrenFriction("cylindrical", pitch_diameter=0.1, f0=2.0, viscosity=20e-6)
    >>> round(float(m.torque(5000.0, 0.0, 3000 * math.pi / 30)), 6)   # N m
    0.456524
    """

    bearing_type: str
    pitch_diameter: float
    f0: float
    viscosity: float
    C0: float | None = None
    contact_angle: float = 0.0
    f1: float | None = None

    def __post_init__(self) -> None:
        where = "PalmgrenFriction"
        if self.bearing_type not in P1_RULES:
            raise TypeError(f"{where}: unknown bearing_type {self.bearing_type!r}; valid: "
                            f"{P1_RULES}")
        for key in ("pitch_diameter", "f0", "viscosity", "C0", "f1"):
            value = getattr(self, key)
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, int | float) \
                    or not math.isfinite(value) or value <= 0:
                raise ModelError(f"{key} must be a finite number > 0, got {value!r}", where)
        if self.f1 is None and F1_FACTORS[self.bearing_type][1] != 0.0 and self.C0 is None:
            raise ModelError(f"f1 of a {self.bearing_type} bearing needs C0 (or give f1)",
                             where)
        if self.bearing_type in ("tapered", "spherical") and not 0 < self.contact_angle < 1.5:
            raise ModelError("a tapered or spherical roller bearing needs its contact angle "
                             "(0 < a < 90 deg) for P1", where)

    def load_term(self, radial: ArrayLike, axial: ArrayLike) -> FloatArray:
        """``P_1`` [N] from radial and axial loads [N] (magnitudes; module docstring)."""
        fr, fa = np.broadcast_arrays(np.abs(np.asarray(radial, float)),
                                     np.abs(np.asarray(axial, float)))
        rule = self.bearing_type
        if rule == "deep_groove":
            p1 = 3.3 * fa - 0.1 * fr
        elif rule == "angular_contact":
            p1 = fa - 0.1 * fr
        elif rule == "thrust_ball":
            p1 = fa
        elif rule == "tapered":
            p1 = 0.8 * fa / math.tan(self.contact_angle)
        elif rule == "spherical":
            e = 1.5 * math.tan(self.contact_angle)
            ratio = np.divide(fa, e * fr, out=np.zeros_like(fa), where=fr > 0)
            p1 = np.where(fa > e * fr, 1.6 * fa / e, fr * (1.0 + 0.6 * ratio**3))
        else:
            p1 = fr
        return np.asarray(np.maximum(p1, fr))

    def load_factor(self, p1: ArrayLike) -> FloatArray:
        """``f_1`` [-] at ``P_1`` [N]."""
        if self.f1 is not None:
            return np.full(np.shape(p1), float(self.f1))
        z, y = F1_FACTORS[self.bearing_type]
        if y == 0.0:
            return np.full(np.shape(p1), z)
        assert self.C0 is not None
        return np.asarray(z * (np.asarray(p1, float) / self.C0) ** y)

    def viscous_torque(self, speed: ArrayLike) -> FloatArray:
        """``M_0`` [N m] at ring speeds ``speed`` [rad/s] (sign ignored)."""
        n = np.abs(np.asarray(speed, float)) * 30.0 / math.pi
        nu_n = self.viscosity * 1e6 * n
        dm3 = (self.pitch_diameter * 1e3) ** 3
        high = 1e-7 * self.f0 * np.cbrt(nu_n * nu_n) * dm3
        return np.asarray(np.where(nu_n >= _LOW_SPEED, high, 160e-7 * self.f0 * dm3) * 1e-3)

    def torque(self, radial: ArrayLike, axial: ArrayLike, speed: ArrayLike) -> FloatArray:
        """``M = M_0 + M_1`` [N m] (broadcast over samples), opposing the rotation."""
        p1 = self.load_term(radial, axial)
        load = self.load_factor(p1) * p1 * self.pitch_diameter
        return np.asarray(self.viscous_torque(speed) + load)

    def torque_law(self, radial: float, axial: float) -> BearingFrictionTorque:
        """The torque at fixed loads as a law ``T(W)`` of a torque-driven transient."""
        return BearingFrictionTorque(self, float(radial), float(axial))


@dataclass(frozen=True)
class BearingFrictionTorque:
    """Palmgren friction at fixed bearing loads as a reactive torque law ``T(W)`` [N m]
    (the interface of :mod:`rotorsim.analyses.transient.torque_laws`)."""

    model: PalmgrenFriction
    radial: float
    axial: float

    reactive = True

    def torque(self, speed: float, t: float, angle: float) -> float:
        return float(self.model.torque(self.radial, self.axial, speed))

    def slope(self, speed: float, t: float, angle: float) -> float:
        """``dM_0/dW``: ``(2/3) M_0 / W`` on the viscous branch, 0 below it."""
        m = self.model
        if m.viscosity * 1e6 * abs(speed) * 30.0 / math.pi < _LOW_SPEED:
            return 0.0
        return float(2.0 / 3.0 * m.viscous_torque(speed) / abs(speed))

    def describe(self) -> dict[str, object]:
        m = self.model
        return {"law": "palmgren_friction", "bearing_type": m.bearing_type,
                "pitch_diameter": m.pitch_diameter, "f0": m.f0, "viscosity": m.viscosity,
                "f1": m.f1, "C0": m.C0, "radial": self.radial, "axial": self.axial}


def friction_torque(model: PalmgrenFriction, force: ArrayLike, speed: ArrayLike
                    ) -> FloatArray:
    """Friction torque [N m] of ``S`` samples of bearing force ``(S, 5)``
    ``[Fx, Fy, Fz, Mx, My]`` (the force of a bearing equilibrium, the reaction of a static
    rotor, or a transient's bearing-force history; moments are not part of ``P_1``) at ring
    speeds ``speed`` (S,) or scalar [rad/s].

    Examples
    --------
    >>> m = PalmgrenFriction("deep_groove", pitch_diameter=0.0385, f0=2.0,
    ...                      viscosity=30e-6, C0=7800.0)
    >>> friction_torque(m, [[1000.0, 0.0, 0.0, 0.0, 0.0]], 0.0).shape
    (1,)
    """
    f = np.atleast_2d(np.asarray(force, dtype=float))
    if f.ndim != 2 or f.shape[1] != 5 or not np.isfinite(f).all():
        raise ModelError(f"force must be finite with shape (S, 5), got {np.shape(force)}",
                         "friction_torque")
    return model.torque(np.hypot(f[:, 0], f[:, 1]), f[:, 2], speed)

