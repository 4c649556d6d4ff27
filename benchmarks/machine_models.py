"""Models of the multi-shaft benchmarks (issue 15): two more 100-element rotors for the ROSS
comparison, described like ``bench_model.benchmark_description`` (plain JSON both codes
build from), and a two-spool machine of any size built with ``rs.ShaftLine``.

Rotor "stepped": 1.5 m, seven sections, elements graded finer towards the disks (lengths
from 5 to 25 mm), two overhung disks, soft well-damped bearings.
Rotor "three_bearing": 2.4 m, a hollow middle section, four disks, three bearings with
different damping, elements of two lengths.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from bench_model import STEEL


def _description(name: str, lengths: np.ndarray, sections: list[tuple[float, float, float]],
                 disks: list[tuple[float, float, float]], bearings: list[tuple[float, dict]],
                 unbalance: list[tuple[float, float, float]]) -> dict[str, Any]:
    """``sections``: (z_end, inner d, outer d) [m]; ``disks``: (z, width, outer d) [m];
    ``bearings``: (z, coefficients); ``unbalance``: (z, kg m, rad)."""
    z = np.concatenate([[0.0], np.cumsum(lengths)])
    mid = 0.5 * (z[:-1] + z[1:])

    def section(x: float) -> tuple[float, float]:
        for end, inner, outer in sections:
            if x < end:
                return inner, outer
        return sections[-1][1], sections[-1][2]

    def node(x: float) -> int:
        return int(np.argmin(np.abs(z - x)))

    shaft = [{"L": float(L), "idl": section(m)[0], "odl": section(m)[1]}
             for L, m in zip(lengths, mid, strict=True)]
    zero = {"kxx": 0.0, "kyy": 0.0, "cxx": 0.0, "cyy": 0.0, "kzz": 0.0, "czz": 0.0}
    return {
        "name": name, "material": dict(STEEL), "shaft": shaft,
        "disks": [{"n": node(x), "width": w, "i_d": section(x)[1], "o_d": d}
                  for x, w, d in disks],
        "bearings": [{"n": node(x), **{**zero, **c}} for x, c in bearings],
        "unbalance": [{"n": node(x), "magnitude": m, "phase": p} for x, m, p in unbalance],
        "n_dof": 6 * (len(shaft) + 1),
    }


def stepped_description() -> dict[str, Any]:
    """100 graded elements, 1.5 m, two overhung disks, soft damped bearings."""
    grading = 1.0 + 4.0 * np.abs(np.sin(np.linspace(0.0, 2.0 * np.pi, 100)))  # 1 ... 5
    lengths = 1.5 * grading / grading.sum()
    sections = [(0.12, 0.0, 0.06), (0.30, 0.0, 0.08), (0.55, 0.0, 0.09), (0.95, 0.03, 0.11),
                (1.20, 0.0, 0.09), (1.38, 0.0, 0.08), (1.50, 0.0, 0.06)]
    disks = [(0.03, 0.05, 0.38), (1.47, 0.06, 0.42)]
    bearings = [(0.20, {"kxx": 2.0e7, "kyy": 1.5e7, "cxx": 2.0e4, "cyy": 1.8e4, "kzz": 3e7,
                        "czz": 2e3}),
                (1.30, {"kxx": 2.5e7, "kyy": 1.8e7, "cxx": 1.5e4, "cyy": 1.2e4})]
    return _description("stepped-100", lengths, sections, disks, bearings,
                        [(0.03, 1e-4, 0.0), (1.47, 1e-4, math.pi)])


def three_bearing_description() -> dict[str, Any]:
    """100 elements of two lengths, 2.4 m, four disks, three bearings."""
    lengths = np.where(np.arange(100) % 2 == 0, 0.016, 0.032)
    lengths = 2.4 * lengths / lengths.sum()
    sections = [(0.15, 0.0, 0.075), (0.60, 0.0, 0.110), (1.80, 0.05, 0.140),
                (2.25, 0.0, 0.110), (2.40, 0.0, 0.075)]
    disks = [(0.45, 0.06, 0.45), (0.95, 0.08, 0.55), (1.45, 0.08, 0.55), (1.95, 0.06, 0.45)]
    bearings = [(0.08, {"kxx": 1.2e8, "kyy": 9e7, "cxx": 3e3, "cyy": 3e3, "kzz": 8e7,
                        "czz": 5e2}),
                (1.20, {"kxx": 6e7, "kyy": 6e7, "cxx": 8e3, "cyy": 6e3}),
                (2.32, {"kxx": 1.0e8, "kyy": 7e7, "cxx": 1.2e3, "cyy": 1.0e3})]
    return _description("three-bearing-100", lengths, sections, disks, bearings,
                        [(0.95, 2e-4, 0.0), (1.45, 2e-4, math.pi / 2)])


def two_spool_machine(n_lp: int = 400, n_hp: int = 200, n_casing: int = 230,
                      hp_ratio: float = 1.45) -> Any:
    """An engine-like machine of three lines (LP spool, HP spool at ``hp_ratio`` times the
    LP speed, non-rotating casing on two pedestals), meshed in ``n_lp``, ``n_hp`` and
    ``n_casing`` elements: the layout of ``models/two_spool.toml`` at any size.
    ``(400, 200, 230)`` gives 835 nodes, 5,010 DOFs."""
    import rotorsim as rs

    steel = rs.Material(name="steel", E=205e9, G_s=79e9, rho=7850)
    titanium = rs.Material(name="titanium", E=114e9, G_s=44e9, rho=4430)

    def line(name: str, n: int, length: float, idl: float, odl: float, mat: Any, z0: float,
             ratio: float, gyroscopic: bool = True) -> Any:
        els = [rs.ShaftElement(L=length / n, idl=idl, odl=odl, material=mat,
                               gyroscopic=gyroscopic) for _ in range(n)]
        return rs.ShaftLine(name, els, z0=z0, speed_ratio=ratio)

    lines = [line("LP", n_lp, 1.6, 0.040, 0.060, steel, 0.0, 1.0),
             line("HP", n_hp, 0.8, 0.096, 0.120, titanium, 0.5, hp_ratio),
             line("casing", n_casing, 1.6, 0.590, 0.600, steel, 0.0, 0.0, gyroscopic=False)]
    first = {"LP": 0, "HP": n_lp + 1, "casing": n_lp + n_hp + 2}
    size = {"LP": (n_lp, 1.6, 0.0), "HP": (n_hp, 0.8, 0.5), "casing": (n_casing, 1.6, 0.0)}

    def at(name: str, z: float) -> int:
        n, length, z0 = size[name]
        return first[name] + round((z - z0) / (length / n))

    ped = n_lp + n_hp + n_casing + 3  # the two pedestal nodes follow the line nodes
    disks = [rs.DiskElement(n=at("LP", 0.1), m=40.0, Id=1.2, Ip=2.3, tag="fan"),
             rs.DiskElement(n=at("LP", 1.5), m=25.0, Id=0.45, Ip=0.85, tag="LP_turbine"),
             rs.DiskElement(n=at("HP", 0.6), m=20.0, Id=0.30, Ip=0.55, tag="HP_compressor"),
             rs.DiskElement(n=at("HP", 1.2), m=15.0, Id=0.20, Ip=0.38, tag="HP_turbine")]
    B = rs.BearingElement
    bearings = [
        B(n=at("LP", 0.2), n_link=at("casing", 0.2), kxx=5e7, kzz=1e8, cxx=5e3, tag="LP_front"),
        B(n=at("LP", 1.6), n_link=at("casing", 1.6), kxx=3e7, cxx=1e3, tag="LP_rear"),
        B(n=at("HP", 0.5), n_link=at("casing", 0.5), kxx=1e8, kzz=1e8, cxx=3e3,
          tag="HP_front"),
        B(n=at("HP", 1.3), n_link=at("LP", 1.3), kxx=2e7, cxx=5e2, tag="inter_shaft"),
        B(n=at("casing", 0.2), n_link=ped, kxx=2e8, kzz=2e8, cxx=2e4, tag="casing_front"),
        # kzz here holds the rear pedestal axially (models/two_spool.toml leaves it free: a
        # zero axial eigenvalue that the rigid-body test does not always recognise)
        B(n=at("casing", 1.4), n_link=ped + 1, kxx=2e8, kzz=2e8, cxx=2e4, tag="casing_rear"),
        B(n=ped, kxx=5e8, kzz=5e8, cxx=5e4, tag="pedestal_front_ground"),
        B(n=ped + 1, kxx=5e8, cxx=5e4, tag="pedestal_rear_ground")]
    masses = [rs.PointMass(n=ped, m=60.0, tag="pedestal_front"),
              rs.PointMass(n=ped + 1, m=60.0, tag="pedestal_rear")]
    rotor = rs.Rotor([], disks, bearings, masses, lines=lines, tag="two-spool")
    unbalance = [(at("LP", 0.1), 5e-5, 0.0), (at("HP", 1.2), 2e-5, math.pi / 2)]
    return rotor, unbalance
