"""Batched equilibrium of rolling elements with 2 internal DOFs each (seed 001 eqs 20-22).

Every rolling element of every sample has a small potential ``Pi(x)`` in its 2 internal
DOFs ``x`` (its position between the rings), convex in the roller coordinates.
:func:`solve_elements` minimises all of them at once by Newton's method with a per-element
backtracking line search. Only the elements still iterating are evaluated (boolean masks):
the loop runs over iterations, never over elements or samples (DESIGN section 4).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.rolling.state import FloatArray
from rotorsim.errors import ConvergenceError, ModelError

Mask = NDArray[np.bool_]


class ElementEvaluation(NamedTuple):
    """Potential of each element and its derivatives in its 2 internal DOFs.

    Arrays have the leading shape of the evaluated elements: ``(S, N)`` for all of them,
    ``(M,)`` for the ``M`` elements of a mask.
    """

    energy: FloatArray  # Pi [J]
    grad: FloatArray  # dPi/dx (..., 2) [N]
    hess: FloatArray  # (h00, h01, h11) (..., 3) [N/m]
    scale: FloatArray  # force scale of the convergence test [N]
    aux: Any  # model quantities (tuples of arrays of the same leading shape)


Evaluate = Callable[[FloatArray, "Mask | None"], ElementEvaluation]
"""``evaluate(x, mask)``: ``x (S, N, 2)`` with ``mask=None``, else ``x (M, 2)`` for the
elements where ``mask (S, N)`` is true."""


class ElementSolution(NamedTuple):
    """Outcome of :func:`solve_elements`."""

    x: FloatArray  # internal DOFs (S, N, 2) [m]
    evaluation: ElementEvaluation  # at x, (S, N)
    iterations: int  # Newton iterations taken
    converged: Mask  # (S, N)
    lost: Mask  # (S, N): touching neither ring (no equilibrium)


def solve_elements(evaluate: Evaluate, x0: FloatArray, floor: FloatArray, length: FloatArray,
                   max_step: FloatArray, *, tol: float, max_iter: int) -> ElementSolution:
    """Minimise the potentials of ``S x N`` elements in 2 DOFs each, all at once.

    Newton steps ``-H^-1 g`` (at most ``max_step`` long; an indefinite ``H`` is shifted to
    be positive definite) with a backtracking (Armijo) line search on the potential, per
    element. An element is converged when ``max |g| <= tol * scale_max``, with
    ``scale_max`` the largest force scale of the elements of its sample (the bearing force
    is then accurate to ``tol`` relative to the largest element load), or when its step
    stalls below ``1e-14 length`` (round-off of its coordinates). An element that touches
    neither ring for two iterations is ``lost``; one whose line search fails (a
    discontinuity) stops. Neither counts as converged.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(x, mask)`` (:data:`Evaluate`).
    x0 : array (S, N, 2)
        Starting internal DOFs [m].
    floor : array (S, N, 2)
        Contact stiffnesses [N/m] that replace a zero diagonal of the Hessian (elements
        touching neither ring; a roller resting on its centre slice alone has no tilt
        stiffness).
    length : array (S, N)
        Size [m] of the coordinates: sets their round-off (stalled steps, potential).
    max_step : array (S, N)
        Longest Newton step [m] (a step along a direction without stiffness, e.g. a roller
        tilting about the one slice it rests on, is cut to this length first).
    tol : float
        Relative force tolerance.
    max_iter : int
        Newton iteration limit.

    Examples
    --------
    >>> def quadratic(x, mask):
    ...     g = 2.0 * x - 1.0
    ...     h = np.broadcast_to([2.0, 0.0, 2.0], (*x.shape[:-1], 3))
    ...     return ElementEvaluation((x * x - x).sum(-1), g, h, np.ones(x.shape[:-1]), ())
    >>> one = np.ones((1, 1))
    >>> sol = solve_elements(quadratic, np.zeros((1, 1, 2)), np.ones((1, 1, 2)), one, one,
    ...                      tol=1e-12, max_iter=5)
    >>> sol.x.ravel().tolist(), sol.iterations, bool(sol.converged.all())
    ([0.5, 0.5], 1, True)
    """
    x = np.array(x0, dtype=float)
    ev = evaluate(x, None)
    shape = x.shape[:2]
    stalled, blocked = np.zeros(shape, dtype=bool), np.zeros(shape, dtype=bool)
    no_contact = np.zeros(shape, dtype=int)
    iterations = 0
    while True:
        ref = ev.scale.max(axis=1, keepdims=True)  # the sample's largest element load
        converged = stalled | (np.abs(ev.grad).max(axis=-1) <= tol * ref)
        free = (ev.hess[..., 0] <= 0.0) & (ev.hess[..., 2] <= 0.0)
        no_contact = np.where(free & ~converged, no_contact + 1, 0)
        lost = no_contact >= 2
        active = ~(converged | blocked | lost)
        if not active.any() or iterations == max_iter:
            return ElementSolution(x, ev, iterations, converged, lost)
        current = _take(ev, active)
        x_new, ev_new, ok = _line_search(evaluate, active, x[active], current,
                                         _newton_step(current, floor[active],
                                                      max_step[active]),
                                         length[active])
        moved = np.abs(x_new - x[active]).max(axis=-1)
        stalled[active] = ok & (moved <= 1e-14 * length[active])
        blocked[active] = ~ok
        x[active] = x_new
        ev = _put(ev, active, ev_new)
        iterations += 1


def _line_search(evaluate: Evaluate, active: Mask, x: FloatArray, ev: ElementEvaluation,
                 step: FloatArray, length: FloatArray
                 ) -> tuple[FloatArray, ElementEvaluation, Mask]:
    """Armijo backtracking along ``step`` for the active elements (arrays ``(M, ...)``);
    elements without a descent after 40 halvings keep their point (``ok`` false)."""
    slope = (ev.grad * step).sum(axis=-1)
    slack = 1e-13 * ev.scale * length  # round-off of the potential
    t = np.ones(x.shape[0])
    trial = evaluate(x + step, active)
    ok = trial.energy <= ev.energy + 1e-4 * slope + slack
    where = np.argwhere(active)
    for _ in range(40):
        if ok.all():
            break
        t = np.where(ok, t, 0.5 * t)
        retry = np.zeros_like(active)
        retry[tuple(where[~ok].T)] = True
        again = evaluate(x[~ok] + t[~ok, None] * step[~ok], retry)
        trial = _put(trial, ~ok, again)
        ok = trial.energy <= ev.energy + 1e-4 * t * slope + slack
    t = np.where(ok, t, 0.0)
    return x + t[:, None] * step, _put(trial, ~ok, _take(ev, ~ok)), ok


def _take(tree: Any, mask: Mask) -> Any:
    """The entries of ``mask`` of every array of a (nested) tuple of arrays."""
    if isinstance(tree, np.ndarray):
        return tree[mask]
    if isinstance(tree, tuple):
        parts = [_take(item, mask) for item in tree]
        return type(tree)(*parts) if hasattr(tree, "_fields") else tuple(parts)
    return tree


def _put(tree: Any, mask: Mask, values: Any) -> Any:
    """A copy of ``tree`` with ``values`` at the entries of ``mask``."""
    if isinstance(tree, np.ndarray):
        out = np.array(tree)
        out[mask] = values
        return out
    if isinstance(tree, tuple):
        parts = [_put(a, mask, b) for a, b in zip(tree, values, strict=True)]
        return type(tree)(*parts) if hasattr(tree, "_fields") else tuple(parts)
    return tree


def check_solution(sol: ElementSolution, where: str, lost_reason: str) -> None:
    """Raise if an element has no equilibrium (:class:`ModelError` with ``lost_reason``)
    or was not converged (:class:`ConvergenceError`)."""
    if sol.lost.any():
        raise ModelError(f"{int(sol.lost.sum())} rolling elements have no equilibrium: "
                         f"{lost_reason}", where)
    if not sol.converged.all():
        ev = sol.evaluation
        rel = np.abs(ev.grad).max(axis=-1) / ev.scale.max(axis=1, keepdims=True)
        raise ConvergenceError(f"rolling-element equilibrium not found for "
                               f"{int((~sol.converged).sum())} elements (a contact opening "
                               "on the far side of a groove, or too few iterations)", where,
                               iteration=sol.iterations,
                               residual=float(rel[~sol.converged].max()))


def _newton_step(ev: ElementEvaluation, floor: FloatArray, max_step: FloatArray
                 ) -> FloatArray:
    """``-H^-1 g`` per element, at most ``max_step`` long (arrays ``(M, ...)``)."""
    h00, h01, h11 = ev.hess[..., 0], ev.hess[..., 1], ev.hess[..., 2]
    h00 = h00 + np.where(h00 > 0.0, 0.0, floor[..., 0])
    h11 = h11 + np.where(h11 > 0.0, 0.0, floor[..., 1])
    # rank-1 Hessians (a roller on one slice: no stiffness about that slice): Marquardt
    # damping of the diagonal; the step cap and the line search handle the null space
    damp = np.where(h00 * h11 - h01 * h01 <= 1e-8 * h00 * h11, 1.0 + 1e-12, 1.0)
    h00, h11 = h00 * damp, h11 * damp
    # an indefinite Hessian (the polar coordinates of a ball far from equilibrium) is
    # shifted to be positive definite: the step is then a descent direction
    lam_min = 0.5 * (h00 + h11) - np.sqrt(0.25 * (h00 - h11) ** 2 + h01 * h01)
    shift = np.where(h00 * h11 - h01 * h01 < 0.0, -1.5 * lam_min, 0.0)
    h00, h11 = h00 + shift, h11 + shift
    det = h00 * h11 - h01 * h01
    g0, g1 = ev.grad[..., 0], ev.grad[..., 1]
    step = np.stack([-(h11 * g0 - h01 * g1) / det, -(h00 * g1 - h01 * g0) / det], axis=-1)
    size = np.abs(step).max(axis=-1)
    return step * np.minimum(1.0, max_step / np.where(size > 0.0, size, 1.0))[..., None]
