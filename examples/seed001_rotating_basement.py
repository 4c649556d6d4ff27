"""Seed 001 section 3.2: the flexible-ring bearing in a transient about a rotating basement.

In the seed (Fig 7a) the bearing of section 3.1 (``g = -40 um``, flexible rings) has its
outer ring B on a rigid link of length ``l = 1 m`` that turns about a basement C at
``w_C = 50 rad/s``; a 2 kg mass sits on the inner ring A, which turns at
``w_A = 12000 rpm + w_C``. Both speeds ramp up linearly (Fig 7b) and the problem is solved
with an implicit Newmark scheme. The centrifugal load on the mass, ``m l w_C^2 = 5000 N``,
equals the static load of section 3.1, so each roller's force must swing between the
largest and smallest loads of the quasi-static distribution as it travels round (Fig 7c).

rotorsim solves the same problem in the frame that turns with the link, where the outer
ring is fixed and the mass feels the centrifugal load ``m l w_C(t)^2`` along the link and
the Euler load ``-m l w_C'(t)`` across it (the Coriolis force ``2 m w_C x v`` on the
micrometre motion of the ring, below 1 N, is left out); the inner ring turns at the relative
speed ``w_A - w_C`` = 12000 rpm and the cage with it (kinematic cage). The node of the mass
is an inner ring with small rotary inertia; its axial and torsional DOFs are held, as the
seed's bearing carries no axial load. The bearing model has no damping, so a radial damper
of 2000 N s/m (2 % of critical for the 2 kg mass on the ~1e9 N/m preloaded bearing) stands
for the structural damping the seed does not specify; without it the step in the Euler
load at the end of the ramp leaves an undamped free vibration of about 5 % of the load.

Run: ``python examples/seed001_rotating_basement.py [--fast] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from examples.seed001_flexible_rings import SPEED, seed_bearing  # noqa: E402
from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium  # noqa: E402

MASS, LINK, OMEGA_C = 2.0, 1.0, 50.0  # kg, m, rad/s (seed section 3.2)
DAMPER = 2000.0  # N s/m
CLEARANCE = -40e-6


def bearing() -> Any:
    """The section 3.1 bearing with a rotating (kinematic) cage."""
    return replace(seed_bearing(CLEARANCE), cage="rotating")


def model() -> rs.Rotor:
    ghost = rs.Material(name="placeholder", E=1.0, G_s=0.4, rho=1e-9)
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.05, material=ghost)]
    ring = rs.DiskElement(n=0, m=MASS, Id=1e-3, Ip=2e-3)
    element = rs.FlexibleRingBearingElement(bearing(), n=0, tag="seed001")
    damper = rs.BearingElement(n=0, kxx=0.0, cxx=DAMPER, cyy=DAMPER, tag="damper")
    fixed = [(0, "uz"), (0, "rz"), *((1, d) for d in rs.DOF_NAMES)]
    return rs.Rotor(shaft, [ring], [element, damper], fixed=fixed, tag="rotating basement")


def run(ramp: float, hold: float, dt: float) -> rs.TransientResult:
    """Both speeds ramp linearly over ``ramp`` [s], then hold for ``hold`` [s]."""
    r = model()
    system = rs.assemble(r)
    ix, iy = system.dofs_of(0, ("ux", "uy"))
    slope = OMEGA_C / ramp

    def basement_loads(t: float) -> np.ndarray:
        w = OMEGA_C * min(t / ramp, 1.0)
        f = np.zeros(system.n_free)
        f[ix] = MASS * LINK * w * w                               # centrifugal, along the link
        f[iy] = -MASS * LINK * (slope if t < ramp else 0.0)       # Euler, across it
        return f

    return rs.transient(r, ramp + hold, dt, speed=rs.LinearSpeed(0.0, SPEED, 0.0, ramp),
                        excitation=rs.Excitation(forces=basement_loads, gravity=None), nodes=[0])


def roller_history(res: rs.TransientResult, roller: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Inner-contact load of one roller at every sample [N], and its angle [rad]."""
    b = bearing()
    delta = res.node_displacement(0)[:, :5]
    psi = b.element_angles(res.angle)
    state = b.state(delta, psi, speed=res.speed)
    return state.element_load[:, roller], np.mod(psi[:, roller], 2 * math.pi)


def quasi_static() -> dict[str, float]:
    """Largest and smallest roller loads of the section 3.1 distribution (rotating cage,
    sampled over one roller pitch)."""
    b = bearing()
    loads = []
    for phi in np.linspace(0.0, 2 * math.pi / (b.n_rollers * b.kappa), 9):
        eq = bearing_equilibrium(b, (MASS * LINK * OMEGA_C ** 2, 0, 0, 0, 0), phi=phi)
        loads.append(eq.element_load)
    arr = np.concatenate(loads)
    return {"max": float(arr.max()), "min": float(arr.min())}


def main(fast: bool = False, out: Path | str | None = None) -> dict[str, Any]:
    ramp, hold, dt = (0.01, 0.012, 4e-5) if fast else (0.05, 0.03, 1e-5)
    res = run(ramp, hold, dt)
    load, _ = roller_history(res)
    steady = res.t >= ramp + 0.25 * hold
    qs = quasi_static()
    report = {"steps": int(res.stats["steps"]), "wall_time": float(res.stats["wall_time"]),
              "roller 1 max [N]": float(load[steady].max()),
              "roller 1 min [N]": float(load[steady].min()),
              "quasi-static max [N]": qs["max"], "quasi-static min [N]": qs["min"],
              "bearing Fx at the end [N]": float(res.bearing_loads[-1, 0, 0])}
    folder = Path(out) if out is not None else ROOT / "docs" / "figures" / "seed001"
    report["figure"] = str(_figure(res, load, qs, ramp, folder))
    return report


def _figure(res: rs.TransientResult, load: np.ndarray, qs: dict[str, float], ramp: float,
            folder: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(res.t * 1e3, res.speed * 30 / math.pi, label="inner ring, relative [rpm]")
    ax1.plot(res.t * 1e3, OMEGA_C * np.minimum(res.t / ramp, 1) * 30 / math.pi * 20,
             label="basement x 20 [rpm]")
    ax1.set_ylabel("speed [rpm]")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    ax2.plot(res.t * 1e3, load, lw=0.8, label="roller 1, inner contact")
    for key, style in (("max", "--"), ("min", ":")):
        ax2.axhline(qs[key], color="k", ls=style, lw=0.8, label=f"quasi-static {key}")
    ax2.set_xlabel("time [ms]")
    ax2.set_ylabel("Q_i [N]")
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    fig.suptitle("Seed 001 Fig 7: bearing with flexible rings about a rotating basement")
    fig.tight_layout()
    path = folder / "fig7_rotating_basement.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args()
    import json

    print(json.dumps(main(args.fast, args.out), indent=2))
