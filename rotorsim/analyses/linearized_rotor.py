"""A rotor on rolling bearings, linearised at the bearings' static loads.

Linear analyses need each ``RollingBearing`` replaced by a ``BearingElement`` with its full
5x5 tangent at a :class:`LinearizationPoint`: the static load (default), a given load or a
given displacement. Static loads come from Newton's method on ``K_s q + sum_b r_b(q) = f``
(``r_b = +F_b`` on the inner node, ``-F_b`` on the outer; the load a bearing carries is
``F_b``): each linear solve (:func:`rotorsim.analyses.static.static`) uses the tangents
``P_b = F_b(d_b) + K_b (q_b - d_b)``, the constant part as point loads, and a backtracking
(Armijo) line search on the convex total potential energy (which along a step needs the
bearing energies only, because every solve has ``K_s q = f - sum_b P_b``) makes it converge.
Start: nominal tangents (mean of 10 probes), then each bearing at the equilibrium of the
forces it carried. Converged when ``max |(F_b - P_b) s| <= tol max |F_b s|``,
``s = (1, 1, 1, 1/r, 1/r)``. Details and checks: ``docs/bearing_statics.md``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.bearing_statics import bearing_equilibrium
from rotorsim.analyses.static import static
from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.rotor import Rotor
from rotorsim.results.bearing import BearingEquilibriumResult
from rotorsim.results.static import StaticResult
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
KINDS = ("static", "load", "displacement")
"""Kinds of :class:`LinearizationPoint`."""
NODE_DOFS = ("ux", "uy", "uz", "rx", "ry")
"""Node DOFs of the 5 relative bearing DOFs ``(x, y, z, rx, ry)``."""
_FORCES = np.array([1.0, 1.0, 1.0, 0.0, 0.0])
_ARMIJO = 1e-4
_MAX_HALVINGS = 30


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


class _Tangent(NamedTuple):
    displacement: FloatArray  # d_b (5,)
    force: FloatArray  # F_b(d_b) (5,)
    stiffness: FloatArray  # K_b (5, 5)


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
    rolling_bearings: Sequence[Any],
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
        Shaft, disks, point masses and linear bearings (no rolling bearings).
    rolling_bearings : sequence of RollingBearing
        The rolling bearings, on nodes of ``rotor``.
    points : sequence of LinearizationPoint, optional
        One per bearing; default all ``"static"``.
    gravity, direction, loads, speed
        The static load case, as for :func:`rotorsim.analyses.static.static`.
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
    rolling = tuple(rolling_bearings)
    at = tuple(points) if points is not None else tuple(LinearizationPoint() for _ in rolling)
    if len(at) != len(rolling) or not all(isinstance(p, LinearizationPoint) for p in at):
        raise ModelError(f"give one LinearizationPoint per rolling bearing ({len(rolling)})",
                         where)
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise ModelError(f"tol must be a positive number, got {tol!r}", where)
    if isinstance(max_iter, bool) or not isinstance(max_iter, int) or max_iter < 1:
        raise ModelError(f"max_iter must be an integer >= 1, got {max_iter!r}", where)
    tags = tuple(str(rb.tag) if rb.tag else str(i) for i, rb in enumerate(rolling))
    stats = Stats()
    fixed = {i: _given_point(rb, p, float(phi), float(speed), tags[i])
             for i, (rb, p) in enumerate(zip(rolling, at, strict=True)) if p.kind != "static"}
    case = _Case(rotor, gravity, direction, tuple(loads), float(speed), float(phi), rolling,
                 tags, {i: f[1] for i, f in fixed.items()})
    tangents, result, iterations, residual = _static_equilibrium(case, tol, max_iter, stats)
    equilibria = {i: f[0] for i, f in fixed.items()}
    for i, t in tangents.items():
        equilibria[i] = _equilibrium(rolling[i], t.force, t.displacement, case.phi, tags[i])
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
def _scale(rb: Any) -> FloatArray:
    arm = float(getattr(rb.bearing, "moment_arm", 0.5 * rb.bearing.pitch_diameter))
    return np.array([1.0, 1.0, 1.0, 1.0 / arm, 1.0 / arm])


def _nominal(rb: Any) -> _Tangent:
    """Force at zero displacement and the mean tangent of 10 probe displacements."""
    bearing = rb.bearing
    size = max(float(bearing.clearance), 0.0) + (1e3 / float(bearing.Kn)) ** (
        1.0 / float(bearing.exponent))
    probes = np.vstack([np.eye(5), -np.eye(5)]) * (size / _scale(rb))
    psi = np.atleast_2d(bearing.element_angles(0.0))
    k = bearing.state(probes, np.broadcast_to(psi, (10, psi.shape[1]))).stiffness.mean(axis=0)
    return _Tangent(np.zeros(5), bearing.state(np.zeros((1, 5)), psi).force[0], 0.5 * (k + k.T))


def _given_point(rb: Any, point: LinearizationPoint, phi: float, speed: float, tag: str
                 ) -> tuple[BearingEquilibriumResult, BearingElement]:
    """Equilibrium and linear element at a given load or displacement."""
    assert point.value is not None
    value = np.array(point.value)
    if point.kind == "displacement":
        value = rb.bearing.state(value[None, :], rb.bearing.element_angles(phi)).force[0]
    eq = _equilibrium(rb, value, None, phi, tag, f"at its given {point.kind}")
    return eq, _linear_element(rb, eq.displacement, phi, speed)


def _linear_element(rb: Any, displacement: FloatArray, phi: float, speed: float
                    ) -> BearingElement:
    """``rb.linearize`` at a displacement (lubricated contacts also need the speed)."""
    extra = {"speed": speed} if getattr(rb, "contact_damping", "") == "ehl" else {}
    return rb.linearize(displacement=displacement, phi=phi, **extra)


def _equilibrium(rb: Any, load: FloatArray, x0: FloatArray | None, phi: float, tag: str,
                 context: str = "at its static load") -> BearingEquilibriumResult:
    where = f"rolling bearing '{tag}'"
    try:
        eq = bearing_equilibrium(rb.bearing, load, phi=phi, x0=x0, method="auto")
    except ModelError as err:
        raise ModelError(f"{context}: {err}", where) from None
    if eq.load_zone.size == 0:
        raise ModelError(
            f"carries no load {context} ({np.round(load, 6).tolist()} N, N m), so its "
            "stiffness is zero: add a load or a preload (negative clearance), or linearise it "
            "at a given load", where)
    return eq


def _static_equilibrium(case: _Case, tol: float, max_iter: int, stats: Stats
                        ) -> tuple[dict[int, _Tangent], StaticResult, int, float]:
    """Newton iteration with line search (module docstring); tangents at the solution."""
    static_idx = case.static_indices
    if not static_idx:
        result, _, _ = case.solve({})
        return {}, result, 0, 0.0
    _, carried, _ = case.solve({i: _nominal(case.rolling[i]) for i in static_idx})
    start = {}
    for k, i in enumerate(static_idx):  # in contact under the forces (moments are soft)
        eq = _equilibrium(case.rolling[i], carried[k] * _FORCES, None, case.phi, case.tags[i])
        start[i] = _Tangent(eq.displacement, eq.force, eq.stiffness)
    result, P, q = case.solve(start)
    for iteration in range(1, max_iter + 1):
        stats.iterations += 1
        tangents = case.tangents(q)
        forces = np.array([tangents[i].force for i in static_idx])
        residual = case.residual(forces - P, forces)
        if residual <= tol:
            result, _, _ = case.solve(tangents)
            return tangents, result, iteration, residual
        _, P_new, q_new = case.solve(tangents)
        step = case.line_search(q, q_new, P, P_new, forces, stats)
        q, P = q + step * (q_new - q), P + step * (P_new - P)
    raise ConvergenceError("static equilibrium with the rolling bearings did not converge",
                           "linearize_rolling_bearings", iteration=max_iter, residual=residual)


@dataclass(frozen=True)
class _Case:
    """The load case, the bearings and one linear solve of the iteration."""

    rotor: Rotor
    gravity: float | None
    direction: ArrayLike
    loads: tuple[tuple[int, str, float], ...]
    speed: float
    phi: float
    rolling: tuple[Any, ...]
    tags: tuple[str, ...]
    fixed: dict[int, BearingElement]

    @property
    def static_indices(self) -> list[int]:
        return [i for i in range(len(self.rolling)) if i not in self.fixed]

    def solve(self, tangents: dict[int, _Tangent]) -> tuple[StaticResult, FloatArray, FloatArray]:
        """Static solve with the bearings' tangents: the result (reactions of the tangent
        bearings = ``-P``, applied load without the offsets), ``P`` (n, 5) and ``q``."""
        elements = [self.fixed[i] if i in self.fixed else BearingElement(
            n=int(rb.n), n_link=rb.n_link, tag=self.tags[i],
            stiffness_matrix=tangents[i].stiffness) for i, rb in enumerate(self.rolling)]
        offsets = [x for i, t in tangents.items() for x in self._offsets(self.rolling[i], t)]
        try:
            result = static(self.rotor.with_bearings([*self.rotor.bearing_elements, *elements]),
                            gravity=self.gravity, direction=self.direction,
                            loads=[*self.loads, *offsets], speed=self.speed)
        except ModelError as err:
            raise ModelError(f"static solve with the linearised rolling bearings: {err} (a "
                             "rolling bearing with too few loaded elements has no stiffness in "
                             "some direction: check its clearance and load)",
                             "linearize_rolling_bearings") from None
        q = result.displacement.reshape(-1, 6)
        P = np.array([t.force + t.stiffness @ (_relative(self.rolling[i], q) - t.displacement)
                      for i, t in tangents.items()]).reshape(-1, 5)
        return self._corrected(result, list(tangents), P, offsets), P, q

    def _offsets(self, rb: Any, t: _Tangent) -> list[tuple[int, str, float]]:
        """Point loads ``-(F(d) - K d)`` on the inner node, ``+`` on the outer node."""
        constant = t.force - t.stiffness @ t.displacement
        fixed = set(self.rotor.fixed)
        out = []
        for node, sign in ((int(rb.n), -1.0), (rb.n_link, 1.0)):
            if node is not None:
                out += [(int(node), dof, float(sign * v))
                        for dof, v in zip(NODE_DOFS, constant, strict=True)
                        if v != 0.0 and (int(node), dof) not in fixed]
        return out

    def _corrected(self, result: StaticResult, indices: list[int], P: FloatArray,
                   offsets: list[tuple[int, str, float]]) -> StaticResult:
        load = result.load.copy()
        for node, dof, value in offsets:
            load[6 * node + NODE_DOFS.index(dof)] -= value
        forces, moments = result.bearing_forces, result.bearing_moments
        if forces is not None and moments is not None:
            forces, moments = forces.copy(), moments.copy()
            first = len(self.rotor.bearing_elements)
            for k, i in enumerate(indices):
                forces[first + i], moments[first + i, :2] = -P[k, :3], -P[k, 3:]
        options = {**result.options, "loads": [tuple(x) for x in self.loads]}
        return dataclasses.replace(result, load=load, bearing_forces=forces,
                                   bearing_moments=moments, options=options)

    def tangents(self, q: FloatArray) -> dict[int, _Tangent]:
        out = {}
        for i in self.static_indices:
            rb = self.rolling[i]
            d = _relative(rb, q)
            st = rb.bearing.state(d[None, :], rb.bearing.element_angles(self.phi))
            out[i] = _Tangent(d, st.force[0], st.stiffness[0])
        return out

    def residual(self, unbalanced: FloatArray, forces: FloatArray) -> float:
        scales = np.array([_scale(self.rolling[i]) for i in self.static_indices])
        top = float(np.abs(forces * scales).max())
        return float(np.abs(unbalanced * scales).max()) / max(top, 1e-300)

    def energy(self, q: FloatArray) -> float:
        """Strain energy of the static bearings at ``q`` [J]."""
        return float(sum(rb.bearing.energy(_relative(rb, q)[None, :],
                                           rb.bearing.element_angles(self.phi))[0]
                         for rb in (self.rolling[i] for i in self.static_indices)))

    def line_search(self, q: FloatArray, q_new: FloatArray, P: FloatArray, P_new: FloatArray,
                    forces: FloatArray, stats: Stats) -> float:
        """Armijo step along ``q_new - q`` on the total potential energy."""
        step_b = np.array([_relative(self.rolling[i], q_new - q) for i in self.static_indices])
        slope = float(np.sum((forces - P) * step_b))
        curvature = float(np.sum((P_new - P) * step_b))
        if slope >= 0.0:  # not a descent direction: round-off near the solution
            return 1.0
        u0, lam = self.energy(q), 1.0
        for _ in range(_MAX_HALVINGS):
            stats.residual_evaluations += 1
            change = (self.energy(q + lam * (q_new - q)) - u0 - lam * float(np.sum(P * step_b))
                      - 0.5 * lam * lam * curvature)
            if change <= _ARMIJO * lam * slope:
                return lam
            stats.rejected_steps += 1
            lam *= 0.5
        return lam


def _relative(rb: Any, q: FloatArray) -> FloatArray:
    """``u_inner[:5] - u_outer[:5]`` from node displacements ``q`` (n_nodes, 6)."""
    delta = q[int(rb.n), :5].copy()
    if rb.n_link is not None:
        delta -= q[int(rb.n_link), :5]
    return delta
