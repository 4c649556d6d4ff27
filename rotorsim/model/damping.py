"""Damping of the whole system, beside the damping of its elements.

Element Rayleigh damping (``ShaftElement.alpha``, ``beta``) damps each shaft element with
its own mass and stiffness. A measured machine is often described instead by damping
of the assembled system:

* **Rayleigh damping of the whole system** ``C += alpha M + beta K`` with the assembled mass
  (shaft, disks, point masses, added masses) and the constant stiffness (shaft and
  bearings); speed-dependent bearings' coefficients are not included, since they change
  with the speed.
* **Modal damping** with a ratio ``zeta_j`` for each of the lowest undamped modes of the
  machine at rest: ``C += M Phi diag(2 zeta_j omega_j) Phi^T M`` with the mass-normalised
  modes ``Phi`` of ``K phi = omega^2 M phi`` (the classical modal damping matrix; each mode
  ``j`` then has the ratio ``zeta_j`` on top of the other damping when the modes are
  uncoupled). Rigid-body modes (``omega = 0``) get none. The matrix is full, so modal
  damping is limited to :data:`MODAL_DAMPING_MAX_DOFS` free DOFs.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from rotorsim.errors import ModelError

MODAL_DAMPING_MAX_DOFS = 2000
"""Largest model (free DOFs) given modal damping: its damping matrix is dense."""


@dataclass(frozen=True)
class SystemDamping:
    """Rayleigh and modal damping of the assembled machine (module docstring).

    Parameters
    ----------
    alpha : float
        Mass-proportional factor [1/s].
    beta : float
        Stiffness-proportional factor [s].
    modal_ratios : sequence of float
        Damping ratio ``zeta_j`` [-] of each of the lowest elastic modes at rest, in order
        of frequency (rigid-body modes are skipped).

    Examples
    --------
    >>> SystemDamping(beta=2e-5, modal_ratios=(0.02, 0.03)).modal_ratios
    (0.02, 0.03)
    """

    alpha: float = 0.0
    beta: float = 0.0
    modal_ratios: Sequence[float] = ()

    def __post_init__(self) -> None:
        for key in ("alpha", "beta"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int | float) \
                    or not math.isfinite(value) or value < 0:
                raise ModelError(f"{key} must be a finite number >= 0, got {value!r}",
                                 "SystemDamping")
        ratios = tuple(self.modal_ratios)
        for j, zeta in enumerate(ratios):
            if isinstance(zeta, bool) or not isinstance(zeta, int | float) \
                    or not math.isfinite(zeta) or not 0 <= zeta < 1:
                raise ModelError(f"modal_ratios[{j}] must be in [0, 1), got {zeta!r}",
                                 "SystemDamping")
        object.__setattr__(self, "modal_ratios", tuple(float(z) for z in ratios))

    @property
    def active(self) -> bool:
        return bool(self.alpha or self.beta or any(self.modal_ratios))
