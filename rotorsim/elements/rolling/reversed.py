"""A rolling bearing mounted the other way round (back-to-back and face-to-face pairs)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
_MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
"""The mirror z -> -z on ``(x, y, z, rx, ry)`` (rotations are pseudovectors)."""


@dataclass(frozen=True, eq=False)
class ReversedBearing:
    """A rolling-bearing model mounted the other way round (mirrored about its radial plane).

    An angular-contact or tapered bearing carries axial load on its inner ring towards
    ``+z`` only; the reversed one towards ``-z`` (the second bearing of a back-to-back or
    face-to-face pair). The mirror ``z -> -z`` maps the relative displacement to
    ``S delta``, ``S = diag(1, 1, -1, -1, -1)`` (rotations are pseudovectors), so
    ``F'(delta) = S F(S delta)`` and ``K' = S K S``; element loads, angles and energy are
    the base model's at ``S delta`` (unit-load directions, if the state has them, are
    mirrored too). Other (non-callable) attributes are the base model's.

    Examples
    --------
    >>> from rotorsim.elements.rolling.roller.bearing import RollerBearing
    >>> base = RollerBearing(14, 0.0425, 0.0075, 0.01, Kn=3e8, contact_angle=0.3)
    >>> d, psi = [[0.0, 0.0, -5e-6, 0.0, 0.0]], base.element_angles()
    >>> bool(ReversedBearing(base).state(d, psi).force[0, 2] < 0), float(
    ...     base.state(d, psi).force[0, 2])
    (True, 0.0)
    """

    bearing: Any

    def __post_init__(self) -> None:
        for attr in ("state", "energy", "element_angles", "n_elements"):
            if not hasattr(self.bearing, attr):
                raise ModelError(f"not a rolling-bearing model (no `{attr}`): "
                                 f"{type(self.bearing).__name__}", "ReversedBearing")

    def state(self, delta: ArrayLike, psi: ArrayLike) -> Any:
        """The base model's ``state`` mirrored (force ``S F``, stiffness ``S K S``)."""
        st = self.bearing.state(np.asarray(delta, dtype=float) * _MIRROR, psi)
        changes = {"force": st.force * _MIRROR,
                   "stiffness": st.stiffness * np.outer(_MIRROR, _MIRROR)}
        if getattr(st, "contact_direction", None) is not None:  # (S, N, 5) unit-load g_j
            changes["contact_direction"] = st.contact_direction * _MIRROR
        return dataclasses.replace(st, **changes)

    def energy(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Strain energy [J] at ``delta`` (S, 5)."""
        return np.asarray(self.bearing.energy(np.asarray(delta, dtype=float) * _MIRROR, psi))

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Element angles of the base model (the mirror keeps x and y)."""
        return np.asarray(self.bearing.element_angles(phi))

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name == "bearing":
            raise AttributeError(name)
        value = getattr(self.bearing, name)
        if callable(value):
            raise AttributeError(f"{name} of the base model is not mirrored; call it on "
                                 "`.bearing` with S delta")
        return value
