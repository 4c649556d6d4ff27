"""Assembly of the ring-and-roller model: geometry checks, mesh, operators, supports.

:func:`build_ring_model` turns the bearing data of
:func:`~rotorsim.verification.ring_fe.ring_fe_roller_loads` into a
:class:`~rotorsim.verification.ring_newton.ContactSystem` on the free DOFs, and keeps what
is needed to post-process the solution (coupling vectors, ring-mean operators, the full
DOF numbering). The modelling choices are described in
:mod:`~rotorsim.verification.ring_fe`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
import skfem
from numpy.typing import NDArray

from rotorsim.elements.rolling.contact.hertz_line import LINE_EXPONENT, iso_roller_constant
from rotorsim.elements.rolling.geometry import cage_ratio as kinematic_cage_ratio
from rotorsim.errors import ModelError
from rotorsim.verification import ring_forms as forms
from rotorsim.verification.ring_contact import RollerContactLaw
from rotorsim.verification.ring_mesh import (
    RingMesh,
    angular_grid,
    bearing_rings_mesh,
    radial_grid,
)
from rotorsim.verification.ring_newton import ContactSystem, rigid_ring_start

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

SUPPORTS = ("faces", "housing", "clamped")
"""Supports of the outer ring."""
CORE_FACTOR = 1.25
"""The refined angular core around a roller covers ``1.25 a`` of the inner raceway."""
WHERE = "ring_fe_roller_loads"


@dataclass(frozen=True, eq=False)
class RingModel:
    """Assembled model (free-DOF system plus post-processing operators on all DOFs)."""

    mesh: RingMesh
    cells: IntArray
    system: ContactSystem
    free: IntArray
    n_dofs: int
    inner_coupling: sp.csr_matrix
    outer_coupling: sp.csr_matrix
    inner_mean: sp.csr_matrix
    outer_mean: sp.csr_matrix
    law: RollerContactLaw
    load: tuple[float, float]
    roller_angles: FloatArray
    restraint: tuple[int, FloatArray, float]
    options: dict[str, Any] = field(default_factory=dict)

    def expand(self, u_free: FloatArray) -> FloatArray:
        """All-DOF displacement [m] from the free DOFs (held DOFs at 0)."""
        u = np.zeros(self.n_dofs)
        u[self.free] = u_free
        return u

    def restraint_force(self, u: FloatArray) -> float:
        """Force [N] in the spring that holds the inner ring's rotation (should be ~0)."""
        node, tangent, k = self.restraint
        return float(k * (tangent @ u[2 * node:2 * node + 2]))


def _check(data: dict[str, Any]) -> None:
    z = data["Z"]
    if isinstance(z, bool) or not isinstance(z, int | np.integer) or z < 3:
        raise ModelError(f"Z must be an integer >= 3, got {z!r}", WHERE)
    for name in ("R_p", "R_b", "L", "R_s", "R_h", "b", "E", "rho"):
        value = data[name]
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0.0):
            raise ModelError(f"{name} must be a positive finite number, got {value!r}", WHERE)
    if not 0.0 <= data["nu"] < 0.5:
        raise ModelError(f"nu must be in [0, 0.5), got {data['nu']!r}", WHERE)
    if not data["R_s"] < data["R_p"] - data["R_b"] < data["R_p"] + data["R_b"] < data["R_h"]:
        raise ModelError(f"radii must satisfy R_s < R_p - R_b < R_p + R_b < R_h, got R_s = "
                         f"{data['R_s']}, R_p = {data['R_p']}, R_b = {data['R_b']}, R_h = "
                         f"{data['R_h']} m", WHERE)
    if not (math.isfinite(data["clearance"]) and abs(data["clearance"]) < data["R_b"]):
        raise ModelError(f"clearance must be finite and smaller than R_b (metres), got "
                         f"{data['clearance']!r}", WHERE)
    for name in ("load", "speed", "psi0"):
        if not np.all(np.isfinite(data[name])):
            raise ModelError(f"{name} must be finite, got {data[name]!r}", WHERE)
    if data["support"] not in SUPPORTS:
        raise TypeError(f"{WHERE}: unknown support {data['support']!r}; valid: {SUPPORTS}")


def _resolve(data: dict[str, Any]) -> dict[str, Any]:
    """Fill the defaults of the mesh, contact and support options."""
    out = dict(data)
    thickness = min(data["R_p"] - data["R_b"] - data["R_s"],
                    data["R_h"] - data["R_p"] - data["R_b"])
    defaults = {"contact_half_width": 0.25 * thickness, "max_size": thickness / 3.0,
                "support_stiffness": 1e-3 * data["E"] * data["b"],
                "Kn": iso_roller_constant(data["L"])}
    for name, value in defaults.items():
        if data[name] is None:
            out[name] = value
    if data["mesh_size"] is None:
        out["mesh_size"] = out["contact_half_width"] / 3.0
    if data["cage_ratio"] is None:
        out["cage_ratio"] = kinematic_cage_ratio(2.0 * data["R_b"], 2.0 * data["R_p"], 0.0)
    for name in ("contact_half_width", "mesh_size", "max_size", "support_stiffness", "Kn"):
        if not (isinstance(out[name], int | float) and math.isfinite(out[name])
                and out[name] > 0.0):
            raise ModelError(f"{name} must be positive and finite, got {out[name]!r}", WHERE)
    limit = math.pi * (data["R_p"] - data["R_b"]) / (CORE_FACTOR * int(data["Z"]))
    if out["contact_half_width"] >= limit:
        raise ModelError(f"contact_half_width {out['contact_half_width']} m must be below "
                         f"{limit:.4g} m (the patches of neighbouring rollers would meet)",
                         WHERE)
    if out["mesh_size"] > out["max_size"] or not 1.0 <= data["growth"] <= 2.0:
        raise ModelError(f"need mesh_size <= max_size and 1 <= growth <= 2, got "
                         f"{out['mesh_size']}, {out['max_size']}, {data['growth']}", WHERE)
    return out


def _mesh(o: dict[str, Any]) -> RingMesh:
    r_i, r_o = o["R_p"] - o["R_b"], o["R_p"] + o["R_b"]
    theta = angular_grid(int(o["Z"]), o["psi0"], CORE_FACTOR * o["contact_half_width"] / r_i,
                         o["mesh_size"] / r_i, o["max_size"] / r_o, o["growth"])
    radii = {"bore": o["R_s"], "inner_raceway": r_i, "outer_raceway": r_o, "housing": o["R_h"]}
    inner = radial_grid(r_i, o["R_s"], o["mesh_size"], o["max_size"], o["growth"])
    outer = radial_grid(r_o, o["R_h"], o["mesh_size"], o["max_size"], o["growth"])
    return bearing_rings_mesh(radii, theta, inner, outer)


def _rotation_restraint(rm: RingMesh, load: FloatArray, k: float
                        ) -> tuple[sp.csr_matrix, tuple[int, FloatArray, float]]:
    """Tangential spring at the bore vertex opposite the load (holds the free rotation)."""
    p = rm.mesh.p
    bore = np.unique(rm.mesh.facets[:, rm.facets["bore"]])
    away = math.atan2(load[1], load[0]) + math.pi if np.any(load) else math.pi
    angle = np.arctan2(p[1, bore], p[0, bore])
    node = int(bore[np.argmin(np.abs(np.angle(np.exp(1j * (angle - away)))))])
    t = np.array([-math.sin(angle[bore == node][0]), math.cos(angle[bore == node][0])])
    n = 2 * rm.n_nodes
    idx = np.array([2 * node, 2 * node + 1])
    block = k * np.outer(t, t)
    rows, cols = np.meshgrid(idx, idx, indexing="ij")
    spring = sp.csr_matrix((block.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n))
    return spring, (node, t, k)


def build_ring_model(**data: Any) -> RingModel:
    """Check the bearing data, mesh the rings and assemble the contact system.

    Keyword arguments are the bearing data of :func:`~rotorsim.verification.ring_fe.
    ring_fe_roller_loads` with ``load = (F_x, F_y)``, the fields of its ``MeshOptions``
    (``contact_half_width``, ``mesh_size``, ``max_size``, ``growth``) and its
    ``OuterRingSupport`` as ``support`` (the kind) and ``support_stiffness``.
    """
    _check(data)
    o = _resolve(data)
    rm = _mesh(o)
    mesh = rm.mesh
    basis = forms.cell_basis(mesh)
    if basis.N != 2 * rm.n_nodes:
        raise ModelError("unexpected DOF numbering of the vector basis", WHERE)
    load = np.asarray(o["load"], dtype=float)
    stiffness = forms.plane_stress_stiffness(basis, o["E"], o["nu"], o["b"])
    spring, restraint = _rotation_restraint(rm, load, o["E"] * o["b"])
    stiffness = stiffness + spring + _support(rm, o)
    psi = o["psi0"] + 2.0 * math.pi * np.arange(int(o["Z"])) / int(o["Z"])
    c_in = forms.contact_coupling(mesh, rm.facets["inner_raceway"], psi, o["contact_half_width"])
    c_out = forms.contact_coupling(mesh, rm.facets["outer_raceway"], psi,
                                   o["contact_half_width"])
    omega_c = o["cage_ratio"] * o["speed"]
    mass = o["rho"] * math.pi * o["R_b"] ** 2 * o["L"]
    law = RollerContactLaw(kn=o["Kn"], centrifugal_force=mass * omega_c**2 * o["R_p"])
    f = forms.bore_traction(mesh, rm.facets["bore"], load, o["R_s"])
    f = f + law.centrifugal_force * np.asarray(c_out @ np.ones(psi.size))
    free = _free_dofs(rm, basis, o["support"])
    coupling = sp.csr_matrix((c_in - c_out)[free])
    offset = np.full(psi.size, -0.5 * o["clearance"])
    start = _start(rm, load, law, psi, offset, o)
    system = ContactSystem(sp.csr_matrix(stiffness[free][:, free]), f[free], coupling, offset,
                           law, _reference_stiffness(o, law), start[free])
    elements = np.arange(mesh.nelements)
    cells = forms.cell_basis(mesh).element_dofs[0::2] // 2  # scalar node of each x DOF
    options = {k: v for k, v in o.items() if k != "load"}
    options["F_x"], options["F_y"] = float(load[0]), float(load[1])
    return RingModel(
        mesh=rm, cells=np.asarray(cells), system=system, free=free, n_dofs=basis.N,
        inner_coupling=c_in, outer_coupling=c_out,
        inner_mean=forms.ring_mean(mesh, elements[rm.ring == 0]),
        outer_mean=forms.ring_mean(mesh, elements[rm.ring == 1]), law=law,
        load=(float(load[0]), float(load[1])), roller_angles=psi, restraint=restraint,
        options=options)


def _support(rm: RingMesh, o: dict[str, Any]) -> sp.csr_matrix:
    n = 2 * rm.n_nodes
    if o["support"] == "faces":
        outer = np.nonzero(rm.ring == 1)[0]
        return forms.face_support(rm.mesh, outer, o["support_stiffness"])
    if o["support"] == "housing":
        return forms.housing_support(rm.mesh, rm.facets["housing"], o["support_stiffness"],
                                     o["R_h"])
    return sp.csr_matrix((n, n))


def _free_dofs(rm: RingMesh, basis: skfem.CellBasis, support: str) -> IntArray:
    if support != "clamped":
        return np.arange(basis.N)
    held = basis.get_dofs(rm.facets["housing"]).all()
    return np.asarray(np.setdiff1d(np.arange(basis.N), held))


def _reference_stiffness(o: dict[str, Any], law: RollerContactLaw) -> float:
    """``k_ref``: the whole-roller tangent at a typical deflection (any value > 0 works)."""
    z, kn = int(o["Z"]), law.kn
    per_roller = 4.0 * (math.hypot(*o["load"]) + z * law.centrifugal_force) / z
    delta = max(abs(o["clearance"]) / 2.0, (per_roller / kn) ** (1.0 / LINE_EXPONENT), 1e-7)
    return float(LINE_EXPONENT * kn * delta ** (LINE_EXPONENT - 1.0))


def _start(rm: RingMesh, load: FloatArray, law: RollerContactLaw, psi: FloatArray,
           offset: FloatArray, o: dict[str, Any]) -> FloatArray:
    """Start of Newton: both rings translated rigidly (outer ring on its support, inner ring
    by the rigid-ring equilibrium relative to it)."""
    outer = np.zeros(2) if o["support"] == "clamped" else load / o["support_stiffness"]
    inner = outer + rigid_ring_start(law, psi, offset, load)
    node_ring = np.zeros(rm.n_nodes, dtype=np.int64)
    cells = forms.cell_basis(rm.mesh).element_dofs[0::2] // 2
    node_ring[cells[:, rm.ring == 1].ravel()] = 1
    u = np.where(node_ring[:, None] == 1, outer[None, :], inner[None, :])
    return np.asarray(u.ravel())
