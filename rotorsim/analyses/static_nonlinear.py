"""Static equilibrium of a rotor with rolling bearings (the nonlinear branch of
:func:`rotorsim.analyses.static.static`): Newton's method with an energy line search on the
linearised bearings, or the minimum of the total potential energy polished by Newton; both
report the reactions, section forces and every rolling element's load."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.analyses.static import _applied_load, free_rigid_motions, held_dofs
from rotorsim.assembly.loads import unit_direction
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.model.rotor import Rotor
from rotorsim.results.static import StaticResult


def newton_static(rotor: Rotor, gravity: float | None, direction: ArrayLike,
                      loads: Sequence[tuple[int, str, float]], speed: float) -> StaticResult:
    from rotorsim.analyses.linearized_rotor import linearize_rolling_bearings

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
                   loads: Sequence[tuple[int, str, float]], speed: float) -> StaticResult:
    """The minimum of the potential energy, polished by Newton's method and reported with
    the bearings' tangents at that minimum (reactions and section forces as for Newton)."""
    from rotorsim.analyses.nonlinear_static import nominal_tangent, nonlinear_equilibrium
    from rotorsim.analyses.rolling_rotor_statics import StaticCase
    from rotorsim.analyses.rotor_energy import energy_equilibrium
    from rotorsim.assembly.system import assemble

    system = assemble(rotor)
    g = 0.0 if gravity is None else float(gravity)
    f, _ = _applied_load(system, rotor.linear_part(), g, unit_direction(direction), loads)
    K = system.matrices(speed).K
    held = held_dofs(free_rigid_motions(system, sp.csr_matrix(K + nominal_tangent(system))))
    eq = energy_equilibrium(system, f, speed=speed, held=held)
    polished = nonlinear_equilibrium(system, f, speed=speed, q0=eq.q, held=held)
    rolling = tuple(rotor.nonlinear_elements)
    tags = tuple(str(getattr(rb, "tag", None) or i) for i, rb in enumerate(rolling))
    case = StaticCase(rotor.linear_part(), gravity, direction, tuple(loads), speed, 0.0,
                      rolling, tags, {})
    q_all = system.dof_map.expand(polished.q).reshape(-1, DOFS_PER_NODE)
    result, _, _ = case.solve(case.tangents(q_all))
    states = [rb.bearing.state(relative_of(rb, q_all)[None, :], rb.bearing.element_angles(0.0))
              for rb in rolling]
    return dataclasses.replace(
        result, element_loads={t: st.element_load[0] for t, st in zip(tags, states, strict=True)},
        contact_angles={t: st.contact_angle[0] for t, st in zip(tags, states, strict=True)},
        options={
        **result.options, "method": "energy", "energy": eq.energy,
        "energy_iterations": eq.iterations, "energy_gradient": eq.gradient,
        "newton_polish_iterations": polished.iterations, "hessian_min": eq.hessian_min})


def relative_of(rb: Any, q_nodes: FloatArray) -> FloatArray:
    """Relative displacement ``(x, y, z, rx, ry)`` of a rolling bearing's rings."""
    u = q_nodes[list(rb.nodes)].reshape(1, -1)
    return np.asarray(rb.relative(u))[0]
