"""ISO 281:2007 basic rating life: dynamic load rating, equivalent load and ``L10``.

Conventions (all stated here once; :class:`BearingRating` records which one was used):

* **C** [N] is either a catalogue value (``C=``) or computed from the internal geometry
  with the ISO 281 formulas (units N and mm inside the formulas, SI at the interface)::

      radial ball,   D_w <= 25.4 mm:  C_r = b_m f_c (i cos a)^0.7 Z^(2/3) D_w^1.8
      radial ball,   D_w >  25.4 mm:  C_r = 3.647 b_m f_c (i cos a)^0.7 Z^(2/3) D_w^1.4
      radial roller:                  C_r = b_m f_c (i L_we cos a)^(7/9) Z^(3/4) D_we^(29/27)

  with ``f_c`` from ISO 281 Table 2 (single-row deep-groove and angular-contact ball
  bearings) or Table 7 (roller bearings) at ``D cos(a) / D_pw``, linearly interpolated as
  the standard prescribes, and the rating factor ``b_m`` of ISO 281 Table 1 (1.3 radial
  ball, 1.1 cylindrical and tapered roller, 1.15 spherical roller).
  Catalogue ratings of "upgraded" steels (SKF Explorer, Schaeffler X-life) are higher
  than the ISO 281 formula; pass them as ``C=`` when the catalogue life is wanted.
* **C0** [N] (static rating, needed by the deep-groove ``X, Y`` table) is given or
  computed with ISO 76: ``C0r = f_0 i Z D_w^2 cos a`` (``f_0`` of ISO 76 Table 1) for
  balls, ``C0r = 44 (1 - D_we cos a / D_pw) i Z L_we D_we cos a`` for rollers.
* **P** = ``X F_r + Y F_a`` from ISO 281 Table 3 (deep-groove: ``e`` and ``Y`` as functions
  of ``f_0 F_a / C0r``, ``X = 0.56``; single-row angular contact 20 to 45 deg: fixed
  ``e, X, Y`` per angle, interpolated between the tabulated angles) and for single-row
  roller bearings with ``a != 0``: ``e = 1.5 tan a``, ``X = 0.4``, ``Y = 0.4 cot a``.
* **L10** = ``(C / P)^p`` million revolutions, ``p = 3`` (balls), ``10/3`` (rollers).

Thrust bearings (``a > 45 deg``) and multi-row bearings need a catalogue ``C`` here.

References
----------
ISO 281:2007, clauses 6-7 (Tables 1, 2, 3, 7); ISO 76:2006 Table 1 (``f_0``);
ISO/TR 1281-1:2021 (derivation of ``f_c``; the roller table equals
``207.9 lambda nu gamma^(2/9) (1-gamma)^(29/27) (1+gamma)^(-1/4) [1 + (1.04
((1-gamma)/(1+gamma))^(143/108))^(9/2)]^(-2/9)`` with ``lambda nu = 0.83``, which the
tests check); Harris & Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed., ch. 11.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

KINDS = ("ball", "roller")
"""Rolling-element kinds of the rating formulas."""

BM_FACTORS = {"deep_groove": 1.3, "angular_contact": 1.3, "cylindrical": 1.1,
              "tapered": 1.1, "spherical": 1.15, "needle": 1.1}
"""ISO 281 Table 1 rating factor ``b_m`` of radial bearings by design."""

_GAMMA_FC = np.array([0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12,
                      0.14, 0.16, 0.18, 0.20, 0.22, 0.24, 0.26, 0.28, 0.30, 0.32, 0.34,
                      0.36, 0.38, 0.40])
_FC_BALL = np.array([29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 57.5, 58.8,
                     59.6, 59.9, 59.9, 59.6, 59.0, 58.2, 57.1, 56.0, 54.6, 53.2, 51.7, 50.0,
                     48.4])
"""ISO 281 Table 2, single-row deep-groove and angular-contact ball bearings."""
_GAMMA_FC_ROLLER = np.array([0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10,
                             0.12, 0.14, 0.16, 0.18, 0.20, 0.22, 0.24, 0.26, 0.28, 0.30])
_FC_ROLLER = np.array([52.1, 60.8, 66.5, 70.7, 74.1, 76.9, 79.2, 81.2, 82.8, 84.2, 86.4,
                       87.7, 88.5, 88.8, 88.7, 88.2, 87.5, 86.4, 85.2, 83.8])
"""ISO 281 Table 7, radial roller bearings."""
_GAMMA_F0 = np.round(np.arange(0.0, 0.405, 0.01), 2)
_F0_BALL = np.array([14.7, 14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4, 16.1,
                     15.9, 15.6, 15.4, 15.2, 14.9, 14.7, 14.4, 14.2, 14.0, 13.7, 13.5, 13.2,
                     13.0, 12.8, 12.5, 12.3, 12.1, 11.8, 11.6, 11.4, 11.2, 10.9, 10.7, 10.5,
                     10.3, 10.0, 9.8, 9.6, 9.4])
"""ISO 76 Table 1, ``f_0`` of radial deep-groove and angular-contact ball bearings."""
_F0FA_C0 = np.array([0.172, 0.345, 0.689, 1.03, 1.38, 2.07, 3.45, 5.17, 6.89])
_E_DEEP = np.array([0.19, 0.22, 0.26, 0.28, 0.30, 0.34, 0.38, 0.42, 0.44])
_Y_DEEP = np.array([2.30, 1.99, 1.71, 1.55, 1.45, 1.31, 1.15, 1.04, 1.00])
"""ISO 281 Table 3, single-row deep-groove ball bearings (``X = 0.56`` above ``e``); all 18
values equal an independent transcription of ISO 281:2007 Table 3 and the SKF catalogue
table quoted by another (docs/validation.md, case 29b)."""
_ANGLES_AC = np.radians([20.0, 25.0, 30.0, 35.0, 40.0, 45.0])
_E_AC = np.array([0.57, 0.68, 0.80, 0.95, 1.14, 1.34])
_X_AC = np.array([0.43, 0.41, 0.39, 0.37, 0.35, 0.33])
_Y_AC = np.array([1.00, 0.87, 0.76, 0.66, 0.57, 0.50])
"""ISO 281 Table 3, single-row angular-contact ball bearings: the 25, 30 and 40 deg rows as
printed by LYC, Koyo and a 7206-B product page (case 29), all six rows equal to an independent
transcription of ISO 281:2007 Table 3 (docs/validation.md, case 29b)."""


def _check_positive(value: Any, name: str, where: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ModelError(f"{name} must be a number, got {value!r}", where) from None
    if not (math.isfinite(number) and number > 0.0):
        raise ModelError(f"{name} must be positive and finite, got {value!r}", where)
    return number


def _gamma(element_diameter: float, pitch_diameter: float, contact_angle: float,
           where: str) -> float:
    d = _check_positive(element_diameter, "element diameter", where)
    dm = _check_positive(pitch_diameter, "pitch diameter", where)
    if d >= dm:
        raise ModelError(f"element diameter {d} m must be below the pitch diameter {dm} m",
                         where)
    if not 0.0 <= contact_angle <= math.radians(45.0):
        raise ModelError(f"contact angle {math.degrees(contact_angle):.4g} deg: the ISO 281 "
                         "geometry formulas here cover radial bearings (0 to 45 deg); give "
                         "the catalogue C of a thrust bearing", where)
    return d * math.cos(contact_angle) / dm


def _table(x: float, xs: FloatArray, ys: FloatArray, name: str, where: str) -> float:
    if not xs[0] - 1e-12 <= x <= xs[-1] + 1e-12:
        raise ModelError(f"D cos(a) / D_pw = {x:.4g} outside the ISO table of {name} "
                         f"({xs[0]:g} to {xs[-1]:g})", where)
    return float(np.interp(x, xs, ys))


def fc_factor(kind: str, gamma: float) -> float:
    """ISO 281 ``f_c`` at ``gamma = D cos(a) / D_pw`` (Table 2 balls, Table 7 rollers).

    Examples
    --------
    >>> fc_factor("ball", 0.19), fc_factor("roller", 0.15)
    (59.9, 88.1)
    """
    where = "fc_factor"
    if kind == "ball":
        return _table(gamma, _GAMMA_FC, _FC_BALL, "f_c (Table 2)", where)
    if kind == "roller":
        return _table(gamma, _GAMMA_FC_ROLLER, _FC_ROLLER, "f_c (Table 7)", where)
    raise ModelError(f"unknown bearing kind {kind!r}; valid: {', '.join(KINDS)}", where)


def dynamic_load_rating(kind: str, *, n_elements: int, element_diameter: float,
                        pitch_diameter: float, contact_angle: float = 0.0,
                        effective_length: float | None = None, rows: int = 1,
                        bm: float | None = None) -> float:
    """Basic dynamic radial load rating ``C_r`` [N] from the geometry (ISO 281 clause 6).

    Parameters
    ----------
    kind : {"ball", "roller"}
    n_elements : int
        Rolling elements per row ``Z``.
    element_diameter, pitch_diameter : float
        ``D_w`` (rollers: ``D_we``) and ``D_pw`` [m].
    contact_angle : float
        Nominal contact angle ``a`` [rad], 0 to 45 deg.
    effective_length : float, optional
        ``L_we`` [m] (rollers).
    rows : int
        ``i``.
    bm : float, optional
        Rating factor ``b_m``; default 1.3 (balls) or 1.1 (cylindrical and tapered
        rollers), ISO 281 Table 1.

    Examples
    --------
    >>> round(dynamic_load_rating("ball", n_elements=8, element_diameter=17.462e-3,
    ...                           pitch_diameter=72.5e-3))   # 6309 internal geometry
    52768
    """
    where = f"dynamic_load_rating({kind!r})"
    if kind not in KINDS:
        raise ModelError(f"unknown bearing kind {kind!r}; valid: {', '.join(KINDS)}", where)
    z = _count(n_elements, "n_elements", where)
    i = _count(rows, "rows", where)
    gamma = _gamma(element_diameter, pitch_diameter, contact_angle, where)
    factor = (1.3 if kind == "ball" else 1.1) if bm is None else _check_positive(bm, "bm",
                                                                                where)
    fc = fc_factor(kind, gamma)
    d_mm, cos_a = element_diameter * 1e3, math.cos(contact_angle)
    if kind == "ball":
        if d_mm <= 25.4:
            return factor * fc * (i * cos_a) ** 0.7 * z ** (2.0 / 3.0) * d_mm ** 1.8
        return 3.647 * factor * fc * (i * cos_a) ** 0.7 * z ** (2.0 / 3.0) * d_mm ** 1.4
    if effective_length is None:
        raise ModelError("effective_length is required for a roller bearing", where)
    length_mm = _check_positive(effective_length, "effective_length", where) * 1e3
    return (factor * fc * (i * length_mm * cos_a) ** (7.0 / 9.0) * z ** 0.75
            * d_mm ** (29.0 / 27.0))


def static_load_rating(kind: str, *, n_elements: int, element_diameter: float,
                       pitch_diameter: float, contact_angle: float = 0.0,
                       effective_length: float | None = None, rows: int = 1) -> float:
    """Basic static radial load rating ``C0r`` [N] (ISO 76 clause 6).

    Examples
    --------
    >>> round(static_load_rating("ball", n_elements=9, element_diameter=7.938e-3,
    ...                          pitch_diameter=38.5e-3))   # 6205
    7834
    """
    where = f"static_load_rating({kind!r})"
    z, i = _count(n_elements, "n_elements", where), _count(rows, "rows", where)
    gamma = _gamma(element_diameter, pitch_diameter, contact_angle, where)
    d_mm, cos_a = element_diameter * 1e3, math.cos(contact_angle)
    if kind == "ball":
        f0 = _table(gamma, _GAMMA_F0, _F0_BALL, "f_0 (ISO 76 Table 1)", where)
        return f0 * i * z * d_mm**2 * cos_a
    if kind == "roller":
        if effective_length is None:
            raise ModelError("effective_length is required for a roller bearing", where)
        length_mm = _check_positive(effective_length, "effective_length", where) * 1e3
        return 44.0 * (1.0 - gamma) * i * z * length_mm * d_mm * cos_a
    raise ModelError(f"unknown bearing kind {kind!r}; valid: {', '.join(KINDS)}", where)


def f0_factor(gamma: float) -> float:
    """ISO 76 ``f_0`` of radial ball bearings at ``gamma = D_w cos(a) / D_pw``.

    Examples
    --------
    >>> f0_factor(0.205)
    13.85
    """
    return round(_table(gamma, _GAMMA_F0, _F0_BALL, "f_0 (ISO 76 Table 1)", "f0_factor"), 10)


def _count(value: Any, name: str, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ModelError(f"{name} must be an integer >= 1, got {value!r}", where)
    return int(value)


@dataclass(frozen=True)
class BearingRating:
    """Ratings of one bearing and the conventions they came from.

    Attributes
    ----------
    kind : {"ball", "roller"}
    C : float
        Basic dynamic load rating [N].
    C0 : float or None
        Basic static load rating [N] (None when neither given nor computable).
    contact_angle : float
        Nominal contact angle [rad] (selects the ``X, Y`` table).
    f0 : float or None
        ISO 76 factor ``f_0`` (deep-groove ``X, Y`` table).
    source : str
        ``"catalogue"`` (C given) or ``"ISO 281 geometry (b_m = ..., f_c = ...)"``.

    Examples
    --------
    >>> r = BearingRating.from_geometry("ball", n_elements=9, element_diameter=7.938e-3,
    ...                                 pitch_diameter=38.5e-3)
    >>> round(r.C), r.source
    (14007, 'ISO 281 geometry (b_m = 1.3, f_c = 59.81)')
    """

    kind: str
    C: float
    C0: float | None = None
    contact_angle: float = 0.0
    f0: float | None = None
    source: str = "catalogue"

    def __post_init__(self) -> None:
        where = "BearingRating"
        if self.kind not in KINDS:
            raise ModelError(f"unknown bearing kind {self.kind!r}; valid: {', '.join(KINDS)}",
                             where)
        _check_positive(self.C, "C", where)
        if self.C0 is not None:
            _check_positive(self.C0, "C0", where)

    @property
    def exponent(self) -> float:
        """Life exponent ``p``: 3 for balls, 10/3 for rollers."""
        return 3.0 if self.kind == "ball" else 10.0 / 3.0

    @classmethod
    def from_geometry(cls, kind: str, *, n_elements: int, element_diameter: float,
                      pitch_diameter: float, contact_angle: float = 0.0,
                      effective_length: float | None = None, bm: float | None = None,
                      C: float | None = None, C0: float | None = None) -> BearingRating:
        """Ratings from the internal geometry; a given ``C`` or ``C0`` (catalogue) wins."""
        geo: dict[str, Any] = {"n_elements": n_elements, "element_diameter": element_diameter,
               "pitch_diameter": pitch_diameter, "contact_angle": contact_angle,
               "effective_length": effective_length}
        where = "BearingRating.from_geometry"
        gamma = _gamma(element_diameter, pitch_diameter, contact_angle, where)
        f0 = f0_factor(gamma) if kind == "ball" else None
        if C is None:
            c = dynamic_load_rating(kind, bm=bm, **geo)
            factor = (1.3 if kind == "ball" else 1.1) if bm is None else bm
            source = f"ISO 281 geometry (b_m = {factor:g}, f_c = {fc_factor(kind, gamma):.4g})"
        else:
            c, source = C, "catalogue"
        c0 = static_load_rating(kind, **geo) if C0 is None else C0
        return cls(kind=kind, C=float(c), C0=float(c0), contact_angle=contact_angle, f0=f0,
                   source=source)

    def equivalent_load(self, radial: ArrayLike, axial: ArrayLike) -> FloatArray:
        """Dynamic equivalent load ``P = X F_r + Y F_a`` [N] (ISO 281 Table 3).

        ``radial`` and ``axial`` (broadcastable) [N], non-negative.

        Examples
        --------
        >>> r = BearingRating("ball", C=14000.0, C0=7800.0, f0=14.0)
        >>> round(float(r.equivalent_load(1000.0, 500.0)), 1)
        1366.1
        """
        where = "BearingRating.equivalent_load"
        fr, fa = np.broadcast_arrays(np.asarray(radial, dtype=float),
                                     np.asarray(axial, dtype=float))
        if not (np.isfinite(fr).all() and np.isfinite(fa).all()):
            raise ModelError("loads must be finite", where)
        if (fr < 0).any() or (fa < 0).any():
            raise ModelError("radial and axial loads must be >= 0 (magnitudes) [N]", where)
        x, y, e = self._factors(fa, where)
        ratio = np.divide(fa, fr, out=np.full(fr.shape, np.inf), where=fr > 0)
        above = ratio > e
        return np.asarray(np.where(above, x * fr + y * fa, fr))

    def _factors(self, fa: FloatArray, where: str) -> tuple[Any, Any, Any]:
        """``X, Y, e`` above ``e`` (arrays or floats)."""
        a = self.contact_angle
        if self.kind == "roller":
            if a == 0.0:
                return 1.0, 0.0, np.inf  # cylindrical: the axial load is not rated
            return 0.4, 0.4 / math.tan(a), 1.5 * math.tan(a)
        if a == 0.0:
            if self.C0 is None or self.f0 is None:
                raise ModelError("the deep-groove X, Y table needs C0 and f0 (give them, or "
                                 "build the rating from geometry)", where)
            rel = np.clip(self.f0 * fa / self.C0, _F0FA_C0[0], _F0FA_C0[-1])
            return 0.56, np.interp(rel, _F0FA_C0, _Y_DEEP), np.interp(rel, _F0FA_C0, _E_DEEP)
        if not _ANGLES_AC[0] - 1e-12 <= a <= _ANGLES_AC[-1] + 1e-12:
            raise ModelError(f"no X, Y table for a single-row ball bearing at "
                             f"{math.degrees(a):.4g} deg here (0 or 20 to 45 deg); give P",
                             where)
        return (float(np.interp(a, _ANGLES_AC, _X_AC)), float(np.interp(a, _ANGLES_AC, _Y_AC)),
                float(np.interp(a, _ANGLES_AC, _E_AC)))

    def basic_life(self, P: ArrayLike) -> FloatArray:
        """``L10 = (C / P)^p`` [million revolutions] at equivalent loads ``P`` [N] (> 0).

        Examples
        --------
        >>> round(float(BearingRating("ball", C=14000.0).basic_life(1400.0)), 6)
        1000.0
        """
        p = np.asarray(P, dtype=float)
        if not np.isfinite(p).all() or (p <= 0).any():
            raise ModelError("equivalent load P must be positive and finite [N]",
                             "BearingRating.basic_life")
        return np.asarray((self.C / p) ** self.exponent)
