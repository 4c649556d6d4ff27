"""Extrema of a scalar measure along a continued branch (amplitude peaks).

A measure ``a(x, lam)`` (e.g. the amplitude of one DOF of a periodic solution) varies along
the branch with the arclength ``s``. Its extrema are the zeros of

    g(s) = da/ds = grad a . t,

``t`` the unit tangent, evaluated by a central difference of ``a`` along the tangent line
(``(a(y + h t) - a(y - h t)) / 2h`` in scaled unknowns: the tangent line and the branch
agree to first order, so this is ``da/ds`` up to ``O(h^2)``). :func:`locate_extrema` finds
the sign changes of ``g`` between the points of a branch (``+ -> -``: a maximum,
``- -> +``: a minimum) and shrinks each bracket by the Illinois method, re-correcting the
probes onto the branch (:mod:`~.continuation_locate`), to ``tol`` in scaled arclength. At
the extremum ``a`` is flat, so its value is then exact to the corrector tolerance.

References
----------
M. Dowell, P. Jarratt, BIT 11 (1971) 168-174 (the Illinois method). E. L. Allgower,
K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003, section 8.1
(locating zeros of functionals along a curve).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    Evaluation,
    FloatArray,
    ResidualCallback,
    ScaledSystem,
    Tangent,
)
from rotorsim.solvers.continuation_locate import Segment, illinois

Measure = Callable[[FloatArray, float], float]
"""``measure(x, lam) -> a``: a smooth scalar of a branch point."""

KINDS = ("max", "min")


@dataclass(frozen=True, eq=False)
class Extremum:
    """An extremum of a measure along a branch.

    Attributes
    ----------
    kind : str
        "max" or "min".
    lam : float
        Parameter at the extremum.
    x : array (m,)
        Unknowns there.
    value : float
        The measure there.
    index : int
        It lies between branch points ``index`` and ``index + 1``.
    located : bool
        True when the bracket shrank below the tolerance.
    """

    kind: str
    lam: float
    x: FloatArray
    value: float
    index: int
    located: bool


def slope(system: ScaledSystem, measure: Measure, y: FloatArray, t: FloatArray,
          h: float) -> float:
    """``da/ds`` at the scaled point ``y`` along the unit tangent ``t`` (central
    difference of step ``h``)."""
    plus, minus = system.from_y(y + h * t), system.from_y(y - h * t)
    return (measure(*plus) - measure(*minus)) / (2.0 * h)


def locate_extrema(residual: ResidualCallback, branch: Branch, measure: Measure, *,
                   kinds: Sequence[str] = ("max",), tol: float = 1e-10, max_iter: int = 60,
                   fd_step: float = 1e-6) -> tuple[Extremum, ...]:
    """Extrema of ``measure`` between the points of ``branch``.

    Parameters
    ----------
    residual : callable
        The continuation callback that produced ``branch``.
    branch : Branch
    measure : callable
        ``measure(x, lam) -> float``, smooth along the branch.
    kinds : sequence of {"max", "min"}
    tol : float
        Width of the final bracket in scaled arclength.
    max_iter : int
        Illinois iterations per extremum.
    fd_step : float
        Scaled step of the central difference of ``measure``.

    Returns
    -------
    tuple of Extremum
        Sorted along the branch.

    Examples
    --------
    The circle ``x^2 + lam^2 = 1`` traced from ``(1, 0)``: ``x`` is largest at the start
    (an end, not an extremum) and smallest at ``(-1, 0)``.

    >>> from rotorsim.solvers.continuation import Continuation, continue_branch
    >>> def circle(x, lam):
    ...     return (np.array([x[0]**2 + lam**2 - 1.0]), np.array([[2 * x[0]]]),
    ...             np.array([2 * lam]))
    >>> b = continue_branch(circle, [1.0], 0.0, Continuation(max_step=0.3, max_points=40))
    >>> e = locate_extrema(circle, b, lambda x, lam: float(x[0]), kinds=("min",))
    >>> [(p.kind, round(p.value, 10), round(abs(p.lam), 6)) for p in e]
    [('min', -1.0, 0.0)]
    """
    unknown = sorted(set(kinds) - set(KINDS))
    if unknown:
        raise TypeError(f"unknown extremum kinds {unknown}; valid: {', '.join(KINDS)}")
    if not (tol > 0 and fd_step > 0 and max_iter >= 1):
        raise ModelError("need tol > 0, fd_step > 0 and max_iter >= 1", "locate_extrema")
    system = ScaledSystem(residual, branch.x_scale, branch.r_scale, branch.lam_scale)
    corrector = CorrectorOptions(branch.options.tol, branch.options.max_iter,
                                 branch.options.max_backtracks, step_tol=tol,
                                 stall_tol=branch.options.stall_tol)
    points = branch.scaled()
    g = np.array([slope(system, measure, y, t, fd_step)
                  for y, t in zip(points, branch.tangents, strict=True)])
    out = []
    for i in np.flatnonzero(np.sign(g[1:]) * np.sign(g[:-1]) < 0):
        kind = "max" if g[i] > 0 else "min"
        if kind in kinds:
            found = _refine(system, corrector, measure, points, int(i), kind, tol, max_iter,
                            fd_step)
            if found is not None:
                out.append(found)
    return tuple(out)


def _refine(system: ScaledSystem, corrector: CorrectorOptions, measure: Measure,
            points: FloatArray, i: int, kind: str, tol: float, max_iter: int,
            fd_step: float) -> Extremum | None:
    def test(y: FloatArray, ev: Evaluation, tan: Tangent,
             border: FloatArray) -> tuple[float, None]:
        return slope(system, measure, y, tan.t, fd_step), None

    segment = Segment.between(system, corrector, points[i], points[i + 1], test)
    lo, hi = segment.endpoint(points[i]), segment.endpoint(points[i + 1])
    if lo is None or hi is None or lo.value * hi.value > 0.0:
        return None
    lo, hi = illinois(segment, lo, hi, tol, max_iter)
    values = [measure(*system.from_y(p.y)) for p in (lo, hi)]
    best = int(np.argmax(values)) if kind == "max" else int(np.argmin(values))
    x, lam = system.from_y((lo, hi)[best].y)
    return Extremum(kind, lam, x, float(values[best]), i, hi.s - lo.s <= tol)
