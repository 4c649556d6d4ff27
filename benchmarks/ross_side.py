"""ROSS side of the benchmark: runs ONLY inside the ROSS virtualenv, never imports rotorsim.

Usage (done by ``bench_vs_ross.py``)::

    $ROSS_VENV/bin/python benchmarks/ross_side.py request.json result.json

``request.json`` holds ``{"description": <bench_model description>, "warmup": <small
description or null>, "tasks": [...]}``; each task is one of

- ``{"kind": "build"}``: time the construction of the ROSS ``Rotor`` (ROSS assembles its dense
  global matrices there);
- ``{"kind": "matrices", "speed": W, "npz": path}``: write ROSS's global ``M, K, C, G`` (dense,
  all DOFs) to ``path``;
- ``{"kind": "modal", "speed": W, "num_modes": n}``: time ``run_modal``;
- ``{"kind": "campbell", "speeds": [...], "num_modes": n}``: time ``run_campbell``;
- ``{"kind": "unbalance", "speeds": [...], "nodes_out": [...], "max_bytes": b}``: time
  ``run_unbalance_response``; when ROSS's stored transfer matrices would exceed ``max_bytes``
  the speeds are run in consecutive chunks and the times added.

A task may hold ``"repeat": r``: it then runs ``r`` times and the median time is reported.
Every analysis runs on a freshly built rotor (ROSS caches ``run_modal`` and the frequency
response per rotor instance), and the ``warmup`` rotor is analysed once first so that import,
unit-registry and JIT costs are not timed. The result file holds wall and process-CPU times
[s] and results (natural frequencies [rad/s], complex responses [m] as re/im lists).
"""

from __future__ import annotations

import io
import json
import platform
import sys
import time
import warnings
from contextlib import redirect_stdout
from typing import Any

import numpy as np

with redirect_stdout(io.StringIO()):  # ROSS's dependencies print licence notes on import
    import ross as rs

warnings.filterwarnings("ignore")


class Clock:
    """Wall-clock and process CPU time [s] of the code inside ``with Clock() as c:``."""

    def __enter__(self) -> Clock:
        self.wall, self.cpu = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc: object) -> None:
        self.wall = time.perf_counter() - self.wall
        self.cpu = time.process_time() - self.cpu


def build(desc: dict[str, Any]) -> Any:
    """ROSS ``Rotor`` of a bench_model description."""
    m = desc["material"]
    mat = rs.Material(name=m["name"], rho=m["rho"], E=m["E"], G_s=m["G_s"])
    shaft = [
        rs.ShaftElement(L=el["L"], idl=el["idl"], odl=el["odl"], material=mat,
                        shear_effects=True, rotary_inertia=True, gyroscopic=True,
                        shear_method_calc="cowper")
        for el in desc["shaft"]
    ]
    disks = [
        rs.DiskElement.from_geometry(n=d["n"], material=mat, width=d["width"], i_d=d["i_d"],
                                     o_d=d["o_d"])
        for d in desc["disks"]
    ]
    bearings = [
        rs.BearingElement(n=b["n"], kxx=b["kxx"], kyy=b["kyy"], cxx=b["cxx"], cyy=b["cyy"],
                          kzz=b["kzz"], czz=b["czz"])
        for b in desc["bearings"]
    ]
    return rs.Rotor(shaft, disks, bearings)


def _ross_modes(num_modes: int) -> int:
    """``num_modes`` argument of ``run_modal`` giving ``num_modes`` positive frequencies.

    ``run_modal(num_modes=k)`` asks ARPACK for ``2 k`` eigenvalues and keeps ``k // 2``
    frequencies; ``run_campbell`` uses ``k = 2 (frequencies + 2)``, done the same here.
    """
    return 2 * (num_modes + 2)


def task_modal(desc, task):
    rotor = build(desc)
    with Clock() as c:
        res = rotor.run_modal(speed=float(task["speed"]),
                              num_modes=_ross_modes(task["num_modes"]))
    n = task["num_modes"]
    return {"time_s": c.wall, "cpu_s": c.cpu, "wd": res.wd[:n].tolist(), "wn": res.wn[:n].tolist(),
            "log_dec": res.log_dec[:n].tolist()}


def task_campbell(desc, task):
    rotor = build(desc)
    speeds = np.asarray(task["speeds"], dtype=float)
    with Clock() as c:
        res = rotor.run_campbell(speeds, frequencies=int(task["num_modes"]))
    return {"time_s": c.wall, "cpu_s": c.cpu, "wd": np.asarray(res.wd).tolist(),
            "log_dec": np.asarray(res.log_dec).tolist()}


def task_unbalance(desc, task):
    speeds = np.asarray(task["speeds"], dtype=float)
    ndof = desc["n_dof"]
    per_speed = 3 * ndof * ndof * 16  # ROSS stores H, i w H and -w^2 H for every speed
    chunk = max(1, int(task.get("max_bytes", 8e9) // per_speed))
    nodes = [u["n"] for u in desc["unbalance"]]
    mags = [u["magnitude"] for u in desc["unbalance"]]
    phases = [u["phase"] for u in desc["unbalance"]]
    out_dofs = [6 * n + k for n in task["nodes_out"] for k in (0, 1)]
    parts, wall, cpu = [], 0.0, 0.0
    for start in range(0, speeds.size, chunk):
        rotor = build(desc)  # fresh rotor: ROSS caches every frequency response it computes
        with Clock() as c:
            # positional speeds: the keyword is `frequency` in ROSS 2.x, `speed_range` in 3.x
            res = rotor.run_unbalance_response(nodes, mags, phases, speeds[start:start + chunk])
        wall, cpu = wall + c.wall, cpu + c.cpu
        parts.append(np.asarray(res.forced_resp)[out_dofs])
        del res, rotor
    resp = np.concatenate(parts, axis=1)
    return {"time_s": wall, "cpu_s": cpu, "chunks": -(-speeds.size // chunk), "dofs": out_dofs,
            "re": resp.real.tolist(), "im": resp.imag.tolist()}


def task_build(desc, task):
    with Clock() as c:
        rotor = build(desc)
    return {"time_s": c.wall, "cpu_s": c.cpu, "ndof": int(rotor.ndof)}


def task_matrices(desc, task):
    rotor = build(desc)
    w = float(task["speed"])
    np.savez(task["npz"], M=rotor.M(w), K=rotor.K(w), C=rotor.C(w), G=rotor.G())
    return {"npz": task["npz"], "ndof": int(rotor.ndof)}


TASKS = {"build": task_build, "matrices": task_matrices, "modal": task_modal,
         "campbell": task_campbell, "unbalance": task_unbalance}


def repeated(desc: dict[str, Any], task: dict[str, Any]) -> dict[str, Any]:
    """Run ``task`` ``task["repeat"]`` times (default 1); median time, all times, last result."""
    runs = [TASKS[task["kind"]](desc, task) for _ in range(int(task.get("repeat", 1)))]
    out = runs[-1]
    if "time_s" in out:
        times = [r["time_s"] for r in runs]
        out.update(time_s=float(np.median(times)), times_s=times,
                   cpu_s=float(np.median([r["cpu_s"] for r in runs])))
    return out


def warm_up(desc: dict[str, Any]) -> float:
    """Run every analysis once on a small rotor; returns the time spent [s]."""
    t0 = time.perf_counter()
    task_modal(desc, {"speed": 10.0, "num_modes": 4})
    task_campbell(desc, {"speeds": [0.0, 10.0], "num_modes": 4})
    task_unbalance(desc, {"speeds": [10.0, 20.0], "nodes_out": [1]})
    return time.perf_counter() - t0


def main(argv: list[str]) -> int:
    with open(argv[1]) as f:
        request = json.load(f)
    out: dict[str, Any] = {
        "versions": {"ross": rs.__version__, "numpy": np.__version__,
                     "scipy": __import__("scipy").__version__,
                     "python": platform.python_version()},
        "results": [],
    }
    if request.get("warmup"):
        out["warmup_s"] = warm_up(request["warmup"])
    for task in request["tasks"]:
        out["results"].append({"kind": task["kind"], **repeated(request["description"], task)})
    with open(argv[2], "w") as f:
        json.dump(out, f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
