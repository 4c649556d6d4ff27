"""Double-row bearings as one element: two rows sharing rigid rings at an axial spacing.

Seed 002 section 2.3 (eqs 2.14-2.17, Fig. 2.6) builds the double-row tapered roller bearing
of a railway axlebox from two single-row sub-models: the displacement of the whole bearing
is carried to each row centre by the rigid-body motion of the rings (eq 2.14), mirrored
for the row whose contacts face the other way (eqs 2.15-2.16), and the row loads are
carried back to the bearing centre with their moments (eq 2.17). Here, in rotorsim's axes
(z the shaft axis, DESIGN section 3; the seed's axis is x):

Row ``k`` sits at ``z_k = -s/2`` (row 0) or ``+s/2`` (row 1), ``s`` the row spacing. The
small rotation ``(rx, ry)`` of the inner ring moves the row centre by
``(rx, ry, 0) x (0, 0, z_k) = (z_k ry, -z_k rx, 0)`` (eq 2.14 linearised), so the row sees

    delta_k = T_k delta,   T_k = I + z_k (e_x e_ry^T - e_y e_rx^T),

and in its own frame (a row mounted the other way round is mirrored by
``S = diag(1, 1, -1, -1, -1)``, eqs 2.15-2.16; see
:class:`~rotorsim.elements.rolling.reversed.ReversedBearing`)

    delta_k' = A_k delta + b_k,   A_k = S_k T_k,   b_k = (0, 0, e_a, 0, 0),

with ``e_a`` the axial interference of each row (a spacer ground shorter than the gap
between the rings preloads both rows by ``e_a > 0``; ``e_a < 0`` leaves an axial end play
``-2 e_a`` of the unit). The strain energy is the sum of the rows', so the force and its
exact tangent are (eq 2.17, with the row moments ``r x F`` about the bearing centre)

    F = sum_k A_k^T F_k(delta_k'),    K = sum_k A_k^T K_k(delta_k') A_k,

and the unit-load direction of an element of row ``k`` is ``A_k^T g_j``.

Arrangements (the row model carries axial load on its inner ring towards ``+z``; its
pressure centre lies at ``z_k - r_p tan(a0)``, on the ``-z`` side of the row):

* ``"back_to_back"`` (O): row 0 as given, row 1 mirrored: the pressure centres lie outside
  the rows, ``s + 2 r_p tan a0`` apart (the stiffer arrangement against tilt);
* ``"face_to_face"`` (X): row 0 mirrored, row 1 as given: pressure centres between the rows;
* ``"tandem"``: both rows as given (both carry axial load towards ``+z`` only).

The elements of row 0 come first in every per-element array (``(S, 2 N)``).

Lives and pressures: :func:`rotorsim.bearing_life` and the history lives rate the unit row
by row (:mod:`rotorsim.analyses.statics.double_row_life`,
:class:`~rotorsim.elements.rolling.rating.double_row.DoubleRowRating`).

Not yet: rows with the centrifugal force of their elements (``CentrifugalBearing``), EHL
contact damping (``RollingBearing(contact_damping="ehl")``) and writing a double-row bearing
back to a model file (``rs.save_model``).

References
----------
Seed 002 (Zhu 2017) eqs 2.14-2.17 and Fig. 2.6; Bercea, Nelias & Cavallaro (2003), *A
unified and simplified treatment of the nonlinear equilibrium problem of double-row
rolling bearings*, Proc. IMechE J 217 (seed 002 ref. [42]).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.geometry import checked_state
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.state import BearingState
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

ARRANGEMENTS = ("back_to_back", "face_to_face", "tandem")
"""Arrangements of the two rows of a :class:`DoubleRowBearing`."""
_MIRRORED = {"back_to_back": (False, True), "face_to_face": (True, False),
             "tandem": (False, False)}
_MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
_DELEGATED = ("pitch_diameter", "contact_angle", "Kn", "exponent", "clearance", "kappa",
              "center_distance", "psi0", "effective_length")


def row_transform(z_row: float, mirrored: bool) -> FloatArray:
    """``A = S T`` (5, 5): bearing displacement ``delta`` to the row's own frame.

    Parameters
    ----------
    z_row : float
        Axial position of the row centre from the bearing centre [m].
    mirrored : bool
        Whether the row is mounted the other way round (``S`` the mirror ``z -> -z``).

    Examples
    --------
    >>> row_transform(0.05, False)[0]  # x at the row = x + z_row ry
    array([1.  , 0.  , 0.  , 0.  , 0.05])
    """
    t = np.eye(5)
    t[0, 4] = z_row
    t[1, 3] = -z_row
    return t * _MIRROR[:, None] if mirrored else t


@dataclass(frozen=True, eq=False)
class DoubleRowBearing:
    """Two identical rows of a rigid-ring bearing model sharing both rings (module docstring).

    Parameters
    ----------
    row : BallBearing or RollerBearing
        The model of one row, mounted to carry axial load on its inner ring towards ``+z``
        (its clearance, contact angle, constant and cage are those of each row).
    row_spacing : float
        Axial distance ``s`` [m] between the row centres (> 0).
    arrangement : {"back_to_back", "face_to_face", "tandem"}
        Which row is mirrored (module docstring).
    axial_interference : float
        ``e_a`` [m]: axial approach of the rings of each row at ``delta = 0`` (a spacer
        preload; negative = axial clearance, end play ``-2 e_a``). Default 0.
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> row = BallBearing(n_balls=12, pitch_diameter=0.05, ball_diameter=0.008, Kn=8e9,
    ...                   f_i=0.52, f_o=0.53, contact_angle=0.52)
    >>> b = DoubleRowBearing(row, row_spacing=0.02)
    >>> st = b.state([[10e-6, 0.0, 0.0, 0.0, 0.0]], b.element_angles())
    >>> st.element_load.shape, abs(float(st.force[0, 2])) < 1e-9 * float(st.force[0, 0])
    ((1, 24), True)
    """

    row: Any
    row_spacing: float
    arrangement: str = "back_to_back"
    axial_interference: float = 0.0
    tag: str | None = None
    transforms: FloatArray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        where = self.label
        for attr in ("state", "energy", "element_angles", "n_elements", "pitch_diameter"):
            if not hasattr(self.row, attr):
                raise ModelError(f"row must be a BallBearing or RollerBearing model (no "
                                 f"`{attr}`), got {type(self.row).__name__}", where)
        if not isinstance(self.row, BallBearing | RollerBearing):
            raise ModelError(f"row must be a BallBearing or RollerBearing, got "
                             f"{type(self.row).__name__} (mount it with `arrangement`, not "
                             f"ReversedBearing; no centrifugal rows)", where)
        s = self.row_spacing
        if isinstance(s, bool) or not isinstance(s, int | float) or not math.isfinite(s) \
                or s <= 0:
            raise ModelError(f"row_spacing must be a finite length > 0 m, got {s!r}", where)
        if self.arrangement not in ARRANGEMENTS:
            raise TypeError(f"{where}: unknown arrangement {self.arrangement!r}; valid: "
                            f"{ARRANGEMENTS}")
        e_a = self.axial_interference
        if isinstance(e_a, bool) or not isinstance(e_a, int | float) or not math.isfinite(e_a):
            raise ModelError(f"axial_interference must be a finite length [m], got {e_a!r}",
                             where)
        mirrored = _MIRRORED[self.arrangement]
        a = np.stack([row_transform(-0.5 * s, mirrored[0]),
                      row_transform(0.5 * s, mirrored[1])])
        a.flags.writeable = False
        object.__setattr__(self, "transforms", a)

    @property
    def label(self) -> str:
        return f"DoubleRowBearing '{self.tag}'" if self.tag else "DoubleRowBearing"

    @property
    def rows(self) -> int:
        return 2

    @property
    def mirrored(self) -> tuple[bool, bool]:
        """Whether row 0 and row 1 are mounted the other way round."""
        return _MIRRORED[self.arrangement]

    @property
    def row_positions(self) -> tuple[float, float]:
        """Axial positions ``z_k`` [m] of the row centres."""
        return (-0.5 * self.row_spacing, 0.5 * self.row_spacing)

    @property
    def n_elements(self) -> int:
        return 2 * int(self.row.n_elements)

    @property
    def moment_arm(self) -> float:
        """Tilt lever [m]: the larger of the row's arm and half the row spacing."""
        arm = float(getattr(self.row, "moment_arm", 0.5 * self.row.pitch_diameter))
        return max(arm, 0.5 * float(self.row_spacing))

    @property
    def element_diameter(self) -> float:
        return float(getattr(self.row, "ball_diameter", None) or self.row.roller_diameter)

    def __getattr__(self, name: str) -> Any:
        if name in _DELEGATED:
            return getattr(self.row, name)
        if name in ("ball_diameter", "roller_diameter") and hasattr(self.row, name):
            return getattr(self.row, name)  # deflection scale of bearing statics
        raise AttributeError(name)

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Angles (S, 2 N) [rad]: both rows' elements at the row model's angles."""
        psi = np.asarray(self.row.element_angles(phi))
        return np.concatenate([psi, psi], axis=-1)

    def row_displacements(self, delta: ArrayLike) -> FloatArray:
        """``delta_k' = A_k delta + b_k`` (2, S, 5) in each row's own frame."""
        d = np.asarray(delta, dtype=float)
        own = np.einsum("kij,sj->ksi", self.transforms, d.reshape(-1, 5))
        own[..., 2] += self.axial_interference
        return own

    def _split(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        d, p = checked_state(delta, psi, self.n_elements, self.label)
        n = int(self.row.n_elements)
        return self.row_displacements(d), np.stack([p[:, :n], p[:, n:]])

    def energy(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Strain energy [J] of both rows, shape ``(S,)``."""
        own, p = self._split(delta, psi)
        return np.asarray(self.row.energy(own[0], p[0]) + self.row.energy(own[1], p[1]))

    def row_states(self, delta: ArrayLike, psi: ArrayLike) -> tuple[BearingState, ...]:
        """The row model's state of each row in its own frame (at ``delta_k'``)."""
        own, p = self._split(delta, psi)
        return tuple(self.row.state(own[k], p[k]) for k in range(2))

    def state(self, delta: ArrayLike, psi: ArrayLike) -> BearingState:
        """Force ``sum A_k^T F_k``, tangent ``sum A_k^T K_k A_k`` and the elements of both
        rows (row 0 first; module docstring)."""
        states = self.row_states(delta, psi)
        a = self.transforms
        force = sum(st.force @ a[k] for k, st in enumerate(states))
        stiffness = sum(np.einsum("ji,sjl,lm->sim", a[k], st.stiffness, a[k])
                        for k, st in enumerate(states))
        def joined(key: str) -> FloatArray:
            return np.concatenate([getattr(st, key) for st in states], axis=1)

        g0, g1 = states[0].contact_direction, states[1].contact_direction
        k0, k1 = states[0].element_stiffness, states[1].element_stiffness
        return BearingState(
            force=np.asarray(force), stiffness=np.asarray(stiffness),
            energy=states[0].energy + states[1].energy, element_load=joined("element_load"),
            contact_angle=joined("contact_angle"), deflection=joined("deflection"),
            contact_direction=None if g0 is None or g1 is None else np.concatenate(
                [g0 @ a[0], g1 @ a[1]], axis=1),
            element_stiffness=None if k0 is None or k1 is None else np.concatenate(
                [k0, k1], axis=1))

    @cached_property
    def _fast(self) -> Any:
        return getattr(self.row, "_force_stiffness", None)

    def _force_stiffness(self, d: FloatArray, c: FloatArray, s: FloatArray
                         ) -> tuple[FloatArray, FloatArray]:
        """Force (..., 5) and tangent (..., 5, 5) only (hot path of ``RollingBearing``);
        ``d`` (..., 5) checked, ``c, s`` (..., 2 N) may omit leading axes of ``d``."""
        n = int(self.row.n_elements)
        a = self.transforms
        own = np.einsum("kij,...j->k...i", a, d)
        own[..., 2] += self.axial_interference
        f0, k0 = self._fast(own[0], c[..., :n], s[..., :n])
        f1, k1 = self._fast(own[1], c[..., n:], s[..., n:])
        force = f0 @ a[0] + f1 @ a[1]
        stiffness = (np.swapaxes(a[0], 0, 1) @ k0 @ a[0]
                     + np.swapaxes(a[1], 0, 1) @ k1 @ a[1])
        return force, stiffness
