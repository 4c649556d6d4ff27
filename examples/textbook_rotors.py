"""Textbook rotors used by the validation tests, the examples and the benchmarks.

Each function returns a :class:`~rotorsim.model.rotor.Rotor` built from the data printed
in the source (SI units). The Friswell rotors use the book's steel (``E = 211 GPa``,
``G = 81.2 GPa``, ``rho = 7810 kg/m^3``), Timoshenko shaft elements with Cowper's shear
coefficient, rotary inertia and gyroscopic effects, and rigid disks built from their
geometry (``Id = Ip/2 + m w^2/12``).

References
----------
Friswell, Penny, Garvey, Lees, *Dynamics of Rotating Machines*, Cambridge University
Press (2010), examples 5.9.1, 5.9.2, 5.9.5 and 5.9.9.

Examples
--------
>>> rotor = friswell_5_9_1()
>>> rotor.n_nodes, round(rotor.length, 3), round(rotor.m_disks, 3)
(7, 1.5, 84.115)
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

FRISWELL_STEEL = Material(name="steel_friswell", E=211e9, G_s=81.2e9, rho=7810.0)
"""Steel of Friswell et al. (2010), chapter 5 examples."""

__all__ = [
    "FRISWELL_STEEL",
    "friswell_5_9_1",
    "friswell_5_9_2",
    "friswell_5_9_5",
    "friswell_5_9_9",
    "friswell_two_disk_rotor",
    "tapered_rotor",
]


def _uniform_shaft(length: float, diameter: float, n_elements: int,
                   material: Material) -> list[ShaftElement]:
    return [ShaftElement(L=length / n_elements, idl=0.0, odl=diameter, material=material)
            for _ in range(n_elements)]


def _node_at(fraction: float, n_elements: int, name: str) -> int:
    """Node number at ``fraction`` of the shaft length for a uniform mesh."""
    node = fraction * n_elements
    if abs(node - round(node)) > 1e-9:
        raise ModelError(
            f"n_elements={n_elements} puts no node at {fraction:.4g} of the length", name
        )
    return round(node)


def friswell_two_disk_rotor(
    kxx: float = 1e6,
    kyy: float | None = None,
    cxx: float = 0.0,
    cyy: float | None = None,
    n_elements: int = 6,
) -> Rotor:
    """The two-disk rotor of Friswell et al. (2010) examples 5.9.1 to 5.9.5.

    A 1.5 m steel shaft of 50 mm diameter with bearings at both ends; disks 70 mm wide
    with a 50 mm bore, of 280 mm outer diameter at 0.5 m and 350 mm at 1.0 m.

    Parameters
    ----------
    kxx, kyy : float
        Bearing stiffness in x and y [N/m]; ``kyy`` defaults to ``kxx``.
    cxx, cyy : float
        Bearing damping in x and y [N s/m]; ``cyy`` defaults to ``cxx``.
    n_elements : int
        Number of equal shaft elements, a multiple of 3 (the book uses 6).

    Returns
    -------
    Rotor
    """
    shaft = _uniform_shaft(1.5, 0.05, n_elements, FRISWELL_STEEL)
    where = "friswell_two_disk_rotor"
    disks = [
        DiskElement.from_geometry(_node_at(1 / 3, n_elements, where), FRISWELL_STEEL,
                                  width=0.07, i_d=0.05, o_d=0.28, tag="disk_280"),
        DiskElement.from_geometry(_node_at(2 / 3, n_elements, where), FRISWELL_STEEL,
                                  width=0.07, i_d=0.05, o_d=0.35, tag="disk_350"),
    ]
    bearings = [BearingElement(n=n, kxx=kxx, kyy=kyy, cxx=cxx, cyy=cyy, tag=f"B{i}")
                for i, n in enumerate((0, n_elements))]
    return Rotor(shaft, disks, bearings, tag="friswell_two_disk")


def friswell_5_9_1(n_elements: int = 6) -> Rotor:
    """Example 5.9.1: isotropic undamped bearings, ``kxx = kyy = 1 MN/m``."""
    return friswell_two_disk_rotor(kxx=1e6, n_elements=n_elements)


def friswell_5_9_2(n_elements: int = 6) -> Rotor:
    """Example 5.9.2: anisotropic undamped bearings, ``kxx = 1 MN/m``, ``kyy = 0.8 MN/m``."""
    return friswell_two_disk_rotor(kxx=1e6, kyy=0.8e6, n_elements=n_elements)


def friswell_5_9_5(n_elements: int = 6) -> Rotor:
    """Example 5.9.5: isotropic damped bearings, ``k = 1 MN/m``, ``c = 3 kN s/m``."""
    return friswell_two_disk_rotor(kxx=1e6, cxx=3e3, n_elements=n_elements)


def friswell_5_9_9(n_elements: int = 6) -> Rotor:
    """Example 5.9.9: overhung rotor.

    A 1.5 m steel shaft of 50 mm diameter on bearings of 10 MN/m (both directions, no
    damping) at 0 and 1.0 m, with a disk (350 mm outer diameter, 50 mm bore, 70 mm wide)
    at the free end, 1.5 m.

    Parameters
    ----------
    n_elements : int
        Number of equal shaft elements, a multiple of 3 (the book uses 6).
    """
    where = "friswell_5_9_9"
    shaft = _uniform_shaft(1.5, 0.05, n_elements, FRISWELL_STEEL)
    disks = [DiskElement.from_geometry(n_elements, FRISWELL_STEEL, width=0.07, i_d=0.05,
                                       o_d=0.35, tag="overhung_disk")]
    bearings = [BearingElement(n=n, kxx=10e6, tag=f"B{i}")
                for i, n in enumerate((0, _node_at(2 / 3, n_elements, where)))]
    return Rotor(shaft, disks, bearings, tag="friswell_overhung")


def tapered_rotor(n_elements: int = 8, shear_effects: bool = True) -> Rotor:
    """A hollow conical shaft with one disk, for the tapered-element validation.

    The shaft is 1.0 m long; its outer diameter falls linearly from 80 mm at z = 0 to
    40 mm at z = 1.0 m, with a constant 20 mm bore, and every element is a linear taper
    (a cone frustum), so the geometry is exact for any ``n_elements``. Bearings of
    ``kxx = kyy = 20 MN/m`` sit at z = 0.125 m and at z = 1.0 m; a steel disk (250 mm
    outer diameter, 50 mm bore, 50 mm wide) sits at z = 0.75 m. This is not a book
    example: it is checked against ROSS on the identical model.

    Parameters
    ----------
    n_elements : int
        Number of equal shaft elements, a multiple of 8.
    shear_effects : bool
        Timoshenko (True) or Euler-Bernoulli (False) shaft elements.
    """
    where = "tapered_rotor"
    edges = np.linspace(0.0, 1.0, n_elements + 1)
    outer = 0.08 - 0.04 * edges
    shaft = [
        ShaftElement(L=float(edges[i + 1] - edges[i]), idl=0.02, odl=float(outer[i]),
                     idr=0.02, odr=float(outer[i + 1]), material=FRISWELL_STEEL,
                     shear_effects=shear_effects)
        for i in range(n_elements)
    ]
    disks = [DiskElement.from_geometry(_node_at(0.75, n_elements, where), FRISWELL_STEEL,
                                       width=0.05, i_d=0.05, o_d=0.25, tag="disk")]
    bearing_nodes: Sequence[int] = (_node_at(0.125, n_elements, where), n_elements)
    bearings = [BearingElement(n=n, kxx=20e6, tag=f"B{i}") for i, n in enumerate(bearing_nodes)]
    return Rotor(shaft, disks, bearings, tag="tapered_rotor")
