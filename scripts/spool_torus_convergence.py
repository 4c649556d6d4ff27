"""Two spools on the torus: convergence of the box against ``rs.transient`` (issue 17,
validation case 41).

The machine of ``tests/analyses/test_quasi_periodic_spools.py``: an LP disk on a 9-ball
bearing with 10 um clearance (cages held, gravity), a counter-rotating HP disk at
``r = -1.3`` on springs, joined by a 2e5 N/m inter-shaft link, both unbalanced, at
``W = 300`` rad/s. For each box ``(H, H)`` the torus is computed, ``rs.transient`` (rtol
1e-6) is started on it, and the largest deviation over 0.06 s (18 HP revolutions) is
printed as a fraction of each signal's peak-to-peak, with the amplitudes of the two base
tones and the largest combination tone at the LP journal and the CPU time of the torus.

Run ``python scripts/spool_torus_convergence.py`` (about a minute on one core).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import rotorsim as rs

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "analyses"))
from test_quasi_periodic_spools import UNBALANCE, machine

SPEED, T = 300.0, 0.06
SIGNALS = ((0, "ux"), (0, "uy"), (1, "ux"), (1, "uy"))


def main() -> None:
    rotor = machine(rolling=True, link=2e5)
    print("| box | torus CPU [s] | LP ux | LP uy | HP ux | HP uy | LP uy (1,0) [nm] | "
          "(0,1) [nm] | (1,1) [nm] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for H in (3, 6, 8, 10, 12):
        clock = time.process_time()
        point = rs.quasi_periodic_point(rotor, SPEED, unbalance=UNBALANCE, harmonics=(H, H),
                                        truncation="box")
        cpu = time.process_time() - clock
        run = rs.transient(rotor, T, speed=SPEED, unbalance=UNBALANCE,
                           initial=point.state(0.0), rtol=1e-6,
                           output=rs.Output(times=np.linspace(0.0, T, 1201)))
        dev = []
        for node, dof in SIGNALS:
            torus = point.response(run.t, node, dof)
            dev.append(np.abs(run.displacement(node, dof) - torus).max() / np.ptp(torus))
        tones = [point.amplitude(0, "uy", *k) * 1e9 for k in ((1, 0), (0, 1), (1, 1))]
        print(f"| ({H}, {H}) | {cpu:.2f} | " + " | ".join(f"{d:.2g}" for d in dev)
              + " | " + " | ".join(f"{a:.3f}" for a in tones) + " |")


if __name__ == "__main__":
    main()
