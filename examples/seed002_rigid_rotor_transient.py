"""Seed 002 section 3.5.1: a rigid rotor on one nonlinear roller bearing, in time.

The seed (Zhu 2017, Fig 3.5) studies a rigid 5-DOF rotor (mass ``m``, transverse and polar
inertias ``J_d``, ``J_p``, gyroscopic coupling) carried at its centre by one cylindrical
roller bearing, under gravity, at 1000 rad/s, and shows (Figs 3.8-3.14):

* a balanced rotor released from the zero position oscillates about its static equilibrium
  (undamped: for ever), with the varying-compliance (VC, roller-pass) vibration on top;
* released from the static equilibrium it shows the VC vibration only;
* an initial velocity (0.002 and 0.02 m/s in the seed) changes the amplitude and, the
  bearing being nonlinear, the frequency of the free vibration;
* an unbalance dominates the response and hides the initial state once damping has removed
  the free vibration;
* damping: a constant 200 N s/m as in the seed's Fig 3.13 (here a damping ratio of only
  0.2 %, so the free vibration is barely touched in 0.1 s), and a contact damping
  proportional to the bearing stiffness (``C = beta K``, ``beta = 20 us``, the seed's
  "proposed damping" of Fig 3.14), which removes the free vibration within a few ms.

The seed prints no numbers for ``m``, ``J`` or the bearing; this example uses a 20 kg rotor
(``J_d = 0.2``, ``J_p = 0.3 kg m^2``) on an NU210-like bearing (14 rollers of 11 mm x 12 mm
on a 70 mm pitch diameter, ISO/TS 16281 contact constant, 10 um diametral clearance), so it
reproduces the behaviour, not the seed's curves. It also checks the integration of this
strongly nonlinear contact problem against an independent integrator: ``solve_ivp``
(DOP853, rtol 1e-10) on the same equations.

Run: ``python examples/seed002_rigid_rotor_transient.py [--fast] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402

SPEED = 1000.0  # rad/s (seed section 3.5.2)
MASS, J_D, J_P = 20.0, 0.2, 0.3
DAMPING = 200.0  # N s/m, seed Fig 3.13
CONTACT_DAMPING = 2e-5  # s, C = beta K of the bearing
UNBALANCE = [(0, 1e-3, 0.0)]  # 1 g m: 50 um eccentricity of the 20 kg rotor


def rotor(damping: float = 0.0, contact_damping: float = 0.0) -> rs.Rotor:
    """The rigid rotor: a disk at node 0 on the roller bearing; node 1 is held, and the
    shaft element between them is a massless placeholder with no stiffness to speak of."""
    ghost = rs.Material(name="placeholder", E=1.0, G_s=0.4, rho=1e-9)
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.05, material=ghost)]
    disk = rs.DiskElement(n=0, m=MASS, Id=J_D, Ip=J_P)
    roller = rs.RollerBearing(n_rollers=14, pitch_diameter=0.070, roller_diameter=0.011,
                              effective_length=0.012, diametral_clearance=10e-6)
    bearings: list[Any] = [rs.RollingBearing(
        roller, n=0, tag="NU210", contact_damping="proportional" if contact_damping else "none",
        damping_factor=contact_damping)]
    if damping:
        bearings.append(rs.BearingElement(n=0, kxx=0.0, cxx=damping, cyy=damping,
                                          tag="damping"))
    fixed = [(1, d) for d in rs.DOF_NAMES]
    return rs.Rotor(shaft, [disk], bearings, fixed=fixed, tag="rigid rotor")


def vc_frequency(r: rs.Rotor) -> float:
    """Roller-pass (varying compliance) frequency ``Z kappa W`` [rad/s]."""
    b = r.nonlinear_elements[0].bearing
    return float(b.n_elements * b.kappa * SPEED)


def run_cases(fast: bool) -> dict[str, Any]:
    """The seed's cases as transients of ``t_end`` with 64 steps per VC period."""
    base = rotor()
    t_vc = 2 * np.pi / vc_frequency(base)
    dt = t_vc / 64
    t_end = dt * round((0.02 if fast else 0.1) / dt)  # whole steps: uniform samples
    ndof = 6 * base.n_nodes
    cases: dict[str, Any] = {}

    def run(name: str, r: rs.Rotor, **kw: Any) -> None:
        cases[name] = rs.transient(r, t_end, dt, speed=SPEED, nodes=[0], **kw)

    run("balanced, zero start", base, initial="zero")
    run("balanced, static start", base)
    static = cases["balanced, static start"].q[0]
    full = np.zeros(ndof)
    full[cases["balanced, static start"].dofs] = static
    for v in (0.002, 0.02):
        v0 = np.zeros(ndof)
        v0[1] = v  # uy of node 0
        run(f"balanced, v0 = {v} m/s", base, initial=(full, v0))
    run("unbalanced", base, unbalance=UNBALANCE)
    run("unbalanced, 200 N s/m", rotor(DAMPING), unbalance=UNBALANCE)
    run("unbalanced, contact damping", rotor(contact_damping=CONTACT_DAMPING),
        unbalance=UNBALANCE)
    return cases


def reference_check(t_end: float = 0.004) -> dict[str, float]:
    """Balanced rotor released from zero: rotorsim (average acceleration and the enhanced
    Adams method of the seed) against ``solve_ivp`` DOP853 on the same first-order
    equations."""
    from scipy.integrate import solve_ivp

    from rotorsim.analyses.transient.equation import rotor_problem as _problem
    from rotorsim.analyses.transient.speed_profile import ConstantSpeed

    r = rotor()
    system = rs.assemble(r)
    profile = ConstantSpeed(SPEED).bind(0.0, t_end)
    problem, loads = _problem(system, profile, 0.0, rs.Excitation())
    n = system.n_free
    M, K = np.asarray(problem.mass), np.asarray(problem.stiffness)
    D = np.asarray(problem.damping) + SPEED * np.asarray(problem.gyroscopic)
    restoring = problem.restoring
    assert restoring is not None

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:n], y[n:]
        rf, _, _ = restoring(q, v, t)
        return np.concatenate([v, np.linalg.solve(M, loads(t) - K @ q - D @ v - rf)])

    times = np.linspace(0.0, t_end, 81)
    ref = solve_ivp(rhs, (0.0, t_end), np.zeros(2 * n), method="DOP853", rtol=1e-10,
                    atol=1e-16, t_eval=times)
    iy = system.dofs_of(0, ("uy",))[0]
    out = {}
    for method, label in (("average_acceleration", ""), ("adams", "adams, ")):
        for steps_per_vc in (64, 128):
            dt = 2 * np.pi / vc_frequency(r) / steps_per_vc
            res = rs.transient(r, t_end, dt, speed=SPEED, initial="zero", nodes=[0],
                               output=rs.Output(times=times), method=method)
            err = np.max(np.abs(res.displacement(0, "uy") - ref.y[iy]))
            out[f"{label}max error uy, {steps_per_vc} steps per VC period [m]"] = float(err)
    out["max |uy| [m]"] = float(np.max(np.abs(ref.y[iy])))
    return out


def measures(cases: dict[str, Any], f_vc: float) -> dict[str, Any]:
    """Mean, peak-to-peak, dominant frequency and the 1X and VC amplitudes (least-squares
    fits) of the second half of each run."""
    out: dict[str, Any] = {}
    for name, res in cases.items():
        t_min = 0.5 * res.t[-1]
        y = res.displacement(0, "uy")[res.t >= t_min]
        spec = res.spectrum(0, "uy", t_min=t_min)
        peak = float(spec.frequency[1:][np.argmax(spec.amplitude[1:])])
        out[name] = {"mean uy [um]": 1e6 * float(y.mean()),
                     "p-p uy [um]": 1e6 * float(np.ptp(y)),
                     "dominant frequency [rad/s]": peak,
                     "1X amplitude [um]": 1e6 * float(res.harmonic(0, "uy", SPEED,
                                                                   t_min).amplitude),
                     "VC amplitude [um]": 1e6 * float(res.harmonic(0, "uy", f_vc,
                                                                   t_min).amplitude)}
    return out


def figures(cases: dict[str, Any], out: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(len(cases), 1, figsize=(8, 2.0 * len(cases)), sharex=True)
    for ax, (name, res) in zip(axes, cases.items(), strict=True):
        ax.plot(res.t * 1e3, res.displacement(0, "uy") * 1e6, lw=0.7)
        ax.set_ylabel("uy [um]")
        ax.set_title(name, fontsize=9)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time [ms]")
    fig.tight_layout()
    path = out / "seed002_rigid_rotor_transients.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return [path]


def main(fast: bool = False, out: Path | str | None = None) -> dict[str, Any]:
    """Run every case and the reference check; write the figure; return the numbers."""
    cases = run_cases(fast)
    f_vc = vc_frequency(rotor())
    report = {"vc frequency [rad/s]": f_vc, "cases": measures(cases, f_vc),
              "reference": reference_check()}
    folder = Path(out) if out is not None else ROOT / "docs" / "figures" / "seed002"
    report["figures"] = [str(p) for p in figures(cases, folder)]
    return report


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args()
    import json

    print(json.dumps(main(args.fast, args.out), indent=2))
