"""Roller profiles (crowning) and the slicing of a roller along its effective length.

A profile gives the **drop** ``c(xi) >= 0`` [m]: the amount by which the roller (or the sum
of roller and raceway profiles) is relieved at the dimensionless position
``xi = z'/L`` in ``[-1/2, 1/2]`` along the effective length ``L`` (``xi = 0`` at the roller
centre, seed 000 eq 6d). The local contact deflection of a roller is then
``delta(xi) = V + xi L omega - c(xi)`` (seed 000 eqs 6a-6d; seed 002 eq 2.2 for the
crowned, sliced roller).

Profiles: :class:`StraightProfile`, :class:`CircularCrown` (a flat centre and circular
arcs of given length at both ends, or a full crown) and :class:`LogarithmicProfile`
(Lundberg, Johns-Gohar, or with a prescribed end drop).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_line import line_half_width
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]


def slice_centres(n_slices: int) -> FloatArray:
    """Centres ``xi_k = -1/2 + (k + 1/2)/K`` of ``K`` equal slices, shape ``(K,)``.

    Each slice has the dimensionless width ``1/K``; sums over slices are the midpoint rule
    of the integrals along the roller (seed 002 eqs 2.4, 2.12).

    Examples
    --------
    >>> slice_centres(4).tolist()
    [-0.375, -0.125, 0.125, 0.375]
    """
    if not isinstance(n_slices, int | np.integer) or n_slices < 1:
        raise ModelError(f"number of slices must be an integer >= 1, got {n_slices!r}",
                         "slice_centres")
    return -0.5 + (np.arange(n_slices) + 0.5) / n_slices


def _check(value: float, name: str, where: str, allow_zero: bool = False) -> None:
    ok = math.isfinite(value) and (value >= 0.0 if allow_zero else value > 0.0)
    if not ok:
        kind = "non-negative" if allow_zero else "positive"
        raise ModelError(f"{name} must be {kind} and finite, got {value!r}", where)


@dataclass(frozen=True)
class StraightProfile:
    """Straight (cylindrical or conical) generatrix: no drop.

    Examples
    --------
    >>> StraightProfile().drop([0.0, 0.5], 0.01).tolist()
    [0.0, 0.0]
    """

    @property
    def is_straight(self) -> bool:
        return True

    def validate(self, length: float, where: str) -> None:
        """Nothing to check."""

    def drop(self, xi: ArrayLike, length: float) -> FloatArray:
        """Drop [m] at dimensionless positions ``xi`` (zero)."""
        return np.zeros_like(np.asarray(xi, dtype=float))


@dataclass(frozen=True)
class CircularCrown:
    """Flat centre with circular arcs at both ends, tangent to the flat part.

    Parameters
    ----------
    crown_drop : float
        Drop at each end of the effective length ``D`` [m].
    crown_length : float, optional
        Axial length ``l_c`` of each crowned end zone [m]; ``None`` crowns the whole
        length (``l_c = L/2``, a single arc). The arc radius is
        ``R = (l_c^2 + D^2) / (2 D)`` and the drop at distance ``x_e`` into the crowned zone
        is ``R - sqrt(R^2 - x_e^2)`` (about ``x_e^2 / (2R)``).

    Examples
    --------
    >>> c = CircularCrown(crown_drop=10e-6)
    >>> [round(float(v) * 1e6, 4) for v in c.drop([0.0, 0.25, 0.5], 0.02)]
    [0.0, 2.5, 10.0]
    """

    crown_drop: float
    crown_length: float | None = None

    @classmethod
    def from_radius(cls, crown_radius: float, crown_length: float) -> CircularCrown:
        """Crown of arc radius ``R`` [m] over end zones of length ``l_c`` [m].

        Examples
        --------
        >>> round(CircularCrown.from_radius(2.0, 0.002).crown_drop * 1e6, 3)
        1.0
        """
        _check(crown_radius, "crown radius", "CircularCrown")
        _check(crown_length, "crown length", "CircularCrown")
        if crown_length > crown_radius:
            raise ModelError(f"crown length {crown_length} m exceeds the crown radius "
                             f"{crown_radius} m", "CircularCrown")
        drop = crown_radius - math.sqrt(crown_radius**2 - crown_length**2)
        return cls(crown_drop=drop, crown_length=crown_length)

    @property
    def is_straight(self) -> bool:
        return self.crown_drop == 0.0

    def validate(self, length: float, where: str) -> None:
        """Check the drop and that the crowned zones fit in the effective length."""
        _check(self.crown_drop, "crown drop", where, allow_zero=True)
        if self.crown_length is not None:
            _check(self.crown_length, "crown length", where)
            if self.crown_length > 0.5 * length:
                raise ModelError(f"crown length {self.crown_length} m exceeds half the "
                                 f"effective length {length} m", where)

    def drop(self, xi: ArrayLike, length: float) -> FloatArray:
        """Drop [m] at dimensionless positions ``xi`` in ``[-1/2, 1/2]``."""
        x = np.abs(np.asarray(xi, dtype=float)) * length
        if self.crown_drop == 0.0:
            return np.zeros_like(x)
        zone = 0.5 * length if self.crown_length is None else self.crown_length
        radius = (zone**2 + self.crown_drop**2) / (2.0 * self.crown_drop)
        x_e = np.clip(x - (0.5 * length - zone), 0.0, zone)
        return np.asarray(x_e**2 / (radius + np.sqrt(radius**2 - x_e**2)))


@dataclass(frozen=True)
class LogarithmicProfile:
    """Logarithmic crown ``c(xi) = A ln(1 / (1 - B (2 xi)^2))``.

    Parameters
    ----------
    scale : float
        ``A`` [m]. Lundberg's profile uses ``A = 2 Q / (pi L E')`` for a design load ``Q``
        (``2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2``).
    shape : float
        ``B`` in ``(0, 1]``; ``B = 1`` (Lundberg) gives an infinite drop at the ends, which
        the slices (centred inside the length) never reach. Johns-Gohar:
        ``B = 1 - 0.3033 b / a`` with ``a = L/2`` and ``b`` the Hertz semi-width at the
        design load. The end drop is ``-A ln(1 - B)``.

    References
    ----------
    Lundberg (1939); Johns and Gohar (1981), both as quoted by Fujiwara and Kawase,
    *Logarithmic profiles of rollers in roller bearings and optimization of the profiles*,
    NTN Technical Review 75 (2007).

    Examples
    --------
    >>> p = LogarithmicProfile.with_end_drop(scale=2e-6, end_drop=10e-6)
    >>> [round(float(v) * 1e6, 6) for v in p.drop([0.0, 0.5], 0.02)]
    [0.0, 10.0]
    """

    scale: float
    shape: float = 1.0

    @classmethod
    def lundberg(cls, design_load: float, length: float, e_prime: float) -> LogarithmicProfile:
        """Lundberg's profile for the design load ``Q`` [N], length ``L`` [m], ``E'`` [Pa]."""
        _check(design_load, "design load", "LogarithmicProfile")
        _check(length, "length", "LogarithmicProfile")
        _check(e_prime, "E'", "LogarithmicProfile")
        return cls(scale=2.0 * design_load / (math.pi * length * e_prime), shape=1.0)

    @classmethod
    def johns_gohar(cls, design_load: float, length: float, e_prime: float,
                    reduced_radius: float) -> LogarithmicProfile:
        """Johns-Gohar profile; ``reduced_radius`` [m] gives the Hertz semi-width ``b``.

        Examples
        --------
        >>> p = LogarithmicProfile.johns_gohar(5000.0, 0.02, 2.26e11, 0.005)
        >>> round(p.shape, 4), round(float(p.drop([0.5], 0.02)[0]) * 1e6, 3)
        (0.9964, 3.963)
        """
        base = cls.lundberg(design_load, length, e_prime)
        b = line_half_width(design_load, length, reduced_radius, e_prime)
        shape = 1.0 - 0.3033 * b / (0.5 * length)
        if shape <= 0.0:
            raise ModelError(f"Hertz semi-width {b} m too large for length {length} m",
                             "LogarithmicProfile.johns_gohar")
        return cls(scale=base.scale, shape=shape)

    @classmethod
    def with_end_drop(cls, scale: float, end_drop: float) -> LogarithmicProfile:
        """Profile of scale ``A`` [m] whose drop at the ends equals ``end_drop`` [m]."""
        _check(scale, "scale", "LogarithmicProfile")
        _check(end_drop, "end drop", "LogarithmicProfile")
        return cls(scale=scale, shape=-math.expm1(-end_drop / scale))

    @property
    def is_straight(self) -> bool:
        return False

    def validate(self, length: float, where: str) -> None:
        """Check ``A > 0`` and ``0 < B <= 1``."""
        _check(self.scale, "logarithmic profile scale", where)
        if not (math.isfinite(self.shape) and 0.0 < self.shape <= 1.0):
            raise ModelError(f"logarithmic profile shape must be in (0, 1], got "
                             f"{self.shape!r}", where)

    def drop(self, xi: ArrayLike, length: float) -> FloatArray:
        """Drop [m] at dimensionless positions ``xi`` in ``[-1/2, 1/2]``."""
        u = self.shape * (2.0 * np.asarray(xi, dtype=float)) ** 2
        with np.errstate(divide="ignore"):
            return np.asarray(-self.scale * np.log1p(-np.minimum(u, 1.0)))


RollerProfile = StraightProfile | CircularCrown | LogarithmicProfile
"""Any roller profile accepted by :class:`RollerBearing`."""
