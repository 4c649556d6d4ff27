"""Linear static analysis under gravity and point loads, with explicit rigid-body checks.

The solve is split so that the nonlinear-bearing version can reuse every stage:
``_applied_load`` (f), :func:`~rotorsim.analyses.rigid_motions.free_rigid_motions` (which
motions of the whole rotor nothing restrains, and whether the load can be equilibrated),
:func:`~rotorsim.analyses.rigid_motions.solve_restrained` (one linear solve with those
motions held) and ``_post_process`` (bearing reactions, shaft internal forces). A nonlinear
static analysis replaces the restrained solve by a Newton iteration on ``K q + r(q) = f``
started from the linear solution.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import check_speed
from rotorsim.analyses.rigid_motions import (
    check_equilibrium,
    free_rigid_motions,
    solve_restrained,
)
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.loads import (
    STANDARD_GRAVITY,
    consistent_gravity,
    gravity_load,
    gravity_load_all_dofs,
    nodal_load,
    unit_direction,
)
from rotorsim.assembly.system import RotorSystem, bearing_matrices
from rotorsim.elements.base import DOFS_PER_NODE, as_float_array
from rotorsim.elements.shaft import shaft_matrices
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.static import StaticResult
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]


@checked_keywords
def static(
    rotor: Rotor | RotorSystem,
    *,
    gravity: float | None = STANDARD_GRAVITY,
    direction: ArrayLike = (0.0, -1.0, 0.0),
    loads: Sequence[tuple[int, str, float]] = (),
    speed: float = 0.0,
    rigid_tol: float = 1e-10,
    method: str = "newton",
    x0: ArrayLike | None = None,
) -> StaticResult:
    """Linear static deflection, bearing reactions and shaft internal forces.

    Solves ``K(W) q = f`` with ``f`` the consistent gravity load plus point loads. Rigid-body
    motions of the whole rotor that nothing restrains (e.g. axial and torsional motion of a
    rotor on radial bearings) are detected: if the load has a resultant along one of them
    the problem has no equilibrium and :class:`ModelError` says which direction is unsupported;
    otherwise the motion is removed by holding one DOF (e.g. ``uz`` of node 0) at zero.

    With nonlinear elements (rolling bearings in ``rotor.nonlinear_elements``) the
    equilibrium ``K q + r(q) = f`` is solved by Newton's method with a line search on the
    total potential energy
    (:func:`rotorsim.analyses.statics.linearized_rotor.linearize_rolling_bearings`,
    relative residual 1e-10); the result then lists each rolling bearing's reaction on the
    shaft beside the linear bearings, and ``linearize_rolling_bearings(rotor).equilibria``
    gives the rolling-element loads.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model. Bearing reactions and internal forces need a :class:`Rotor`; with a
        RotorSystem they are ``None``.
    gravity : float or None
        Acceleration of gravity [m/s^2]; ``None`` or 0 switches gravity off.
    direction : 3 floats
        Direction in which gravity acts; default ``-y``.
    loads : list of (node, dof, value)
        Point forces [N] (``ux, uy, uz``) and moments [N m] (``rx, ry, rz``).
    speed : float
        Spin speed W [rad/s], finite and >= 0, at which speed-dependent bearing stiffness
        is evaluated (negative speeds are refused: :mod:`rotorsim.analyses.linear.argument_checks`).
    rigid_tol : float
        A rigid motion ``r`` is free when ``||S K r|| <= rigid_tol ||S K S||_F ||S^-1 r||``
        with ``S = diag(|K_ii|^-1/2)`` (:func:`free_rigid_motions`): a support softer than
        about ``rigid_tol`` times the stiffness of the shaft DOFs it acts on counts as
        absent, whatever the stiffest spring elsewhere (e.g. 1e20 N/m pinned supports).
    method : {"newton", "energy"}
        With nonlinear elements: Newton's method with an energy line search, or the
        minimisation of the total potential energy of the rotor and its bearings
        (:mod:`rotorsim.analyses.statics.rotor_energy`, seed 000 for the whole rotor). Both give
        the same equilibrium; ``options`` record the method (and the energy).
    x0 : array (ndof,), optional
        Starting displacement of the nonlinear solve on all DOFs [m, rad] (e.g. the
        ``displacement`` of an earlier result; zero on fixed DOFs). Newton's method then
        starts there (falling back to the energy minimum, then to load steps, when it
        fails), or the energy minimisation does. A linear rotor has a unique solution and
        only checks it.

    Returns
    -------
    StaticResult
        Displacements on all DOFs; with a Rotor also the force of each bearing on the shaft
        and the section forces at both ends of every shaft element: the force and moment
        that the part at larger ``z`` exerts on the part at smaller ``z`` (tension-positive
        axial force, ``M_x = E I d(rx)/dz``, ``M_y = E I d(ry)/dz``), computed as element
        stiffness times element displacements minus the element's consistent gravity load.

    Raises
    ------
    ModelError
        If the load cannot be equilibrated (e.g. no bearings) or an input is invalid
        (``x0`` not ``ndof`` finite numbers, or nonzero on a fixed DOF).

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e8),
    ...                              rs.BearingElement(n=4, kxx=1e8)])
    >>> s = static(rotor)
    >>> s.free_rigid_motions
    ('rotation about z', 'z (translation)')
    >>> bool(np.allclose(s.bearing_forces[:, 1], 9.80665 * rotor.m / 2))
    True
    """
    speed = check_speed(speed, "static")
    if not np.isfinite(rigid_tol) or rigid_tol <= 0:
        raise ModelError(f"rigid_tol must be > 0, got {rigid_tol!r}", "static")
    if method not in ("newton", "energy"):
        raise ModelError(f"method must be 'newton' or 'energy', got {method!r}", "static")
    if isinstance(rotor, Rotor) and rotor.nonlinear_elements:
        from rotorsim.analyses.statics.rolling_dispatch import (
            energy_static,
            newton_static,
            started_static,
        )

        if method == "energy":
            return energy_static(rotor, gravity, direction, loads, float(speed), x0)
        if x0 is not None:
            return started_static(rotor, gravity, direction, loads, float(speed), x0)
        return newton_static(rotor, gravity, direction, loads, float(speed))
    system = as_system(rotor)
    if x0 is not None:
        from rotorsim.analyses.statics.nonlinear_static import start_point

        start_point(system, x0, "static.x0")
    model = rotor if isinstance(rotor, Rotor) else None
    g_given = 0.0 if gravity is None else as_float_array(gravity, "value", "gravity")
    if np.ndim(g_given) or not np.isfinite(g_given):
        raise ModelError(f"must be finite or None, got {gravity!r}", "gravity")
    g = float(g_given)
    unit = unit_direction(direction)
    stats = Stats()
    K = system.matrices(float(speed)).K
    f, f_all = _applied_load(system, model, g, unit, loads)
    rigid = free_rigid_motions(system, K, rigid_tol, scaled=True)
    check_equilibrium(rigid, f)
    q_free, held = solve_restrained(K, f, rigid, stats)
    residual = float(np.linalg.norm(K @ q_free - f)) / max(float(np.linalg.norm(f)), 1e-300)
    q = system.dof_map.expand(q_free)
    post = _post_process(model, q, f_all, g, unit, float(speed)) if model else {}
    extra: dict[str, Any] = {key: post.get(key) for key in _POST_KEYS}
    names = system.dof_map.names()
    return StaticResult(
        displacement=q, load=f_all, dof_map=system.dof_map, nodes_pos=system.nodes_pos,
        speed=float(speed), free_rigid_motions=rigid.labels,
        restrained_dofs=tuple(names[system.dof_map.free[i]] for i in held), residual=residual,
        options={"gravity": g, "direction": unit.tolist(),
                 "loads": [tuple(x) for x in loads], "rigid_tol": rigid_tol},
        stats=stats.finish(), summary=system.summary,
        **extra,
    )


_POST_KEYS = ("bearing_nodes", "bearing_forces", "bearing_moments", "constraint_reactions",
              "element_z", "shear_force", "bending_moment", "axial_force", "torque")


def _applied_load(
    system: RotorSystem, model: Rotor | None, g: float, unit: FloatArray,
    loads: Sequence[tuple[int, str, float]],
) -> tuple[FloatArray, FloatArray]:
    """Load on the free DOFs and on all DOFs (gravity exact on fixed DOFs with a Rotor)."""
    point = np.zeros(system.n_free)
    if isinstance(loads, str) or not isinstance(loads, Sequence):
        raise ModelError("give a list of (node, dof, value)", "loads")
    for i, item in enumerate(loads):
        if isinstance(item, str) or not isinstance(item, Sequence) or len(item) != 3:
            raise ModelError(f"expected (node, dof, value), got {item!r}", f"loads[{i}]")
        point += nodal_load(system, item[0], item[1], item[2], where=f"loads[{i}]")
    f_all = system.dof_map.expand(point)
    if g == 0.0:
        return point, f_all
    if model is None:
        f = point + gravity_load(system, g, unit)
        return f, system.dof_map.expand(f)
    f_all += gravity_load_all_dofs(model, g, unit)
    return f_all[system.dof_map.free], f_all


def _post_process(model: Rotor, q: FloatArray, f_all: FloatArray, g: float,
                  unit: FloatArray, speed: float) -> dict[str, Any]:
    """Bearing reactions, constraint reactions and shaft section forces from the elements."""
    internal = np.zeros(model.ndof)  # K_full q assembled element by element
    sections, z = _shaft_sections(model, q, g, unit, internal)
    b_nodes, b_forces = [], []
    ratios = model.node_speed_ratio if model.multi_line else None
    for b in model.bearing_elements:
        bdofs = (DOFS_PER_NODE * np.asarray(b.nodes)[:, None] + np.arange(6)).ravel()
        force = bearing_matrices(b, speed, ratios).K @ q[bdofs]
        np.add.at(internal, bdofs, force)
        b_nodes.append(b.n)
        b_forces.append(-force[:6])
    reactions = np.array(b_forces).reshape(-1, 6)
    return {
        "bearing_nodes": np.array(b_nodes, dtype=np.int64),
        "bearing_forces": reactions[:, :3], "bearing_moments": reactions[:, 3:],
        "constraint_reactions": internal - f_all,
        "element_z": z, "shear_force": sections[..., 0:2], "axial_force": sections[..., 2],
        "bending_moment": sections[..., 3:5], "torque": sections[..., 5],
    }



def _shaft_sections(model: Rotor, q: FloatArray, g: float, unit: FloatArray,
                    internal: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Section forces ``(E, 2, 6)`` at both ends of every shaft element and their axial
    positions ``(E, 2)`` [m]; adds the elements' ``K q`` to ``internal``. A rigid rotor
    (no shaft element) has none: arrays of length 0."""
    shaft = model.shaft_elements
    if not shaft:
        return np.zeros((0, 2, DOFS_PER_NODE)), np.zeros((0, 2))
    mats = shaft_matrices(shaft)
    nodes = np.array([el.nodes for el in shaft])
    dofs = (DOFS_PER_NODE * nodes[:, :, None] + np.arange(DOFS_PER_NODE)).reshape(len(shaft), -1)
    end_forces = np.einsum("eij,ej->ei", mats.K, q[dofs])
    np.add.at(internal, dofs, end_forces)
    if g != 0.0:
        end_forces = end_forces - consistent_gravity(mats.M, g, unit)
    sections = np.stack([-end_forces[:, :6], end_forces[:, 6:]], axis=1)
    return sections, model.nodes_pos[nodes]
