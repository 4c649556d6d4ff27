"""Automatic scales of the harmonic-balance unknowns.

Continuation measures its arclength in ``x / x_scale``; a scale of 1 m for a response of
a few micrometres makes every step a jump in frequency alone and hides the resonance.
:func:`unknown_scales` takes the scales from the response of the underlying linear system
at the start frequency (one Newton step from ``x = 0``, which is exact for the linear
part and ignores a nonlinear force that vanishes at rest): per DOF the largest of its
harmonic coefficients, the same in every harmonic, floored at ``FLOOR`` times the largest
over the DOFs (a DOF the forcing does not reach at the start still gets a sensible size).
A start ``x0`` given by the user (a solved point) takes the place of the linear response;
1 is left only when the start is zero (no forcing: the zero solution).
"""

from __future__ import annotations

import numpy as np

from rotorsim.harmonic_balance.fourier import FloatArray
from rotorsim.harmonic_balance.residual import HBResidual

FLOOR = 1e-3
"""Smallest scale of a DOF relative to the largest one."""


def linear_guess(residual: HBResidual, omega: float) -> FloatArray:
    """Newton step from ``x = 0`` at ``omega`` [rad/s]: the linear response when the
    nonlinear forces and their tangents vanish at rest (zeros when it is singular)."""
    x0 = np.zeros(residual.size)
    ev = residual.evaluate(x0, omega)
    assert ev.jacobian is not None
    try:
        step = np.asarray(np.linalg.solve(ev.jacobian, -ev.r), dtype=np.float64)
    except np.linalg.LinAlgError:
        return x0
    return step if np.all(np.isfinite(step)) else x0


def unknown_scales(residual: HBResidual, x: FloatArray) -> FloatArray:
    """Scale (residual.size,) of each unknown from a response ``x`` (module docstring);
    ones when ``x`` is zero."""
    X = np.abs(np.asarray(x, dtype=float).reshape(residual.aft.rows, -1))
    per_dof = X.max(axis=0, initial=0.0)
    top = float(per_dof.max(initial=0.0))
    if top == 0.0:
        return np.ones(residual.size)
    return np.tile(np.maximum(per_dof, FLOOR * top), residual.aft.rows)
