"""Contact-level formulas of lubricated (EHL) rolling contacts: lubricant, entrainment
speed, central film thickness, film and Hertz stiffness in series, race combination.

Seed 002 section 3.2 (eqs 3.1-3.5); the bearing-level matrices are in
:mod:`rotorsim.elements.rolling.lubrication`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_point import (
    BEARING_STEEL_E,
    BEARING_STEEL_NU,
)
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
STEEL_REDUCED_MODULUS = BEARING_STEEL_E / (1.0 - BEARING_STEEL_NU**2)
"""``E'`` of two bearing-steel bodies (208 GPa, 0.3): 2.2857e11 Pa."""
POINT_FILM_EXPONENT = 0.067
"""``h ~ F^-0.067`` (Hamrock-Dowson central film): ``K_EHL = -F / (0.067 h)``."""
LINE_FILM_EXPONENT = 0.13
"""``h ~ F^-0.13`` (Dowson-Higginson): ``K_EHL = -F / (0.13 h)``."""


@dataclass(frozen=True)
class Lubricant:
    """Lubricant and contact parameters of the EHL model (seed 002 section 3.7).

    Parameters
    ----------
    eta0 : float
        Dynamic viscosity at the inlet (ambient pressure) [Pa s].
    alpha : float
        Pressure-viscosity coefficient [1/Pa] (mineral oils 1e-8 to 3e-8).
    reduced_modulus : float
        ``E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` [Pa] of the contacting bodies;
        default bearing steel.
    name : str
        Label.

    Examples
    --------
    >>> oil = Lubricant(eta0=0.04, alpha=2.0e-8)
    >>> round(oil.alpha * oil.reduced_modulus)
    4571
    """

    eta0: float
    alpha: float
    reduced_modulus: float = STEEL_REDUCED_MODULUS
    name: str = ""

    def __post_init__(self) -> None:
        for key in ("eta0", "alpha", "reduced_modulus"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int | float) \
                    or not math.isfinite(value) or value <= 0.0:
                raise ModelError(f"{key} must be a positive finite number (SI), got "
                                 f"{value!r}", f"Lubricant {self.name!r}")


def entrainment_speed(shaft_speed: ArrayLike, element_diameter: float,
                      pitch_diameter: float, contact_angle: float) -> FloatArray:
    """Entrainment (rolling) speed ``u = |W| d_m (1 - gamma^2)/4`` [m/s] (module docstring).

    Examples
    --------
    >>> round(float(entrainment_speed(400.0, 0.0127, 0.065, 0.0)), 4)
    6.2519
    """
    gamma = element_diameter * math.cos(contact_angle) / pitch_diameter
    speed = np.abs(np.asarray(shaft_speed, dtype=float))
    return np.asarray(speed * pitch_diameter * (1.0 - gamma * gamma) / 4.0)


def central_film_point(load: ArrayLike, speed: ArrayLike, rx: float, ry: float,
                       lubricant: Lubricant) -> FloatArray:
    """Hamrock-Dowson central film thickness [m] of a point contact (seed 002 sec 3.2).

    ``load`` [N] > 0, entrainment ``speed`` [m/s] > 0, radii ``rx`` (rolling direction)
    and ``ry`` [m].

    Examples
    --------
    >>> oil = Lubricant(eta0=0.04, alpha=2.0e-8)
    >>> round(float(central_film_point(500.0, 3.0, 3.8e-3, 0.16, oil)) * 1e6, 3)
    0.397
    """
    e = lubricant.reduced_modulus
    u = lubricant.eta0 * np.asarray(speed, dtype=float) / (e * rx)
    w = np.asarray(load, dtype=float) / (e * rx * rx)
    k = 1.0339 * (ry / rx) ** 0.636
    return np.asarray(2.69 * rx * u**0.67 * (lubricant.alpha * e) ** 0.53
                      * w**-POINT_FILM_EXPONENT * (1.0 - 0.61 * math.exp(-0.73 * k)))


def central_film_line(line_load: ArrayLike, speed: ArrayLike, rx: float,
                      lubricant: Lubricant) -> FloatArray:
    """Dowson-Higginson central film thickness [m] of a line contact (seed 002 sec 3.2).

    ``line_load`` = load per unit length [N/m] > 0, entrainment ``speed`` [m/s] > 0.

    Examples
    --------
    >>> oil = Lubricant(eta0=0.04, alpha=2.0e-8)
    >>> round(float(central_film_line(2.0e5, 3.0, 3.0e-3, oil)) * 1e6, 3)
    0.428
    """
    e = lubricant.reduced_modulus
    u = lubricant.eta0 * np.asarray(speed, dtype=float) / (e * rx)
    w = np.asarray(line_load, dtype=float) / (e * rx)
    return np.asarray(4.0 / 3.0 * 1.6 * rx * u**0.7 * (lubricant.alpha * e) ** 0.6
                      * w**-LINE_FILM_EXPONENT)


def series_stiffness(k_hertz: ArrayLike, k_film: ArrayLike) -> FloatArray:
    """Eq 3.1: ``k = K_H K_EHL / (K_EHL - K_H)`` [N/m], ``K_EHL = dF/dh < 0``.

    Examples
    --------
    >>> float(series_stiffness(1e8, -1e8))
    50000000.0
    """
    kh, kf = np.asarray(k_hertz, dtype=float), np.asarray(k_film, dtype=float)
    return np.asarray(kh * kf / (kf - kh))


def combine_races(k_i: ArrayLike, c_i: ArrayLike, k_o: ArrayLike, c_o: ArrayLike,
                  frequency: float = 0.0) -> tuple[FloatArray, FloatArray]:
    """Inner and outer contact in series (eq 3.5, ``s = 1``): ``(k, c)`` at ``frequency``.

    Examples
    --------
    >>> k, c = combine_races(2.0, 1.0, 2.0, 1.0)
    >>> float(k), float(c)
    (1.0, 0.5)
    """
    ki, ci, ko, co = (np.asarray(x, dtype=float) for x in (k_i, c_i, k_o, c_o))
    w2 = frequency * frequency
    den = (ko + ki) ** 2 + (co + ci) ** 2 * w2
    k = (ki * (ko * ko + w2 * co * co) + ko * (ki * ki + w2 * ci * ci)) / den
    c = (ci * (ko * ko + w2 * co * co) + co * (ki * ki + w2 * ci * ci)) / den
    return np.asarray(k), np.asarray(c)
