"""Bearing statics: the displacement of a rigid-ring bearing under given forces and moments.

Finds ``delta = [x, y, z, rx, ry]`` of the inner ring relative to the outer ring such that
the bearing force equals the load, ``F(delta) = dU/d delta = load`` (seed 000 eqs 5, 11),
i.e. the stationary points of the potential energy ``Pi = U(delta) - load.delta``
(eqs 18, 26). Three methods:

* ``"newton"``: damped Newton with line search on ``F(delta) - load`` (exact tangent,
  seed 000 eq 27), :mod:`rotorsim.solvers.newton`;
* ``"energy"``: trust-region minimisation of ``Pi`` with its exact gradient and Hessian
  (SciPy ``trust-exact``), :func:`rotorsim.solvers.minimize.minimize_energy`;
* ``"global"``: the energy method of seed 000 section 4 (Fig. 4): a multi-start search over
  the physical range that reports every distinct admissible minimum and keeps the lowest.

All three start from the point on the ray along the (scaled) load direction where the
bearing force balances the load's projection (one batched evaluation of the model).

Degenerate directions (seed 000 section 4) are detected from the model, not from the
bearing type: the stiffness is probed at 20 displacements that load the bearing in every
direction; a DOF that never carries stiffness (the contacts do not depend on it: ``z`` of a
cylindrical roller bearing, ``x``, ``y`` of a thrust roller bearing) is held at 0 and named
in the result. A load on such a DOF raises :class:`ModelError`. So does a load that has no
equilibrium within the physical range of displacements (``max_displacement``, default
``|r_L| + A0 + d / 20``: clearance, groove-centre distance of a ball bearing and a twentieth
of the rolling-element diameter).

For the rigid-ring models of this package the strain energy is convex (each contact
deflection is a convex function of ``delta``, raised to a power ``>= 1``), so a
physically meaningful load has a single minimum and the three methods agree; several minima
appear with a destabilising ``load_stiffness`` (e.g. unbalanced magnetic pull), which the
global search resolves.

:func:`linearize_at_load` linearises a 2-node bearing element at the equilibrium under a
load: the equilibrium is found here, the element only evaluates its tangent at the
displacement found (physics never calls analyses).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.statics.bearing_problem import (
    METHODS,
    bearing_summary,
    check_positive,
    make_result,
    make_setup,
    solve_global,
    solve_local,
)
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.results.bearing import (
    BearingEquilibriumResult,
    StiffnessVariation,
)
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]


@checked_keywords
def bearing_equilibrium(
    bearing: Any,
    load: ArrayLike,
    *,
    phi: float = 0.0,
    method: str = "auto",
    x0: ArrayLike | None = None,
    tol: float = 1e-10,
    max_iter: int = 50,
    load_stiffness: ArrayLike | None = None,
    max_displacement: float | None = None,
    n_starts: int = 64,
    seed: int = 0,
) -> BearingEquilibriumResult:
    """Displacement, contact loads and stiffness of a bearing under a static load.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        A rigid-ring model (``state``, ``element_angles``).
    load : array (5,)
        ``[Fx, Fy, Fz, Mx, My]`` applied to the inner ring [N, N m].
    phi : float
        Shaft angle [rad]: places the rolling elements (``bearing.element_angles(phi)``).
    method : {"auto", "newton", "energy", "global"}
        Solution method (module docstring). ``"auto"`` tries Newton, then the energy
        minimisation, then the global search (which also diagnoses a load without
        equilibrium); the result names the method that succeeded and notes the failures.
    x0 : array (5,), optional
        Starting displacement (local methods); default: the load-direction ray guess.
    tol : float
        ``max |(F - load) s| <= tol max |load s|`` (moments divided by the pitch radius).
    max_iter : int
        Iteration limit (Newton; the energy methods use 4x this many).
    load_stiffness : array (5, 5), optional
        Symmetric stiffness ``K_L`` of a displacement-dependent load, ``load + K_L delta``
        (positive = destabilising, e.g. unbalanced magnetic pull of a motor).
    max_displacement : float, optional
        Physical range [m] of the translations (tilts: divided by the pitch radius).
    n_starts, seed : int
        Sobol starts of the global search and their seed.

    Returns
    -------
    BearingEquilibriumResult

    Raises
    ------
    ModelError
        Load on a DOF the bearing cannot resist, or no equilibrium within the range.
    ConvergenceError
        If the solver fails although an equilibrium may exist.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> b = BallBearing(n_balls=12, pitch_diameter=39.3e-3, ball_diameter=7.9e-3,
    ...                 Kn=8.5e9, A0=0.05e-3, contact_angle=0.7, cage="fixed")
    >>> r = bearing_equilibrium(b, [0.0, 0.0, 3000.0, 0.0, 0.0])
    >>> round(float(r.displacement[2]) * 1e6, 3), r.load_zone.size, r.held_dofs
    (15.615, 12, ())
    """
    if method == "auto":
        return _auto(bearing, load, phi=phi, x0=x0, tol=tol, max_iter=max_iter,
                     load_stiffness=load_stiffness, max_displacement=max_displacement,
                     n_starts=n_starts, seed=seed)
    if method not in METHODS:
        raise TypeError(f"bearing_equilibrium: unknown method {method!r}; valid: "
                        f"{('auto', *METHODS)}")
    if not math.isfinite(phi):
        raise ModelError(f"phi must be finite, got {phi!r}", "bearing_equilibrium")
    check_positive(tol, max_iter, n_starts)
    stats = Stats()
    psi = np.atleast_2d(bearing.element_angles(float(phi)))
    setup = make_setup(bearing, load, psi, load_stiffness, max_displacement)
    options = {"method": method, "phi": float(phi), "tol": tol, "max_iter": max_iter,
               "max_displacement": setup.range, "n_starts": n_starts, "seed": seed}
    search: dict[str, int] = {}
    if method == "global":
        delta, iterations, minima = solve_global(setup, tol, max_iter, n_starts, seed, stats,
                                                  search)
    else:
        delta, iterations = solve_local(setup, method, x0, tol, max_iter, stats)
        minima = ()
    result = make_result(setup, delta, method, float(phi), iterations, minima, stats, options)
    return dataclasses.replace(result, search=search) if search else result


def _auto(bearing: Any, load: ArrayLike, **options: Any) -> BearingEquilibriumResult:
    """Newton, then energy minimisation, then the global search; failures are noted."""
    failures: list[str] = []
    for method in METHODS:
        try:
            result = bearing_equilibrium(bearing, load, method=method, **options)
        except ConvergenceError as exc:
            failures.append(f"{method}: {exc}")
            continue
        notes = tuple(f"{f} (then tried the next method)" for f in failures)
        return dataclasses.replace(result, notes=(*result.notes, *notes))
    raise ConvergenceError("no method converged: " + "; ".join(failures),
                           "bearing_equilibrium")


def stiffness_over_pass(
    bearing: Any,
    load: ArrayLike | None = None,
    n_points: int = 24,
    *,
    displacement: ArrayLike | None = None,
    method: str = "newton",
    tol: float = 1e-10,
    max_iter: int = 50,
    load_stiffness: ArrayLike | None = None,
    max_displacement: float | None = None,
) -> StiffnessVariation:
    """Displacement and stiffness over one element-pass period (varying compliance).

    The element set is turned by ``2 pi k / (N P)``, ``k = 0 .. P-1``; under a ``load`` the
    equilibrium is solved at each position (warm-started from the previous one), under a
    prescribed ``displacement`` the stiffness is evaluated directly (one batched call).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
    load : array (5,), optional
        Applied load [N, N m]; give it or ``displacement``.
    n_points : int
        Positions ``P`` per element pass.
    displacement : array (5,), optional
        Prescribed ``delta`` [m, rad].
    method, tol, max_iter, load_stiffness, max_displacement
        As for :func:`bearing_equilibrium` (``method`` "newton" or "energy").

    References
    ----------
    Seed 000 Figs 6c-6d and 12 (case vi).

    Examples
    --------
    >>> from rotorsim.elements.rolling.roller.bearing import RollerBearing
    >>> b = RollerBearing(14, 42.5e-3, 7.5e-3, 7.5e-3, Kn=3.0e8, cage="fixed")
    >>> v = stiffness_over_pass(b, [5000.0, 0, 0, 0, 0], n_points=8)
    >>> v.held_dofs, bool(v.stiffness_fluctuation[0, 0] > 0)
    (('z',), True)
    """
    if (load is None) == (displacement is None):
        raise ModelError("give exactly one of load and displacement", "stiffness_over_pass")
    if method not in ("newton", "energy"):
        raise TypeError(f"stiffness_over_pass: unknown method {method!r}; valid: "
                        "('newton', 'energy')")
    if isinstance(n_points, bool) or not isinstance(n_points, int | np.integer) or n_points < 1:
        raise ModelError(f"n_points must be an integer >= 1, got {n_points!r}",
                         "stiffness_over_pass")
    check_positive(tol, max_iter, 1)
    stats = Stats()
    pitch = 2.0 * math.pi / bearing.n_elements
    cage = pitch * np.arange(n_points) / n_points
    psi = np.atleast_2d(bearing.element_angles(0.0)) + cage[:, None]
    kappa = float(getattr(bearing, "kappa", 0.0))
    shaft = cage / kappa if kappa > 0 else np.full(n_points, np.nan)
    held: tuple[str, ...] = ()
    if displacement is not None:
        d = np.asarray(displacement, dtype=float).reshape(5)
        deltas = np.tile(d, (n_points, 1))
        states = bearing.state(deltas, psi)
        load_arr = None
    else:
        assert load is not None
        deltas = np.zeros((n_points, 5))
        first = make_setup(bearing, load, psi[:1], load_stiffness, max_displacement)
        held = tuple(name for name, _ in first.held)
        x0 = None
        for k in range(n_points):
            setup = first if k == 0 else make_setup(bearing, load, psi[k:k + 1], load_stiffness,
                                                max_displacement, first.held)
            deltas[k] = _pass_point(setup, method, x0, tol, max_iter, stats)
            x0 = deltas[k]
        states = bearing.state(deltas, psi)
        load_arr = first.load
    return StiffnessVariation(
        position=np.arange(n_points) / n_points, cage_angle=cage, shaft_angle=shaft,
        displacement=deltas, force=states.force, stiffness=states.stiffness,
        max_element_load=states.element_load.max(axis=1), load=load_arr, held_dofs=held,
        options={"n_points": n_points, "method": method, "tol": tol},
        stats=stats.finish(), status=Status.OK, summary=bearing_summary(bearing))


def _pass_point(setup: Any, method: str, x0: FloatArray | None, tol: float, max_iter: int,
                stats: Stats) -> FloatArray:
    """One position of :func:`stiffness_over_pass`, warm-started from the previous one; when
    that fails, from the load-direction ray guess, then by the other local method (as
    ``method="auto"`` of :func:`bearing_equilibrium`). With a clearance a ball entering or
    leaving the contact zone moves the ring sideways between two positions (the textbook
    varying-compliance case: one ball under the load has no lateral stiffness), and Newton
    may find no useful tangent on the way."""
    other = "energy" if method == "newton" else "newton"
    tries = [(method, x0), (method, None), (other, None)] if x0 is not None \
        else [(method, None), (other, None)]
    failure = None
    for name, start in tries:
        try:
            delta, _ = solve_local(setup, name, start, tol, max_iter, stats)
            return np.asarray(delta, dtype=float)
        except ConvergenceError as exc:
            failure = exc
    assert failure is not None
    raise failure


def linearize_at_load(element: Any, load: ArrayLike, *, phi: float = 0.0,
                      speed: float | None = None, frequency: float | None = None,
                      **options: Any) -> BearingElement:
    """Linear ``BearingElement`` of a 2-node rolling-bearing element at the equilibrium
    under a static load (for modal, Campbell and critical-speed analyses).

    Solves :func:`bearing_equilibrium` of the element's model at ``speed``
    (``element.model_at_speed``) and linearises the element at that displacement with the
    equilibrium's tangent (``element.linearize(displacement=..., tangent=...)``).

    Parameters
    ----------
    element : RollingBearing or FlexibleRingBearingElement
    load : array (5,)
        ``[Fx, Fy, Fz, Mx, My]`` on the inner ring [N, N m].
    phi : float
        Shaft angle [rad] (element positions).
    speed : float, optional
        Shaft speed [rad/s]: the centrifugal force of the rolling elements, the
        entrainment speed of ``"ehl"`` contact damping (required there).
    frequency : float, optional
        ``"ehl"``: vibration frequency [rad/s] of the damping (``RollingBearing.linearize``).
    **options
        Passed on to :func:`bearing_equilibrium` (``method``, ``tol``, ``max_iter``, ...).

    Returns
    -------
    BearingElement
        The full 5x5 tangent (and damping) at the equilibrium; same nodes and tag.

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> from rotorsim.elements.rolling.element import RollingBearing
    >>> ball = BallBearing(n_balls=8, pitch_diameter=0.04, ball_diameter=0.008, Kn=8e9,
    ...                    f_i=0.52, f_o=0.52)
    >>> lin = linearize_at_load(RollingBearing(ball, n=0), [0.0, -500.0, 0.0, 0.0, 0.0])
    >>> lin.stiffness_matrix.shape, bool(lin.stiffness_matrix[1, 1] > 0)
    ((5, 5), True)
    """
    if not (callable(getattr(element, "model_at_speed", None))
            and callable(getattr(element, "linearize", None))):
        raise TypeError("linearize_at_load: expected a 2-node rolling-bearing element "
                        "(RollingBearing or FlexibleRingBearingElement), got "
                        f"{type(element).__name__}; a bare bearing model goes to "
                        "bearing_equilibrium")
    at_speed: dict[str, Any] = {} if speed is None else {"speed": speed}
    model = element.model_at_speed(**at_speed)
    eq = bearing_equilibrium(model, load, phi=phi, **options)
    extra = at_speed if frequency is None else {**at_speed, "frequency": frequency}
    return element.linearize(displacement=eq.displacement, phi=phi, tangent=eq.stiffness,
                             **extra)


def linearized_bearings(bearings: Sequence[Any], loads: Sequence[ArrayLike], *,
                        phi: float = 0.0, speed: float | None = None,
                        frequency: float = 0.0) -> tuple[Any, ...]:
    """Linear ``BearingElement`` of each 2-node ``RollingBearing`` at its static load
    (:func:`linearize_at_load`).

    ``loads[i]`` is the load ``[Fx, Fy, Fz, Mx, My]`` on the inner ring of ``bearings[i]``
    (e.g. minus the bearing reaction of a static analysis). ``speed`` [rad/s] and
    ``frequency`` [rad/s] are needed by lubricated (EHL) contact damping.
    """
    if len(bearings) != len(loads):
        raise ModelError(f"{len(bearings)} bearings but {len(loads)} loads",
                         "linearized_bearings")
    options: dict[str, Any] = {} if speed is None else {"speed": speed, "frequency": frequency}
    return tuple(linearize_at_load(b, f, phi=phi, **options)
                 for b, f in zip(bearings, loads, strict=True))
