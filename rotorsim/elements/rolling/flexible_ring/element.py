"""The 2-node element of the flexible-ring roller bearing (seed 001 section 2.1, DESIGN 4).

The inner ring sits on node ``n`` (node A of seed 001), the outer ring on node ``n_link``
(node B, a housing) or on ground. The element acts on ``delta = u_inner[:5] - u_outer[:5]``
(``ux, uy, uz, rx, ry``; DESIGN section 3), the inner node gets ``+F``, the outer ``-F``
with ``F = dU/d delta`` of
:class:`~rotorsim.elements.rolling.flexible_ring.bearing.FlexibleRingRollerBearing`; ``uz`` and
``rz`` carry nothing. The roller equilibrium (4 internal DOFs per roller) is solved inside
:meth:`FlexibleRingBearingElement.force` and condensed; the converged roller states are
returned in ``ElementForce.internal`` (S, N, 4) and accepted back as the warm start of the
next call. The element has no damping (``C = 0``).

Small-rotation kinematics: the large-rotation operator ``H`` of seed 001 eqs 27-42 is not
implemented.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.elements.base import ElementForce
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing
from rotorsim.elements.rolling.flexible_ring.geometry import FloatArray
from rotorsim.elements.rolling.flexible_ring.state import FlexibleRingState
from rotorsim.errors import ModelError


@dataclass(frozen=True, eq=False)
class FlexibleRingBearingElement:
    """A flexible-ring roller bearing between shaft node ``n`` and node ``n_link`` (or
    ground), implementing the ``NonlinearElement`` protocol.

    Parameters
    ----------
    bearing : FlexibleRingRollerBearing
    n : int
        Node of the inner ring.
    n_link : int, optional
        Node of the outer ring; ``None`` = ground.
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> b = FlexibleRingRollerBearing(n_rollers=24, pitch_radius=0.075,
    ...     roller_radius=0.0065, effective_length=0.016, diametral_clearance=-40e-6,
    ...     shaft_radius=0.054, housing_radius=0.097, ring_width=0.030, n_slices=4)
    >>> el = FlexibleRingBearingElement(b, n=0, n_link=1)
    >>> u = np.zeros((2, 12)); u[:, 0] = 5e-6
    >>> out = el.force(u, np.zeros((2, 12)), [0.0, 0.1], 1000.0)
    >>> out.f.shape, out.K.shape, out.internal.shape, bool(out.f[0, 0] > 0 > out.f[0, 6])
    ((2, 12), (2, 12, 12), (2, 24, 4), True)
    """

    bearing: FlexibleRingRollerBearing
    n: int
    n_link: int | None = None
    tag: str | None = None

    def __post_init__(self) -> None:
        where = self.label
        if not isinstance(self.bearing, FlexibleRingRollerBearing):
            raise ModelError(f"bearing must be a FlexibleRingRollerBearing, got "
                             f"{type(self.bearing).__name__}", where)
        for key, node in (("n", self.n), ("n_link", self.n_link)):
            if node is None and key == "n_link":
                continue
            if isinstance(node, bool) or not isinstance(node, int | np.integer) or node < 0:
                raise ModelError(f"{key} must be a non-negative integer, got {node!r}", where)
        if self.n_link is not None and self.n_link == self.n:
            raise ModelError(f"n_link must differ from n (both {self.n})", where)

    @property
    def label(self) -> str:
        return f"FlexibleRingBearingElement '{self.tag}'" if self.tag \
            else f"FlexibleRingBearingElement(n={self.n})"

    @property
    def nodes(self) -> tuple[int, ...]:
        return (int(self.n),) if self.n_link is None else (int(self.n), int(self.n_link))

    @property
    def n_dofs(self) -> int:
        return 6 * len(self.nodes)

    def relative(self, u: ArrayLike) -> FloatArray:
        """``delta = u_inner[:5] - u_outer[:5]`` (S, 5) from element DOFs ``u`` (S, n)."""
        arr = np.asarray(u, dtype=float)
        arr = arr[None, :] if arr.ndim == 1 else arr
        if arr.ndim != 2 or arr.shape[1] != self.n_dofs:
            raise ModelError(f"element DOFs must have shape (S, {self.n_dofs}), got "
                             f"{np.shape(u)}", self.label)
        if not np.all(np.isfinite(arr)):
            raise ModelError("element DOFs must be finite", self.label)
        return arr[:, :5] - arr[:, 6:11] if self.n_link is not None else arr[:, :5].copy()

    def state(self, u: ArrayLike, phi: ArrayLike, speed: ArrayLike,
              internal: Any = None, details: bool = True) -> FlexibleRingState:
        """The bearing state (roller loads, ring deflections, inner Newton statistics) at
        element DOFs ``u`` (S, n), shaft angles ``phi`` and speeds ``speed`` (S,)."""
        delta = self.relative(u)
        n_s = delta.shape[0]
        phis = np.broadcast_to(np.asarray(phi, dtype=float).reshape(-1), (n_s,))
        speeds = np.broadcast_to(np.asarray(speed, dtype=float).reshape(-1), (n_s,))
        return self.bearing.state(delta, self.bearing.element_angles(phis), speeds,
                                  internal, details)

    def force(self, u: ArrayLike, v: ArrayLike, phi: ArrayLike, speed: ArrayLike,
              internal: Any = None) -> ElementForce:
        """Restoring force and its exact tangent for ``S`` samples.

        Parameters
        ----------
        u, v : array (S, n)
            Displacements and velocities of the element DOFs (``n = 6`` to ground, 12
            node-to-node); ``v`` is not used (no damping).
        phi : array (S,) or float
            Shaft angle [rad] (roller positions, cage kinematics).
        speed : array (S,) or float
            Shaft speed [rad/s] (centrifugal force of the rollers, seed 001 eq 18).
        internal : array (S, N, 4), optional
            ``internal`` of a previous call (warm start of the roller equilibrium).

        Returns
        -------
        ElementForce
            ``f`` (S, n), ``K = df/du`` (S, n, n), ``C = 0``, ``internal`` (S, N, 4).
        """
        n_s = self.relative(u).shape[0]
        if np.shape(v) not in ((n_s, self.n_dofs), (self.n_dofs,) if n_s == 1 else ()):
            raise ModelError(f"velocities must have shape ({n_s}, {self.n_dofs}), got "
                             f"{np.shape(v)}", self.label)
        st = self.state(u, phi, speed, internal, details=False)
        f = np.zeros((st.force.shape[0], self.n_dofs))
        k = np.zeros((st.force.shape[0], self.n_dofs, self.n_dofs))
        f[:, :5], k[:, :5, :5] = st.force, st.stiffness
        if self.n_link is not None:
            f[:, 6:11] = -st.force
            k[:, 6:11, 6:11] = st.stiffness
            k[:, :5, 6:11] = -st.stiffness
            k[:, 6:11, :5] = -st.stiffness
        return ElementForce(f, k, np.zeros_like(k), st.internal)

    def model_at_speed(self, speed: float = 0.0) -> FlexibleRingRollerBearing:
        """The bearing at shaft speed ``speed`` [rad/s] (centrifugal force of the rollers),
        whose equilibrium bearing statics at speed solve."""
        return self.bearing.at_speed(float(speed))

    def linearize(self, *, displacement: ArrayLike, phi: float = 0.0, speed: float = 0.0,
                  tangent: ArrayLike | None = None) -> BearingElement:
        """Linear bearing element at a given state (modal, Campbell, critical speeds).

        The element does not solve for an equilibrium: at a given load use
        :func:`~rotorsim.analyses.statics.bearing_statics.linearize_at_load`.

        Parameters
        ----------
        displacement : array (5,)
            Relative displacement ``delta = [x, y, z, rx, ry]`` of the inner ring [m, rad].
        phi : float
            Shaft angle [rad] (roller positions).
        speed : float
            Shaft speed [rad/s] (centrifugal force).
        tangent : array (5, 5), optional
            The condensed tangent at ``displacement`` when the caller has it already (the
            ``stiffness`` of a bearing equilibrium); evaluated here otherwise.

        Returns
        -------
        BearingElement
            ``stiffness_matrix`` = the condensed 5x5 tangent at ``displacement``; same
            nodes and tag; no damping.
        """
        d = np.asarray(displacement, dtype=float).reshape(1, 5)
        if tangent is None:
            model = self.model_at_speed(speed)
            k5 = model.state(d, model.element_angles(float(phi)), details=False).stiffness[0]
        else:
            k5 = np.asarray(tangent, dtype=float)
            if k5.shape != (5, 5):
                raise ModelError(f"tangent must have shape (5, 5), got {k5.shape}", self.label)
        return BearingElement(n=int(self.n), n_link=self.n_link, stiffness_matrix=k5,
                              tag=self.tag)
