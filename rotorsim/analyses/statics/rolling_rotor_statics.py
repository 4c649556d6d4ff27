"""Nonlinear static equilibrium of a rotor on rolling bearings (Newton on the whole problem
with an Armijo line search on the total potential energy), the engine of
:func:`rotorsim.analyses.statics.linearized_rotor.linearize_rolling_bearings` (see its
module notes).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium
from rotorsim.analyses.statics.static import static
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.bearing import BearingEquilibriumResult
from rotorsim.results.static import StaticResult
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
NODE_DOFS = ("ux", "uy", "uz", "rx", "ry")
"""Node DOFs of the 5 relative bearing DOFs ``(x, y, z, rx, ry)``."""
_FORCES = np.array([1.0, 1.0, 1.0, 0.0, 0.0])
_ARMIJO = 1e-4
_MAX_HALVINGS = 30


class Tangent(NamedTuple):
    """A bearing's linearisation point: displacement, force and stiffness there."""

    displacement: FloatArray  # d_b (5,)
    force: FloatArray  # F_b(d_b) (5,)
    stiffness: FloatArray  # K_b (5, 5)


def bearing_scale(rb: Any) -> FloatArray:
    """Scale of the 5 relative DOFs: 1 for forces, ``1 / arm`` for moments."""
    arm = float(getattr(rb.bearing, "moment_arm", 0.5 * rb.bearing.pitch_diameter))
    return np.array([1.0, 1.0, 1.0, 1.0 / arm, 1.0 / arm])


def nominal_tangent(rb: Any) -> Tangent:
    """Force at zero displacement and the mean tangent of 10 probe displacements."""
    bearing = rb.bearing
    size = max(float(bearing.clearance), 0.0) + (1e3 / float(bearing.Kn)) ** (
        1.0 / float(bearing.exponent))
    probes = np.vstack([np.eye(5), -np.eye(5)]) * (size / bearing_scale(rb))
    psi = np.atleast_2d(bearing.element_angles(0.0))
    k = bearing.state(probes, np.broadcast_to(psi, (10, psi.shape[1]))).stiffness.mean(axis=0)
    return Tangent(np.zeros(5), bearing.state(np.zeros((1, 5)), psi).force[0], 0.5 * (k + k.T))


def bearing_at_load(rb: Any, load: FloatArray, x0: FloatArray | None, phi: float, tag: str,
                    context: str = "at its static load") -> BearingEquilibriumResult:
    """Equilibrium of one rolling bearing under ``load``; an unloaded bearing is an error."""
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


ROUNDOFF_FLOOR = 1e-8
"""A Newton iteration asked for less that stalls at or below this relative residual is
accepted at its best iterate, with that residual reported: a contact model whose force is
computed through an active set or a solve (the roller ``model="influence"``) has a
round-off floor near 1e-10 that differs between BLAS kernels (measured 1.6e-10 under
OPENBLAS_CORETYPE=Zen and Haswell against a requested 1e-10)."""


def static_equilibrium(case: StaticCase, tol: float, max_iter: int, stats: Stats
                       ) -> tuple[dict[int, Tangent], StaticResult, int, float]:
    """Newton iteration with line search (module docstring); tangents at the solution."""
    static_idx = case.static_indices
    if not static_idx:
        result, _, _ = case.solve({})
        return {}, result, 0, 0.0
    _, carried, _ = case.solve({i: nominal_tangent(case.rolling[i]) for i in static_idx})
    start = {}
    for k, i in enumerate(static_idx):  # in contact under the forces (moments are soft)
        eq = bearing_at_load(case.rolling[i], carried[k] * _FORCES, None, case.phi, case.tags[i])
        start[i] = Tangent(eq.displacement, eq.force, eq.stiffness)
    result, P, q = case.solve(start)
    best: tuple[float, dict[int, Tangent] | None] = (np.inf, None)
    for iteration in range(1, max_iter + 1):
        stats.iterations += 1
        tangents = case.tangents(q)
        forces = np.array([tangents[i].force for i in static_idx])
        residual = case.residual(forces - P, forces)
        if residual <= tol:
            result, _, _ = case.solve(tangents)
            return tangents, result, iteration, residual
        best = min(best, (residual, tangents), key=lambda b: b[0])
        _, P_new, q_new = case.solve(tangents)
        step = case.line_search(q, q_new, P, P_new, forces, stats)
        q, P = q + step * (q_new - q), P + step * (P_new - P)
    if best[1] is not None and best[0] <= ROUNDOFF_FLOOR:
        # stalled at the force's own round-off (the residual is reported as reached)
        result, _, _ = case.solve(best[1])
        return best[1], result, max_iter, best[0]
    raise ConvergenceError("static equilibrium with the rolling bearings did not converge",
                           "linearize_rolling_bearings", iteration=max_iter, residual=residual)


@dataclass(frozen=True)
class StaticCase:
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

    def solve(self, tangents: dict[int, Tangent]) -> tuple[StaticResult, FloatArray, FloatArray]:
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

    def _offsets(self, rb: Any, t: Tangent) -> list[tuple[int, str, float]]:
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

    def tangents(self, q: FloatArray) -> dict[int, Tangent]:
        out = {}
        for i in self.static_indices:
            rb = self.rolling[i]
            d = _relative(rb, q)
            st = rb.bearing.state(d[None, :], rb.bearing.element_angles(self.phi))
            out[i] = Tangent(d, st.force[0], st.stiffness[0])
        return out

    def residual(self, unbalanced: FloatArray, forces: FloatArray) -> float:
        scales = np.array([bearing_scale(self.rolling[i]) for i in self.static_indices])
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
