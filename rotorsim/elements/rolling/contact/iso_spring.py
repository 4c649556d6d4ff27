"""The ISO/TS 16281 spring constant of a ball (the option beside exact Hertz).

ISO/TS 16281:2008 gives the load-deflection constant of one ball, inner and outer contact
in series (``Q = c_p delta^1.5``; N and mm inside, with ``E`` in N/mm^2), as::

    c_p = 1.48 E / (1 - nu^2) [sum_{i,e} K(chi) (Sum rho / (chi^2 E(chi)))^(1/3)]^(-3/2)

with, at ``gamma = D cos(a) / d_m`` (upper signs inner race)::

    Sum rho = (2/D) (2 +- gamma / (1 -+ gamma) - 1 / (2 f))
    F(rho)  = (+-gamma / (1 -+ gamma) + 1 / (2 f)) / (2 +- gamma / (1 -+ gamma) - 1 / (2 f))
    1 - 2 / (chi^2 - 1) (K / E - 1) = F(rho)       (defines the ellipse ratio chi)

``K``, ``E`` the complete elliptic integrals of parameter ``1 - 1/chi^2``. This is Hertz's
solution (Harris & Kotzalas, *Advanced Concepts*, ch. 1; the same relations as
:mod:`~rotorsim.elements.rolling.contact.hertz_point`): the exact constant is
``pi / sqrt(4.5) = 1.48096...`` where the standard prints 1.48, so the ISO constant is
``1.48 / 1.48096 = 0.99935`` times the exact one (deflections 0.043 % larger at equal
load). Here ``chi`` is solved with scipy's elliptic integrals and ``brentq``, independently
of the exact-Hertz code, and the tests check the ratio.

Use it as ``BallBearing(Kn=iso16281_ball_constant(...), ...)``; for rollers the ISO/TS
16281 constant ``c_L = 35948 L^(8/9)`` is the default of ``RollerBearing`` without ``Kn``.
"""

from __future__ import annotations

import math

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from rotorsim.errors import ModelError

ISO_CONSTANT = 1.48
"""The rounded ``pi / sqrt(4.5)`` of ISO/TS 16281."""


def _ellipse_ratio(curvature_difference: float) -> float:
    """``chi = a / b`` with ``1 - 2 / (chi^2 - 1) (K / E - 1) = F(rho)``."""
    def residual(chi: float) -> float:
        m = 1.0 - 1.0 / chi**2
        return 1.0 - 2.0 / (chi**2 - 1.0) * (ellipk(m) / ellipe(m) - 1.0) \
            - curvature_difference
    return float(brentq(residual, 1.0 + 1e-9, 1e4, xtol=1e-14, rtol=1e-14))


def iso16281_ball_constant(ball_diameter: float, pitch_diameter: float, contact_angle: float,
                           f_i: float, f_o: float, E: float = 2.08e11, nu: float = 0.3
                           ) -> float:
    """ISO/TS 16281 ``c_p`` of one ball (both contacts) [N/m^1.5] (module docstring).

    Parameters
    ----------
    ball_diameter, pitch_diameter : float
        ``D``, ``d_m`` [m].
    contact_angle : float
        [rad].
    f_i, f_o : float
        Groove curvature factors (> 0.5).
    E, nu : float
        Young's modulus [Pa] and Poisson ratio of balls and rings (the same material).

    Examples
    --------
    >>> round(iso16281_ball_constant(11.5e-3, 43.5e-3, 0.0, 0.52, 0.53, 2.1e11) / 1e9, 3)
    10.542
    """
    where = "iso16281_ball_constant"
    if not 0.0 < ball_diameter < pitch_diameter:
        raise ModelError(f"need 0 < ball_diameter < pitch_diameter, got {ball_diameter}, "
                         f"{pitch_diameter} m", where)
    if not (f_i > 0.5 and f_o > 0.5):
        raise ModelError(f"groove factors must be > 0.5, got {f_i}, {f_o}", where)
    if not (E > 0 and 0 <= nu < 0.5):
        raise ModelError(f"need E > 0 and 0 <= nu < 0.5, got {E}, {nu}", where)
    d_mm = ball_diameter * 1e3
    gamma = ball_diameter * math.cos(contact_angle) / pitch_diameter
    total = 0.0
    for sign, f in ((1.0, f_i), (-1.0, f_o)):
        conform = sign * gamma / (1.0 - sign * gamma)
        denominator = 2.0 + conform - 1.0 / (2.0 * f)
        sum_rho = 2.0 / d_mm * denominator
        chi = _ellipse_ratio((conform + 1.0 / (2.0 * f)) / denominator)
        m = 1.0 - 1.0 / chi**2
        total += ellipk(m) * (sum_rho / (chi**2 * ellipe(m))) ** (1.0 / 3.0)
    c_p = ISO_CONSTANT * (E * 1e-6) / (1.0 - nu**2) * total ** -1.5  # N/mm^1.5
    return float(c_p * 1e3**1.5)
