"""Why a linear run-up step keeps two solves with the iteration matrix frozen at a speed node.

One step of the trapezoidal rule (average acceleration) of an undamped gyroscopic rotor is a
linear map of ``(q, v, a)``. With the iteration matrix ``S_0`` factorised at ``W_node`` and
the step taken at ``W``, one Newton solve from ``a_n`` gives ``S_0 a + (W - W_node) (h / 2)
G a_n = rhs``: the gyroscopic increment lags one step. This script prints the spectral radius
of the one-step map, exact and with one or two frozen solves, for the 6-element rotor of
``tests/analyses/transient/test_runup_speed_nodes.py`` (constant bearings, no damping) at
1000 rad/s; and again with bearing stiffnesses tabulated over speed (no damping either)
folded into ``S_0`` at ``W_node``, their change since the node lagging with the gyroscopic
term (``rotorsim/time_integration/folded_tables.py``).

Run: ``.venv/bin/python benchmarks/frozen_speed_stability.py``
"""

from __future__ import annotations

import numpy as np

import rotorsim as rs
from rotorsim.assembly.system import assemble

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def rotor(tabulated: bool = False) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(6)]
    disk = rs.DiskElement.from_geometry(n=3, material=STEEL, width=0.03, i_d=0.04, o_d=0.25)
    coefficients: dict = dict(kxx=2e7, kyy=3e7)
    if tabulated:  # the direct stiffness tables of the test (no damping, no cross terms)
        coefficients = dict(frequency=[0.0, 500.0, 1500.0], kxx=[1e7, 2e7, 3e7],
                            kyy=[2e7, 3e7, 4e7])
    bearings = [rs.BearingElement(n=n, **coefficients) for n in (0, 6)]
    return rs.Rotor(shaft, [disk], bearings)


def spectral_radii(M: np.ndarray, K: np.ndarray, G: np.ndarray, h: float, speed: float,
                   node: float, K_node: np.ndarray | None = None) -> tuple[float, float, float]:
    """Spectral radius of the exact step's map and with one and two frozen solves
    (``K_node``: the stiffness folded into the frozen matrix, if not ``K``)."""
    n = M.shape[0]
    eye, zero = np.eye(n), np.zeros((n, n))
    S = M + h / 2 * speed * G + h * h / 4 * K
    S0 = M + h / 2 * node * G + h * h / 4 * (K if K_node is None else K_node)
    q_base = np.hstack([eye, h * eye, h * h / 4 * eye])
    v_base = np.hstack([zero, eye, h / 2 * eye])
    rhs = -(K @ q_base + speed * G @ v_base)  # S a = rhs x for the state x = (q, v, a)
    exact = np.linalg.solve(S, rhs)
    one = np.hstack([zero, zero, eye]) - np.linalg.solve(S0, S @ np.hstack([zero, zero, eye])
                                                         - rhs)
    two = one - np.linalg.solve(S0, S @ one - rhs)
    radii = []
    for a in (exact, one, two):
        step = np.vstack([q_base + h * h / 4 * a, v_base + h / 2 * a, a])
        radii.append(float(np.max(np.abs(np.linalg.eigvals(step)))))
    return radii[0], radii[1], radii[2]


def main() -> None:
    mats = assemble(rotor()).matrices(0.0)
    M, K, G = (m.toarray() for m in (mats.M, mats.K, mats.G))
    print("| h [us] | W - W_node [rad/s] | exact step | one frozen solve: excess | "
          "two frozen solves: excess |")
    print("|---|---|---|---|---|")
    for h in (1e-5, 5e-5, 2e-4):
        for gap in (0.1, 1.0, 10.0, 100.0):
            exact, one, two = spectral_radii(M, K, G, h, 1000.0, 1000.0 - gap)
            print(f"| {h * 1e6:g} | {gap:g} | {exact:.12f} | {one - exact:.2e} | "
                  f"{two - exact:.1e} |")
    system = assemble(rotor(tabulated=True))
    print("\nStiffness tabulated over speed, folded into S_0 at W_node:\n")
    print("| h [us] | W - W_node [rad/s] | exact step | one frozen solve: excess | "
          "two frozen solves: excess |")
    print("|---|---|---|---|---|")
    at_speed = system.matrices(1000.0)
    M, K, G = (m.toarray() for m in (at_speed.M, at_speed.K, at_speed.G))
    for h in (1e-5, 5e-5, 2e-4):
        for gap in (0.1, 1.0, 10.0, 100.0):
            K_node = system.matrices(1000.0 - gap).K.toarray()
            exact, one, two = spectral_radii(M, K, G, h, 1000.0, 1000.0 - gap, K_node)
            print(f"| {h * 1e6:g} | {gap:g} | {exact:.12f} | {one - exact:.2e} | "
                  f"{two - exact:.1e} |")


if __name__ == "__main__":
    main()
