"""Rigid-ring reference of the ring FE model: the same bearing with the package's roller model.

:func:`rigid_ring_bearing` builds the
:class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing` (wrapped in a
:class:`~rotorsim.elements.rolling.centrifugal.CentrifugalBearing` at speed) with the data
of :func:`~rotorsim.verification.ring_fe.ring_fe_roller_loads`: the same whole-roller
constant ``Kn``, diametral clearance ``g``, roller angles (cage held), roller mass
``rho pi R_b^2 L`` and cage ratio. :func:`rigid_ring_roller_loads` solves its statics with
:func:`~rotorsim.analyses.statics.bearing_statics.bearing_equilibrium`; with very stiff rings the
FE model must reproduce these loads (the rigid-ring limit).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.geometry import cage_ratio as kinematic_cage_ratio
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.results.bearing import BearingEquilibriumResult

FloatArray = NDArray[np.float64]


def rigid_ring_bearing(Z: int, R_p: float, R_b: float, L: float, clearance: float, *,
                       rho: float = 7850.0, speed: float = 0.0, Kn: float | None = None,
                       psi0: float = 0.0, cage_ratio: float | None = None) -> Any:
    """The rigid-ring bearing of the ring FE model's data.

    Parameters
    ----------
    Z, R_p, R_b, L, clearance, rho, speed, Kn, psi0, cage_ratio
        As in :func:`~rotorsim.verification.ring_fe.ring_fe_roller_loads`.

    Returns
    -------
    RollerBearing, or CentrifugalBearing at ``speed`` when ``speed != 0``.

    Examples
    --------
    >>> b = rigid_ring_bearing(24, 0.075, 0.0065, 0.016, -40e-6)
    >>> b.n_rollers, round(b.clearance * 1e6, 6)
    (24, -20.0)
    """
    bearing = RollerBearing(n_rollers=int(Z), pitch_diameter=2.0 * R_p,
                            roller_diameter=2.0 * R_b, effective_length=L, Kn=Kn,
                            diametral_clearance=clearance, psi0=psi0, cage="fixed",
                            tag="rigid-ring reference")
    if speed == 0.0:
        return bearing
    kappa = kinematic_cage_ratio(2.0 * R_b, 2.0 * R_p, 0.0) if cage_ratio is None \
        else cage_ratio
    mass = rho * math.pi * R_b**2 * L
    return CentrifugalBearing(bearing, element_mass=mass, cage_ratio=kappa, speed=speed)


def rigid_ring_equilibrium(Z: int, R_p: float, R_b: float, L: float, clearance: float,
                           F_x: float, F_y: float = 0.0, **options: Any
                           ) -> BearingEquilibriumResult:
    """Statics of :func:`rigid_ring_bearing` under ``(F_x, F_y)`` on the inner ring.

    ``options`` are the keyword arguments of :func:`rigid_ring_bearing`.
    """
    bearing = rigid_ring_bearing(Z, R_p, R_b, L, clearance, **options)
    return bearing_equilibrium(bearing, [F_x, F_y, 0.0, 0.0, 0.0], tol=1e-12)


def rigid_ring_roller_loads(Z: int, R_p: float, R_b: float, L: float, clearance: float,
                            F_x: float, F_y: float = 0.0, **options: Any) -> FloatArray:
    """Inner-contact roller loads ``Q_i`` [N], shape ``(Z,)``, of the rigid-ring bearing.

    Examples
    --------
    >>> q = rigid_ring_roller_loads(24, 0.075, 0.0065, 0.016, 10e-6, 5000.0)
    >>> q.shape, bool(q[0] == q.max())
    ((24,), True)
    """
    result = rigid_ring_equilibrium(Z, R_p, R_b, L, clearance, F_x, F_y, **options)
    return np.asarray(result.element_load)
