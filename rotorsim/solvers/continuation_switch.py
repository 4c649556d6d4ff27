"""Branch switching: start a second branch of ``R(x, lam) = 0`` off a bifurcation point.

At a simple branch point ``(x*, lam*)`` the ``m x (m + 1)`` extended Jacobian
``A = [dR/dx, dR/dlam]`` has a two-dimensional null space holding the tangents of both
branches. :func:`branch_point_direction` takes the two right singular vectors of ``A``
(scaled unknowns, :class:`~.continuation_core.ScaledSystem`) with the smallest singular
values, projects the known branch's tangent onto their span and returns the unit vector of
the span orthogonal to it: a direction that the second branch crosses transversally and
the first branch only touches to second order.

:func:`continue_from` then *jumps*: the point ``y* + step d`` is corrected on the
hyperplane ``d . y = d . y* + step`` (seed 002 eq 3.42 with the border ``d``), which meets
the second branch at distance ``O(step)`` and the first one only far away, and the branch
is continued from there by :func:`~.continuation.continue_branch`, oriented away from the
bifurcation. The same jump serves a pitchfork of a symmetric problem (period doubling in
a doubled harmonic-balance basis, :mod:`rotorsim.harmonic_balance.branch_switching`),
where the direction is the null vector of the symmetry-breaking block.

References
----------
E. L. Allgower, K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003,
section 8.3 (branching off via the null space of the extended Jacobian); R. Seydel,
Practical Bifurcation and Stability Analysis, Springer 2010, section 5.6.3 (branch
switching by a parallel-hyperplane jump).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.continuation import Branch, continue_branch
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    FloatArray,
    ResidualCallback,
    ScaledSystem,
    correct,
)
from rotorsim.solvers.continuation_state import resolve_scales
from rotorsim.solvers.continuation_stepper import Continuation
from rotorsim.solvers.stats import Stats

WHERE = "branch switching"


@dataclass(frozen=True, eq=False)
class Jump:
    """The first point of a switched branch.

    Attributes
    ----------
    x : array (m,)
        Unknowns at the corrected point.
    lam : float
        Its parameter.
    origin : array (m + 1,)
        The bifurcation point ``(x*, lam*)`` it left.
    direction : array (m + 1,)
        Unit direction of the jump, physical units ``(dx, dlam)`` normalised in scaled ones.
    options : Continuation
        The continuation options with the scales resolved at the bifurcation point (the
        switched branch is measured with them).
    iterations : int
        Corrector iterations of the jump.
    singular_values : array (2,) or None
        At a branch point: the two smallest singular values of the scaled extended
        Jacobian (:func:`branch_point_direction`); None for a given direction.
    """

    x: FloatArray
    lam: float
    origin: FloatArray
    direction: FloatArray
    options: Continuation
    iterations: int
    singular_values: FloatArray | None = None


def scaled_system(residual: ResidualCallback, x: FloatArray, lam: float,
                  options: Continuation) -> tuple[ScaledSystem, Continuation]:
    """The residual in the scales of ``options`` resolved at ``(x, lam)``, and the options
    with those scales written in (so that the switched branch keeps them)."""
    xs, rs, ls = resolve_scales(residual, x, lam, options.x_scale, options.r_scale,
                                options.lam_scale, Stats())
    fixed = dataclasses.replace(options, x_scale=tuple(float(v) for v in xs),
                                r_scale=tuple(float(v) for v in rs), lam_scale=float(ls))
    return ScaledSystem(residual, xs, rs, ls), fixed


def extended_jacobian(system: ScaledSystem, y: FloatArray) -> FloatArray:
    """Dense scaled ``[dR/dx, dR/dlam]`` (m, m + 1) at the scaled point ``y``."""
    ev = system.evaluate(y, Stats())
    jh = ev.jh.toarray() if sp.issparse(ev.jh) else np.asarray(ev.jh)
    return np.column_stack([jh, ev.jlh])


def branch_point_direction(system: ScaledSystem, y: FloatArray, along: FloatArray
                           ) -> tuple[FloatArray, FloatArray]:
    """Scaled unit direction (m + 1,) of the second branch at a branch point ``y``.

    Parameters
    ----------
    system : ScaledSystem
    y : array (m + 1,)
        The branch point (scaled), located to the continuation's tolerance.
    along : array (m + 1,)
        Tangent (or chord) of the known branch there (scaled).

    Returns
    -------
    direction : array (m + 1,)
        Unit vector in the two-dimensional null space orthogonal to the known tangent,
        signed so that its largest component is positive.
    singular_values : array (2,) or (1,)
        The two smallest of the ``m`` singular values of the extended Jacobian (its
        ``(m + 1)``-th is zero), smallest last: at a simple branch point the last one
        vanishes (to the location accuracy) and the other does not (a check).
    """
    A = extended_jacobian(system, y)
    _, s, vt = np.linalg.svd(A)
    null = vt[-2:].T                               # (m + 1, 2), orthonormal columns
    t1 = null @ (null.T @ along)
    t1 /= np.linalg.norm(t1)
    d = null @ (null.T @ _perpendicular(null, t1))
    d /= np.linalg.norm(d)
    return d * (1.0 if d[np.argmax(np.abs(d))] > 0 else -1.0), s[-2:]


def locate_branch_point(system: ScaledSystem, options: Continuation, y0: FloatArray,
                        y1: FloatArray, *, tol: float = 1e-10,
                        max_iter: int = 60) -> tuple[FloatArray, float] | None:
    """The branch point between two scaled points of a branch: ``(y, width)`` or None.

    Points at abscissa ``s`` of the chord ``u = (y1 - y0) / |y1 - y0|`` are corrected on
    the hyperplane ``u . y = u . y0 + s`` (started on the segment between the current
    bracket's corrected ends) and the determinant of ``[[dR/dy], [u^T]]`` is evaluated
    directly: it changes sign at a simple branch point. No tangent is solved (it is
    undefined at the branch point; the tangent-based location of
    :mod:`rotorsim.harmonic_balance.bifurcation` stops short of it when the tangents of
    its probes turn). The Illinois iteration shrinks the bracket to ``tol`` in scaled
    arclength; ``width`` is the final bracket. None when the determinant has the same
    sign at both ends or a probe fails at the start.
    """
    u = (y1 - y0) / np.linalg.norm(y1 - y0)
    corrector = CorrectorOptions(options.tol, options.max_iter, options.max_backtracks,
                                 step_tol=tol)
    reference = [math.nan]

    def probe(start: FloatArray) -> tuple[FloatArray, float] | None:
        corr = correct(system, start, u, float(u @ start), corrector, Stats())
        if not corr.converged or corr.evaluation is None:
            return None
        ev = corr.evaluation
        jh = ev.jh.toarray() if sp.issparse(ev.jh) else np.asarray(ev.jh)
        sign, log_det = np.linalg.slogdet(np.block([[jh, ev.jlh[:, None]], [u[None, :]]]))
        if math.isnan(reference[0]):
            reference[0] = float(log_det)
        return corr.y, float(sign) * math.exp(max(-700.0, min(700.0,
                                                              log_det - reference[0])))

    first, last = probe(y0), probe(y1)
    if first is None or last is None or first[1] * last[1] > 0.0:
        return None
    (lo, f_lo), (hi, f_hi) = first, last
    s_lo, s_hi, g_lo, g_hi, side = 0.0, float(u @ (hi - y0)), f_lo, f_hi, 0
    for _ in range(max_iter):
        if s_hi - s_lo <= tol:
            break
        s = s_hi - g_hi * (s_hi - s_lo) / (g_hi - g_lo)
        mid = 0.5 * (s_lo + s_hi)
        s = s if s_lo < s < s_hi else mid
        new = None
        # the corrector fails exactly on the branch point (its Jacobian is singular
        # there): then a point a little towards the middle, then the middle
        for trial in (s, s + 1e-3 * (mid - s), mid):
            new = probe(lo + (trial - s_lo) / (s_hi - s_lo) * (hi - lo))
            if new is not None:
                break
        if new is None:
            break
        y, f = new
        if f == 0.0:
            return y, 0.0
        if (f > 0.0) == (f_hi > 0.0):
            hi, f_hi, g_hi, s_hi = y, f, f, float(u @ (y - y0))
            g_lo = 0.5 * g_lo if side == -1 else g_lo
            side = -1
        else:
            lo, f_lo, g_lo, s_lo = y, f, f, float(u @ (y - y0))
            g_hi = 0.5 * g_hi if side == 1 else g_hi
            side = 1
    best = lo if abs(f_lo) <= abs(f_hi) else hi
    return best, s_hi - s_lo


def _perpendicular(null: FloatArray, t1: FloatArray) -> FloatArray:
    """The column combination of ``null`` orthogonal to ``t1`` (both in its span)."""
    c = null.T @ t1
    return null @ np.array([-c[1], c[0]])


def jump(system: ScaledSystem, options: Continuation, y0: FloatArray, direction: FloatArray,
         step: float) -> Jump:
    """Correct ``y0 + step direction`` on the hyperplane ``direction . y = direction . y0 +
    step`` (all scaled).

    Raises
    ------
    ConvergenceError
        When the corrector does not converge there (try another ``step``).
    """
    d = direction / np.linalg.norm(direction)
    start = y0 + step * d
    corr = correct(system, start, d, float(d @ start), options.corrector, Stats())
    if not corr.converged:
        raise ConvergenceError(f"the jump of {step:g} (scaled) off the bifurcation point did "
                               f"not converge: {corr.message}", WHERE,
                               iteration=corr.iterations)
    x, lam = system.from_y(corr.y)
    physical = np.concatenate([d[:-1] * system.x_scale, [d[-1] * system.lam_scale]])
    x0, lam0 = system.from_y(y0)
    return Jump(x, lam, np.append(x0, lam0), physical, options, corr.iterations)


def continue_from(residual: ResidualCallback, x: ArrayLike, lam: float,
                  direction: ArrayLike | None, options: Continuation, *,
                  along: ArrayLike | None = None, step: float | None = None,
                  sign: int = 1, **driver: Any) -> tuple[Branch, Jump]:
    """Continue the branch that leaves the bifurcation point ``(x, lam)``.

    Parameters
    ----------
    residual : callable
        ``residual(x, lam) -> (R, dR/dx, dR/dlam)`` as for
        :func:`~rotorsim.solvers.continuation.continue_branch`.
    x : array-like (m,)
        The bifurcation point.
    lam : float
    direction : array-like (m + 1,) or None
        Direction ``(dx, dlam)`` of the new branch in physical units (e.g. a null vector of
        a symmetry-breaking block); None: a simple branch point, the direction is
        :func:`branch_point_direction` with the known branch's tangent ``along``.
    options : Continuation
        Options of the new branch (bounds, steps, scales; "auto" scales are resolved at
        the bifurcation point).
    along : array-like (m + 1,), optional
        Tangent or chord ``(dx, dlam)`` of the known branch (needed when ``direction`` is
        None).
    step : float, optional
        Scaled length of the jump (default ``options.initial_step``).
    sign : {1, -1}
        Which way along the direction.
    **driver
        Passed to ``continue_branch`` (checkpoint, progress, monitor, ...).

    Returns
    -------
    (Branch, Jump)
        The new branch (its first point is the jumped one) and the jump.

    Examples
    --------
    The pitchfork ``R = x (lam - x^2)`` at the origin: the trivial branch ``x = 0`` runs
    along ``lam``, the second branch leaves along ``x``.

    >>> def pitchfork(x, lam):
    ...     return x * (lam - x**2), np.diag(lam - 3 * x**2), x.copy()
    >>> opts = Continuation(initial_step=0.05, max_step=0.1, lam_min=-1.0, lam_max=1.0)
    >>> b, j = continue_from(pitchfork, [0.0], 0.0, None, opts, along=[0.0, 1.0])
    >>> b.status.name, round(float(b.lam[-1]), 12), round(float(b.x[-1, 0]), 9)
    ('OK', 1.0, 1.0)
    """
    if sign not in (1, -1):
        raise ModelError(f"sign must be 1 or -1, got {sign!r}", WHERE)
    x0 = np.array(x, dtype=float).reshape(-1)
    system, fixed = scaled_system(residual, x0, float(lam), options)
    y0 = system.to_y(x0, float(lam))
    singular = None
    if direction is None:
        if along is None:
            raise ModelError("give the known branch's tangent 'along' at a branch point, "
                             "or the direction of the new branch", WHERE)
        d, singular = branch_point_direction(system, y0, _scaled(system, along))
    else:
        d = _scaled(system, direction)
    d = sign * d / np.linalg.norm(d)
    length = float(fixed.initial_step or 0.0) if step is None else float(step)
    if not (math.isfinite(length) and length > 0):
        raise ModelError(f"step must be positive, got {step!r}", WHERE)
    start = dataclasses.replace(jump(system, fixed, y0, d, length),
                                singular_values=singular)
    lo, hi = min(fixed.lam_min, start.lam), max(fixed.lam_max, start.lam)
    run = dataclasses.replace(fixed, lam_min=lo, lam_max=hi)
    branch = continue_branch(residual, start.x, start.lam, run,
                             orientation=np.concatenate([start.x, [start.lam]]) - start.origin,
                             **driver)
    return branch, start


def _scaled(system: ScaledSystem, vector: ArrayLike) -> FloatArray:
    v = np.asarray(vector, dtype=float).reshape(-1)
    if v.shape != (system.m + 1,) or not np.all(np.isfinite(v)) or not np.any(v):
        raise ModelError(f"a direction needs {system.m + 1} finite numbers (dx, dlam), not all "
                         f"zero; got shape {v.shape}", WHERE)
    out = np.concatenate([v[:-1] / system.x_scale, [v[-1] / system.lam_scale]])
    return out / np.linalg.norm(out)
