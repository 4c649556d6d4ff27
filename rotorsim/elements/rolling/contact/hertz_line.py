"""Line-contact load-deflection constants of rollers (exponent 10/9).

A roller squeezed between two raceways carries ``Q = Kn delta^n`` with ``n = 10/9``.
Two conventions for ``Kn`` are in use and differ by ``2^(10/9) = 2.16``:

* **per contact** (Palmgren): ``delta`` is the approach of *one* raceway towards the
  roller, ``Q = K_c delta_c^n``;
* **whole roller** (ISO/TS 16281, Lim and Singh, this package): ``delta`` is the total
  approach of the two raceways, ``delta = delta_inner + delta_outer``.

With equal inner and outer contacts ``delta = 2 delta_c`` so that
``Kn_roller = K_c / 2^n``. Every ``Kn`` of :class:`RollerBearing
<rotorsim.elements.rolling.roller.bearing.RollerBearing>` is a whole-roller constant in SI units
``N/m^n``. Published values are often in ``N/mm^n`` with the length in mm; use
:func:`constant_to_si`.

References
----------
ISO/TS 16281:2008 (``c_L = 35948 L^(8/9)`` N/mm^(10/9), whole roller, steel);
seed 002 eqs 2.5-2.7 and 2.19 (Palmgren ``delta = 3.84e-5 Q^0.9 / L^0.8`` per contact,
N and mm; slice constant ``k_lc`` per unit length); reference README (2^(10/9) remark).

The integrals of the line load ``Kn delta(xi)^n`` along a roller are in
:mod:`~rotorsim.elements.rolling.contact.line_integrals` (:func:`tilted_line_integrals`,
:func:`line_moments` and :func:`slice_weights` are importable from here too).
"""

from __future__ import annotations

import math

from rotorsim.elements.rolling.contact.line_integrals import (
    line_moments,
    slice_weights,
    tilted_line_integrals,
)
from rotorsim.errors import ModelError

__all__ = [
    "ISO_LINE_COEFFICIENT",
    "LINE_EXPONENT",
    "PALMGREN_COMPLIANCE",
    "constant_to_si",
    "iso_roller_constant",
    "line_half_width",
    "line_moments",
    "palmgren_contact_constant",
    "palmgren_roller_constant",
    "roller_constant_from_contacts",
    "slice_constant",
    "slice_weights",
    "tilted_line_integrals",
]

LINE_EXPONENT = 10.0 / 9.0
"""Load-deflection exponent of a line contact."""

ISO_LINE_COEFFICIENT = 35948.0
"""ISO/TS 16281 whole-roller coefficient [N/mm^(10/9)] of ``c_L = 35948 L^(8/9)``, L in mm."""

PALMGREN_COMPLIANCE = 3.84e-5
"""Palmgren per-contact compliance of ``delta = 3.84e-5 Q^0.9 / L^0.8`` (N, mm; steel)."""


def _positive(value: float, name: str, where: str) -> float:
    if not (math.isfinite(value) and value > 0.0):
        raise ModelError(f"{name} must be a positive finite number, got {value!r}", where)
    return float(value)


def constant_to_si(k_mm: float, exponent: float = LINE_EXPONENT) -> float:
    """Convert a load-deflection constant from ``N/mm^n`` to ``N/m^n``.

    Examples
    --------
    >>> round(constant_to_si(1.0, 1.5))
    31623
    """
    return _positive(k_mm, "constant", "constant_to_si") * 1000.0 ** exponent


def iso_roller_constant(length: float) -> float:
    """Whole-roller constant ``Kn`` of ISO/TS 16281 for steel rollers [N/m^(10/9)].

    ``Kn = 35948 (L/mm)^(8/9)`` N/mm^(10/9), i.e. ``3.5948e10 L^(8/9)`` with L in m.

    Parameters
    ----------
    length : float
        Effective roller length ``L`` [m].

    Examples
    --------
    >>> f"{iso_roller_constant(1.0):.4e}"
    '3.5948e+10'
    """
    length_mm = 1000.0 * _positive(length, "effective length", "iso_roller_constant")
    return constant_to_si(ISO_LINE_COEFFICIENT * length_mm ** (8.0 / 9.0))


def palmgren_contact_constant(length: float) -> float:
    """Per-contact constant of Palmgren's line-contact formula [N/m^(10/9)].

    Inverts ``delta_c = 3.84e-5 Q^0.9 / L^0.8`` (N, mm; steel, seed 002 eq 2.6):
    ``K_c = 3.84e-5^(-10/9) L^(8/9)`` = about ``8.06e4 L^(8/9)`` N/mm^(10/9).

    Parameters
    ----------
    length : float
        Effective roller length ``L`` [m].

    Examples
    --------
    >>> f"{palmgren_contact_constant(0.001) / 1000.0 ** (10 / 9):.4g}"
    '8.059e+04'
    """
    length_mm = 1000.0 * _positive(length, "effective length", "palmgren_contact_constant")
    k_mm = PALMGREN_COMPLIANCE ** (-LINE_EXPONENT) * length_mm ** (8.0 / 9.0)
    return constant_to_si(k_mm)


def roller_constant_from_contacts(k_inner: float, k_outer: float,
                                  exponent: float = LINE_EXPONENT) -> float:
    """Whole-roller constant of an inner and an outer contact in series.

    ``delta = (Q/k_i)^(1/n) + (Q/k_o)^(1/n)`` gives
    ``Kn = (k_i^(-1/n) + k_o^(-1/n))^(-n)``; equal contacts give ``k / 2^n``
    (the ``2^(10/9)`` between Palmgren per contact and whole roller).

    Parameters
    ----------
    k_inner, k_outer : float
        Per-contact constants [N/m^n].
    exponent : float
        Load-deflection exponent ``n``.

    Examples
    --------
    >>> round(roller_constant_from_contacts(1.0, 1.0) * 2 ** (10 / 9), 12)
    1.0
    """
    where = "roller_constant_from_contacts"
    n = _positive(exponent, "exponent", where)
    ki = _positive(k_inner, "inner contact constant", where)
    ko = _positive(k_outer, "outer contact constant", where)
    return float((ki ** (-1.0 / n) + ko ** (-1.0 / n)) ** (-n))


def palmgren_roller_constant(length: float) -> float:
    """Whole-roller constant from Palmgren's per-contact formula [N/m^(10/9)].

    Equal inner and outer contacts: ``palmgren_contact_constant(L) / 2^(10/9)``, about
    ``3.74e4 L^(8/9)`` N/mm^(10/9) (3.8 % above ISO/TS 16281, which uses other elastic
    constants).

    Examples
    --------
    >>> round(palmgren_roller_constant(0.01) / iso_roller_constant(0.01), 3)
    1.038
    """
    k_c = palmgren_contact_constant(length)
    return roller_constant_from_contacts(k_c, k_c, LINE_EXPONENT)


def slice_constant(kn: float, n_slices: int) -> float:
    """Constant of one of ``K`` equal slices of a roller with whole-roller constant ``Kn``.

    A slice of width ``L/K`` carries ``q_k = (Kn/K) delta_k^n`` (the "linearised fraction"
    of the whole-roller stiffness, seed 002 eq 2.7 with ``k_lc L/K``). When the deflection
    is uniform, ``sum_k q_k = Kn delta^n``: ``K`` slices reproduce the whole roller exactly.

    Examples
    --------
    >>> slice_constant(2.0e9, 20)
    100000000.0
    """
    if not isinstance(n_slices, int) or n_slices < 1:
        raise ModelError(f"number of slices must be an integer >= 1, got {n_slices!r}",
                         "slice_constant")
    return _positive(kn, "Kn", "slice_constant") / n_slices


def line_half_width(load: float, length: float, reduced_radius: float,
                    e_prime: float) -> float:
    """Hertz semi-width ``b`` of a line contact [m].

    ``b = sqrt(8 Q R / (pi L E'))`` with ``2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2`` (for two
    identical bodies ``E' = E / (1 - nu^2)``).

    Parameters
    ----------
    load : float
        Contact load ``Q`` [N].
    length : float
        Contact length ``L`` [m].
    reduced_radius : float
        ``R = 1/(1/R1 + 1/R2)`` in the rolling plane [m].
    e_prime : float
        Plane-strain modulus ``E'`` as above [Pa].

    Examples
    --------
    >>> f"{line_half_width(1000.0, 0.01, 0.004, 2.26e11):.3e}"
    '6.713e-05'
    """
    where = "line_half_width"
    q = _positive(load, "load", where)
    ell = _positive(length, "length", where)
    r = _positive(reduced_radius, "reduced radius", where)
    e = _positive(e_prime, "E'", where)
    return math.sqrt(8.0 * q * r / (math.pi * ell * e))
