"""2D finite-element verification model of a roller bearing with flexible rings (seed 001).

Public functions
----------------
* :func:`ring_fe_roller_loads` ``(Z, R_p, R_b, L, R_s, R_h, b, E, nu, rho, clearance, F_x,
  speed=0.0, *, F_y, Kn, psi0, cage_ratio, mesh, support, newton) -> RingFEResult``: roller
  loads of the bearing with both rings modelled as plane-stress continua; the options are
  grouped in :class:`MeshOptions`, :class:`OuterRingSupport` and :class:`NewtonOptions`
  (:mod:`~rotorsim.verification.ring_options`, importable from here);
* :func:`export_vtu` ``(result, path)``: the deformed rings and the roller loads for
  ParaView;
* :data:`SEED001_CASE`: the bearing of seed 001 section 3.1 as keyword arguments.

Reference numbers with rigid rings come from
:func:`rotorsim.verification.ring_reference.rigid_ring_roller_loads`.

The model is the counterpart of seed 001's NX Nastran verification (section 3.1, Fig. 6),
reduced to the plane of the rollers, and is independent of the fast flexible-ring element
(seed 001 section 2, :mod:`rotorsim.elements.rolling`); only the contact law is shared.

* **Rings**: inner ring ``R_s <= r <= R_p - R_b``, outer ring ``R_p + R_b <= r <= R_h``,
  linear elastic, plane stress of thickness ``b``, biquadratic 9-node quadrilaterals on a
  polar mesh refined at the contacts (:mod:`~rotorsim.verification.ring_mesh`).
* **Rollers**: ``Z`` rigid rollers at ``psi_j = psi0 + 2 pi j / Z`` (cage held, statics),
  each between two Hertz line contacts in series, ``Q = Kn Delta^(10/9)`` for the whole
  roller (ISO/TS 16281 constant by default, the law of
  :mod:`rotorsim.elements.rolling.contact.hertz_line` used by every roller model of the package),
  diametral clearance ``g`` (negative: preload), centrifugal force
  ``F_c = m omega_c^2 R_p`` (seed 001 eq 18; ``m = rho pi R_b^2 L``,
  ``omega_c = kappa speed``, ``kappa = (1 - R_b/R_p)/2`` for a turning inner and a fixed
  outer ring) pushing each roller onto the outer raceway
  (:mod:`~rotorsim.verification.ring_contact`). The contact force is spread over a
  raceway arc ``|s| <= a`` (``MeshOptions.contact_half_width``) and the raceway deflection
  is its work-conjugate mean (:mod:`~rotorsim.verification.ring_forms` explains why).
* **Load**: ``F = (F_x, F_y)`` on the inner ring as a cosine traction on the half of the
  bore facing the load (seed 001 section 3.1: ``q_x = q_0 b cos phi``). The inner ring is
  held by the rollers only; a tangential spring at one bore node (on the unloaded side)
  removes its free rotation (the contact and bore loads have no moment about the axis, so
  the spring carries nothing: its force is reported in ``stats``).
* **Outer ring support** (``OuterRingSupport.kind``): ``"faces"`` (default) a soft elastic
  support of the ring faces of total lateral stiffness ``OuterRingSupport.stiffness``
  (default ``1e-3 E b``): the plane counterpart of the soft cylinders glued to the outer
  ring in the NX model and of the small nodal springs of seed 001 section 2.5, so that the
  outer ring deforms freely;
  ``"housing"`` a Winkler housing on ``r = R_h`` of the same total stiffness;
  ``"clamped"`` the outer surface fixed (the rigid housing of seed 001's rigid-ring NX
  model).
* **Solver**: Newton on the ``Z`` contact nonlinearities with the Woodbury identity and an
  energy line search (:mod:`~rotorsim.verification.ring_newton`).

Not modelled (as in seed 001 section 2.3): centrifugal expansion of the rings, thermal
effects, friction, roller tilt; ``g`` is the operating clearance.

References
----------
Seed 001 eqs 13-19 (contact deflections, contact law, roller potential), section 2.5 (ring
FE with roller elements) and section 3.1 (bearing data, NX Nastran model, Fig. 5-6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError, Status
from rotorsim.solvers.stats import Stats
from rotorsim.verification.ring_model import RingModel, build_ring_model
from rotorsim.verification.ring_newton import solve_contacts
from rotorsim.verification.ring_options import (
    MeshOptions,
    NewtonOptions,
    OuterRingSupport,
    grouped_options,
)

__all__ = [
    "SEED001_CASE",
    "MeshOptions",
    "NewtonOptions",
    "OuterRingSupport",
    "RingFEResult",
    "export_vtu",
    "ring_fe_roller_loads",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

SEED001_CASE: dict[str, Any] = {
    "Z": 24, "R_p": 0.075, "R_b": 0.0065, "L": 0.016, "R_s": 0.054, "R_h": 0.097,
    "b": 0.030, "E": 2.0e11, "nu": 0.3, "rho": 7850.0, "F_x": 5000.0,
    "speed": 12000.0 * math.pi / 30.0,
}
"""Seed 001 section 3.1: 24 rollers, ``R_p = 75``, ``R_b = 6.5``, ``L = 16``, ``R_s = 54``,
``R_h = 97``, ``b = 30`` mm, ``F_x = 5000`` N, inner ring at 12000 rpm, steel. The clearance
is ``-40e-6`` or ``10e-6`` m; pass it as ``clearance=``."""


@dataclass(frozen=True, eq=False)
class RingFEResult:
    """Equilibrium of the ring finite-element model.

    Attributes
    ----------
    roller_angles : array (Z,)
        ``psi_j`` [rad].
    roller_loads : array (Z,)
        Inner-contact loads ``Q_i`` [N] (the loads of seed 001 Fig. 5).
    outer_loads : array (Z,)
        Outer-contact loads ``Q_e = Q_i + F_c`` [N].
    approach : array (Z,)
        Total approach ``Delta = -g/2 + w_i - w_e`` [m] (negative: the roller is loose).
    inner_deflection, outer_deflection : array (Z,)
        Hertz deflections of the inner and outer contacts [m].
    inner_raceway_deflection, outer_raceway_deflection : array (Z,)
        Patch-mean raceway displacements ``w_i``, ``w_e`` along ``e_j`` (outwards) [m].
    inner_ring_displacement, outer_ring_displacement : array (2,)
        Area-mean ``(u_x, u_y)`` of each ring [m] (its centre displacement).
    force_sum : array (2,)
        ``sum_j Q_j e_j`` [N]: equals ``load`` at equilibrium.
    load : array (2,)
        ``(F_x, F_y)`` [N].
    centrifugal_force : float
        ``F_c`` of one roller [N].
    nodes : array (N, 2)
        Node coordinates [m].
    displacement : array (N, 2)
        Node displacements [m].
    cells : int array (n_elements, 9)
        Node indices of each 9-node quadrilateral (VTK ``quad9`` order).
    ring : int array (n_elements,)
        0 inner ring, 1 outer ring.
    iterations : int
        Newton iterations.
    residual : float
        Final relative residual.
    history : tuple of float
        Relative residual of every iteration.
    options, stats, summary : dict
        Options used, cost counters (factorisations, solves, iterations, wall time, ...),
        and model size.
    status : Status
    """

    roller_angles: FloatArray
    roller_loads: FloatArray
    outer_loads: FloatArray
    approach: FloatArray
    inner_deflection: FloatArray
    outer_deflection: FloatArray
    inner_raceway_deflection: FloatArray
    outer_raceway_deflection: FloatArray
    inner_ring_displacement: FloatArray
    outer_ring_displacement: FloatArray
    force_sum: FloatArray
    load: FloatArray
    centrifugal_force: float
    nodes: FloatArray
    displacement: FloatArray
    cells: IntArray
    ring: IntArray
    iterations: int
    residual: float
    history: tuple[float, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    summary: dict[str, Any] = field(default_factory=dict)
    status: Status = Status.OK

    @property
    def max_roller_load(self) -> float:
        """Largest inner-contact load [N]."""
        return float(self.roller_loads.max())

    @property
    def relative_displacement(self) -> FloatArray:
        """Inner minus outer ring centre displacement [m] (the bearing's ``delta_x, y``)."""
        return np.asarray(self.inner_ring_displacement - self.outer_ring_displacement)


def ring_fe_roller_loads(
    Z: int, R_p: float, R_b: float, L: float, R_s: float, R_h: float, b: float,
    E: float, nu: float, rho: float, clearance: float, F_x: float, speed: float = 0.0, *,
    F_y: float = 0.0, Kn: float | None = None, psi0: float = 0.0,
    cage_ratio: float | None = None, mesh: MeshOptions | None = None,
    support: OuterRingSupport | None = None, newton: NewtonOptions | None = None,
    **moved: Any,
) -> RingFEResult:
    """Roller loads of a radial roller bearing whose two rings are 2D elastic continua.

    Parameters
    ----------
    Z : int
        Number of rollers.
    R_p, R_b, L : float
        Pitch radius, roller radius and effective roller length [m].
    R_s, R_h : float
        Bore radius of the inner ring and outer radius of the outer ring [m].
    b : float
        Ring width [m] (plane-stress thickness).
    E, nu, rho : float
        Young's modulus [Pa], Poisson's ratio, density [kg/m^3] (roller mass).
    clearance : float
        Operating diametral clearance ``g`` [m]; negative = preload.
    F_x : float
        Radial load on the inner ring along x [N].
    speed : float
        Inner-ring speed [rad/s] (roller centrifugal force); 0 for pure statics.
    F_y : float
        Radial load along y [N].
    Kn : float, optional
        Whole-roller constant [N/m^(10/9)]; default ISO/TS 16281 for length ``L``.
    psi0 : float
        Angle of roller 0 [rad] from +x.
    cage_ratio : float, optional
        ``omega_c / speed``; default ``(1 - R_b / R_p) / 2``.
    mesh : MeshOptions, optional
        Contact patch half-width ``a`` and element sizes (default ``MeshOptions()``).
    support : OuterRingSupport, optional
        Support of the outer ring (default ``OuterRingSupport()``: soft faces, module
        docstring).
    newton : NewtonOptions, optional
        Newton tolerance (relative residual) and iteration limit (default
        ``NewtonOptions()``).

    Returns
    -------
    RingFEResult

    Raises
    ------
    ModelError
        Invalid geometry or options.
    TypeError
        For a keyword that moved into an option group (the message names the group), or
        an unknown support kind.
    ConvergenceError
        If Newton's method fails.

    Examples
    --------
    >>> r = ring_fe_roller_loads(**SEED001_CASE, clearance=10e-6,
    ...                          mesh=MeshOptions(mesh_size=3e-3, max_size=7e-3))
    >>> r.roller_loads.shape, bool(abs(r.force_sum[0] - 5000.0) < 1e-4)
    ((24,), True)
    """
    mesh, support, newton = grouped_options(mesh, support, newton, moved)
    stats = Stats()
    model = build_ring_model(
        Z=Z, R_p=R_p, R_b=R_b, L=L, R_s=R_s, R_h=R_h, b=b, E=E, nu=nu, rho=rho,
        clearance=clearance, load=(F_x, F_y), speed=speed, Kn=Kn, psi0=psi0,
        cage_ratio=cage_ratio, contact_half_width=mesh.contact_half_width,
        mesh_size=mesh.mesh_size, max_size=mesh.max_size, growth=mesh.growth,
        support=support.kind, support_stiffness=support.stiffness)
    tol, max_iter = newton.tol, newton.max_iter
    if not (tol > 0.0 and isinstance(max_iter, int) and max_iter >= 1):
        raise ModelError(f"tol must be > 0 and max_iter an integer >= 1, got {tol!r}, "
                         f"{max_iter!r}", "ring_fe_roller_loads")
    solution = solve_contacts(model.system, tol=tol, max_iter=max_iter, stats=stats)
    return _result(model, solution, stats)


def _result(model: RingModel, solution: Any, stats: Stats) -> RingFEResult:
    u = model.expand(solution.displacement)
    contacts = solution.contacts
    psi = model.roller_angles
    directions = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    q = contacts.inner_load
    nodal = u.reshape(-1, 2)
    counters = stats.finish()
    counters["rotation_restraint_force"] = model.restraint_force(u)
    return RingFEResult(
        roller_angles=psi, roller_loads=q, outer_loads=contacts.outer_load,
        approach=solution.approach, inner_deflection=contacts.inner_deflection,
        outer_deflection=contacts.outer_deflection,
        inner_raceway_deflection=np.asarray(model.inner_coupling.T @ u),
        outer_raceway_deflection=np.asarray(model.outer_coupling.T @ u),
        inner_ring_displacement=np.asarray(model.inner_mean.T @ u),
        outer_ring_displacement=np.asarray(model.outer_mean.T @ u),
        force_sum=np.asarray(q @ directions), load=np.asarray(model.load, dtype=float),
        centrifugal_force=model.law.centrifugal_force,
        nodes=np.asarray(model.mesh.mesh.doflocs.T), displacement=nodal,
        cells=np.asarray(model.cells.T), ring=model.mesh.ring,
        iterations=solution.iterations, residual=solution.residual,
        history=solution.history, options=dict(model.options), stats=counters,
        summary={"n_dofs": int(u.size), "n_free_dofs": int(solution.displacement.size),
                 "n_elements": int(model.mesh.mesh.nelements),
                 "n_nodes": int(model.mesh.n_nodes), "Kn": model.law.kn,
                 "step_lengths": solution.step_lengths})


def export_vtu(result: RingFEResult, path: str | Path) -> Path:
    """Write the deformed rings and the roller loads to a VTU file (ParaView).

    Points are the ring nodes (``z = 0``) followed by the ``Z`` roller centres at the pitch
    radius. Cells: ``quad9`` ring elements and ``vertex`` rollers. Point data:
    ``displacement`` ``(u_x, u_y, 0)`` [m] (warp by vector to see the deformed rings; the
    rollers get their mean raceway displacement) and ``roller_load`` [N] (0 on ring nodes).
    Cell data: ``ring`` (0 inner, 1 outer, -1 roller), ``roller_load`` and ``outer_load`` [N]
    (0 on ring elements).

    Returns
    -------
    Path
        The written file.
    """
    import meshio

    path = Path(path)
    z = result.roller_angles.size
    pitch = float(result.options["R_p"])
    psi = result.roller_angles
    rollers = pitch * np.stack([np.cos(psi), np.sin(psi)], axis=1)
    w = 0.5 * (result.inner_raceway_deflection + result.outer_raceway_deflection)
    roller_u = w[:, None] * np.stack([np.cos(psi), np.sin(psi)], axis=1)
    n = result.nodes.shape[0]
    points = np.zeros((n + z, 3))
    points[:n, :2], points[n:, :2] = result.nodes, rollers
    disp = np.zeros((n + z, 3))
    disp[:n, :2], disp[n:, :2] = result.displacement, roller_u
    load = np.concatenate([np.zeros(n), result.roller_loads])
    n_cells = result.cells.shape[0]
    mesh = meshio.Mesh(
        points, [("quad9", result.cells), ("vertex", (n + np.arange(z))[:, None])],
        point_data={"displacement": disp, "roller_load": load},
        cell_data={"ring": [result.ring.astype(np.int64), np.full(z, -1, dtype=np.int64)],
                   "roller_load": [np.zeros(n_cells), result.roller_loads],
                   "outer_load": [np.zeros(n_cells), result.outer_loads]})
    path.parent.mkdir(parents=True, exist_ok=True)
    meshio.write(path, mesh, file_format="vtu")
    return path

