"""Rolling-element kinematics: cage ratio and angular positions (DESIGN section 3).

For a bearing whose inner ring turns with the shaft (angle ``phi``) and whose outer ring is
fixed, the cage turns at ``kappa * phi`` with ``kappa = (1 - d cos(alpha0) / d_m) / 2``;
element ``j`` sits at ``psi_j = psi_0 + 2 pi j / N + kappa * phi``. The element-pass
(varying-compliance) frequency is ``N * kappa * W``.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]


def cage_ratio(element_diameter: float, pitch_diameter: float, contact_angle: float) -> float:
    """Cage speed over shaft speed for a rotating inner and a fixed outer ring.

    Parameters
    ----------
    element_diameter : float
        Ball or (mean) roller diameter ``d`` [m].
    pitch_diameter : float
        Pitch diameter ``d_m`` [m].
    contact_angle : float
        Unloaded contact angle ``alpha0`` [rad].

    Examples
    --------
    >>> round(cage_ratio(0.01, 0.05, 0.0), 6)
    0.4
    """
    if not 0 < element_diameter < pitch_diameter:
        raise ModelError(
            f"element diameter {element_diameter} m must be in (0, pitch diameter "
            f"{pitch_diameter} m)", "cage_ratio")
    return 0.5 * (1.0 - element_diameter * math.cos(contact_angle) / pitch_diameter)


MAX_INTERFERENCE_RATIO = 0.01
"""Largest radial interference (negative radial clearance, preload) accepted, as a fraction
of the rolling-element diameter. A steel contact at the ISO 76 static-capacity stress of
4.2 GPa deflects of the order of 0.1 to 0.3 % of the element diameter, so an interference
above 1 % would need contact stresses far beyond what bearing steel carries: it is a sign
or unit mistake, not a preload."""


def interference_problem(radial_clearance: float, element_diameter: float,
                         element: str) -> str | None:
    """Why a radial clearance [m] is a physically absurd interference for rolling elements
    of diameter ``element_diameter`` [m] (``element`` names them: "ball", "roller"), or
    None when it is plausible.

    Examples
    --------
    >>> interference_problem(-2e-6, 0.008, "ball") is None
    True
    >>> print(interference_problem(-0.5e-3, 0.008, "ball")[:67])
    radial interference 500 um (diametral clearance -1000 um) is 6.25 %
    """
    if radial_clearance >= -MAX_INTERFERENCE_RATIO * element_diameter:
        return None
    return (f"radial interference {-radial_clearance * 1e6:.4g} um (diametral clearance "
            f"{2e6 * radial_clearance:.4g} um) is {-100 * radial_clearance / element_diameter:.3g}"
            f" % of the {element} diameter {element_diameter * 1e3:.4g} mm; a preload is at "
            f"most {100 * MAX_INTERFERENCE_RATIO:g} % "
            f"({MAX_INTERFERENCE_RATIO * element_diameter * 1e6:.4g} um): check the sign and "
            "the units")


def element_angles(n_elements: int, phi: ArrayLike = 0.0, kappa: float = 0.0,
                   psi0: float = 0.0) -> FloatArray:
    """Angular positions ``psi`` [rad] of the rolling elements, shape ``(S, N)``.

    Parameters
    ----------
    n_elements : int
        Number of rolling elements ``N``.
    phi : array_like (S,) or float
        Shaft rotation angle [rad] of each sample.
    kappa : float
        Cage ratio (0 holds the elements fixed: quasi-static studies).
    psi0 : float
        Position of element 0 at ``phi = 0`` [rad], measured from +x towards +y.

    Examples
    --------
    >>> element_angles(4, [0.0, np.pi], kappa=0.5).round(6).tolist()
    [[0.0, 1.570796, 3.141593, 4.712389], [1.570796, 3.141593, 4.712389, 6.283185]]
    """
    if not isinstance(n_elements, int | np.integer) or n_elements < 1:
        raise ModelError(f"number of rolling elements must be >= 1, got {n_elements!r}",
                         "element_angles")
    phi_arr = np.asarray(phi, dtype=float)
    if phi_arr.ndim == 0:
        phi_arr = phi_arr.reshape(1)
    return base_angles(int(n_elements), float(psi0))[None, :] + kappa * phi_arr[:, None]


def checked_state(delta: ArrayLike, psi: ArrayLike, n_elements: int,
                  where: str) -> tuple[FloatArray, FloatArray]:
    """Ring displacements ``delta`` (5,) or (S, 5) [m, rad] and element angles ``psi`` (N,)
    or (S, N) [rad] of a bearing with ``n_elements`` rolling elements, checked (shapes,
    finite values; a ModelError at ``where`` otherwise) and returned as ``(S, 5)`` and
    ``(S, N)``."""
    d = np.asarray(delta, dtype=float)
    d = d[None, :] if d.ndim == 1 else d
    p = np.asarray(psi, dtype=float)
    p = p[None, :] if p.ndim == 1 else p
    if d.ndim != 2 or d.shape[1] != 5:
        raise ModelError(f"delta must have shape (S, 5), got {np.shape(delta)}", where)
    if p.ndim != 2 or p.shape[1] != n_elements or p.shape[0] not in (1, d.shape[0]):
        raise ModelError(f"psi must have shape (S, {n_elements}) with S = 1 or "
                         f"{d.shape[0]}, got {np.shape(psi)}", where)
    if not (np.isfinite(d).all() and np.isfinite(p).all()):
        raise ModelError("delta and psi must be finite", where)
    return d, np.broadcast_to(p, (d.shape[0], n_elements))


@functools.lru_cache(maxsize=256)
def base_angles(n_elements: int, psi0: float = 0.0) -> FloatArray:
    """``psi0 + 2 pi j / N`` [rad], shape ``(N,)``: the element angles at ``phi = 0``.

    Cached (read-only array): bearings evaluated at every time step reuse it.

    Examples
    --------
    >>> base_angles(4).round(6).tolist()
    [0.0, 1.570796, 3.141593, 4.712389]
    """
    base = psi0 + 2.0 * np.pi * np.arange(n_elements) / n_elements
    base.flags.writeable = False
    return base


def angle_basis(c: FloatArray, s: FloatArray) -> FloatArray:
    """``c^2, c s, s^2, c, s, 1`` stacked on a new axis ``(..., 6, N)``, from ``c, s``
    (..., N) ``= cos, sin(psi_j)``: the angle functions whose sums over the rolling
    elements give the bearing force and tangent (ball and roller models).

    Examples
    --------
    >>> angle_basis(np.array([[1.0]]), np.array([[0.0]]))[0, :, 0].tolist()
    [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]
    """
    basis = np.empty((*c.shape[:-1], 6, c.shape[-1]))
    np.multiply(c, c, out=basis[..., 0, :])
    np.multiply(c, s, out=basis[..., 1, :])
    np.multiply(s, s, out=basis[..., 2, :])
    basis[..., 3, :] = c
    basis[..., 4, :] = s
    basis[..., 5, :] = 1.0
    return basis
