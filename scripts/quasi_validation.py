"""Quasi-periodic harmonic balance against long integrations in time (validation case 40).

Two rotors with unbalance on ball bearings whose cages turn, so that the response is a
2-torus of the shaft frequency ``W`` and the varying-compliance (VC) frequency
``w2 = Z kappa W``:

* **rigid**: a rigid 1 kg rotor in a 9-ball bearing (2 um radial clearance, 50 N along
  -y, contact damping ``beta_c = 20 us``), whose pitch and ball diameters put the VC order
  at ``Z kappa = 2 + golden ratio = 3.6180``, a noble number (as far from low-order
  fractions as a number can be), with 2e-6 kg m of unbalance;
* **default**: ``models/default.toml`` (the model of ``make run``) with its 0.2 g m
  unbalance; its first modes have about 0.1 % damping, so its integrations start on the
  HB torus (a start from the static state takes seconds to settle).

Reference: ``rs.transient`` (the error-controlled Radau IIA, balls moving with the cage)
started on the HB torus (``QuasiPeriodicPoint.state``); after a settling time, the tone
amplitudes of the integration are fitted by linear least squares on the known
frequencies ``k1 W + k2 w2`` of a larger box than the HB's
(:func:`rotorsim.verification.tone_fit.fit_tones`), over a long window.

Run ``python scripts/quasi_validation.py [rigid|convergence|default|stability|all]``
(about 10 min for ``all`` on one core); the printed tables are the numbers of case 40 in
``docs/validation.md``. ``tests/validation/test_quasi_periodic_validation.py`` runs
shortened versions.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

import rotorsim as rs
from rotorsim.harmonic_balance.quasi import TorusHarmonics
from rotorsim.verification.tone_fit import fit_tones, tone_frequencies

FloatArray = NDArray[np.float64]
GOLDEN = (1 + 5**0.5) / 2
VC_ORDER = 2 + GOLDEN
"""``Z kappa`` of the rigid rotor's bearing."""
DEFAULT_MODEL = Path(__file__).resolve().parents[1] / "models" / "default.toml"
RIGID_LOAD = 50.0  # N along -y
RIGID_UNBALANCE = ((0, 2e-6, 0.0),)
RIGID_BOX = (10, 4)
"""Harmonic set of the rigid rotor's comparisons (the convergence table picks it)."""
RIGID_SAMPLES = (128, 64)
"""Its AFT grid: the default (64, 32) aliases the balls' contact onsets into the smallest
combination tones by up to 1.6 % (the convergence table)."""
DEFAULT_HARMONICS = 6  # diamond
DEFAULT_SAMPLES = (64, 64)
RIGID_SPEEDS = (800.0, 1200.0, 1600.0, 2000.0)  # rad/s
DEFAULT_SPEEDS_RPM = (700.0, 1060.0, 1800.0)
BASE_TONES = ((1, 0), (0, 1))


def rigid_rotor(clearance: float = 2e-6, damping_factor: float = 2e-5,
                n_balls: int = 9) -> rs.Rotor:
    """The rigid rotor (module docstring): 1 kg, radial motion only, one ball bearing of
    ``n_balls`` balls whose ball-to-pitch diameter ratio makes ``Z kappa = VC_ORDER``
    (``kappa = (1 - d / d_m) / 2``)."""
    kappa = VC_ORDER / n_balls
    pitch = 0.0385
    bearing = rs.BallBearing(n_balls=n_balls, pitch_diameter=pitch,
                             ball_diameter=(1 - 2 * kappa) * pitch, Kn=9.3e9, f_i=0.52,
                             f_o=0.52, radial_clearance=clearance, cage="rotating")
    rolling = rs.RollingBearing(bearing, n=0, tag="B", contact_damping="proportional",
                                damping_factor=damping_factor)
    disk = rs.DiskElement(n=0, m=1.0, Id=2.5e-4, Ip=4.5e-4)
    return rs.Rotor([], [disk], fixed=[(0, d) for d in ("uz", "rx", "ry", "rz")],
                    nonlinear_elements=[rolling])


def rigid_excitation() -> rs.Excitation:
    """50 N along -y, no gravity."""
    return rs.Excitation(gravity=None, loads=[(0, "uy", -RIGID_LOAD)])


def default_rotor() -> tuple[rs.Rotor, tuple[tuple[int, float, float], ...]]:
    """``models/default.toml`` with its ball bearings, and its unbalance."""
    model = rs.load_model(DEFAULT_MODEL)
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    return rotor, tuple(model.loads.unbalance)


@dataclass(frozen=True)
class Case:
    """A rotor, its loads and the DOFs compared."""

    name: str
    rotor: rs.Rotor
    unbalance: tuple[tuple[int, float, float], ...]
    excitation: rs.Excitation
    channels: tuple[tuple[int, str], ...]
    rtol: float
    harmonics: int | tuple[int, int]
    truncation: str
    samples: tuple[int, int] | None
    combination_nodes: tuple[int, ...]
    """Nodes whose largest combination tones are compared (elsewhere: the base tones)."""

    def tones(self, point: Any, node: int, dof: str) -> list[tuple[int, int]]:
        """The tones of ``(node, dof)`` held to the 1 % bound."""
        return compared_tones(point, node, dof, 3 if node in self.combination_nodes else 0)


def rigid_case() -> Case:
    return Case("rigid", rigid_rotor(), RIGID_UNBALANCE, rigid_excitation(),
                ((0, "ux"), (0, "uy")), 1e-8, RIGID_BOX, "box", RIGID_SAMPLES, (0,))


def default_case() -> Case:
    rotor, unbalance = default_rotor()
    return Case("default", rotor, unbalance, rs.Excitation(),
                ((8, "ux"), (8, "uy"), (0, "ux"), (0, "uy")), 1e-7, DEFAULT_HARMONICS,
                "diamond", DEFAULT_SAMPLES, (0,))


def solve_point(case: Case, speed: float, harmonics: int | tuple[int, int] | None = None,
                truncation: str | None = None, samples: tuple[int, int] | None = None
                ) -> tuple[Any, float]:
    """The HB point and its wall time [s] (the case's harmonic set and grid by default)."""
    if harmonics is None:
        harmonics, truncation, samples = case.harmonics, case.truncation, case.samples
    clock = time.perf_counter()
    point = rs.quasi_periodic_point(case.rotor, speed, unbalance=case.unbalance,
                                    harmonics=harmonics, truncation=truncation or "box",
                                    samples=samples, excitation=case.excitation)
    return point, time.perf_counter() - clock


def fit_set(box: tuple[int, int]) -> NDArray[np.int64]:
    """Wave vectors of the fit: a box, the mean left out."""
    return TorusHarmonics.box(*box).k


def fitted_tones(t: FloatArray, y: FloatArray, k: NDArray[np.int64], w1: float,
                 w2: float) -> dict[tuple[int, int], float]:
    """Amplitude of every tone ``k`` in ``y(t)`` (columns: channels)."""
    c = fit_tones(t, y, tone_frequencies(k, w1, w2))
    amps = np.abs(c[1:])
    return {(int(a), int(b)): amps[j] for j, (a, b) in enumerate(k)}


def compared_tones(point: Any, node: int, dof: str, n_mixed: int = 3
                   ) -> list[tuple[int, int]]:
    """The base tones and the ``n_mixed`` largest combination tones (``k1, k2 != 0``) of
    ``(node, dof)`` in the HB point."""
    k = point.solution.aft.harmonics.k
    mixed = [(int(a), int(b)) for a, b in k if a != 0 and b != 0]
    mixed.sort(key=lambda kk: -point.amplitude(node, dof, *kk))
    return list(BASE_TONES) + mixed[:n_mixed]


@dataclass(frozen=True)
class Comparison:
    """HB tones against the tones fitted to an integration started on the torus."""

    speed: float
    rows: list[tuple[int, str, tuple[int, int], float, float]]  # node, dof, k, HB, fitted
    hb_time: float
    transient_time: float
    deviation: float  # largest |q - torus| over the window / peak-to-peak of the torus

    def errors(self) -> FloatArray:
        return np.array([(hb - ti) / ti for *_, hb, ti in self.rows])


def compare(case: Case, speed: float, settle: float, window: float,
            fit_box: tuple[int, int] = (14, 6), samples_per_period: int = 60) -> Comparison:
    """Integrate from the HB torus over ``settle + window`` [s] and fit the window."""
    point, hb_time = solve_point(case, speed)
    nodes = sorted({n for n, _ in case.channels})
    w_top = max(speed, point.vc_frequency)
    times = np.linspace(settle, settle + window,
                        int(window * w_top / (2 * np.pi) * samples_per_period) + 1)
    clock = time.perf_counter()
    run = rs.transient(case.rotor, settle + window, speed=speed, unbalance=case.unbalance,
                       excitation=case.excitation, initial=point.state(0.0),
                       rtol=case.rtol,
                       output=rs.Output(nodes=nodes, times=np.concatenate([[0.0], times])))
    transient_time = time.perf_counter() - clock
    t = run.t[1:]
    k = fit_set(fit_box)
    rows, deviation = [], 0.0
    for node, dof in case.channels:
        y = run.q[1:, run.dof_labels.index(f"node {node} {dof}")]
        torus = point.response(t, node, dof)
        deviation = max(deviation, float(np.abs(y - torus).max() / np.ptp(torus)))
        fitted = fitted_tones(t, y, k, speed, point.vc_frequency)
        for kk in compared_tones(point, node, dof):
            rows.append((node, dof, kk, point.amplitude(node, dof, *kk), fitted[kk]))
    return Comparison(speed, rows, hb_time, transient_time, deviation)


def print_comparison(c: Comparison, unit: float = 1e-9, unit_name: str = "nm") -> None:
    print(f"  {c.speed:.1f} rad/s: HB {c.hb_time:.2f} s, integration {c.transient_time:.1f}"
          f" s, largest deviation from the torus {c.deviation:.2e} of the peak-to-peak")
    for node, dof, k, hb, ti in c.rows:
        print(f"    node {node} {dof} tone {k!s:>8}: HB {hb / unit:12.4f} {unit_name}, "
              f"integration {ti / unit:12.4f} {unit_name}, error {(hb - ti) / ti:+.2e}")


def convergence(case: Case, speed: float, sets: Sequence[tuple[str, Any, Any]],
                reference: tuple[str, Any, Any], node: int, dofs: Sequence[str]
                ) -> list[tuple[str, int, float, dict[tuple[str, tuple[int, int]], float]]]:
    """Relative change of the compared tones of each (truncation, harmonics, samples)
    against ``reference``: rows (label, tones, time, {(dof, k): relative difference})."""
    ref, _ = solve_point(case, speed, reference[1], reference[0], reference[2])
    tones = {dof: compared_tones(ref, node, dof) for dof in dofs}
    out = []
    for truncation, harmonics, samples in sets:
        point, wall = solve_point(case, speed, harmonics, truncation, samples)
        diffs = {}
        for dof in dofs:
            for k in tones[dof]:
                a_ref = ref.amplitude(node, dof, *k)
                a = point.amplitude(node, dof, *k) if _has(point, k) else 0.0
                diffs[(dof, k)] = (a - a_ref) / a_ref
        grid = "x".join(str(n) for n in point.solution.aft.samples)
        out.append((f"{truncation} {harmonics} {grid}", point.solution.aft.harmonics.size,
                    wall, diffs))
    return out


def _has(point: Any, k: tuple[int, int]) -> bool:
    kk = point.solution.aft.harmonics.k
    return bool(np.any((kk[:, 0] == k[0]) & (kk[:, 1] == k[1])
                       | (kk[:, 0] == -k[0]) & (kk[:, 1] == -k[1])))


def print_convergence(rows: list[Any]) -> None:
    keys = list(rows[0][3])
    print("    set            tones  time[s]  " + "  ".join(f"{d} {k!s:>8}" for d, k in keys))
    for label, size, wall, diffs in rows:
        print(f"    {label:14s} {size:5d} {wall:8.2f}  "
              + "  ".join(f"{diffs[key]:+11.2e}" for key in keys))


def run_rigid() -> list[Comparison]:
    case = rigid_case()
    print(f"rigid rotor, VC order {VC_ORDER:.5f}, box {RIGID_BOX} on {RIGID_SAMPLES}, "
          f"integration rtol "
          f"{case.rtol:g} from the torus, 0.05 s settling, 0.25 s fitted")
    out = []
    for speed in RIGID_SPEEDS:
        c = compare(case, speed, settle=0.05, window=0.25)
        print_comparison(c)
        out.append(c)
    return out


RIGID_SETS = [("box", (4, 2), (128, 128)), ("box", (6, 2), (128, 128)),
              ("box", (8, 3), (128, 128)), ("box", (10, 4), (128, 128)),
              ("box", (12, 5), (128, 128)), ("diamond", 6, (128, 128)),
              ("diamond", 8, (128, 128)), ("diamond", 10, (128, 128)),
              ("diamond", 12, (128, 128)), ("box", (10, 4), None),
              ("box", (10, 4), (64, 64)), ("box", (10, 4), (128, 64)),
              ("box", (10, 4), (256, 256))]
DEFAULT_SETS = [("box", (2, 1), (64, 64)), ("box", (4, 2), (64, 64)),
                ("box", (6, 2), (64, 64)), ("diamond", 4, (64, 64)),
                ("diamond", 6, (64, 64)), ("diamond", 8, (64, 64)),
                ("diamond", 6, None), ("diamond", 6, (64, 128))]


def run_convergence() -> None:
    case = rigid_case()
    for speed in (800.0, 2000.0):
        print(f"rigid rotor at {speed} rad/s, node 0: change of the tones against box "
              "(16, 6) on 256 x 256")
        print_convergence(convergence(case, speed, RIGID_SETS, ("box", (16, 6), (256, 256)),
                                      0, ("ux", "uy")))
    dcase = default_case()
    print("default model at 1060 rpm, node 0 (DE bearing): change of the tones against "
          "box (8, 4) on 64 x 128")
    print_convergence(convergence(dcase, 1060.0 * np.pi / 30, DEFAULT_SETS,
                                  ("box", (8, 4), (64, 128)), 0, ("ux", "uy")))


def run_default() -> list[Comparison]:
    case = default_case()
    print(f"default model, diamond {DEFAULT_HARMONICS} on {DEFAULT_SAMPLES}, integration "
          f"rtol {case.rtol:g} from the torus, 0.1 s settling, 2.0 s fitted (the VC order "
          "4.093 puts the tones k and k + (4, -1) 0.093 W apart: a window of several "
          "2 pi / (0.093 W) separates them)")
    out = []
    for rpm in DEFAULT_SPEEDS_RPM:
        c = compare(case, rpm * np.pi / 30, settle=0.1, window=2.0)
        print_comparison(c)
        out.append(c)
    return out


STABLE = (2e-6, 1200.0)
"""Clearance [m] and speed [rad/s] of the stable torus of the stability check."""
UNSTABLE = (5e-6, 1600.0)
"""... and of the unstable one (the same rotor with 5 um of clearance)."""


@dataclass(frozen=True)
class GrowthCheck:
    """The Lyapunov exponent of a torus against the growth of perturbations in time."""

    clearance: float
    speed: float
    exponent: float
    difference_rate: float  # slope of the difference of the two integrations [1/s]
    deviation_rate: float  # slope of the unperturbed run's distance from the torus [1/s]
    revolutions: tuple[int, int]  # fitted, [first, last)
    first: float  # the difference at the first fitted revolution, of the peak-to-peak
    last: float  # ... at the last one
    deviation_end: float  # the unperturbed run's distance from the torus at the end, ditto


def _slope(t: NDArray[Any], y: NDArray[Any]) -> float:
    return float(np.polyfit(t, np.log(y), 1)[0])


def perturbation_growth(clearance: float, speed: float, duration: float, size: float,
                        periods: int = 80, skip: int = 2, rtol: float = 1e-9,
                        linear: float = 0.05) -> GrowthCheck:
    """Two integrations of the rigid rotor from its HB torus, one with ``ux`` and ``uy``
    moved by ``size`` [m], against the largest Lyapunov exponent of the torus over
    ``periods`` revolutions. Per revolution: the largest state distance
    ``sqrt(|dq|^2 + |dv|^2 / W^2)`` between the two runs, and the largest distance of the
    unperturbed run from the torus (which it leaves when the torus is unstable, from the
    HB's own truncation error); the least-squares slopes of their logarithms from
    revolution ``skip`` on, while the unperturbed run stays within ``linear`` of the
    peak-to-peak from the torus and within twice its distance over the first revolutions
    (the linear regime)."""
    case = rigid_case()
    rotor = rigid_rotor(clearance)
    point = rs.quasi_periodic_point(rotor, speed, unbalance=case.unbalance,
                                    harmonics=case.harmonics, truncation=case.truncation,
                                    samples=case.samples, excitation=case.excitation)
    exponent = point.stability(periods=periods).exponent
    q0, v0 = point.state(0.0)
    revolution = 2 * np.pi / speed
    n_rev = int(duration / revolution)
    times = np.linspace(0.0, n_rev * revolution, 200 * n_rev + 1)
    runs = []
    for shift in (0.0, size):
        q = q0.copy()
        q[:2] += shift  # node 0 ux, uy
        runs.append(rs.transient(rotor, times[-1], speed=speed, unbalance=case.unbalance,
                                 excitation=case.excitation, initial=(q, v0), rtol=rtol,
                                 output=rs.Output(times=times, velocities=True)))
    cols = [runs[0].dof_labels.index(f"node 0 {d}") for d in ("ux", "uy")]
    dq = runs[1].q[:, cols] - runs[0].q[:, cols]
    v1, v0_run = runs[1].v, runs[0].v
    assert v1 is not None and v0_run is not None  # kept by Output(velocities=True)
    dv = v1[:, cols] - v0_run[:, cols]
    between = np.sqrt((dq**2).sum(axis=1) + (dv**2).sum(axis=1) / speed**2)
    off = np.hypot(runs[0].q[:, cols[0]] - point.response(times, 0, "ux"),
                   runs[0].q[:, cols[1]] - point.response(times, 0, "uy"))
    ptp = float(np.ptp(point.response(times, 0, "ux")))
    between_rev = between[:-1].reshape(n_rev, 200).max(axis=1)
    off_rev = off[:-1].reshape(n_rev, 200).max(axis=1)
    t_rev = revolution * (np.arange(n_rev) + 0.5)
    # the linear regime ends where the run's distance from the torus exceeds ``linear`` of
    # the peak-to-peak and twice its size over the first revolutions (the HB's truncation
    # error starts free vibration, which decays on a stable torus)
    bound = max(linear * ptp, 2 * float(off_rev[:skip + 1].max()))
    beyond = np.flatnonzero(off_rev[skip:] > bound)
    stop = skip + int(beyond[0]) if beyond.size else n_rev
    fit = slice(skip, stop)
    return GrowthCheck(clearance, speed, float(exponent),
                       _slope(t_rev[fit], between_rev[fit]), _slope(t_rev[fit], off_rev[fit]),
                       (skip, stop), float(between_rev[skip] / ptp),
                       float(between_rev[stop - 1] / ptp), float(off_rev[-1] / ptp))


def run_stability() -> list[GrowthCheck]:
    print("stability of the rigid rotor's tori: Lyapunov exponent (80 revolutions) against "
          "perturbations in two integrations (rtol 1e-9), one moved by 1 nm")
    out = []
    for (clearance, speed), duration in ((STABLE, 0.06), (UNSTABLE, 0.12)):
        g = perturbation_growth(clearance, speed, duration, 1e-9)
        print(f"  clearance {clearance * 1e6:.0f} um, {speed:.0f} rad/s: exponent "
              f"{g.exponent:+.1f} 1/s; over revolutions {g.revolutions[0]}-"
              f"{g.revolutions[1] - 1}: difference of the runs {g.difference_rate:+.1f} 1/s "
              f"({g.first:.1e} -> {g.last:.1e} of the peak-to-peak), distance of the "
              f"unperturbed run from the torus {g.deviation_rate:+.1f} 1/s; that distance "
              f"at the end {g.deviation_end:.1e} of the peak-to-peak", flush=True)
        out.append(g)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("part", nargs="?", default="all",
                        choices=["rigid", "convergence", "default", "stability", "all"])
    part = parser.parse_args().part
    if part in ("convergence", "all"):
        run_convergence()
    if part in ("rigid", "all"):
        run_rigid()
    if part in ("default", "all"):
        run_default()
    if part in ("stability", "all"):
        run_stability()


if __name__ == "__main__":
    main()
