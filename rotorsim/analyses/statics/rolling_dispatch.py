"""Static equilibrium of a rotor with rolling bearings (the nonlinear branch of
:func:`rotorsim.analyses.statics.static.static`): Newton's method with an energy line search on the
linearised bearings, Newton's method on the whole system from a user's start ``x0``, or the
minimum of the total potential energy polished by Newton; all report the reactions, section
forces and every rolling element's load."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.analyses.rigid_motions import free_rigid_motions, held_dofs
from rotorsim.analyses.statics.static import _applied_load
from rotorsim.assembly.loads import unit_direction
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.model.rotor import Rotor
from rotorsim.results.static import StaticResult


def newton_static(rotor: Rotor, gravity: float | None, direction: ArrayLike,
                      loads: Sequence[tuple[int, str, float]], speed: float) -> StaticResult:
    from rotorsim.analyses.statics.linearized_rotor import linearize_rolling_bearings

    lin = linearize_rolling_bearings(rotor, gravity=gravity, direction=direction, loads=loads,
                                     speed=speed, tol=1e-10, max_iter=50)
    return dataclasses.replace(
        lin.static,
        element_loads={t: e.element_load for t, e in zip(lin.tags, lin.equilibria, strict=True)},
        contact_angles={t: e.contact_angle for t, e in zip(lin.tags, lin.equilibria,
                                                           strict=True)},
        options={**lin.static.options, "method": "newton",
                 "nonlinear_elements": len(rotor.nonlinear_elements),
                 "newton_iterations": lin.iterations, "newton_residual": lin.residual})


def energy_static(rotor: Rotor, gravity: float | None, direction: ArrayLike,
                  loads: Sequence[tuple[int, str, float]], speed: float,
                  x0: ArrayLike | None = None) -> StaticResult:
    """The minimum of the potential energy (from ``x0`` on all DOFs when given), polished by
    Newton's method and reported with the bearings' tangents at that minimum (reactions and
    section forces as for Newton)."""
    from rotorsim.analyses.statics.nonlinear_static import nonlinear_equilibrium
    from rotorsim.analyses.statics.rotor_energy import energy_equilibrium

    system, f, q0, held, nominal = _problem(rotor, gravity, direction, loads, speed, x0)
    eq = energy_equilibrium(system, f, speed=speed, q0=q0, held=held)
    polished = nonlinear_equilibrium(system, f, speed=speed, q0=eq.q, held=held,
                                     nominal=nominal)  # regularises a singular tangent
    return _report(rotor, system, polished.q, gravity, direction, loads, speed, {
        "method": "energy", "energy": eq.energy, "energy_iterations": eq.iterations,
        "energy_gradient": eq.gradient, "newton_polish_iterations": polished.iterations,
        "hessian_min": eq.hessian_min, "x0_given": x0 is not None})


def started_static(rotor: Rotor, gravity: float | None, direction: ArrayLike,
                   loads: Sequence[tuple[int, str, float]], speed: float,
                   x0: ArrayLike) -> StaticResult:
    """Newton's method from the user's start ``x0`` (all DOFs [m, rad]), with the energy
    minimum and load stepping as fall-backs
    (:func:`~rotorsim.analyses.statics.nonlinear_static.nonlinear_equilibrium`)."""
    from rotorsim.analyses.statics.nonlinear_static import nonlinear_equilibrium

    system, f, q0, held, nominal = _problem(rotor, gravity, direction, loads, speed, x0)
    eq = nonlinear_equilibrium(system, f, speed=speed, q0=q0, held=held, nominal=nominal)
    return _report(rotor, system, eq.q, gravity, direction, loads, speed, {
        "method": "newton", "newton_iterations": eq.iterations, "newton_residual": eq.residual,
        "solver": eq.method, "x0_given": True})


def _problem(rotor: Rotor, gravity: float | None, direction: ArrayLike,
             loads: Sequence[tuple[int, str, float]], speed: float, x0: ArrayLike | None
             ) -> tuple[Any, FloatArray, FloatArray | None, list[int], sp.csr_matrix]:
    """Assembled system, load and start on the free DOFs, held DOFs, nominal tangent."""
    from rotorsim.analyses.statics.nonlinear_static import nominal_tangent, start_point
    from rotorsim.assembly.system import assemble

    system = assemble(rotor)
    q0 = None if x0 is None else start_point(system, x0, "static.x0")
    g = 0.0 if gravity is None else float(gravity)
    f, _ = _applied_load(system, rotor.linear_part(), g, unit_direction(direction), loads)
    nominal = nominal_tangent(system)
    K = system.matrices(speed).K
    held = held_dofs(free_rigid_motions(system, sp.csr_matrix(K + nominal)))
    return system, f, q0, held, nominal


def _report(rotor: Rotor, system: Any, q: FloatArray, gravity: float | None,
            direction: ArrayLike, loads: Sequence[tuple[int, str, float]], speed: float,
            options: dict[str, Any]) -> StaticResult:
    """The static result at the equilibrium ``q`` (n_free,): reactions and section forces
    from the bearings' tangents there, and every rolling element's load."""
    from rotorsim.analyses.statics.rolling_rotor_statics import StaticCase

    rolling = tuple(rotor.nonlinear_elements)
    tags = tuple(str(getattr(rb, "tag", None) or i) for i, rb in enumerate(rolling))
    case = StaticCase(rotor.linear_part(), gravity, direction, tuple(loads), speed, 0.0,
                      rolling, tags, {})
    q_all = system.dof_map.expand(q).reshape(-1, DOFS_PER_NODE)
    result, _, _ = case.solve(case.tangents(q_all))
    states = [rb.bearing.state(relative_of(rb, q_all)[None, :], rb.bearing.element_angles(0.0))
              for rb in rolling]
    return dataclasses.replace(
        result, element_loads={t: st.element_load[0] for t, st in zip(tags, states, strict=True)},
        contact_angles={t: st.contact_angle[0] for t, st in zip(tags, states, strict=True)},
        options={**result.options, **options})


def relative_of(rb: Any, q_nodes: FloatArray) -> FloatArray:
    """Relative displacement ``(x, y, z, rx, ry)`` of a rolling bearing's rings."""
    u = q_nodes[list(rb.nodes)].reshape(1, -1)
    return np.asarray(rb.relative(u))[0]
