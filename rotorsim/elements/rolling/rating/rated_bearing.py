"""A bearing model with its rating: loads, lives and pressures at given ring displacements.

:class:`RatedBearing` ties a ``BallBearing`` or ``RollerBearing`` (or either mounted the
other way round, :class:`~rotorsim.elements.rolling.reversed.ReversedBearing`) to its
:class:`~.iso281.BearingRating` and :class:`~.iso16281.ReferenceRating`. Everything is
evaluated at displacements an analysis found; nothing here solves an equilibrium.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.double_row import DoubleRowBearing
from rotorsim.elements.rolling.geometry import cage_ratio
from rotorsim.elements.rolling.rating.hertz_pressure import (
    BallContactPressure,
    RollerContactPressure,
    ball_pressures,
    contact_pressures,
    roller_pressures,
)
from rotorsim.elements.rolling.rating.iso281 import BearingRating
from rotorsim.elements.rolling.rating.iso16281 import (
    ReferenceLife,
    ReferenceRating,
    lamina_loads,
    rating_for,
    reference_rating,
)
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
_MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])


def _unwrap(model: Any) -> tuple[Any, FloatArray]:
    """Base model and the factor on ``delta`` (the mirror of a reversed bearing)."""
    inner = getattr(model, "bearing", None)
    if isinstance(model, DoubleRowBearing):  # one row's rating: cage ratio, C of a row
        return _unwrap(model.row)[0], np.full(5, np.nan)
    if isinstance(model, ReversedBearing):
        base, factor = _unwrap(model.bearing)
        return base, factor * _MIRROR
    if hasattr(model, "n_balls") or hasattr(model, "n_rollers"):
        return model, np.ones(5)
    if inner is not None and hasattr(model, "relative"):  # a 2-node RollingBearing element
        return _unwrap(inner)
    raise ModelError(f"bearing rating supports BallBearing and RollerBearing (also reversed "
                     f"or in a RollingBearing element), not {type(model).__name__}",
                     "RatedBearing")


@dataclass(frozen=True, eq=False)
class RatedBearing:
    """A bearing model with its ratings (module docstring).

    Parameters
    ----------
    model : BallBearing, RollerBearing, ReversedBearing or RollingBearing
        (a ``DoubleRowBearing`` gives one row's rating and cage ratio only: its loads,
        lives and pressures are refused; :func:`rotorsim.bearing_life` rates the unit)
    options : RatingOptions

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> b = BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
    ...                               ball_diameter=7.938e-3, f_i=0.52, f_o=0.53)
    >>> rb = RatedBearing(b)
    >>> rb.kind, round(rb.rating.C)
    ('ball', 14007)
    """

    model: Any
    options: RatingOptions = field(default_factory=RatingOptions)
    base: Any = field(init=False, repr=False)
    mirror: FloatArray = field(init=False, repr=False)
    rating: BearingRating = field(init=False)
    reference: ReferenceRating = field(init=False, repr=False)

    def __post_init__(self) -> None:
        base, mirror = _unwrap(self.model)
        o = self.options
        object.__setattr__(self, "base", base)
        object.__setattr__(self, "mirror", mirror)
        if o.C is not None and base.contact_angle > math.radians(45.0):
            rating = BearingRating(self.kind_of(base), C=o.C, C0=o.C0,
                                   contact_angle=base.contact_angle)
        else:
            rating = rating_for(base, C=o.C, C0=o.C0, bm=o.bm)
        object.__setattr__(self, "rating", rating)
        object.__setattr__(self, "reference", reference_rating(base, rating, o.n_laminae))

    @staticmethod
    def kind_of(base: Any) -> str:
        return "ball" if hasattr(base, "n_balls") else "roller"

    @property
    def kind(self) -> str:
        return self.rating.kind

    @property
    def geometric_cage_ratio(self) -> float:
        """``(1 - D cos a / d_m) / 2`` (also for a model built with ``cage="fixed"``)."""
        d = self.base.ball_diameter if self.kind == "ball" \
            else self.base.diameter_for("the cage ratio of a rating")
        return cage_ratio(d, self.base.pitch_diameter, self.base.contact_angle)

    def _single(self) -> None:
        if np.isnan(self.mirror).any():
            raise ModelError("a RatedBearing of a DoubleRowBearing is one row's rating only; "
                             "rate the unit with rotorsim.bearing_life (or DoubleRowRating)",
                             "RatedBearing")

    def _delta(self, delta: ArrayLike) -> FloatArray:
        self._single()
        d = np.atleast_2d(np.asarray(delta, dtype=float))
        if d.ndim != 2 or d.shape[1] != 5 or not np.isfinite(d).all():
            raise ModelError(f"delta must be finite with shape (S, 5), got {np.shape(delta)}",
                             "RatedBearing")
        return np.asarray(d * self.mirror)

    def normalized(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """``Q / Q_c`` of every contact (S, N, 2) or lamina (S, Z, K, 2)."""
        return self.loads(delta, psi)[1]

    def loads(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Element loads ``Q`` (S, N) [N] (rollers: summed over the laminae) and
        ``Q / Q_c`` (:meth:`normalized`)."""
        d = self._delta(delta)
        if self.kind == "roller":
            laminae = lamina_loads(self.base, d, psi)
            return laminae.sum(axis=-1), self.reference.normalized(laminae)
        st = self.base.state(d, psi)
        return st.element_load, self.reference.normalized(
            st.element_load, st.contact_angle, st.outer_load, st.outer_contact_angle)

    def damage_density(self, delta: ArrayLike, psi: ArrayLike
                       ) -> tuple[FloatArray, FloatArray, tuple[float, float]]:
        """A load score (S, N) of each element and the damage density ``u^p`` of
        :func:`~.load_history.ring_damage_density`: balls (S, N, 1, 2) with their loads as
        the score; rollers the laminae of the inner race (S, Z, K),
        ``(Kn / (K q_ci))^p max(delta_k, 0)^(n p)`` (one power per lamina), with the ring
        factors ``(1, (q_ci/q_ce)^p)`` and the summed density as the score."""
        p = self.reference.exponents[0]
        if self.kind == "roller":
            b = self.base
            cap = self.reference.capacities()
            if getattr(b, "slice_model", "independent") == "influence":  # half-space laminae
                density = (b.slice_loads(self._delta(delta), psi) / cap[0]) ** p
                return density.sum(axis=-1), density, (1.0, float((cap[0] / cap[1]) ** p))
            _, _, v, lw = b._kinematics(*b._inputs(self._delta(delta), psi))
            line = b._line
            # rollers that may touch (largest slice deflection bound > 0): only their
            # slices are evaluated, typically half the rollers
            reach = v + 0.5 * np.abs(lw) - float(np.min(line.drop))
            rollers = reach > 0.0
            part = line.slice_deflection(v[rollers], lw[rollers])  # (R, K) [m]
            # micrometres: no subnormal powers near the load-zone edge
            np.maximum(part, 0.0, out=part)
            part *= 1e6
            np.power(part, b.exponent * p, out=part)
            part *= (b.kn / (b.n_slices * cap[0]) * 1e-6 ** b.exponent) ** p
            density = np.zeros((*v.shape, b.n_slices))
            density[rollers] = part
            score = np.zeros(v.shape)
            score[rollers] = part.sum(axis=-1)
            return score, density, (1.0, float((cap[0] / cap[1]) ** p))
        loads, u = self.loads(delta, psi)
        return loads, (u * u * u)[:, :, None, :], (1.0, 1.0)

    def element_angles(self, phi: ArrayLike, inner_ratio: float = 1.0,
                       outer_ratio: float = 0.0) -> FloatArray:
        """Element angles (S, N) [rad] at shaft angles ``phi`` (S,) with the rings turning
        at ``inner_ratio phi`` and ``outer_ratio phi``: the cage at
        ``(kappa r_i + (1 - kappa) r_o) phi``, ``kappa`` the model's cage ratio, or the
        geometric one for a model built with ``cage="fixed"`` (a life needs orbiting
        elements)."""
        phi_arr = np.asarray(phi, dtype=float)
        kappa = float(getattr(self.base, "kappa", 0.0)) or self.geometric_cage_ratio
        cage = kappa * inner_ratio + (1.0 - kappa) * outer_ratio
        return np.asarray(self.base.element_angles(0.0)[0] + cage * phi_arr[:, None])

    def life(self, delta: ArrayLike, psi: ArrayLike, rotating_ring: str | None = None
             ) -> ReferenceLife:
        """``L10r`` of steady load distributions at ``delta`` (S, 5), ``psi`` (S, N)."""
        ring = self.options.rotating_ring if rotating_ring is None else rotating_ring
        d = self._delta(delta)
        if self.kind == "roller":
            return self.reference.life(lamina_loads(self.base, d, psi), rotating_ring=ring)
        st = self.base.state(d, psi)
        return self.reference.life(st.element_load, st.contact_angle,
                                   outer_load=st.outer_load,
                                   outer_contact_angle=st.outer_contact_angle,
                                   rotating_ring=ring)

    def pressures(self, delta: ArrayLike, psi: ArrayLike
                  ) -> BallContactPressure | RollerContactPressure:
        """Hertz pressures of every contact at ``delta`` (S, 5), ``psi`` (S, N)."""
        return contact_pressures(self.base, self._delta(delta), psi,
                                 shoulder_heights=self.options.shoulder_heights,
                                 **self.options.materials)

    def steady(self, delta: ArrayLike, psi: ArrayLike, element_load: ArrayLike | None = None,
               contact_angle: ArrayLike | None = None
               ) -> tuple[ReferenceLife, BallContactPressure | RollerContactPressure]:
        """Life (:meth:`life`) and pressures (:meth:`pressures`) of steady states from one
        evaluation of the contacts; balls may pass their known loads and angles (S, N)
        (an equilibrium result has them) to skip it."""
        o = self.options
        self._single()
        if self.kind == "roller":
            laminae = lamina_loads(self.base, self._delta(delta), psi)
            line = laminae * (self.base.n_slices / self.base.effective_length)
            return (self.reference.life(laminae, rotating_ring=o.rotating_ring),
                    roller_pressures(self.base.diameter_for("contact pressures"),
                                     self.base.pitch_diameter, self.base.contact_angle, line,
                                     self.base._line.xi, **o.materials))
        if element_load is None or contact_angle is None:
            st = self.base.state(self._delta(delta), psi)
            element_load, contact_angle = st.element_load, st.contact_angle
        q = np.atleast_2d(np.asarray(element_load, dtype=float))
        a = np.atleast_2d(np.asarray(contact_angle, dtype=float))
        if self.base.f_i is None or self.base.f_o is None:
            raise ModelError("contact pressures need the groove curvature factors f_i and "
                             "f_o (the bearing has only A0)", self.base.label)
        return (self.reference.life(q, a, rotating_ring=o.rotating_ring),
                ball_pressures(self.base.ball_diameter, self.base.pitch_diameter,
                               self.base.f_i, self.base.f_o, q, a,
                               shoulder_heights=o.shoulder_heights, **o.materials))


@functools.lru_cache(maxsize=64)
def rated(model: Any, options: RatingOptions) -> RatedBearing:
    """:class:`RatedBearing` of ``model`` (compared by identity: models are immutable)
    and ``options``, built once (the ratings, reference loads and tables of a bearing)."""
    return RatedBearing(model, options)
