"""Exact static bending stiffness of a variable-section Timoshenko beam element.

For a cantilever clamped at its left node, the tip flexibility under a tip force P and a
tip moment M0 follows from the unit-load method with bending moment ``P (L - z) + M0`` and
shear force ``P``:

    f11 = int (L - z)^2 / EI dz + int 1 / (kappa G A) dz
    f12 = int (L - z) / EI dz,     f22 = int 1 / EI dz

so ``[w2, theta2] = F [P, M0]`` with ``theta = dw/dz`` in the Euler-Bernoulli sense. The
stiffness of the free element follows from ``K22 = F^-1`` and rigid-body equilibrium,
``K = B^T K22 B`` with ``B = [[-1, -L, 1, 0], [0, -1, 0, 1]]`` on ``[w1, theta1, w2, theta2]``.
This is exact for any section variation (up to the quadrature of the flexibility
integrals, 12-point Gauss-Legendre here, exact for a uniform element and accurate to about
1e-12 for tapers of practical ratio); for a uniform element it equals the interdependent
interpolation element of Friswell et al. (2010, section 5.4.4).

The same flexibilities give the shear parameter ``Phi = 4 f_shear / f_bending`` used by the
element's interpolation functions (``12 E I / (kappa G A L^2)`` for a uniform element).
"""

from __future__ import annotations

import numpy as np

from rotorsim.elements.base import FloatArray

_X, _W = np.polynomial.legendre.leggauss(12)
XI_FLEX = 0.5 * (_X + 1.0)
"""Quadrature points on [0, 1] for the flexibility integrals."""
_WF = 0.5 * _W


def plane_bending_stiffness(length: FloatArray, EI: FloatArray,
                            inv_kGA: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Exact bending stiffness ``(E, 4, 4)`` on ``[w1, theta1, w2, theta2]`` and ``Phi (E,)``.

    Parameters
    ----------
    length : array (E,)
        Element lengths [m].
    EI : array (E, 12)
        Bending stiffness [N m^2] at :data:`XI_FLEX`.
    inv_kGA : array (E, 12)
        Shear compliance ``1 / (kappa G A)`` [1/N] at :data:`XI_FLEX`; zeros for
        Euler-Bernoulli.

    Examples
    --------
    >>> K, phi = plane_bending_stiffness(np.array([2.0]), np.full((1, 12), 3.0),
    ...                                  np.zeros((1, 12)))
    >>> round(float(K[0, 0, 0]), 12), round(float(K[0, 0, 1]), 12)  # 12 EI / L^3, 6 EI / L^2
    (4.5, 4.5)
    """
    L = length[:, None]
    arm = L * (1.0 - XI_FLEX[None, :])  # L - z
    bend11 = (arm**2 / EI) @ _WF * length
    f12 = (arm / EI) @ _WF * length
    f22 = (1.0 / EI) @ _WF * length
    shear = inv_kGA @ _WF * length
    f11 = bend11 + shear
    det = f11 * f22 - f12**2
    k22 = np.empty((length.size, 2, 2))
    k22[:, 0, 0], k22[:, 0, 1] = f22 / det, -f12 / det
    k22[:, 1, 0], k22[:, 1, 1] = -f12 / det, f11 / det
    B = np.zeros((length.size, 2, 4))
    B[:, 0, 0], B[:, 0, 1], B[:, 0, 2] = -1.0, -length, 1.0
    B[:, 1, 1], B[:, 1, 3] = -1.0, 1.0
    K = np.einsum("eai,eab,ebj->eij", B, k22, B)
    return K, 4.0 * shear / bend11
