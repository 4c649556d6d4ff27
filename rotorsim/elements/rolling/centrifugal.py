"""Centrifugal force of the rolling elements (issue 4): the element between the rings.

At the spin speed ``W`` the cage (and with it every rolling element) orbits at
``omega_c = kappa_c W``; an element of mass ``m`` at the pitch radius ``d_m / 2`` carries the
centrifugal force ``Fc = m (d_m / 2) omega_c^2`` outwards. The outer-ring contact then
carries more load than the inner one, and an element whose approach is too small to
overcome ``Fc`` rides on the outer race alone and carries nothing to the inner ring: at speed
the inner-ring load zone shrinks, a radially loaded bearing deflects more and an
angular-contact bearing loses axial stiffness (the classic high-speed effects; numbers in
``docs/rolling_bearings.md``).

Model (per element, batched over samples x elements; no loop over either):

* the inner and outer contacts act in series; each has the Hertz constant
  ``K_c = 2^n Kn`` of the whole-element constant ``Kn`` (equal contacts: two of them in
  series give back ``Q = Kn delta^n``), ``n`` the load-deflection exponent;
* the element's position between the rings is an internal DOF (2 per element, see
  :mod:`~rotorsim.elements.rolling.ball.centrifugal` and
  :mod:`~rotorsim.elements.rolling.roller.centrifugal`); its equilibrium minimises the
  element potential ``Pi = U_inner + U_outer - (work of Fc)`` with ``Fc`` constant (the
  radius change of the element is neglected against ``d_m / 2``: seed 001 eq 18 linearised,
  dropping a negative stiffness ``m omega_c^2``, below 1e-4 of the contact stiffness);
* the equilibrium is found by a batched damped Newton method with an energy line search
  (:mod:`~rotorsim.elements.rolling.element_equilibrium`), warm-started from the previous
  internal DOFs (DESIGN section 4);
* condensation: the bearing potential is ``U*(delta) = sum_j min Pi_j``; its gradient is the
  inner-contact force (envelope theorem) and its Hessian the Schur complement
  ``K* = K_ii - K_ir K_rr^-1 K_ri`` (inner and outer contact stiffness in series), so
  ``force = dU*/d delta`` and ``stiffness = d force / d delta`` hold exactly.

:class:`CentrifugalBearing` wraps a :class:`~rotorsim.elements.rolling.ball.bearing.BallBearing` or
:class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing` (or a
:class:`~rotorsim.elements.rolling.reversed.ReversedBearing` of one) and adds the element
mass and the speed; at zero speed it returns the wrapped model's state unchanged.

References
----------
Seed 001 eqs 18-22 (centrifugal potential of a roller from the cage speed, roller
equilibrium by Newton), eqs 23-26 (static condensation).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.elements.rolling import geometry
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.ball.centrifugal import ball_state
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.centrifugal import roller_state
from rotorsim.elements.rolling.state import BearingState, FloatArray
from rotorsim.errors import ModelError

_MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
"""The mirror z -> -z of a reversed bearing on ``(x, y, z, rx, ry)``."""


@dataclass(frozen=True, eq=False)
class CentrifugalBearing:
    """A ball or roller bearing whose rolling elements carry their centrifugal force.

    Parameters
    ----------
    bearing : BallBearing, RollerBearing or ReversedBearing of one
        The rigid-ring model.
    element_mass : float, optional
        Mass of one rolling element [kg].
    element_density : float, optional
        Density [kg/m^3] instead of the mass: a ball ``pi d^3 / 6``, a roller the cylinder
        ``pi d^2 L / 4`` of its mean diameter and effective length (the real roller is a
        little longer; give ``element_mass`` when it matters). Give exactly one of the two.
    cage_ratio : float, optional
        ``kappa_c = omega_c / W`` [-] of the centrifugal force. Default: the kinematic cage
        ratio ``(1 - d cos(alpha0) / d_m) / 2`` of a turning inner and a fixed outer ring,
        also when the wrapped model holds its elements fixed (``cage="fixed"`` only freezes
        their angular positions for quasi-static studies).
    speed : float
        Spin speed [rad/s] used when :meth:`state` is called without one (bearing statics at
        speed: :meth:`at_speed`).
    tol : float
        Relative force tolerance of the element equilibrium.
    max_iter : int
        Newton iteration limit of the element equilibrium.

    Examples
    --------
    >>> ball = BallBearing(n_balls=8, pitch_diameter=0.04, ball_diameter=0.008, Kn=8e9,
    ...                    f_i=0.52, f_o=0.52)
    >>> b = CentrifugalBearing(ball, element_density=7850.0)
    >>> round(b.mass * 1e3, 3), round(b.centrifugal_force(1000.0), 2)
    (2.104, 6.73)
    >>> st = b.state([[5e-6, 0, 0, 0, 0]], b.element_angles(), speed=3000.0)
    >>> bool(st.outer_load[0, 0] > st.element_load[0, 0] > 0), st.internal.shape
    (True, (1, 8, 2))
    """

    bearing: Any
    element_mass: float | None = None
    element_density: float | None = None
    cage_ratio: float | None = None
    speed: float = 0.0
    tol: float = 1e-10
    max_iter: int = 100
    _resolved: tuple[float, float] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        base = self.base_model
        if not isinstance(base, BallBearing | RollerBearing):
            raise ModelError(f"the centrifugal model needs a BallBearing or RollerBearing "
                             f"(or a ReversedBearing of one), got "
                             f"{type(self.bearing).__name__}", "CentrifugalBearing")
        where = self.label
        if isinstance(base, RollerBearing) and base.model == "influence":
            raise ModelError("the centrifugal model splits each roller into its inner and "
                             "outer contact, which model='influence' (both races in one "
                             "half-space law) does not; use model='slices'", where)
        if (self.element_mass is None) == (self.element_density is None):
            raise ModelError("give exactly one of element_mass [kg] and element_density "
                             "[kg/m^3]", where)
        value: Any = self.element_mass if self.element_mass is not None \
            else self.element_density
        name = "element_mass" if self.element_mass is not None else "element_density"
        if not _positive_number(value):
            raise ModelError(f"{name} must be a positive finite number, got {value!r}", where)
        mass = float(value) if self.element_mass is not None else float(value) * _volume(base)
        if self.cage_ratio is None:
            kappa = _kinematic_cage_ratio(base)
        elif isinstance(self.cage_ratio, bool) or not _finite_number(self.cage_ratio):
            raise ModelError(f"cage_ratio must be a finite number, got {self.cage_ratio!r}",
                             where)
        else:
            kappa = float(self.cage_ratio)
        if not _finite_number(self.speed):
            raise ModelError(f"speed must be a finite number [rad/s], got {self.speed!r}",
                             where)
        if not (_positive_number(self.tol) and float(self.tol) < 1e-3):
            raise ModelError(f"tol must be in (0, 1e-3), got {self.tol!r}", where)
        if isinstance(self.max_iter, bool) or not isinstance(self.max_iter, int) \
                or self.max_iter < 1:
            raise ModelError(f"max_iter must be an integer >= 1, got {self.max_iter!r}", where)
        object.__setattr__(self, "_resolved", (mass, kappa))

    # ------------------------------------------------------------------ properties
    @property
    def base_model(self) -> Any:
        """The ball or roller model (unwrapped from a :class:`ReversedBearing`)."""
        return self.bearing.bearing if isinstance(self.bearing, ReversedBearing) \
            else self.bearing

    @property
    def label(self) -> str:
        tag = getattr(self.base_model, "tag", None)
        return f"CentrifugalBearing '{tag}'" if tag else "CentrifugalBearing"

    @property
    def mass(self) -> float:
        """Mass of one rolling element [kg] (given or from the density)."""
        return self._resolved[0]

    @property
    def centrifugal_cage_ratio(self) -> float:
        """``kappa_c``: orbital speed of the elements over the spin speed [-]."""
        return self._resolved[1]

    @property
    def n_elements(self) -> int:
        return int(self.bearing.n_elements)

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Element angles [rad] (S, N) of the wrapped model at shaft angles ``phi`` (S,)."""
        return np.asarray(self.bearing.element_angles(phi))

    def centrifugal_force(self, speed: ArrayLike) -> float | FloatArray:
        """``Fc = m (d_m / 2) (kappa_c W)^2`` [N] at the spin speed ``W`` [rad/s].

        Examples
        --------
        >>> b = CentrifugalBearing(RollerBearing(14, 0.05, 0.008, 0.008, Kn=3e8),
        ...                        element_mass=0.003)
        >>> round(float(b.centrifugal_force(1000.0)), 3)
        13.23
        """
        w = np.asarray(speed, dtype=float) * self.centrifugal_cage_ratio
        force = self.mass * 0.5 * self.base_model.pitch_diameter * w * w
        return float(force) if force.ndim == 0 else force

    def at_speed(self, speed: float) -> CentrifugalBearing:
        """A copy whose default speed is ``speed`` [rad/s], e.g. for bearing statics:
        ``bearing_equilibrium(b.at_speed(W), load)``."""
        return dataclasses.replace(self, speed=float(speed))

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name == "bearing":
            raise AttributeError(name)
        value = getattr(self.bearing, name)
        if callable(value):
            raise AttributeError(f"{name} of the wrapped model ignores the centrifugal "
                                 "force; call it on `.bearing`")
        return value

    # ------------------------------------------------------------------ state
    def energy(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike | None = None,
               internal: ArrayLike | None = None) -> FloatArray:
        """Condensed potential ``U*`` [J] (S,): contact energies minus the work of ``Fc``."""
        return np.asarray(self.state(delta, psi, speed, internal).energy)

    def state(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike | None = None,
              internal: ArrayLike | None = None) -> BearingState:
        """Force, exact tangent and element loads with the centrifugal force at ``speed``.

        Parameters
        ----------
        delta : array (S, 5)
            ``[x, y, z, rx, ry]`` of the inner ring relative to the outer ring [m, rad].
        psi : array (S, N) or (N,)
            Element angles [rad].
        speed : float or array (S,), optional
            Spin speed ``W`` [rad/s]; default :attr:`speed`. Samples at ``W = 0`` get the
            wrapped model's state exactly.
        internal : array (S, N, 2), optional
            Internal DOFs of a previous call (``state.internal``) to start from; NaN rows
            start cold.

        Returns
        -------
        BearingState
            ``force = dU*/d delta`` (the inner-ring contacts), ``stiffness`` its exact
            Jacobian, ``energy`` ``U*``, ``element_load`` the inner-contact loads,
            ``outer_load``, ``contact_angle`` (inner; balls: ``outer_contact_angle`` too),
            ``internal`` (S, N, 2) and ``iterations``.
        """
        base = self.base_model
        mirror = isinstance(self.bearing, ReversedBearing)
        d_in = np.asarray(delta, dtype=float)
        d, p = base._inputs(d_in * _MIRROR if mirror else d_in, psi)
        n_s = d.shape[0]
        w = np.asarray(self.speed if speed is None else speed, dtype=float).reshape(-1)
        if w.size not in (1, n_s) or not np.all(np.isfinite(w)):
            raise ModelError(f"speed must be finite, a scalar or ({n_s},), got shape "
                             f"{w.shape}", self.label)
        fc = np.broadcast_to(np.asarray(self.centrifugal_force(w), dtype=float), (n_s,))
        guess = self._guess(internal, n_s)
        if isinstance(base, RollerBearing) and math.cos(base.contact_angle) < 1e-9:
            fc = np.zeros(n_s)  # thrust rollers: Fc is normal to both contact normals
        active = fc > 0.0
        ball = isinstance(base, BallBearing)
        if not active.any():
            st = _at_rest(base.state(d, p), ball)
        else:
            solve = ball_state if ball else roller_state
            st = solve(base, d[active], p[active], fc[active],
                       None if guess is None else guess[active], self.tol, self.max_iter,
                       self.label)
            if not active.all():
                st = _merge(_at_rest(base.state(d[~active], p[~active]), ball), st, active)
        return _mirrored(st) if mirror else st

    def _guess(self, internal: ArrayLike | None, n_samples: int) -> FloatArray | None:
        if internal is None:
            return None
        guess = np.asarray(internal, dtype=float)
        shape = (n_samples, self.n_elements, 2)
        if guess.shape != shape:
            raise ModelError(f"internal must have shape {shape} (state.internal of a call "
                             f"with the same samples), got {guess.shape}", self.label)
        return guess


def _at_rest(st: BearingState, ball: bool) -> BearingState:
    """The wrapped model's state without ``Fc``: both contacts carry the element load,
    no internal DOFs were solved (NaN: the next call starts cold)."""
    return dataclasses.replace(
        st, outer_load=st.element_load, outer_contact_angle=st.contact_angle if ball else None,
        internal=np.full((*st.element_load.shape, 2), np.nan), iterations=0)


def _merge(rest: BearingState, active_state: BearingState,
           active: np.ndarray) -> BearingState:
    """Rows of the centrifugal state where ``active``, of the state at rest elsewhere."""
    values: dict[str, Any] = {"iterations": active_state.iterations}
    for f in dataclasses.fields(BearingState):
        if f.name == "iterations":
            continue
        a, b = getattr(active_state, f.name), getattr(rest, f.name)
        if a is None or b is None:
            values[f.name] = None
            continue
        out = np.empty((active.size, *a.shape[1:]))
        out[active], out[~active] = a, b
        values[f.name] = out
    return BearingState(**values)


def _mirrored(st: BearingState) -> BearingState:
    """The state of the reversed (mirrored z -> -z) bearing."""
    changes = {"force": st.force * _MIRROR, "stiffness": st.stiffness * np.outer(_MIRROR,
                                                                                  _MIRROR)}
    if st.contact_direction is not None:
        changes["contact_direction"] = st.contact_direction * _MIRROR
    return dataclasses.replace(st, **changes)


def _volume(base: Any) -> float:
    if isinstance(base, BallBearing):
        return math.pi * base.ball_diameter**3 / 6.0
    return 0.25 * math.pi * base.diameter_for("the roller mass") ** 2 * base.effective_length


def _kinematic_cage_ratio(base: Any) -> float:
    diameter = base.ball_diameter if isinstance(base, BallBearing) \
        else base.diameter_for("the cage ratio")
    return geometry.cage_ratio(diameter, base.pitch_diameter, base.contact_angle)


def _finite_number(value: object) -> bool:
    return isinstance(value, int | float | np.floating | np.integer) and math.isfinite(
        float(value))


def _positive_number(value: object) -> bool:
    return _finite_number(value) and float(value) > 0.0  # type: ignore[arg-type]
