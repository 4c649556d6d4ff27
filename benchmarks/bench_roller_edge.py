"""Roller edge effect (issue 18 item 7): the numbers of docs/validation.md and the cost.

Run: ``python benchmarks/bench_roller_edge.py`` (about 30 s). Prints (a) the Hertz
recovery of a long line contact away from its ends, (b) the edge peak of a straight
roller under slice refinement and the profiles that remove it, (c) the half-space approach
of crowned rollers against the ISO/TS 16281 (Palmgren) law, (d) the bearing's 1-D slice
model against the 2-D half-space solution, (e) the cost per evaluation, (f) the roller
load centre of the contact model ``"influence"`` and of strips of each slice's own width
(``own_width_strips``) against the 2-D half-space, (g) its equilibria against
independent slices and (h) its cost against ``model="slices"``.
Run only (f)-(h): ``python benchmarks/bench_roller_edge.py influence`` (about 20 s).
"""

from __future__ import annotations

import dataclasses
import sys
import time

import numpy as np
from scipy.optimize import brentq

import rotorsim as rs
from rotorsim.elements.rolling.roller.half_space import hertz_line
from rotorsim.elements.rolling.roller.influence_model import InfluenceSlices
from rotorsim.elements.rolling.roller.own_width_strips import (
    own_width_slice_loads,
    strip_average_compliance,
)
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    slice_centres,
)
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


def _coupled_centre(k: int, prof, tilt: float) -> float:
    """Load centre e [m] of the coupled slices of ``model="influence"`` (linear; strips of
    the Hertz width of Q/L, strip-averaged) at load Q."""
    xi = slice_centres(k)
    b = hertz_line(Q / L, R, E_STAR)[1]
    model = InfluenceSlices(strip_average_compliance(xi * L, L / k, b, E_STAR), 1.0, xi)
    drop = prof.drop(xi, L)

    def excess(d0: float) -> float:
        return float(model.solve((d0 + tilt * xi * L - drop)[None])[0].sum() - Q)
    d0 = brentq(excess, -1e-3, 1e-3, xtol=1e-16)
    u = model.solve((d0 + tilt * xi * L - drop)[None])[0][0]
    return float(u @ xi) * L / Q


def influence_moments() -> None:
    print("(f) tilted roller at Q: load centre e = M/Q and slice loads (largest difference "
          "over the largest 2-D slice load) against the 2-D half-space: coupled slices of "
          "model='influence' (mean-width strips, strip-averaged), eq 2.29's centre-line "
          "strips, own-width strips (at x = 0 and strip-averaged), independent slices (at "
          "the 2-D approach)")
    for name, prof in (("straight", CircularCrown(0.0)),
                       ("Lundberg", LogarithmicProfile.lundberg(Q, L, 2 * E_STAR)),
                       ("circular 10 um / 4 mm", CircularCrown(10e-6, 4e-3))):
        for tilt in (1e-4, 4e-4):
            for k in (20, 40, 80):
                c = rs.HalfSpaceLineContact.for_load(
                    Q, L, R, E_STAR, None if name == "straight" else prof, n_slices=k,
                    n_strips=12 if k < 80 else 16, width_factor=2.0)
                s = c.solve_load(Q, tilt=tilt)
                xi = slice_centres(k)
                dk = np.maximum(s.approach + tilt * xi * L - prof.drop(xi, L), 0.0)
                e_ind, e_2d = float(dk @ xi) * L / dk.sum(), s.moment / Q
                e_1d = _coupled_centre(k, prof, tilt)
                d = tilt * xi * L - prof.drop(xi, L)
                out = []  # (e / e 2-D, largest load difference / largest 2-D slice load)
                for own, avg in ((False, True), (False, False), (True, False), (True, True)):
                    q, _ = own_width_slice_loads(d, Q, L, (R,), E_STAR, own_width=own,
                                                 averaged=avg)
                    out.append((float(q @ xi) * L / Q / e_2d,
                                np.abs(q - s.slice_load).max() / s.slice_load.max()))
                print(f"  {name:22s} tilt {tilt:.0e} K={k:2d}: e 2-D {e_2d * 1e3:.4f} mm; "
                      f"e / 2-D (loads): coupled {e_1d / e_2d:.3f} ({out[0][1]:.3f}), eq 2.29 "
                      f"{out[1][0]:.3f} ({out[1][1]:.3f}), own width at x = 0 "
                      f"{out[2][0]:.3f} ({out[2][1]:.3f}), own width {out[3][0]:.3f} "
                      f"({out[3][1]:.3f}), independent {e_ind / e_2d:.3f}"
                      f"{' (truncated)' if s.truncated else ''}")


def _bearings() -> tuple[rs.RollerBearing, rs.RollerBearing]:
    base = rs.RollerBearing(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
                            effective_length=0.0075, model="slices", n_slices=20)
    return base, dataclasses.replace(base, model="influence")


def influence_sensitivity() -> None:
    print("(g0) model='influence', 14 x 7.5 mm rollers, K = 20: strip width reference "
          "influence_pressure against the end-slice load (uniform deflection) and the load "
          "centre of a tilted roller (deflection 1 + 1.6 xi, fully loaded)")
    base = _bearings()[1]
    xi = slice_centres(base.n_slices)
    for p_ref in (0.5e9, 1.0e9, 1.5e9, 2.0e9, 4.0e9):
        line = dataclasses.replace(base, influence_pressure=p_ref)._line.influence
        assert line is not None
        q = line.slice_loads(np.ones((1, xi.size)))[0]
        t = line.slice_loads((1.0 + 1.6 * xi)[None])[0]
        print(f"  p_ref {p_ref / 1e9:.1f} GPa: end slice / mean {q[0] / q.mean():.3f}, "
              f"load centre {float(t @ xi) / t.sum():.4f} L")


def influence_equilibria() -> None:
    print("(g) bearing equilibria, model='influence' against 'slices' (14 rollers, K = 20)")
    for crown in (0.0, 4e-6):
        for load in ([8000.0, 0, 0, 0, 0], [8000.0, 0, 0, 8.0, 0], [8000.0, 0, 0, 0, 8.0]):
            res = [rs.bearing_equilibrium(dataclasses.replace(b, profile=CircularCrown(crown)),
                                          load) for b in _bearings()]
            x0, x1 = (r.displacement for r in res)
            k0, k1 = (np.diag(r.stiffness) for r in res)
            tilt = 3 if load[3] else 4
            print(f"  crown {crown * 1e6:.0f} um, load {load}: radial {x0[0] * 1e6:.3f} -> "
                  f"{x1[0] * 1e6:.3f} um ({x1[0] / x0[0] - 1:+.2%}); tilt "
                  f"{x0[tilt] * 1e3:.3f} -> {x1[tilt] * 1e3:.3f} mrad "
                  f"({x1[tilt] / x0[tilt] - 1:+.1%}); tilt stiffness x{k1[tilt] / k0[tilt]:.3f}"
                  if load[3] or load[4] else
                  f"  crown {crown * 1e6:.0f} um, load {load}: radial {x0[0] * 1e6:.3f} -> "
                  f"{x1[0] * 1e6:.3f} um ({x1[0] / x0[0] - 1:+.2%}); tilt stiffness "
                  f"x{k1[4] / k0[4]:.3f}")


def _best(fn, *args, repeat: int = 5) -> float:
    """Best of ``repeat`` wall times [s] of ``fn(*args)`` after one warm-up call."""
    fn(*args)
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn(*args)
        best = min(best, time.perf_counter() - t)
    return best


def _one_at_a_time(bearing, delta, c, s) -> None:
    """50 force-and-tangent calls of one sample each (a transient's evaluations)."""
    for i in range(50):
        bearing._force_stiffness(delta[i:i + 1], c, s)


def influence_cost() -> None:
    print("(h) cost of model='influence' against model='slices' (force + tangent), best of 5")
    rng = np.random.default_rng(0)
    n = 400
    for crown in (0.0, 4e-6):
        base, infl = (dataclasses.replace(b, profile=CircularCrown(crown)) for b in _bearings())
        c, s = np.cos(base.element_angles()), np.sin(base.element_angles())  # (1, Z)
        cs, ss = np.repeat(c, n, axis=0), np.repeat(s, n, axis=0)
        for label, mean in (("heavy (20 um)", 20e-6), ("light (3 um)", 3e-6)):
            delta = np.column_stack([mean * (1 + 0.1 * rng.standard_normal(n)),
                                     rng.normal(0, 0.1 * mean, n), np.zeros(n),
                                     rng.normal(0, 1e-4, n), rng.normal(0, 1e-4, n)])
            t0, t1 = (_best(b._force_stiffness, delta, cs, ss) for b in (base, infl))
            one0, one1 = (_best(_one_at_a_time, b, delta, c, s) / 50 for b in (base, infl))
            print(f"  crown {crown * 1e6:.0f} um, {label}: batch {t0 / n * 1e6:6.1f} -> "
                  f"{t1 / n * 1e6:6.1f} us/sample (x{t1 / t0:.1f}); one sample per call "
                  f"{one0 * 1e6:6.1f} -> {one1 * 1e6:6.1f} us (x{one1 / one0:.1f})")
        load = [8000.0, 0, 0, 8.0, 0]
        e0, e1 = (_best(rs.bearing_equilibrium, b, load) for b in (base, infl))
        print(f"  crown {crown * 1e6:.0f} um: bearing_equilibrium (8 kN, 8 N m) "
              f"{e0 * 1e3:.2f} -> {e1 * 1e3:.2f} ms (x{e1 / e0:.1f})")
    _history_cost()
    times = [_transient_time(b) for b in _bearings()]
    print(f"  transient, rotor on two 4 um crowned bearings, 1000 steps: {times[0]:.2f} -> "
          f"{times[1]:.2f} s (x{times[1] / times[0]:.1f})")


def _history_cost(n: int = 20_000) -> None:
    """CPU time of the lamina damage densities of an ``n``-sample history (the work of
    ``rs.transient_life``): independent slices, the post-processing ``slice_model=
    "influence"`` and the contact model ``"influence"``."""
    from rotorsim.elements.rolling.rating.options import RatingOptions
    from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing

    base, infl = _bearings()
    phi = np.linspace(0.0, 400.0, n)
    delta = np.column_stack([20e-6 + 2e-6 * np.sin(phi), 2e-6 * np.cos(phi), np.zeros(n),
                             1e-4 * np.sin(phi), np.zeros(n)])
    row = []
    for b in (base, dataclasses.replace(base, slice_model="influence"), infl):
        rated = RatedBearing(b, RatingOptions())
        psi = b.element_angles(phi)
        t = time.process_time()
        rated.damage_density(delta, psi)
        row.append(time.process_time() - t)
    print(f"  lamina densities of a {n}-sample history (transient_life's work), CPU: slices "
          f"{row[0]:.2f} s, slice_model='influence' {row[1]:.2f} s, model='influence' "
          f"{row[2]:.2f} s")


def _transient_time(bearing: rs.RollerBearing) -> float:
    """CPU time [s] of a 1000-step transient of a 0.3 m rotor (gravity, 300 rad/s) on two
    copies of ``bearing`` with a 4 um crown and 2 um clearance (light load: 60 N each)."""
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    rb = dataclasses.replace(bearing, profile=CircularCrown(4e-6), radial_clearance=2e-6)
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=steel) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.04, i_d=0.04, o_d=0.2)
    rotor = rs.Rotor(shaft, [disk], [rs.BearingElement(n=n, kxx=0.0, cxx=3000.0, cyy=3000.0)
                                     for n in (0, 2)],
                     nonlinear_elements=[rs.RollingBearing(rb, n=n, tag=f"B{n}")
                                         for n in (0, 2)], fixed=[(1, "uz")])
    t = time.process_time()
    rs.transient(rotor, 0.02, 2e-5, speed=300.0)
    return time.process_time() - t


if __name__ == "__main__":
    if sys.argv[1:] == ["influence"]:
        influence_moments()
        influence_sensitivity()
        influence_equilibria()
        influence_cost()
        raise SystemExit(0)
    hertz_recovery()
    edge_peaks()
    approach_vs_iso()
    one_d_vs_two_d()
    cost()
    influence_moments()
    influence_sensitivity()
    influence_equilibria()
    influence_cost()
