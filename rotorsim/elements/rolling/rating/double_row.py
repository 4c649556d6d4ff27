"""Ratings of a double-row bearing: ISO 281 for the unit, ISO/TS 16281 row by row.

* **ISO 281, the unit.** ``C`` of a double-row bearing is the geometry formula with
  ``i = 2`` rows, i.e. ``C_unit = 2^0.7 C_row`` (balls) and ``2^(7/9) C_row`` (rollers) with
  ``C_row`` the rating of one row (:func:`~.iso281.dynamic_load_rating`); ``C0_unit =
  2 C0_row`` (ISO 76). The equivalent load ``P`` uses the double-row factors::

      F_a / F_r <= e:  P = F_r + Y_1 F_a,     F_a / F_r > e:  P = X_2 F_r + Y_2 F_a

  double-row angular-contact ball bearings (ISO 281 Table 3, double-row columns; the 25,
  30 and 40 deg rows as printed in the Koyo and LYC catalogues, the 35 deg row as SKF prints
  it for its 35 deg four-point contact bearings, the 20 deg row as NSK prints it (for its
  18 deg pairs), the 45 deg ``Y_1, X_2, Y_2`` as Schaeffler prints them for its 45 deg
  series 33..-DA; the catalogues print ``e = 1.33`` there, rotorsim keeps ISO's 1.34),
  double-row roller
  bearings with ``a != 0`` (ISO 281 Table 8): ``e = 1.5 tan a``, ``Y_1 = 0.45 cot a``,
  ``X_2 = 0.67``, ``Y_2 = 0.67 cot a``. ``L10 = (C_unit / P)^p``.
* **ISO/TS 16281, per row.** Each row is rated as a single-row bearing (its ``C_row``, its
  own rolling-element loads in its own frame, :class:`~.rated_bearing.RatedBearing`), and
  the rows combine like the raceways of one row, with the Weibull slope ``e`` (10/9 balls,
  9/8 rollers)::

      L10r = (L_row0^(-e) + L_row1^(-e))^(-1/e),     P_ref = C_unit L10r^(-1/p)

  Two equally loaded rows then give ``L10r = 2^(-1/e) L_row``, which is ISO 281's
  ``i^0.7`` (``p = 3, e = 10/9``) and ``i^(7/9)`` (lamina exponent ``p = 4, e = 9/8``) rule
  for ``C`` exactly: the per-row method reduces to the unit's ISO 281 rating in the
  reference case (the tests check it).

A catalogue ``C`` (and ``C0``) in :class:`~.options.RatingOptions` is the unit's; the rows
get ``C / 2^0.7`` (``C / 2^(7/9)``) and ``C0 / 2``.

References
----------
ISO 281:2007 clause 6.1 (``i``), Tables 3 and 8; ISO/TS 16281:2008 clause 7; Koyo
catalogue "Calculation of equivalent load" (koyousa.com technical section 3.1),
double-row angular-contact rows ``e = 0.8: Y1 = 0.78, X2 = 0.63, Y2 = 1.24`` (30 deg) and
``e = 1.14: 0.55, 0.57, 0.93`` (40 deg); LYC "Equivalent dynamic load, angular contact ball
bearings" (25 deg: ``0.68, 0.92, 0.67, 1.41``); Koyo's double-row rows at 24 deg
(``0.66, 0.95, 0.68, 1.45``) and 32 deg (``0.86, 0.73, 0.62, 1.17``), which are the table
interpolated linearly in the angle; SKF Rolling bearings catalogue, four-point contact ball
bearings: ``P = F_r + 0.66 F_a`` (``F_a/F_r <= 0.95``), ``0.6 F_r + 1.07 F_a`` above;
NSK *Super Precision Bearings* (2009), Table 1.1 (20 deg: ``0.57, 1.09, 0.70, 1.63``);
Schaeffler catalogue HR 1 (2006), double row angular contact ball bearings, pp. 251-253
(45 deg: ``P = F_r + 0.47 F_a`` up to ``F_a/F_r = 1.33``, ``0.54 F_r + 0.81 F_a`` above)
(docs/validation.md, case 29b).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.double_row import DoubleRowBearing
from rotorsim.elements.rolling.rating.iso281 import BearingRating
from rotorsim.elements.rolling.rating.iso16281 import LIFE_EXPONENTS
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

_ANGLES = np.radians([20.0, 25.0, 30.0, 35.0, 40.0, 45.0])
_E = np.array([0.57, 0.68, 0.80, 0.95, 1.14, 1.34])
_Y1 = np.array([1.09, 0.92, 0.78, 0.66, 0.55, 0.47])
_X2 = np.array([0.70, 0.67, 0.63, 0.60, 0.57, 0.54])
_Y2 = np.array([1.63, 1.41, 1.24, 1.07, 0.93, 0.81])
"""ISO 281 Table 3, double-row angular-contact ball bearings (``X_1 = 1``); sources per row in
the module docstring."""
ROW_RATING_POWER = {"ball": 0.7, "roller": 7.0 / 9.0}
"""ISO 281 exponent of the row count ``i`` in ``C``."""


def double_row_factors(kind: str, contact_angle: float) -> tuple[float, float, float, float]:
    """``(e, Y_1, X_2, Y_2)`` of a double-row bearing (module docstring; ``X_1 = 1``).

    Examples
    --------
    >>> double_row_factors("ball", math.radians(30.0))
    (0.8, 0.78, 0.63, 1.24)
    """
    where = "double_row_factors"
    if kind == "roller":
        if not 0.0 < contact_angle < 0.5 * math.pi:
            raise ModelError("the double-row roller table needs 0 < a < 90 deg (a "
                             "double-row cylindrical bearing carries no rated axial load)",
                             where)
        t = math.tan(contact_angle)
        return 1.5 * t, 0.45 / t, 0.67, 0.67 / t
    if kind != "ball":
        raise ModelError(f"unknown bearing kind {kind!r}; valid: ball, roller", where)
    if not _ANGLES[0] - 1e-12 <= contact_angle <= _ANGLES[-1] + 1e-12:
        raise ModelError(f"no double-row X, Y table at {math.degrees(contact_angle):.4g} deg "
                         f"(20 to 45 deg); give P", where)
    values = (float(np.interp(contact_angle, _ANGLES, t)) for t in (_E, _Y1, _X2, _Y2))
    return tuple(round(v, 12) for v in values)  # type: ignore[return-value]


def double_row_equivalent_load(kind: str, contact_angle: float, radial: ArrayLike,
                               axial: ArrayLike) -> FloatArray:
    """ISO 281 ``P`` [N] of a double-row bearing under radial and axial loads [N] (>= 0).

    Examples
    --------
    >>> float(double_row_equivalent_load("ball", math.radians(30.0), 1000.0, 500.0))
    1390.0
    """
    e, y1, x2, y2 = double_row_factors(kind, contact_angle)
    fr, fa = np.broadcast_arrays(np.asarray(radial, float), np.asarray(axial, float))
    if not (np.isfinite(fr).all() and np.isfinite(fa).all()) or (fr < 0).any() \
            or (fa < 0).any():
        raise ModelError("radial and axial loads must be finite and >= 0 [N]",
                         "double_row_equivalent_load")
    above = fa > e * fr
    return np.asarray(np.where(above, x2 * fr + y2 * fa, fr + y1 * fa))


@dataclass(frozen=True, eq=False)
class DoubleRowLife:
    """ISO/TS 16281 life of ``S`` load distributions of a double-row bearing.

    Attributes
    ----------
    L10r : array (S,)
        Life of the unit [million revolutions] (rows combined).
    row_life : array (S, 2)
        ``L10r`` of row 0 and row 1.
    P_ref : array (S,)
        ``C_unit L10r^(-1/p)`` [N].
    rows : tuple
        The :class:`~.iso16281.ReferenceLife` of each row (raceways, equivalent loads).
    """

    L10r: FloatArray
    row_life: FloatArray
    P_ref: FloatArray
    rows: tuple[Any, Any]


@dataclass(frozen=True, eq=False)
class DoubleRowRating:
    """ISO 281 rating of a :class:`DoubleRowBearing` and its ISO/TS 16281 row lives.

    Parameters
    ----------
    bearing : DoubleRowBearing
    options : RatingOptions, optional
        ``C``, ``C0``: the unit's catalogue ratings (module docstring); default
        ``RatingOptions()``.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> row = BallBearing.from_geometry(n_balls=12, pitch_diameter=0.05,
    ...                                 ball_diameter=0.008, f_i=0.52, f_o=0.53,
    ...                                 contact_angle=math.radians(30.0))
    >>> r = DoubleRowRating(DoubleRowBearing(row, row_spacing=0.02))
    >>> round(r.rating.C / r.row.rating.C, 6) == round(2 ** 0.7, 6)
    True
    """

    bearing: DoubleRowBearing
    options: RatingOptions | None = None
    row: RatedBearing = field(init=False, repr=False)
    rating: BearingRating = field(init=False)

    def __post_init__(self) -> None:
        if not isinstance(self.bearing, DoubleRowBearing):
            raise ModelError(f"bearing must be a DoubleRowBearing, got "
                             f"{type(self.bearing).__name__}", "DoubleRowRating")
        o = RatingOptions() if self.options is None else self.options
        kind = RatedBearing.kind_of(self.bearing.row)
        factor = 2.0 ** ROW_RATING_POWER[kind]
        row_options = dataclasses.replace(
            o, C=None if o.C is None else o.C / factor, C0=None if o.C0 is None else o.C0 / 2)
        row = RatedBearing(self.bearing.row, row_options)
        r = row.rating
        unit = BearingRating(kind, C=r.C * factor, C0=None if r.C0 is None else 2.0 * r.C0,
                             contact_angle=r.contact_angle, f0=r.f0,
                             source=f"{r.source}, i = 2 rows")
        object.__setattr__(self, "row", row)
        object.__setattr__(self, "rating", unit)

    def equivalent_load(self, radial: ArrayLike, axial: ArrayLike) -> FloatArray:
        """ISO 281 ``P`` [N] of the unit (:func:`double_row_equivalent_load`)."""
        return double_row_equivalent_load(self.rating.kind, self.rating.contact_angle,
                                          radial, axial)

    def basic_life(self, radial: ArrayLike, axial: ArrayLike) -> FloatArray:
        """ISO 281 ``L10 = (C_unit / P)^p`` [million revolutions]."""
        return self.rating.basic_life(self.equivalent_load(radial, axial))

    def _rows(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        d = np.atleast_2d(np.asarray(delta, dtype=float))
        p = np.atleast_2d(np.asarray(psi, dtype=float))
        if d.ndim != 2 or d.shape[1] != 5 or not np.isfinite(d).all():
            raise ModelError(f"delta must be finite with shape (S, 5), got {np.shape(delta)}",
                             "DoubleRowRating")
        n = int(self.bearing.row.n_elements)
        if p.shape[-1] != 2 * n:
            raise ModelError(f"psi must have 2 N = {2 * n} angles, got {p.shape[-1]}",
                             "DoubleRowRating")
        p = np.broadcast_to(p, (d.shape[0], 2 * n))
        return self.bearing.row_displacements(d), np.stack([p[:, :n], p[:, n:]])

    def life(self, delta: ArrayLike, psi: ArrayLike, rotating_ring: str | None = None
             ) -> DoubleRowLife:
        """``L10r`` of the unit and of each row at ``delta`` (S, 5), ``psi`` (S, 2 N)."""
        own, p = self._rows(delta, psi)
        rows = (self.row.life(own[0], p[0], rotating_ring),
                self.row.life(own[1], p[1], rotating_ring))
        row_life = np.stack([rows[0].L10r, rows[1].L10r], axis=-1)
        expo, slope = LIFE_EXPONENTS[self.rating.kind]
        with np.errstate(divide="ignore"):
            l10r = np.sum(row_life ** (-slope), axis=-1) ** (-1.0 / slope)
        return DoubleRowLife(L10r=l10r, row_life=row_life,
                             P_ref=self.rating.C * l10r ** (-1.0 / expo), rows=rows)

    def pressures(self, delta: ArrayLike, psi: ArrayLike) -> tuple[Any, Any]:
        """Hertz pressures of each row's contacts (:meth:`RatedBearing.pressures`)."""
        own, p = self._rows(delta, psi)
        return self.row.pressures(own[0], p[0]), self.row.pressures(own[1], p[1])
