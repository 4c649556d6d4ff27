"""Roller edge effect (issue 18 item 7): the numbers of docs/validation.md and the cost.

Run: ``python benchmarks/bench_roller_edge.py`` (about 30 s). Prints (a) the Hertz
recovery of a long line contact away from its ends, (b) the edge peak of a straight
roller under slice refinement and the profiles that remove it, (c) the half-space approach
of crowned rollers against the ISO/TS 16281 (Palmgren) law, (d) the bearing's 1-D slice
model against the 2-D half-space solution, and (e) the cost per evaluation.
"""

from __future__ import annotations

import time

import numpy as np

import rotorsim as rs
from rotorsim.elements.rolling.roller.half_space import hertz_line
from rotorsim.elements.rolling.roller.profile import CircularCrown, LogarithmicProfile
from rotorsim.elements.rolling.roller.slice_influence import influence_slice_loads

E_STAR = 1.13e11
R, L, Q = 0.005, 0.02, 10_000.0


def hertz_recovery() -> None:
    print("(a) long straight contact, L/b = 119, mid slice against Hertz of its line load")
    for k, m in ((30, 16), (40, 24), (60, 32)):
        c = rs.HalfSpaceLineContact.for_load(Q, L, R, E_STAR, n_slices=k, n_strips=m)
        s = c.solve_load(Q)
        p0, b = hertz_line(float(s.line_load[k // 2]), R, E_STAR)
        p = s.pressure[k // 2]
        slope, icpt = np.polyfit(c.x[p > 0] ** 2, p[p > 0] ** 2, 1)
        print(f"  K={k:3d} M={m:3d}: p0 error {np.sqrt(icpt) / p0 - 1:+.2e}, "
              f"b error {np.sqrt(-icpt / slope) / b - 1:+.2e}, "
              f"mid line load / mean {s.line_load[k // 2] / (Q / L):.4f}")


def edge_peaks() -> None:
    p_mean = hertz_line(Q / L, R, E_STAR)[0]
    print(f"(b) peak pressure / Hertz p0 of Q/L = {p_mean / 1e9:.3f} GPa")
    profiles = {"straight": None,
                "Lundberg (Q)": LogarithmicProfile.lundberg(Q, L, 2 * E_STAR),
                "Johns-Gohar (Q)": LogarithmicProfile.johns_gohar(Q, L, 2 * E_STAR, R),
                "flat + radiused ends (5 um over 4 mm)": CircularCrown(5e-6, 4e-3),
                "full circular crown (10 um)": CircularCrown(10e-6)}
    for name, prof in profiles.items():
        row = []
        for k in (20, 40, 80):
            s = rs.HalfSpaceLineContact.for_load(Q, L, R, E_STAR, prof, n_slices=k,
                                                 n_strips=12).solve_load(Q)
            row.append(f"K={k}: end {s.peak[0] / p_mean:.3f} max {s.peak.max() / p_mean:.3f}")
        print(f"  {name:40s} " + "; ".join(row))


def approach_vs_iso() -> None:
    print("(c) approach inner + outer [um] against ISO/TS 16281 (c_L = 35948 L^(8/9))")
    d, length, dm = 0.012, 0.012, 0.085
    radii = (0.5 * d * (1 - d / dm), 0.5 * d * (1 + d / dm))
    for name, prof in (("Lundberg 5 kN", LogarithmicProfile.lundberg(5e3, length, 2 * E_STAR)),
                       ("circular 5 um / 3 mm", CircularCrown(5e-6, 3e-3))):
        for load in (1e3, 2.5e3, 5e3, 1e4):
            hs = sum(rs.HalfSpaceLineContact.for_load(load, length, r, E_STAR, prof,
                                                      n_slices=40, n_strips=16)
                     .solve_load(load).approach for r in radii)
            iso = (load / (35948 * 12 ** (8 / 9))) ** 0.9 * 1e-3
            print(f"  {name:22s} Q={load:7.0f} N: half-space {hs * 1e6:6.2f}, ISO "
                  f"{iso * 1e6:6.2f}, ratio {hs / iso:.3f}")


def one_d_vs_two_d() -> None:
    print("(d) bearing 1-D slice model against the 2-D half-space (normalised shapes)")
    for name, prof in (("straight", None),
                       ("Lundberg", LogarithmicProfile.lundberg(Q, L, 2 * E_STAR)),
                       ("circular 10 um / 4 mm", CircularCrown(10e-6, 4e-3))):
        for k in (20, 40):
            c = rs.HalfSpaceLineContact.for_load(Q, L, R, E_STAR, prof, n_slices=k,
                                                 n_strips=14)
            s = c.solve_load(Q)
            drop = c.profile.drop(c.y / L, L)
            q1 = influence_slice_loads((s.approach - drop)[None], 1e9, 10 / 9, L, (R,),
                                       E_STAR)[0]
            a, b = q1 / q1.sum(), s.slice_load / s.load
            print(f"  {name:22s} K={k}: end slice / mean 2-D {b[0] * k:.3f}, 1-D "
                  f"{a[0] * k:.3f}; largest difference {np.abs(a - b).max() / b.max():.3f}"
                  " of the largest slice load")


def cost() -> None:
    print("(e) cost per evaluation (one sample = all rollers of the bearing)")
    base = rs.RollerBearing(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
                            effective_length=0.0075, model="slices", n_slices=20)
    infl = rs.RollerBearing(**{**base.__dict__, "slice_model": "influence"})
    n = 400
    rng = np.random.default_rng(0)
    delta = np.column_stack([20e-6 + 2e-6 * rng.standard_normal(n), rng.normal(0, 3e-6, n),
                             np.zeros(n), rng.normal(0, 1e-4, n), rng.normal(0, 1e-4, n)])
    psi = np.tile(base.element_angles(), (n, 1))
    for label, fn in (("state (force + tangent), independent", lambda: base.state(delta, psi)),
                      ("slice_loads, independent", lambda: base.slice_loads(delta, psi)),
                      ("slice_loads, influence", lambda: infl.slice_loads(delta, psi))):
        fn()
        t = time.perf_counter()
        fn()
        print(f"  {label:40s} {(time.perf_counter() - t) / n * 1e6:9.1f} us per sample")
    for k, m in ((20, 12), (40, 12), (80, 16)):
        c = rs.HalfSpaceLineContact.for_load(Q, L, R, E_STAR, n_slices=k, n_strips=m)
        t = time.perf_counter()
        _ = c.compliance
        t_build = time.perf_counter() - t
        t = time.perf_counter()
        s = c.solve_load(Q)
        print(f"  2-D K={k} M={m}: matrix {t_build * 1e3:7.1f} ms, solve "
              f"{(time.perf_counter() - t) * 1e3:7.1f} ms ({s.iterations} active-set steps)")


if __name__ == "__main__":
    hertz_recovery()
    edge_peaks()
    approach_vs_iso()
    one_d_vs_two_d()
    cost()
