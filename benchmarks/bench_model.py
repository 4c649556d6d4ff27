"""The benchmark rotor as a neutral, JSON-able description, and its rotorsim builder.

The same description is handed (as JSON) to ``ross_side.py``, which builds the identical rotor
in ROSS, so both codes see exactly the same element lengths, diameters, disks and bearings.

The rotor is a 1.8 m steel shaft with four diameter steps and a hollow middle section,
three disks made from their geometry and two anisotropic, damped bearings:

==============  ===========  ==========  ==========
z range [m]     outer d [m]  bore [m]    role
==============  ===========  ==========  ==========
0.00 - 0.18     0.070        0           journal, bearing A at z = 0.09
0.18 - 0.45     0.100        0
0.45 - 1.35     0.130        0.040       disks at z = 0.54, 0.90, 1.26
1.35 - 1.62     0.100        0
1.62 - 1.80     0.070        0           journal, bearing B at z = 1.71
==============  ===========  ==========  ==========

The shaft is meshed in ``n_elements`` equal elements; each takes the section at its midpoint,
so for multiples of 100 elements the steps fall exactly on element boundaries.
"""

from __future__ import annotations

import math
from typing import Any

SHAFT_LENGTH = 1.8
"""Shaft length [m]."""

STEEL = {"name": "steel", "E": 211e9, "G_s": 81.2e9, "rho": 7810.0}
"""Steel of Friswell et al. (2010): E [Pa], G_s [Pa], rho [kg/m^3]."""

SECTIONS = (
    # (z_start, z_end, inner diameter, outer diameter) [m]
    (0.00, 0.18, 0.000, 0.070),
    (0.18, 0.45, 0.000, 0.100),
    (0.45, 1.35, 0.040, 0.130),
    (1.35, 1.62, 0.000, 0.100),
    (1.62, 1.80, 0.000, 0.070),
)

DISKS = (
    # (z, width, outer diameter) [m]; the bore is the local shaft diameter
    (0.54, 0.06, 0.40),
    (0.90, 0.08, 0.50),
    (1.26, 0.06, 0.40),
)

BEARINGS = (
    # z [m] and coefficients: kxx != kyy (anisotropic), damped, with an axial stiffness
    (0.09, {"kxx": 8.0e7, "kyy": 5.0e7, "cxx": 6.0e3, "cyy": 4.0e3, "kzz": 5.0e7, "czz": 1.0e3}),
    (1.71, {"kxx": 7.0e7, "kyy": 4.5e7, "cxx": 5.0e3, "cyy": 3.5e3, "kzz": 0.0, "czz": 0.0}),
)

UNBALANCE = ((0.90, 2.0e-4, 0.0), (0.54, 1.0e-4, math.pi / 2))
"""Unbalances (z [m], magnitude [kg m], phase [rad]) at the middle and first disk."""


def _section_at(z: float) -> tuple[float, float]:
    for z0, z1, inner, outer in SECTIONS:
        if z0 <= z < z1:
            return inner, outer
    return SECTIONS[-1][2], SECTIONS[-1][3]


def node_at(z: float, n_elements: int) -> int:
    """Shaft node nearest the axial position ``z`` [m] for a mesh of ``n_elements``."""
    return round(z / (SHAFT_LENGTH / n_elements))


def benchmark_description(n_elements: int = 100) -> dict[str, Any]:
    """JSON-able description of the benchmark rotor meshed in ``n_elements`` shaft elements.

    Parameters
    ----------
    n_elements : int
        Number of equal shaft elements (>= 20).

    Returns
    -------
    dict
        ``material`` (E, G_s, rho), ``shaft`` (per element L, idl, odl [m]), ``disks``
        (node, width, i_d, o_d [m]), ``bearings`` (node and k [N/m], c [N s/m]),
        ``unbalance`` (node, magnitude [kg m], phase [rad]) and ``n_dof`` (6 per node).
    """
    if n_elements < 20:
        raise ValueError(f"n_elements must be >= 20, got {n_elements}")
    length = SHAFT_LENGTH / n_elements
    shaft = []
    for i in range(n_elements):
        inner, outer = _section_at((i + 0.5) * length)
        shaft.append({"L": length, "idl": inner, "odl": outer})
    disks = []
    for z, width, outer in DISKS:
        n = node_at(z, n_elements)
        disks.append({"n": n, "width": width, "i_d": _section_at(z)[1], "o_d": outer})
    bearings = [{"n": node_at(z, n_elements), **coef} for z, coef in BEARINGS]
    unbalance = [
        {"n": node_at(z, n_elements), "magnitude": m, "phase": p} for z, m, p in UNBALANCE
    ]
    return {
        "name": f"bench-{n_elements}",
        "material": dict(STEEL),
        "shaft": shaft,
        "disks": disks,
        "bearings": bearings,
        "unbalance": unbalance,
        "n_dof": 6 * (n_elements + 1),
    }


def build_rotorsim(description: dict[str, Any]) -> Any:
    """Build the rotorsim :class:`~rotorsim.model.rotor.Rotor` of ``description``.

    Shaft elements use Timoshenko beams with shear (Cowper coefficient), rotary inertia and
    gyroscopic terms; disks come from their geometry; bearings connect shaft nodes to ground.
    """
    from rotorsim.elements.disk import DiskElement
    from rotorsim.elements.linear_bearing import BearingElement
    from rotorsim.elements.shaft import ShaftElement
    from rotorsim.model.material import Material
    from rotorsim.model.rotor import Rotor

    mat = Material(**description["material"])
    shaft = [
        ShaftElement(L=el["L"], idl=el["idl"], odl=el["odl"], material=mat,
                     shear_effects=True, rotary_inertia=True, gyroscopic=True)
        for el in description["shaft"]
    ]
    disks = [
        DiskElement.from_geometry(d["n"], mat, width=d["width"], i_d=d["i_d"], o_d=d["o_d"])
        for d in description["disks"]
    ]
    bearings = [
        BearingElement(n=b["n"], kxx=b["kxx"], kyy=b["kyy"], cxx=b["cxx"], cyy=b["cyy"],
                       kzz=b["kzz"], czz=b["czz"])
        for b in description["bearings"]
    ]
    return Rotor(shaft, disks, bearings, tag=description["name"])


def unbalance_list(description: dict[str, Any]) -> list[tuple[int, float, float]]:
    """Unbalances as ``(node, magnitude [kg m], phase [rad])`` tuples (rotorsim's form)."""
    return [(u["n"], u["magnitude"], u["phase"]) for u in description["unbalance"]]
