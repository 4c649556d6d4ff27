"""The accepted point of a continuation step, and the local parametrisation tried when
the predictor's normal plane misses the branch (:mod:`.continuation_stepper`).

At a non-smooth point of a branch (a contact that opens or closes in a harmonic-balance
residual) the corrector on the plane normal to the predictor can fail at every step size,
or converge farther away than the step. Holding instead the component the predictor moves
most, or else the parameter, at its predicted value (a natural parametrisation in that
component) finds the branch beyond the corner; the point is accepted as a corner and the
next predictor is the secant.

References
----------
E. L. Allgower, K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003,
section 2.3 (local parametrisation); R. Seydel, Practical Bifurcation and Stability
Analysis, Springer 2010, section 4.6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    FloatArray,
    ScaledSystem,
    Tangent,
    correct,
    tangent,
)
from rotorsim.solvers.stats import Stats

LOCAL_AFTER = 4
"""Rejected trials (the step cut 16-fold) after which a step in the local parametrisation
is tried (:func:`local_step`); it is tried again at ``min_step``."""


@dataclass(frozen=True, eq=False)
class Accepted:
    """A corrected point the stepper accepts: scaled ``y``, its tangent, corrector
    iterations and residual, the step ``ds``, the tangent's turn [rad], whether it is a
    corner, and whether the corrector was accepted as relaxed."""

    y: FloatArray
    tangent: Tangent | None
    iterations: int
    residual: float
    ds: float
    turn: float
    corner: bool
    relaxed: bool = False


def angle(a: FloatArray, b: FloatArray) -> float:
    """Angle between two unit vectors [rad], accurate for small angles."""
    return 2.0 * math.asin(min(1.0, 0.5 * float(np.linalg.norm(a - b))))


def local_step(system: ScaledSystem, corrector: CorrectorOptions, y0: FloatArray,
               b: FloatArray, ds: float, stats: Stats) -> Accepted | None:
    """A step in a local parametrisation, for a non-smooth point where the corrector
    on the predictor's normal plane fails: the component the predictor moves most, or
    else the parameter, is held at its predicted value. Accepted as a corner, or
    None."""
    y_pred = y0 + ds * b
    for k in dict.fromkeys((int(np.argmax(np.abs(b))), b.size - 1)):
        border = np.zeros_like(b)
        border[k] = 1.0
        corr = correct(system, y_pred, border, float(y_pred[k]), corrector, stats)
        if not corr.converged or corr.evaluation is None:
            continue
        chord = corr.y - y0  # past a corner the branch may turn by 90 degrees or more
        if np.linalg.norm(chord) > 2.0 * ds or float(chord @ b) <= 0.0:
            continue
        tan = tangent(corr.evaluation, chord / np.linalg.norm(chord), stats)
        turn = 0.0 if tan is None else angle(b, tan.t)
        return Accepted(corr.y, tan, corr.iterations, corr.evaluation.residual, ds, turn,
                        True, corr.relaxed)
    return None

