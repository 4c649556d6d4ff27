"""Growth of a bifurcation's critical Floquet mode along free transients of the full model.

The check of :func:`rotorsim.verify_events` with ``measure="floquet"``. At an event the
branch's Floquet multipliers cross ``|mu| = 1``: on the *unstable side* some ``|mu| > 1 +
margin``, on the *stable side* the mode it continues is inside (or on) the unit circle. On
each side:

1. the critical mode: on the unstable side the multiplier of largest modulus, on the stable
   side the mode whose shape matches it best (modal assurance criterion), with its right and
   left eigenvectors (:mod:`rotorsim.verification.floquet_modes`, expanded to all DOFs);
2. two free transients of the full model (:class:`~.period_map.PeriodMap`), from the
   harmonic-balance state ``z0`` at phase 0 and from ``z0`` plus the real part of the right
   eigenvector scaled to a small translation; their difference ``d_k`` at ``t = k T``
   removes the drift of the transient from the (truncated) harmonic-balance orbit;
3. the mode's coordinate ``c_k = l^H P d_k`` (left eigenvector, mass-weighted projection):
   other modes drop out, neutral ones (``|mu| = 1``: rigid axial play, undamped modes)
   included, so a neutral mode cannot pose as the instability; the measured multiplier is
   the least-squares ratio ``m = sum c_(k+1) conj(c_k) / sum |c_k|^2``.

The verdict of a side (:func:`side_verdict`):

* unstable (``|mu| > 1 + margin``): ``|m| > 1 + margin / 2``, the growth rate of the right
  order, ``1 / band <= ln |m| / ln |mu| <= band`` (the transient follows the real
  trajectory, which differs from the truncated harmonic-balance orbit the multiplier is
  computed on: the rate is not expected to agree to more than a factor), and its *direction*
  as Floquet's: a real ``mu > 1`` departs monotonically (``Re(c_k / c_0) > 0`` for every
  ``k``: a fold or pitchfork), a real ``mu < -1`` alternates sign every period (a period
  doubling), a complex pair turns by ``arg mu`` per period (within ``angle``);
* stable: ``|m| <= 1 + margin``: no growth beyond the margin (a neutral mode passes).

A fold is confirmed the same way: its middle sheet carries the real multiplier above 1 (the
saddle), its outer sheet the same mode inside the circle (the node), and the free transient
on the middle sheet departs monotonically along that mode -- the saddle-node's signature. A
jump test (a transient past the fold leaving it) is not used: the passage time near a
saddle-node grows like ``(offset)^(-1/2)`` periods, hundreds on a lightly damped rotor.

References
----------
Seydel (2010), *Practical Bifurcation and Stability Analysis*, sections 7.1-7.4 (multipliers
crossing at +1, -1 and as a complex pair; the saddle-node's real multiplier).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.verification.floquet_modes import BranchModes, PointModes
from rotorsim.verification.period_map import FloatArray, PeriodMap

ComplexArray = NDArray[np.complex128]
BAND = 3.0
"""Largest factor between the measured and Floquet's growth rates ``ln |mu|``."""
ANGLE = 0.3
"""Largest difference of the turn per period of a complex pair [rad]."""


@dataclass(frozen=True, eq=False)
class ModeGrowth:
    """A Floquet mode's coordinate along two free transients.

    Attributes
    ----------
    mode : int
        Index of the mode in the point's multipliers.
    floquet : complex
        Its multiplier (Hsu's monodromy of the stability model).
    measured : complex
        Least-squares multiplier of its coordinate per period.
    coordinates : complex array (K + 1,)
        ``c_k / c_0``.
    """

    mode: int
    floquet: complex
    measured: complex
    coordinates: ComplexArray


def mode_growth(pm: PeriodMap, q0: FloatArray, v0: FloatArray, modes: BranchModes,
                point: PointModes, j: int, size: float, periods: int
                ) -> tuple[ModeGrowth, FloatArray]:
    """Two free transients over ``periods`` periods, from ``(q0, v0)`` and from it plus
    mode ``j`` scaled to a largest translation ``size`` [m]; returns the growth and the
    displacements of the first run at ``t = k T`` (periods + 1, ALL DOFs) [m, rad]."""
    dq, dv = modes.perturbation(point, j, size)
    qb, vb = pm.flow(q0, v0, periods)
    qp, vp = pm.flow(q0 + dq, v0 + dv, periods)
    c = modes.coordinates(point, j, qp - qb, vp - vb)
    c = c / c[0]
    m = complex(np.sum(c[1:] * np.conj(c[:-1])) / np.sum(np.abs(c[:-1]) ** 2))
    return ModeGrowth(j, complex(point.multipliers[j]), m, c), qb


def side_verdict(growth: ModeGrowth, margin: float, band: float = BAND,
                 angle: float = ANGLE) -> str:
    """Why the measured growth disagrees with Floquet's multiplier ("" when it agrees;
    module docstring)."""
    mu, m, c = growth.floquet, growth.measured, growth.coordinates
    if not (np.all(np.isfinite(c)) and cmath.isfinite(m)):
        return "the mode's coordinate is not finite"
    text = f"mode {growth.mode}: measured {_show(m)} against Floquet {_show(mu)}"
    if abs(mu) <= 1.0 + margin:
        return "" if abs(m) <= 1.0 + margin else f"{text}: grows on the stable side"
    if abs(m) <= 1.0 + 0.5 * margin:
        return f"{text}: does not grow"
    ratio = math.log(abs(m)) / math.log(abs(mu))
    if not 1.0 / band <= ratio <= band:
        return f"{text}: growth rate off by a factor {ratio:.3g}"
    sign = np.real(c)
    if abs(mu.imag) <= 1e-9 * abs(mu) and mu.real > 0.0:
        return "" if np.all(sign > 0.0) else f"{text}: not a monotone departure"
    if abs(mu.imag) <= 1e-9 * abs(mu):
        alternating = np.all(sign * (-1.0) ** np.arange(sign.size) > 0.0)
        return "" if alternating else f"{text}: does not alternate sign"
    turn = abs(cmath.phase(m / mu))
    return "" if turn <= angle else f"{text}: turns {turn:.3g} rad per period off"


def kind_of(mu: complex) -> str:
    """Which crossing a multiplier outside the unit circle stands for."""
    if abs(mu.imag) > 1e-9 * abs(mu):
        return "neimark_sacker"
    return "period_doubling" if mu.real < 0.0 else "fold or branch point"


def _show(mu: complex) -> str:
    if abs(mu.imag) <= 1e-9 * max(abs(mu), 1e-300):
        return f"{mu.real:.4g}"
    return f"{abs(mu):.4g} at {cmath.phase(mu):+.3g} rad"
