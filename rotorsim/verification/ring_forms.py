"""Finite-element operators of the ring model: stiffness, loads, contact coupling, supports.

All operators act on the vector field ``u = (u_x, u_y)`` [m] of the rings, discretised with
:class:`skfem.ElementVector` of :class:`skfem.ElementQuad2` (9-node biquadratic, 2 DOFs a
node, interleaved: node ``k`` has DOFs ``2k`` and ``2k + 1``). Plane stress with the ring
width ``b`` as thickness: ``K = b int sigma(u) : eps(v) dA``.

Contact coupling (why a patch and not a node). A roller ``j`` at ``psi_j`` presses on each
raceway with a force along its line of action ``e_j = (cos psi_j, sin psi_j)``. In 2D
elasticity a point force gives a logarithmically infinite displacement under the load, so a
nodal force would make the result depend on the mesh; and the local indentation of the ring
is already part of the Hertz-Palmgren load-deflection law of the roller, which would then
be counted twice. The force is therefore spread over an arc ``|s| <= a`` of the raceway
(``s`` the arc length from ``psi_j``) with the smooth weight ``phi(s) = cos^2(pi s / 2a)``,
and the raceway deflection that enters the contact law is the same weighted mean of
``e_j . u``::

    w_j = int phi e_j . u ds / int phi ds = c_j . U,     force on the ring = Q_j c_j

(work-conjugate: the tangent stays symmetric and the model has a potential energy). With
``e_j`` fixed, a rigid translation ``U`` gives exactly ``w_j = U . e_j``: the rigid-ring
limit is reproduced to round-off. ``a`` (a few millimetres, a fraction of the ring
thickness) averages the local indentation away while leaving the ring's bending and hoop
deformation (the "structural" deflection of seed 001 eqs 8-11 and of its ring-beam model,
section 2.5) intact. For the seed 001 bearing, ``a`` from 0.5 to 7 mm changes the largest
roller load by -3.4 % to +1.2 % around the default ``a = 3.6`` mm with a 40 um preload, and
by less than 0.2 % with a 10 um clearance (``examples/seed001_ring_fe.py`` prints this
study).

References
----------
Seed 001 section 3.1 (cosine traction ``q_x = q_0 b cos phi`` on the loaded half of the
inner ring, soft supports of the outer ring: section 2.5 and Fig. 6).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
import skfem
from numpy.typing import NDArray
from skfem.models.elasticity import linear_elasticity, plane_stress

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

CELL_ORDER = 5
"""Quadrature order of cell integrals (3 x 3 Gauss points, standard for 9-node quads)."""
FACET_ORDER = 10
"""Quadrature order of facet integrals (6 points: the cos^2 patch weight is not polynomial)."""


def vector_element() -> skfem.ElementVector:
    """The displacement element: biquadratic, two components."""
    return skfem.ElementVector(skfem.ElementQuad2())


def cell_basis(mesh: skfem.MeshQuad2, elements: IntArray | None = None) -> skfem.CellBasis:
    """Cell basis of the displacement field (on ``elements`` only when given)."""
    return skfem.CellBasis(mesh, vector_element(), intorder=CELL_ORDER, elements=elements)


def facet_basis(mesh: skfem.MeshQuad2, facets: IntArray) -> skfem.FacetBasis:
    """Facet basis of the displacement field on ``facets``."""
    return skfem.FacetBasis(mesh, vector_element(), facets=facets, intorder=FACET_ORDER)


def plane_stress_stiffness(basis: skfem.CellBasis, E: float, nu: float,
                           thickness: float) -> sp.csr_matrix:
    """Plane-stress stiffness ``b int sigma : eps dA`` [N/m], shape ``(n_dofs, n_dofs)``."""
    lam, mu = plane_stress(E, nu)
    return sp.csr_matrix(thickness * linear_elasticity(lam, mu).assemble(basis))


def _polar(basis: skfem.FacetBasis) -> tuple[FloatArray, FloatArray]:
    """Radius and angle of the facet quadrature points, shape ``(n_facets, n_points)``."""
    x = np.asarray(basis.global_coordinates())
    return np.hypot(x[0], x[1]), np.arctan2(x[1], x[0])


def _facet_matrix(basis: skfem.FacetBasis, weights: FloatArray,
                  directions: FloatArray) -> sp.csr_matrix:
    """``int weights_j directions_j . v ds`` for every column ``j`` as a sparse matrix.

    ``weights`` has shape ``(J, n_facets, n_points)`` (the quadrature weights ``ds`` are
    included here) and ``directions`` ``(J, 2)`` or ``(2, J, n_facets, n_points)``.
    """
    n_cols = weights.shape[0]
    d = directions.T[:, :, None, None] if directions.ndim == 2 else directions
    values = np.stack([np.asarray(phi[0]) for phi in basis.basis])  # (n_local, 2, F, P)
    dx = basis.dx
    # entry (local dof, column, facet) = sum_p w_j d_j . phi_k dx
    local = np.einsum("kcfp,cjfp,jfp,fp->kjf", values, d * np.ones_like(weights), weights, dx)
    rows = np.broadcast_to(basis.element_dofs[:, None, :], local.shape)
    cols = np.broadcast_to(np.arange(n_cols)[None, :, None], local.shape)
    keep = local != 0.0
    return sp.csr_matrix((local[keep], (rows[keep], cols[keep])), shape=(basis.N, n_cols))


def contact_coupling(mesh: skfem.MeshQuad2, facets: IntArray, psi: FloatArray,
                     half_width: float) -> sp.csr_matrix:
    """Patch coupling vectors ``c_j`` of the rollers on one raceway, shape ``(n_dofs, Z)``.

    ``c_j . U`` is the ``cos^2``-weighted mean of ``e_j . u`` over ``|s| <= half_width``
    around ``psi_j`` (module docstring); ``Q_j c_j`` is the nodal force of a contact load
    ``Q_j`` along ``e_j``. The normalisation uses the same quadrature, so a unit rigid
    translation along ``e_j`` gives exactly ``c_j . U = 1``.
    """
    basis = facet_basis(mesh, facets)
    radius, angle = _polar(basis)
    gap = (angle[None] - psi[:, None, None] + math.pi) % (2.0 * math.pi) - math.pi
    s = radius[None] * gap
    phi = np.where(np.abs(s) < half_width, np.cos(0.5 * math.pi * s / half_width) ** 2, 0.0)
    total = np.einsum("jfp,fp->j", phi, basis.dx)
    if np.any(total <= 0.0):
        raise ValueError("a contact patch has no quadrature point: refine the mesh")
    directions = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    return _facet_matrix(basis, phi / total[:, None, None], directions)


def bore_traction(mesh: skfem.MeshQuad2, facets: IntArray, force: FloatArray,
                  bore_radius: float) -> FloatArray:
    """Nodal load of the cosine traction that carries ``force`` into the bore [N].

    The traction is parallel to the force and acts on the half of the bore that faces it:
    ``t(phi) = |F| cos(phi - phi_F) / (2 b R_s)`` for ``|phi - phi_F| < pi/2`` (per unit
    area, ``phi_F`` the direction of ``F``), so that ``b int t R_s dphi = F``: seed 001
    section 3.1, ``q_x(phi) = q_0 b cos phi`` with ``F_x = int q_x dphi``. The ring width
    ``b`` cancels, so it is not a parameter here.
    """
    magnitude = float(np.hypot(force[0], force[1]))
    basis = facet_basis(mesh, facets)
    if magnitude == 0.0:
        return np.zeros(basis.N)
    _, angle = _polar(basis)
    direction = math.atan2(force[1], force[0])
    c = np.cos(angle - direction)
    weight = np.where(c > 0.0, c, 0.0)[None]
    # |F| cos / (2 R_s), normalised with the quadrature itself (the kinks of the traction at
    # +-pi/2 need not be facet ends), so that the nodal loads add up to F exactly
    weight = weight * magnitude / float(np.einsum("jfp,fp->", weight, basis.dx))
    unit = np.asarray(force, dtype=float)[:, None] / magnitude
    return np.asarray(_facet_matrix(basis, weight, unit.T).toarray()[:, 0])


def pressure_load(mesh: skfem.MeshQuad2, facets: IntArray, pressure: float,
                  thickness: float, outward: bool) -> FloatArray:
    """Nodal load [N] of a uniform pressure [Pa] on a circle, pushing into the material.

    ``outward=True`` pushes along ``+e_r`` (a pressure on the inner surface of an annulus).
    """
    basis = facet_basis(mesh, facets)
    _, angle = _polar(basis)
    sign = 1.0 if outward else -1.0
    d = sign * np.stack([np.cos(angle), np.sin(angle)])[:, None]
    weight = np.full((1, *angle.shape), pressure * thickness)
    return np.asarray(_facet_matrix(basis, weight, d).toarray()[:, 0])


def face_support(mesh: skfem.MeshQuad2, elements: IntArray, stiffness: float) -> sp.csr_matrix:
    """Elastic support of the ring faces: ``k_A int u . v dA``, total stiffness ``stiffness``.

    ``k_A = stiffness / A`` [N/m^3] with ``A`` the area of ``elements``: a rigid translation
    ``U`` meets the force ``-stiffness U``. This is the plane counterpart of the soft
    cylinders glued to both faces of the outer ring in seed 001's NX Nastran model (Fig. 6)
    and of the small nodal springs of its ring-beam model (section 2.5).
    """
    basis = cell_basis(mesh, elements)

    @skfem.BilinearForm
    def mass(u, v, _):
        return u[0] * v[0] + u[1] * v[1]

    @skfem.Functional
    def area(_):
        return 1.0

    k_area = stiffness / float(area.assemble(basis))
    return sp.csr_matrix(k_area * mass.assemble(basis))


def housing_support(mesh: skfem.MeshQuad2, facets: IntArray, stiffness: float,
                    housing_radius: float) -> sp.csr_matrix:
    """Winkler housing on the outer surface, radial and tangential, total ``stiffness`` [N/m].

    Per unit area ``k = stiffness / (pi R_h b)`` in both directions, i.e.
    ``b k int u . v ds`` on the circle ``r = R_h``; a rigid translation meets
    ``-stiffness U``.
    """
    basis = facet_basis(mesh, facets)

    @skfem.BilinearForm
    def winkler(u, v, _):
        return u[0] * v[0] + u[1] * v[1]

    return sp.csr_matrix(stiffness / (math.pi * housing_radius) * winkler.assemble(basis))


def ring_mean(mesh: skfem.MeshQuad2, elements: IntArray) -> sp.csr_matrix:
    """Area-mean operator of the displacement over ``elements``, shape ``(n_dofs, 2)``.

    ``ring_mean(...).T @ U`` is the mean ``(u_x, u_y)`` [m] of the ring: its centre
    displacement in the sense of a rigid-body fit.
    """
    basis = cell_basis(mesh, elements)
    columns = []
    for k in range(2):
        @skfem.LinearForm
        def component(v, _, k=k):
            return v[k]
        columns.append(component.assemble(basis))

    @skfem.Functional
    def area(_):
        return 1.0

    return sp.csr_matrix(np.stack(columns, axis=1) / float(area.assemble(basis)))
