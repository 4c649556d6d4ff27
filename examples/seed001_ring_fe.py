"""The seed 001 bearing with the 2D ring FE model: roller loads, mesh study, sensitivities.

For the bearing of seed 001 section 3.1 at 12000 rpm and at rest, with the diametral
clearances -40 um and +10 um, the example tabulates:

* the largest and smallest roller loads of the flexible-ring FE model
  (:mod:`rotorsim.verification.ring_fe`) and of the rigid-ring model
  (:mod:`~rotorsim.verification.ring_reference`), and their ratio (seed 001 section 3.1:
  with -40 um the rigid rings give loads "2.5 higher");
* the mesh study (three refinements), the effect of the contact patch half-width ``a`` and
  of the outer-ring support (soft faces, Winkler housing, clamped);
* cost: degrees of freedom, Newton iterations, wall time.

Needs scikit-fem (and meshio for ``--vtu``).

Run: ``python examples/seed001_ring_fe.py [--fast] [--vtu DIR]`` (``--fast`` for coarse
meshes, ``--vtu DIR`` to also write the deformed rings).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from rotorsim.verification.ring_fe import (  # noqa: E402
    SEED001_CASE,
    MeshOptions,
    OuterRingSupport,
    export_vtu,
    ring_fe_roller_loads,
)
from rotorsim.verification.ring_reference import rigid_ring_roller_loads  # noqa: E402

CLEARANCES = (-40e-6, 10e-6)
"""Operating diametral clearances of seed 001 section 3.1 [m]."""
THINNER_RING = 14.5e-3
"""Radial thickness of the inner ring (the thinner one) [m]."""


def _case(speed: bool) -> dict[str, Any]:
    case = dict(SEED001_CASE)
    if not speed:
        case["speed"] = 0.0
    return case


def load_table(fast: bool = False, vtu: Path | None = None) -> list[dict[str, Any]]:
    """FE and rigid-ring roller loads for both clearances, at speed and at rest."""
    rows = []
    mesh = MeshOptions(mesh_size=2e-3, max_size=5e-3) if fast else None
    for speed in (True, False):
        for g in CLEARANCES:
            case = _case(speed)
            t0 = time.perf_counter()
            fe = ring_fe_roller_loads(**case, clearance=g, mesh=mesh)
            elapsed = time.perf_counter() - t0
            rigid = rigid_ring_roller_loads(case["Z"], case["R_p"], case["R_b"], case["L"], g,
                                            case["F_x"], rho=case["rho"], speed=case["speed"])
            if vtu is not None:
                rpm = "12000rpm" if speed else "rest"
                export_vtu(fe, vtu / f"seed001_g{g * 1e6:+.0f}um_{rpm}.vtu")
            rows.append({"clearance_um": g * 1e6, "rpm": 12000 if speed else 0,
                         "fe_max": fe.max_roller_load, "fe_min": float(fe.roller_loads.min()),
                         "rigid_max": float(rigid.max()), "rigid_min": float(rigid.min()),
                         "ratio": float(rigid.max()) / fe.max_roller_load,
                         "dofs": fe.summary["n_dofs"], "iterations": fe.iterations,
                         "seconds": elapsed, "F_c": fe.centrifugal_force})
    return rows


def mesh_study(fast: bool = False) -> list[dict[str, Any]]:
    """Largest roller load for mesh sizes ``a/2, a/3, a/6`` (``a/2, a/3`` with ``fast``)."""
    a = 0.25 * THINNER_RING
    divisions = (2, 3) if fast else (2, 3, 6)
    rows = []
    for g in CLEARANCES:
        for k in divisions:
            t0 = time.perf_counter()
            fe = ring_fe_roller_loads(**SEED001_CASE, clearance=g,
                                      mesh=MeshOptions(mesh_size=a / k,
                                                       max_size=THINNER_RING / k))
            rows.append({"clearance_um": g * 1e6, "mesh_size_mm": a / k * 1e3,
                         "dofs": fe.summary["n_dofs"], "fe_max": fe.max_roller_load,
                         "seconds": time.perf_counter() - t0})
    return rows


def sensitivity(fast: bool = False) -> list[dict[str, Any]]:
    """Largest roller load vs. the patch half-width ``a`` and the outer-ring support."""
    max_size = 5e-3 if fast else None
    variants: list[tuple[str, dict[str, Any]]] = [
        (f"a = {a * 1e3:.1f} mm",
         {"mesh": MeshOptions(contact_half_width=a, max_size=max_size)})
        for a in (1e-3, 2e-3, 5e-3)]
    supports = [("faces, 6e5 N/m", OuterRingSupport("faces", 6e5)),
                ("faces, 6e7 N/m", OuterRingSupport("faces", 6e7)),
                ("housing, 6e8 N/m", OuterRingSupport("housing", 6e8)),
                ("clamped", OuterRingSupport("clamped"))]
    variants += [(name, {"mesh": MeshOptions(max_size=max_size), "support": support})
                 for name, support in supports]
    rows = []
    for g in CLEARANCES:
        for name, options in variants:
            fe = ring_fe_roller_loads(**SEED001_CASE, clearance=g, **options)
            rows.append({"clearance_um": g * 1e6, "variant": name,
                         "fe_max": fe.max_roller_load})
    return rows


def main(fast: bool = False, vtu: str | Path | None = None) -> dict[str, list[dict[str, Any]]]:
    """Run the three studies and return their tables.

    Parameters
    ----------
    fast : bool
        Coarse meshes (and two refinements instead of three in the mesh study).
    vtu : path, optional
        Folder for VTU files of the deformed rings (one per load case).

    Returns
    -------
    dict
        ``loads`` (:func:`load_table`), ``mesh_study`` and ``sensitivity``: lists of rows,
        each a dict of column name to value.
    """
    return {"loads": load_table(fast, None if vtu is None else Path(vtu)),
            "mesh_study": mesh_study(fast), "sensitivity": sensitivity(fast)}


def _table(title: str, rows: list[dict[str, Any]]) -> str:
    keys = list(rows[0])
    lines = ["", title, "  ".join(f"{k:>13}" for k in keys)]
    for row in rows:
        lines.append("  ".join(f"{v:13.7g}" if isinstance(v, float) else f"{v!s:>13}"
                               for v in row.values()))
    return "\n".join(lines)


def _report(out: dict[str, list[dict[str, Any]]]) -> str:
    """The tables of the module docstring as text."""
    return "\n".join([
        _table("Roller loads [N] (FE flexible rings vs rigid rings; ratio = rigid max / FE "
               "max)", out["loads"]),
        _table("Mesh study (12000 rpm)", out["mesh_study"]),
        _table("Sensitivity (12000 rpm)", out["sensitivity"])])


def _cli(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse meshes")
    parser.add_argument("--vtu", type=Path, default=None, help="folder for VTU files")
    args = parser.parse_args(argv)
    print(_report(main(args.fast, args.vtu)))
    return 0


if __name__ == "__main__":
    raise SystemExit(_cli())
