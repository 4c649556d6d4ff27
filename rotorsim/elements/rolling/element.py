"""The 2-node rolling-bearing element: a rigid-ring bearing model between two nodes.

DESIGN section 4 (``NonlinearElement``): the inner ring sits on shaft node ``n``, the outer
ring on node ``n_link`` (a housing) or on ground. With ``u`` the element DOFs (6 per node:
``ux, uy, uz, rx, ry, rz``) the bearing acts on ``delta = u_inner[:5] - u_outer[:5]``
(DESIGN section 3); the inner node gets ``+F``, the outer ``-F`` (``F = dU/d delta``, the
restoring force of the equation of motion ``... + r(q, q') = f``). ``rz`` carries nothing.

Contact damping: ``"none"``, or ``"proportional"``: ``F_d = beta_c K(delta) delta'`` with the
contact stiffness ``K`` (stiffness-proportional, Rayleigh type; ``beta_c`` [s]). Then
``C = dF/d delta' = beta_c K`` exactly, and ``dF/d delta`` gains ``beta_c (dK/d delta)
delta'``, the derivative of the tangent along the velocity, evaluated by a central
difference of the exact tangent (step 1e-9 m in the scaled displacement; an algorithmic
tangent, DESIGN section 4).

``"ehl"``: the lubricated-contact model of seed 002 section 3.2
(:mod:`~rotorsim.elements.rolling.lubrication`): ``F_d = C(delta, W) delta'`` with
``C = sum_p c_p g_p g_p^T`` from the squeeze-film damping ``c_p`` of every loaded ball or
roller slice (inner and outer contact in series, eq 3.5 at zero frequency) along its
unit-load direction ``g_p``; ``C = dF/d delta'`` exactly and ``dF/d delta`` gains the
exact derivative of ``C delta'`` (analytic: the load dependence of ``c_p`` and, for balls,
the turning of ``g_p``). The shaft speed ``W`` sets the entrainment speed and must not be
zero. The EHL-softened stiffness (Hertz and film in series, eq 3.1) is not the Jacobian of
any force: it is offered for linear analyses only (``linearize`` with
``ehl_stiffness=True``); ``force().K`` is always the exact Jacobian.

Centrifugal force of the rolling elements: wrap the model in a
:class:`~rotorsim.elements.rolling.centrifugal.CentrifugalBearing`; ``force`` then passes
the spin speed of every sample and returns the converged positions of the elements in
``ElementForce.internal`` (S, N, 2), which the next call accepts back as a warm start
(DESIGN section 4). Not combined with ``"ehl"`` damping.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import ElementForce, frozen_scalar
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.element_force import (
    damped_tangents,
    expand_matrix,
    expand_vector,
    per_sample,
)
from rotorsim.elements.rolling.lubrication import Lubricant, LubricatedContacts
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
CONTACT_DAMPING = ("none", "proportional", "ehl")
"""Contact damping models of :class:`RollingBearing`."""


@dataclass(frozen=True, eq=False)
class RollingBearing:
    """A rolling bearing between shaft node ``n`` and node ``n_link`` (or ground).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        The rigid-ring model (:mod:`~rotorsim.elements.rolling.ball.bearing`,
        :mod:`~rotorsim.elements.rolling.roller.bearing`).
    n : int
        Shaft node of the inner ring.
    n_link : int, optional
        Node of the outer ring (housing, pedestal); ``None`` = ground.
    tag : str, optional
        Name used in messages.
    contact_damping : {"none", "proportional", "ehl"}
        Contact damping model (module docstring).
    damping_factor : float
        ``beta_c`` [s] of ``"proportional"`` damping.
    lubricant : Lubricant, optional
        Lubricant of ``"ehl"`` damping (viscosity, pressure-viscosity coefficient, ``E'``).
    ehl_stiffness : bool
        ``"ehl"`` only: :meth:`linearize` returns the EHL-softened stiffness (Hertz and
        film in series, seed 002 eqs 3.1, 3.15, 3.19) instead of the Hertz tangent.
    inner_speed_ratio, outer_speed_ratio : float
        Speed of the inner and outer ring per unit shaft speed ``W`` [-]: ``(1, 0)`` for a
        bearing whose outer ring stands in a housing. Between two turning shafts (an
        inter-shaft bearing) both rings turn; a :class:`~rotorsim.model.rotor.Rotor` of
        several lines sets them from the lines of ``n`` and ``n_link``. The cage then
        turns at ``omega_c = ((1 - g) W_i + (1 + g) W_o) / 2`` with ``g = D cos(a) / d_m``
        (``= kappa W_i + (1 - kappa) W_o`` with the model's cage ratio ``kappa =
        (1 - g) / 2``), which places the rolling elements, sets their centrifugal force
        and the varying-compliance frequency ``N omega_c``.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> ball = BallBearing(n_balls=8, pitch_diameter=0.04, ball_diameter=0.008, Kn=8e9,
    ...                    f_i=0.52, f_o=0.52)
    >>> rb = RollingBearing(ball, n=0)
    >>> u = np.zeros((1, 6)); u[0, 0] = 1e-5
    >>> out = rb.force(u, np.zeros((1, 6)), 0.0, 0.0)
    >>> out.f.shape, out.K.shape, bool(out.f[0, 0] > 0)
    ((1, 6), (1, 6, 6), True)
    """

    bearing: Any
    n: int
    n_link: int | None = None
    tag: str | None = None
    contact_damping: str = "none"
    damping_factor: float = 0.0
    lubricant: Lubricant | None = None
    ehl_stiffness: bool = False
    inner_speed_ratio: float = 1.0
    outer_speed_ratio: float = 0.0
    _ehl: LubricatedContacts | None = field(init=False, repr=False, default=None)

    def __post_init__(self) -> None:
        where = self.label
        for key, node in (("n", self.n), ("n_link", self.n_link)):
            if node is None and key == "n_link":
                continue
            if isinstance(node, bool) or not isinstance(node, int | np.integer) or node < 0:
                raise ModelError(f"{key} must be a non-negative integer, got {node!r}", where)
        if self.n_link is not None and self.n_link == self.n:
            raise ModelError(f"n_link must differ from n (both {self.n})", where)
        for attr in ("state", "element_angles", "n_elements"):
            if not hasattr(self.bearing, attr):
                raise ModelError(f"bearing must be a rolling-bearing model with `{attr}` "
                                 f"(BallBearing, RollerBearing), got "
                                 f"{type(self.bearing).__name__}", where)
        if isinstance(self.bearing, ReversedBearing) and isinstance(self.bearing.bearing,
                                                                    CentrifugalBearing):
            raise ModelError("a ReversedBearing of a CentrifugalBearing would lose the speed: "
                             "wrap the other way round, CentrifugalBearing(ReversedBearing("
                             "...), ...)", where)
        if self.contact_damping not in CONTACT_DAMPING:
            raise TypeError(f"{where}: unknown contact_damping {self.contact_damping!r}; "
                            f"valid: {CONTACT_DAMPING}")
        beta = self.damping_factor
        if not (isinstance(beta, int | float) and math.isfinite(beta) and beta >= 0):
            raise ModelError(f"damping_factor must be a finite number >= 0 s, got {beta!r}",
                             where)
        if self.contact_damping != "proportional" and beta != 0:
            raise ModelError(f"damping_factor is given but contact_damping is "
                             f"{self.contact_damping!r} (use 'proportional')", where)
        self._check_ehl(where)
        for key in ("inner_speed_ratio", "outer_speed_ratio"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int | float | np.floating) \
                    or not math.isfinite(value):
                raise ModelError(f"{key} must be a finite number, got {value!r}", where)
        if self.cage_speed_factor != 1.0 and self.contact_damping == "ehl":
            raise ModelError("contact_damping='ehl' takes its entrainment speed from a "
                             "standing outer ring; with both rings turning use "
                             "'proportional' or 'none'", where)

    @cached_property
    def cage_speed_factor(self) -> float:
        """Cage speed over that of the same bearing with a standing outer ring [-].

        ``omega_c = kappa W_i + (1 - kappa) W_o`` (class docstring) divided by
        ``kappa W``: ``r_i + r_o (1 - kappa) / kappa``. The model then sees the shaft angle
        and speed multiplied by it, which turns its cage (``kappa phi``) and its centrifugal
        loads (``kappa W``) at the true cage speed. 1 for rings at ``(1, 0)``.
        """
        r_i, r_o = float(self.inner_speed_ratio), float(self.outer_speed_ratio)
        if (r_i, r_o) == (1.0, 0.0):
            return 1.0
        kappa = float(getattr(self.bearing, "kappa", 0.0))
        return r_i if kappa == 0.0 else r_i + r_o * (1.0 - kappa) / kappa

    @property
    def cage_speed_ratio(self) -> float:
        """Cage speed per unit shaft speed ``omega_c / W`` [-]."""
        return float(getattr(self.bearing, "kappa", 0.0)) * self.cage_speed_factor

    def _check_ehl(self, where: str) -> None:
        ehl = self.contact_damping == "ehl"
        if ehl and self.lubricant is None:  # a missing argument: TypeError, as in Python
            raise TypeError(f"{where}: contact_damping='ehl' needs lubricant=Lubricant(...) "
                            f"(other models: 'none', 'proportional')")
        if self.lubricant is not None and not ehl:
            raise ModelError("a lubricant is given but contact_damping is "
                             f"{self.contact_damping!r} (use 'ehl')", where)
        if self.ehl_stiffness and not ehl:
            raise ModelError("ehl_stiffness=True needs contact_damping='ehl'", where)
        if ehl and self.centrifugal:
            raise ModelError("contact_damping='ehl' is not implemented with the centrifugal "
                             "force of the rolling elements (the EHL films need the inner "
                             "and outer contact loads); use 'proportional' or 'none'", where)
        if ehl:
            assert self.lubricant is not None
            object.__setattr__(self, "_ehl", LubricatedContacts(self.bearing, self.lubricant))

    @property
    def label(self) -> str:
        return f"RollingBearing '{self.tag}'" if self.tag else f"RollingBearing(n={self.n})"

    @property
    def centrifugal(self) -> bool:
        """Whether the rolling elements carry their centrifugal force (speed-dependent)."""
        return isinstance(self.bearing, CentrifugalBearing)

    @property
    def nodes(self) -> tuple[int, ...]:
        return (int(self.n),) if self.n_link is None else (int(self.n), int(self.n_link))

    @property
    def n_dofs(self) -> int:
        return 6 if self.n_link is None else 12

    @property
    def beta(self) -> float:
        """Stiffness-proportional damping factor ``beta_c`` [s] (0 without damping)."""
        return float(self.damping_factor) if self.contact_damping == "proportional" else 0.0

    def relative(self, u: ArrayLike) -> FloatArray:
        """``delta = u_inner[:5] - u_outer[:5]`` (S, 5) from element DOFs ``u`` (S, n)."""
        arr = np.asarray(u, dtype=float)
        arr = arr[None, :] if arr.ndim == 1 else arr
        n_dofs = 6 if self.n_link is None else 12
        if arr.ndim != 2 or arr.shape[1] != n_dofs:
            raise ModelError(f"element DOFs must have shape (S, {n_dofs}), got "
                             f"{np.shape(u)}", self.label)
        if not np.isfinite(arr).all():
            raise ModelError("element DOFs must be finite", self.label)
        return arr[:, :5] - arr[:, 6:11] if self.n_link is not None else arr[:, :5].copy()

    def force(self, u: ArrayLike, v: ArrayLike, phi: ArrayLike, speed: ArrayLike,
              internal: Any = None) -> ElementForce:
        """Restoring force and its exact tangents for ``S`` samples.

        Parameters
        ----------
        u, v : array (S, n)
            Displacements and velocities of the element DOFs (``n = 6`` to ground, 12
            node-to-node).
        phi : array (S,) or float
            Shaft angle [rad]: places the rolling elements (cage kinematics).
        speed : array (S,) or float
            Spin speed [rad/s]: the entrainment speed of ``"ehl"`` damping (non-zero) and
            the centrifugal force of a :class:`CentrifugalBearing`; unused otherwise.
        internal : array (S, N, 2), optional
            ``internal`` of a previous call with the same samples (centrifugal model: the
            element positions), the start of the element equilibrium; ``None`` starts cold.

        Returns
        -------
        ElementForce
            ``f`` (S, n), ``K = df/du`` and ``C = df/dv`` (S, n, n); ``internal`` the
            converged element positions (centrifugal model) or ``None``.
        """
        delta, rate = self.relative(u), self.relative(v)
        n_samples = delta.shape[0]
        if rate.shape[0] != n_samples:
            raise ModelError(f"u and v have {n_samples} and {rate.shape[0]} samples",
                             self.label)
        phis = per_sample(phi, n_samples)
        speeds = per_sample(speed, n_samples)
        if self.cage_speed_factor != 1.0:  # both rings turn: the cage's own angle and speed
            phis, speeds = phis * self.cage_speed_factor, speeds * self.cage_speed_factor
        psi = self.bearing.element_angles(phis)
        if self._ehl is not None:
            st = self.bearing.state(delta, psi)
            ehl = self._ehl.matrices(delta, psi, speeds, rate=rate, state=st)
            f5, k5, c5 = (st.force + ehl.damping_force, st.stiffness + ehl.damping_tangent,
                          ehl.damping)
            solved = None
        else:
            f5, k5, c5, solved = self._tangents(delta, rate, psi, speeds, internal)
        return ElementForce(self._expand_vector(f5), self._expand_matrix(k5),
                            self._expand_matrix(c5), solved)

    def _state(self, delta: FloatArray, psi: FloatArray, speeds: FloatArray,
               internal: Any) -> Any:
        """The model's state; with the speed and warm start of a centrifugal model."""
        if self.centrifugal:
            return self.bearing.state(delta, psi, speed=speeds, internal=internal)
        return self.bearing.state(delta, psi)

    def _tangents(self, delta: FloatArray, rate: FloatArray, psi: FloatArray,
                  speeds: FloatArray, internal: Any
                  ) -> tuple[FloatArray, FloatArray, FloatArray, Any]:
        """Force (S, 5), ``dF/d delta``, ``dF/d delta'`` (S, 5, 5) and internal DOFs
        (:func:`~.element_force.damped_tangents`)."""
        beta, scale = self._damping
        return damped_tangents(self._fast, self._state, beta, scale, delta, rate, psi,
                               speeds, internal)

    @cached_property
    def _fast(self) -> Any:
        return getattr(self.bearing, "_force_stiffness", None)  # rigid ball/roller models

    @cached_property
    def _damping(self) -> tuple[FloatArray | None, FloatArray]:
        """``beta_c`` as a 0-d array (``None`` without damping) and ``(1, 1, 1, arm,
        arm)``, which scales the rate to metres (rotations x arm) for the FD step."""
        beta = None if self.beta == 0.0 else frozen_scalar(self.beta)
        arm = float(getattr(self.bearing, "moment_arm", 0.5 * self.bearing.pitch_diameter))
        scale = np.array([1.0, 1.0, 1.0, arm, arm])
        scale.flags.writeable = False
        return beta, scale

    def _arm(self) -> float:
        return float(self._damping[1][3])

    def _expand_vector(self, f5: FloatArray) -> FloatArray:
        return expand_vector(f5, self.n_link is not None)

    def _expand_matrix(self, k5: FloatArray) -> FloatArray:
        return expand_matrix(k5, self.n_link is not None)

    def model_at_speed(self, speed: float | None = None) -> Any:
        """The bearing model whose ``state`` a linearisation at shaft speed ``speed``
        evaluates: a :class:`CentrifugalBearing` frozen at that speed, the model itself
        otherwise (bearing statics at speed solve the equilibrium of this model).

        Parameters
        ----------
        speed : float, optional
            Shaft speed [rad/s]; required (finite, non-zero) by ``"ehl"`` damping, the
            centrifugal force of a :class:`CentrifugalBearing` (default 0).

        Raises
        ------
        ModelError
            ``"ehl"`` damping without a finite non-zero ``speed``.
        """
        if self._ehl is not None and (speed is None or not math.isfinite(speed)
                                      or speed == 0.0):
            raise ModelError(f"EHL damping needs the shaft speed to linearise: speed=... "
                             f"finite and non-zero [rad/s], got {speed!r}", self.label)
        factor = self.cage_speed_factor
        return self.bearing.at_speed(float(speed or 0.0) * factor) if self.centrifugal \
            else self.bearing

    def linearize(self, *, displacement: ArrayLike, phi: float = 0.0,
                  speed: float | None = None, frequency: float = 0.0,
                  tangent: ArrayLike | None = None) -> BearingElement:
        """Linear bearing element at a given state (for modal, Campbell, critical speeds).

        The element does not solve for an equilibrium: at a given load use
        :func:`~rotorsim.analyses.statics.bearing_statics.linearize_at_load`, which solves
        the bearing equilibrium and calls this method at its displacement.

        Parameters
        ----------
        displacement : array (5,)
            Relative displacement ``delta = [x, y, z, rx, ry]`` of the inner ring [m, rad].
        phi : float
            Shaft angle [rad] (element positions).
        speed : float, optional
            Shaft speed [rad/s]; required by ``"ehl"`` damping (entrainment speed); the
            centrifugal force of a :class:`CentrifugalBearing` (default 0).
        frequency : float
            ``"ehl"``: vibration frequency ``w`` [rad/s] at which the inner and outer
            contacts are combined (seed 002 eq 3.5); 0 = quasi-static.
        tangent : array (5, 5), optional
            The model tangent ``dF/d delta`` at ``displacement`` when the caller has it
            already (the ``stiffness`` of a bearing equilibrium); evaluated here otherwise.

        Returns
        -------
        BearingElement
            ``stiffness_matrix`` = the 5x5 tangent at ``displacement`` (``"ehl"`` with
            ``ehl_stiffness``: the EHL-softened stiffness, for linear analyses only),
            ``damping_matrix`` = ``beta_c`` times the tangent (``"proportional"``), the EHL
            damping matrix (``"ehl"``) or ``None``; same nodes and tag.
        """
        model = self.model_at_speed(speed)
        phi = float(phi) * self.cage_speed_factor
        d = np.asarray(displacement, dtype=float).reshape(1, 5)
        if tangent is None:
            k5 = model.state(d, self.bearing.element_angles(float(phi))).stiffness[0]
        else:
            k5 = np.asarray(tangent, dtype=float)
            if k5.shape != (5, 5):
                raise ModelError(f"tangent must have shape (5, 5), got {k5.shape}", self.label)
        c5 = self.beta * k5 if self.beta > 0 else None
        if self._ehl is not None:
            ehl = self._ehl.matrices(d, self.bearing.element_angles(float(phi)),
                                     float(speed or 0.0), frequency=frequency)
            c5 = ehl.damping[0]
            k5 = ehl.stiffness[0] if self.ehl_stiffness else k5
        return BearingElement(n=int(self.n), n_link=self.n_link, stiffness_matrix=k5,
                              damping_matrix=c5, tag=self.tag)
