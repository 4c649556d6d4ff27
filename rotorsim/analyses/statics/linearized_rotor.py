"""A rotor on rolling bearings, linearised at the bearings' static loads.

Linear analyses need each ``RollingBearing`` replaced by a ``BearingElement`` with its full
5x5 tangent at a :class:`LinearizationPoint`: the static load (default), a given load or a
given displacement. Static loads come from Newton's method on ``K_s q + sum_b r_b(q) = f``
(``r_b = +F_b`` on the inner node, ``-F_b`` on the outer; the load a bearing carries is
``F_b``): each linear solve (:func:`rotorsim.analyses.statics.static.static`) uses the tangents
``P_b = F_b(d_b) + K_b (q_b - d_b)``, the constant part as point loads, and a backtracking
(Armijo) line search on the convex total potential energy (which along a step needs the
bearing energies only, because every solve has ``K_s q = f - sum_b P_b``) makes it converge.
Start: nominal tangents (mean of 10 probes), then each bearing at the equilibrium of the
forces it carried. Converged when ``max |(F_b - P_b) s| <= tol max |F_b s|``,
``s = (1, 1, 1, 1/r, 1/r)``. Details and checks: ``docs/bearing_statics.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.linear.argument_checks import check_speed
from rotorsim.analyses.statics.rolling_rotor_statics import (
    StaticCase,
    bearing_at_load,
    static_equilibrium,
)
from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import NonlinearElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.rotor import Rotor
from rotorsim.results.bearing import BearingEquilibriumResult
from rotorsim.results.static import StaticResult
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
KINDS = ("static", "load", "displacement")
"""Kinds of :class:`LinearizationPoint`."""


@dataclass(frozen=True)
class LinearizationPoint:
    """Where a rolling bearing is linearised.

    Parameters
    ----------
    kind : {"static", "load", "displacement"}
        At the rotor's static load, at a given load or at a given displacement.
    value : 5 floats, optional
        ``[Fx, Fy, Fz, Mx, My]`` [N, N m] on the inner ring, or ``[x, y, z, rx, ry]``
        [m, rad] of the inner ring relative to the outer; ``None`` for ``"static"``.

    Examples
    --------
    >>> LinearizationPoint("load", (0, -500, 0, 0, 0)).value
    (0.0, -500.0, 0.0, 0.0, 0.0)
    """

    kind: str = "static"
    value: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        where = "LinearizationPoint"
        if self.kind not in KINDS:
            raise ModelError(f"kind must be one of {KINDS}, got {self.kind!r}", where)
        if (self.kind == "static") != (self.value is None):
            raise ModelError("give a value for 'load' and 'displacement', none for 'static'",
                             where)
        if self.value is not None:
            value = tuple(float(v) for v in np.asarray(self.value, dtype=float).reshape(-1))
            if len(value) != 5 or not all(math.isfinite(v) for v in value):
                raise ModelError(f"{self.kind} must be 5 finite numbers, got {self.value!r}",
                                 where)
            object.__setattr__(self, "value", value)


@dataclass(frozen=True, eq=False)
class LinearizedRotor:
    """A rotor with its rolling bearings linearised (module docstring).

    Attributes
    ----------
    rotor : Rotor
        The input rotor with the linearised bearings (``bearings``: full 5x5
        ``stiffness_matrix``, ``damping_matrix`` with proportional contact damping) appended
        to its ``bearing_elements`` in order.
    equilibria : tuple of BearingEquilibriumResult
        Each bearing's equilibrium at its linearisation point; ``loads`` (n, 5) their
        loads ``[Fx, Fy, Fz, Mx, My]`` on the inner rings [N, N m].
    points, tags
        Linearisation point and tag (index when untagged) of each bearing.
    static : StaticResult
        The static equilibrium: rolling-bearing reactions ``-F_b``, applied ``load`` only.
    iterations, residual
        Newton iterations (0 without ``"static"`` bearings) and the final residual.
    options, stats, status
    """

    rotor: Rotor
    bearings: tuple[BearingElement, ...]
    equilibria: tuple[BearingEquilibriumResult, ...]
    loads: FloatArray
    points: tuple[LinearizationPoint, ...]
    tags: tuple[str, ...]
    static: StaticResult
    iterations: int
    residual: float
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK

    def describe(self) -> dict[str, Any]:
        """JSON-ready description, stored in the options of analyses run on the rotor."""
        return {"tags": list(self.tags), "points": [p.kind for p in self.points],
                "loads": self.loads.tolist(), "iterations": self.iterations,
                "residual": self.residual}


def linearize_rolling_bearings(
    rotor: Rotor,
    rolling_bearings: Sequence[Any] | None = None,
    *,
    points: Sequence[LinearizationPoint] | None = None,
    gravity: float | None = STANDARD_GRAVITY,
    direction: ArrayLike = (0.0, -1.0, 0.0),
    loads: Sequence[tuple[int, str, float]] = (),
    speed: float = 0.0,
    phi: float = 0.0,
    tol: float = 1e-6,
    max_iter: int = 30,
) -> LinearizedRotor:
    """Linearise rolling bearings at their static loads (or given points) into a rotor.

    Parameters
    ----------
    rotor : Rotor
        Shaft, disks, point masses and linear bearings, and possibly its rolling bearings
        (``nonlinear_elements``).
    rolling_bearings : sequence of RollingBearing, optional
        More rolling bearings, on nodes of ``rotor``, after the rotor's own.
    points : sequence of LinearizationPoint, optional
        One per bearing; default all ``"static"``.
    gravity, direction, loads, speed
        The static load case, as for :func:`rotorsim.analyses.statics.static.static` (``speed``
        finite and >= 0 [rad/s]).
    phi : float
        Shaft angle [rad] that places the rolling elements.
    tol : float
        Relative residual of the static equilibrium (module docstring).
    max_iter : int
        Newton iteration limit.

    Returns
    -------
    LinearizedRotor

    Raises
    ------
    ModelError
        Bad input, a bearing without load (zero stiffness) or with a load it cannot carry.
    ConvergenceError
        The static equilibrium did not converge in ``max_iter`` iterations.

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.03, material=steel) for _ in range(4)]
    >>> ball = rs.BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794,
    ...                       Kn=8.5e9, f_i=0.52, f_o=0.52)
    >>> rolling = [rs.RollingBearing(ball, n=0), rs.RollingBearing(ball, n=4)]
    >>> lin = linearize_rolling_bearings(rs.Rotor(shaft), rolling)
    >>> half_weight = 9.80665 * lin.rotor.m / 2
    >>> bool(np.allclose(lin.loads[:, 1], -half_weight, rtol=1e-6)), len(lin.bearings)
    (True, 2)
    """
    where = "linearize_rolling_bearings"
    if not isinstance(rotor, Rotor):
        raise ModelError(f"needs a Rotor, got {type(rotor).__name__}", where)
    rolling = (*rotor.nonlinear_elements, *(rolling_bearings or ()))
    rotor = rotor.linear_part()
    at = tuple(points) if points is not None else tuple(LinearizationPoint() for _ in rolling)
    if len(at) != len(rolling) or not all(isinstance(p, LinearizationPoint) for p in at):
        raise ModelError(f"give one LinearizationPoint per rolling bearing ({len(rolling)})",
                         where)
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise ModelError(f"tol must be a positive number, got {tol!r}", where)
    if isinstance(max_iter, bool) or not isinstance(max_iter, int) or max_iter < 1:
        raise ModelError(f"max_iter must be an integer >= 1, got {max_iter!r}", where)
    speed = check_speed(speed, where)
    if isinstance(phi, bool) or not isinstance(phi, int | float | np.floating) \
            or not math.isfinite(phi):
        raise ModelError(f"phi must be a finite angle [rad], got {phi!r}", where)
    tags = tuple(str(rb.tag) if rb.tag else str(i) for i, rb in enumerate(rolling))
    stats = Stats()
    fixed = {i: _given_point(rb, p, float(phi), float(speed), tags[i])
             for i, (rb, p) in enumerate(zip(rolling, at, strict=True)) if p.kind != "static"}
    case = StaticCase(rotor, gravity, direction, tuple(loads), float(speed), float(phi), rolling,
                 tags, {i: f[1] for i, f in fixed.items()})
    tangents, result, iterations, residual = static_equilibrium(case, tol, max_iter, stats)
    equilibria = {i: f[0] for i, f in fixed.items()}
    for i, t in tangents.items():
        equilibria[i] = bearing_at_load(rolling[i], t.force, t.displacement, case.phi, tags[i])
    elements = tuple(fixed[i][1] if i in fixed else _linear_element(
        rolling[i], equilibria[i].displacement, case.phi, case.speed)
        for i in range(len(rolling)))
    ordered = tuple(equilibria[i] for i in range(len(rolling)))
    return LinearizedRotor(
        rotor=rotor.with_bearings([*rotor.bearing_elements, *elements]), bearings=elements,
        equilibria=ordered, loads=np.array([e.load for e in ordered]).reshape(-1, 5),
        points=at, tags=tags, static=result, iterations=iterations, residual=residual,
        options={"tol": tol, "max_iter": max_iter, "phi": case.phi, "speed": case.speed},
        stats=stats.finish())


# ----------------------------------------------------------------------------- helpers
def _given_point(rb: Any, point: LinearizationPoint, phi: float, speed: float, tag: str
                 ) -> tuple[BearingEquilibriumResult, BearingElement]:
    """Equilibrium and linear element at a given load or displacement."""
    assert point.value is not None
    value = np.array(point.value)
    if point.kind == "displacement":
        value = rb.bearing.state(value[None, :], rb.bearing.element_angles(phi)).force[0]
    eq = bearing_at_load(rb, value, None, phi, tag, f"at its given {point.kind}")
    return eq, _linear_element(rb, eq.displacement, phi, speed)


def _linear_element(rb: Any, displacement: FloatArray, phi: float, speed: float
                    ) -> BearingElement:
    """``rb.linearize`` at a displacement (lubricated contacts also need the speed)."""
    extra = {"speed": speed} if getattr(rb, "contact_damping", "") == "ehl" else {}
    return rb.linearize(displacement=displacement, phi=phi, **extra)


def rolling_start(model: Rotor, nonlinear: Sequence[NonlinearElement], system: RotorSystem,
                   gravity: float | None, direction: ArrayLike, loads: Sequence[Any],
                   speed: float, phi: float) -> FloatArray | None:
    """A start for the static Newton iteration from the robust rolling-bearing statics
    (:func:`~rotorsim.analyses.statics.linearized_rotor.linearize_rolling_bearings`: nominal
    tangents, then each bearing at the equilibrium of its load, energy line search); None
    when some element is not a RollingBearing or that solve fails."""
    from rotorsim.elements.rolling.element import RollingBearing

    elements = (*model.nonlinear_elements, *nonlinear)
    if not all(isinstance(el, RollingBearing) for el in elements):
        return None
    try:
        lin = linearize_rolling_bearings(model.with_nonlinear(elements), gravity=gravity,
                                         direction=direction, loads=loads, speed=speed,
                                         phi=phi, tol=1e-8, max_iter=50)
    except (ModelError, ConvergenceError):
        return None
    return np.asarray(lin.static.displacement)[system.dof_map.free]
