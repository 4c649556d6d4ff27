"""Structured polar meshes of the two bearing rings (quadratic quadrilaterals, scikit-fem).

Each ring is an annulus meshed on a tensor grid in ``(r, theta)`` and mapped to ``(x, y)``
by ``x = r cos theta, y = r sin theta``. The elements are 9-node quadrilaterals
(:class:`skfem.MeshQuad2`): the mid-side and centre nodes are placed on the polar grid
(half steps in ``r`` and ``theta``), so the curved edges are quadratic interpolations of
the circles (isoparametric mapping). The grid is periodic in ``theta`` (no seam: the last
element column shares the nodes of the first).

Refinement: the angular grid is uniform and fine over a core ``|theta - psi_j| <= beta``
around every roller angle ``psi_j`` (where the contact load is spread, see
:mod:`~rotorsim.verification.ring_forms`), and grows geometrically towards the middle of
the gap between rollers; the radial grid is fine at the raceway and grows towards the bore
(inner ring) or the housing surface (outer ring).

Both rings live in one mesh (two disjoint annuli); :attr:`RingMesh.ring` gives the ring of
every element (0 inner, 1 outer) and :attr:`RingMesh.facets` the facet indices of the four
circles ``"bore"``, ``"inner_raceway"``, ``"outer_raceway"``, ``"housing"``.

References
----------
Seed 001 section 3.1 (bearing geometry ``R_s, R_p, R_b, R_h, b``; NX Nastran model of
Fig. 6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import skfem
from numpy.typing import NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

BOUNDARIES = ("bore", "inner_raceway", "outer_raceway", "housing")
"""Names of the four circles of the two rings, from the inside out."""


def graded_sizes(length: float, first: float, largest: float, growth: float) -> FloatArray:
    """Cell sizes that start at ``first``, grow by ``growth`` up to ``largest`` and fill ``length``.

    The sizes are generated until they reach ``length`` and then scaled so that they sum to
    it exactly (the first one may therefore be a little smaller than ``first``).

    Parameters
    ----------
    length, first, largest : float
        Interval length, first and largest cell size (any unit, the same for all).
    growth : float
        Ratio of neighbouring sizes, ``>= 1``.

    Examples
    --------
    >>> graded_sizes(7.0, 1.0, 2.0, 2.0).round(6).tolist()
    [1.0, 2.0, 2.0, 2.0]
    """
    if not (length > 0.0 and first > 0.0 and largest >= first and growth >= 1.0):
        raise ModelError(f"graded sizes need length, first > 0, largest >= first and growth "
                         f">= 1, got {length}, {first}, {largest}, {growth}", "graded_sizes")
    sizes = [first]
    while sum(sizes) < length * (1.0 - 1e-12):
        sizes.append(min(sizes[-1] * growth, largest))
    out = np.asarray(sizes)
    if len(out) > 1 and out.sum() - length > 0.5 * out[-1]:
        out = out[:-1]  # drop a last cell that would mostly stick out; stretch the rest
    return np.asarray(out * (length / out.sum()))


def angular_grid(n_rollers: int, psi0: float, core_half_angle: float, fine_angle: float,
                 coarse_angle: float, growth: float) -> FloatArray:
    """Vertex angles [rad] of the ring grid, fine around every roller angle.

    Roller ``j`` sits at ``psi_j = psi0 + 2 pi j / Z``. Around it, ``|theta - psi_j| <=
    core_half_angle`` is split into cells of at most ``fine_angle`` (an even number, so that
    ``psi_j`` is a vertex); from there to the middle of the gap the cells grow by ``growth``
    up to ``coarse_angle``.

    Returns
    -------
    array (N_theta,)
        Increasing angles in ``[psi0 - pi/Z, psi0 - pi/Z + 2 pi)``.

    Examples
    --------
    >>> th = angular_grid(4, 0.0, 0.1, 0.05, 0.5, 1.5)
    >>> th.size, bool(np.isclose(th, 0.0).any())
    (48, True)
    """
    half_gap = math.pi / n_rollers
    if not 0.0 < core_half_angle < half_gap:
        raise ModelError(f"the refined core +-{core_half_angle:.4g} rad around a roller must "
                         f"be smaller than half the roller spacing {half_gap:.4g} rad",
                         "angular_grid")
    n_half = max(1, math.ceil(core_half_angle / fine_angle - 1e-9))
    core = np.full(n_half, core_half_angle / n_half)
    outer = graded_sizes(half_gap - core_half_angle, core[-1] * growth,
                         max(coarse_angle, core[-1] * growth), growth)
    half = np.concatenate([core, outer])  # from psi_j to the middle of the gap
    sector = np.concatenate([half[::-1], half])  # one roller sector, centred on psi_j
    cells = np.tile(sector, n_rollers)
    vertices = psi0 - half_gap + np.concatenate([[0.0], np.cumsum(cells)[:-1]])
    return np.asarray(vertices)


def radial_grid(r_raceway: float, r_far: float, first: float, largest: float,
                growth: float) -> FloatArray:
    """Vertex radii [m] of one ring, fine at the raceway, increasing order.

    Examples
    --------
    >>> radial_grid(10.0, 4.0, 1.0, 3.0, 2.0).round(6).tolist()
    [4.0, 7.0, 9.0, 10.0]
    """
    sizes = graded_sizes(abs(r_raceway - r_far), first, largest, growth)
    steps = np.concatenate([[0.0], np.cumsum(sizes)])
    radii = r_raceway + math.copysign(1.0, r_far - r_raceway) * steps
    radii[-1] = r_far
    return np.asarray(np.sort(radii))


def annulus_nodes(radii: FloatArray, theta: FloatArray) -> tuple[FloatArray, IntArray]:
    """Nodes ``(2, N)`` [m] and 9-node connectivity ``(9, n_elements)`` of one annulus.

    The nodes are the polar grid at half steps, ``2 n_r + 1`` radii times ``2 n_theta``
    angles (periodic); the connectivity lists the four vertices counter-clockwise, the
    mid-side nodes of the edges 0-1, 1-2, 2-3, 3-0 and the centre (the local order of
    :class:`skfem.ElementQuad2` and of VTK's biquadratic quad).
    """
    r_half = np.empty(2 * radii.size - 1)
    r_half[0::2], r_half[1::2] = radii, 0.5 * (radii[:-1] + radii[1:])
    closed = np.concatenate([theta, [theta[0] + 2.0 * math.pi]])
    t_half = np.empty(2 * theta.size)
    t_half[0::2], t_half[1::2] = theta, 0.5 * (closed[:-1] + closed[1:])
    n_t = t_half.size
    rr, tt = np.meshgrid(r_half, t_half, indexing="ij")
    points = np.stack([(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel()])
    ii, jj = np.meshgrid(np.arange(radii.size - 1), np.arange(theta.size), indexing="ij")
    i, j = 2 * ii.ravel(), 2 * jj.ravel()

    def node(di: int, dj: int) -> IntArray:
        return np.asarray((i + di) * n_t + (j + dj) % n_t)

    t9 = np.stack([node(0, 0), node(2, 0), node(2, 2), node(0, 2),
                   node(1, 0), node(2, 1), node(1, 2), node(0, 1), node(1, 1)])
    return points, t9


@dataclass(frozen=True, eq=False)
class RingMesh:
    """Mesh of the two rings and its named parts.

    Attributes
    ----------
    mesh : skfem.MeshQuad2
        Both annuli.
    ring : int array (n_elements,)
        0 for the inner ring, 1 for the outer ring.
    radii : dict
        ``{"bore": R_s, "inner_raceway": R_p - R_b, "outer_raceway": R_p + R_b,
        "housing": R_h}`` [m].
    facets : dict
        Facet indices of each circle of :data:`BOUNDARIES`.
    theta : array (N_theta,)
        Vertex angles of the grid [rad].
    """

    mesh: skfem.MeshQuad2
    ring: IntArray
    radii: dict[str, float]
    facets: dict[str, IntArray]
    theta: FloatArray

    @property
    def n_nodes(self) -> int:
        """Number of nodes (vertices, mid-side and centre nodes)."""
        return int(self.mesh.doflocs.shape[1])


def bearing_rings_mesh(radii: dict[str, float], theta: FloatArray, inner_radii: FloatArray,
                       outer_radii: FloatArray) -> RingMesh:
    """Mesh both rings on the angular grid ``theta`` and the radial grids of each ring.

    Parameters
    ----------
    radii : dict
        The four radii of :data:`BOUNDARIES` [m].
    theta : array (N_theta,)
        Vertex angles [rad] (:func:`angular_grid`).
    inner_radii, outer_radii : array
        Vertex radii of each ring [m] (:func:`radial_grid`), from bore to inner raceway and
        from outer raceway to housing.

    Examples
    --------
    >>> th = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    >>> rm = bearing_rings_mesh({"bore": 1.0, "inner_raceway": 1.5, "outer_raceway": 2.0,
    ...                          "housing": 2.5}, th, np.array([1.0, 1.5]),
    ...                         np.array([2.0, 2.5]))
    >>> rm.mesh.nelements, [rm.facets[k].size for k in BOUNDARIES]
    (32, [16, 16, 16, 16])
    """
    p_in, t_in = annulus_nodes(inner_radii, theta)
    p_out, t_out = annulus_nodes(outer_radii, theta)
    points = np.hstack([p_in, p_out])
    t9 = np.hstack([t_in, t_out + p_in.shape[1]])
    mesh = skfem.MeshQuad2(points, t9)
    ring = np.concatenate([np.zeros(t_in.shape[1], dtype=np.int64),
                           np.ones(t_out.shape[1], dtype=np.int64)])
    vertex_radius = np.hypot(*mesh.p)
    facets = {}
    for name in BOUNDARIES:
        on = np.abs(vertex_radius - radii[name]) <= 1e-9 * radii[name]
        facets[name] = np.nonzero(on[mesh.facets].all(axis=0))[0]
        if facets[name].size != theta.size:
            raise ModelError(f"found {facets[name].size} facets on the {name} circle, "
                             f"expected {theta.size}", "bearing_rings_mesh")
    return RingMesh(mesh, ring, dict(radii), facets, np.asarray(theta, dtype=float))
