"""Seed 002 section 3.5.2: periodic responses of a rigid rotor on a cylindrical roller bearing
by harmonic balance, with Floquet stability (``rotorsim.analyses.periodic.periodic.periodic``).

The seed's system (its Fig. 3.5): a symmetric rigid rotor, 5 DOFs ``x y z theta_y theta_z``
(its x is the shaft axis), carried at its centre by one cylindrical roller bearing, under
gravity, spinning at ``W``; the bearing's varying compliance (VC) excites it at
``w_vc = Z kappa W``. The seed gives no numbers for the rotor or the bearing, so they are
chosen here (documented, not fitted):

* rotor: ``m = 10 kg``, ``J_d = 0.05 kg m^2``, ``J_p = 0.08 kg m^2`` (a disk of about
  200 mm), modelled as one node with a rigid disk; a stub shaft element of negligible
  stiffness and mass joins it to a fully fixed node (written before rotors without shaft
  elements existed; ``rs.Rotor([], [disk], ...)`` now gives the model without it);
  the axial and torsional motions, which no cylindrical roller restrains, are held
  (the seed's two multipliers at +1 belong to them);
* bearing: NU205-like, 12 rollers of 7 mm x 7 mm on a 38.5 mm pitch diameter, no
  clearance, ISO/TS 16281 line-contact constant (``Kn = 4.37e8 N/m^(10/9)``), rigid rings,
  ``Z kappa = 4.909``;
* damping: none at 1000 rad/s (the seed's point, "critically stable"); the swept studies
  add a viscous support damping of 2000 N s/m laterally and 5 N m s/rad in tilt (an
  undamped branch grows without bound in the parametric resonances of the tilt modes).

Studies and figures (``docs/figures/seed002``):

1. ``fig3_1000rads.png``: harmonic content of ``y`` (vertical) and ``z`` (horizontal, our
   ``ux``) at 1000 rad/s and the Floquet multipliers (Hill and Hsu) on the unit circle; the
   seed prints ``y(t)`` (mean -0.1646 um, first VC harmonic 2.2 nm) and 10 multipliers of
   modulus 1.
2. ``fig3_17_18_vc.png``: VC harmonics of ``y`` and ``z`` against speed (damped branch).
3. ``fig3_19_stability.png``: largest Floquet multiplier against speed, undamped, one
   independent HB point every 10 rad/s (as the seed) -- and along the damped branch.
4. ``fig3_20_26_housing.png``: housing excitation ``-M a_b`` (eq 3.43) with the housing
   displacement ``a cos(k w_vc t)``: ``(k, a) = (1, 1 mm), (1, 0.1 mm), (2, 0.1 mm)``;
   peak-to-peak ``y``, ``z`` and radial motion against speed, stable solid, unstable dashed.

Run: ``python examples/seed002_periodic.py [--fast] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from rotorsim.analyses.periodic.excitation import HarmonicBase  # noqa: E402
from rotorsim.analyses.periodic.periodic import periodic  # noqa: E402
from rotorsim.elements.rolling.element import RollingBearing  # noqa: E402
from rotorsim.elements.rolling.roller.bearing import RollerBearing  # noqa: E402
from rotorsim.results.periodic import PeriodicResult  # noqa: E402

FIGURES = ROOT / "docs" / "figures" / "seed002"
ROTOR = {"m": 10.0, "Id": 0.05, "Ip": 0.08}
"""Rigid rotor mass [kg] and diametral / polar moments of inertia [kg m^2] (chosen)."""
BEARING = {"n_rollers": 12, "pitch_diameter": 0.0385, "roller_diameter": 0.007,
           "effective_length": 0.007}
"""NU205-like cylindrical roller bearing (chosen), no clearance, ISO line-contact constant."""
DAMPING = (2000.0, 5.0)
"""Support damping of the swept studies: lateral [N s/m], tilt [N m s/rad]."""
SEED_Y = {"mean": -16.45858e-8, "c1": -0.2219e-8, "s1": -0.0109e-8}
"""Seed 002 y(t) at 1000 rad/s: mean and first VC harmonic ``A cos - B sin`` [m]."""
HOUSING = {"k1_a1mm": (1, 1e-3), "k1_a01mm": (1, 1e-4), "k2_a01mm": (2, 1e-4)}
"""Housing excitation cases: (multiple k of w_vc, displacement amplitude [m])."""
VOID = rs.Material(name="void", E=1.0, G_s=0.4, rho=1e-6)
"""Stub shaft material: stiffness and mass negligible (1 Pa, 1e-6 kg/m^3)."""


def seed_rotor(damped: bool = False) -> rs.Rotor:
    """The rigid rotor on its roller bearing (module docstring)."""
    stub = [rs.ShaftElement(L=0.01, idl=0.0, odl=0.001, material=VOID)]
    disk = rs.DiskElement(n=0, m=ROTOR["m"], Id=ROTOR["Id"], Ip=ROTOR["Ip"])
    bearing = RollingBearing(RollerBearing(**BEARING), n=0, tag="NU205")
    supports = [rs.BearingElement(n=0, kxx=0.0, cxx=DAMPING[0], crr=DAMPING[1])] \
        if damped else []
    fixed = [(1, d) for d in ("ux", "uy", "uz", "rx", "ry", "rz")]
    return rs.Rotor(stub, [disk], supports, nonlinear_elements=[bearing], fixed=fixed,
                    tag="seed002_rigid_rotor")


def vc_order() -> float:
    """``Z kappa`` of the bearing."""
    b = RollerBearing(**BEARING)
    return b.n_elements * b.kappa


def point_1000(fast: bool) -> dict[str, Any]:
    """Undamped response and multipliers at 1000 rad/s (seed's printed y(t))."""
    out: dict[str, Any] = {}
    for method in ("hill", "hsu"):
        res = periodic(seed_rotor(), start=1000.0, stop=1001.0, harmonics=10,
                       continuation=rs.ContinuationOptions(max_points=2, tol=1e-11),
                       stability=rs.StabilityOptions(method, bifurcations=False))
        out[method] = res
    res = out["hill"]
    y, z = res.harmonic_amplitudes(0, 0, "uy"), res.harmonic_amplitudes(0, 0, "ux")
    mu_hill, mu_hsu = out["hill"].multipliers[0], out["hsu"].multipliers[0]
    out.update({
        "y_harmonics": y, "z_harmonics": z, "mean_y": float(res.coefficients[0, 0,
                                                                            res.column(0, "uy")]),
        "multipliers": mu_hill, "max_modulus_hill": float(np.abs(mu_hill).max()),
        "max_modulus_hsu": float(np.abs(mu_hsu).max()),
        "hill_hsu_difference": float(np.max(np.min(np.abs(mu_hill[:, None]
                                                           - mu_hsu[None, :]), axis=1))),
        "seed_mean_y": SEED_Y["mean"], "seed_vc1_y": math.hypot(SEED_Y["c1"], SEED_Y["s1"]),
        "held": res.held_dofs.tolist(), "order": res.order})
    return out


def stability_map(fast: bool) -> dict[str, Any]:
    """Undamped HB points every 10 rad/s (20 in fast mode) and their largest multiplier."""
    speeds = np.arange(100.0, 1001.0, 20.0 if fast else 10.0)
    max_mu = np.full(speeds.size, np.nan)
    for i, W in enumerate(speeds):
        try:
            res = periodic(seed_rotor(), start=float(W), stop=float(W) + 0.5, harmonics=8,
                           continuation=rs.ContinuationOptions(max_points=2, tol=1e-10),
                           stability=rs.StabilityOptions("hill", bifurcations=False))
        except rs.ConvergenceError:
            continue
        max_mu[i] = res.max_multiplier[0]
    return {"speeds": speeds, "max_multiplier": max_mu}


def sweep(base: HarmonicBase | None, fast: bool, max_step: float) -> PeriodicResult:
    """Damped branch from 100 to 1000 rad/s (400 in fast mode)."""
    return periodic(seed_rotor(damped=True), start=100.0, stop=400.0 if fast else 1000.0,
                    harmonics=6 if fast else 10, excitation=rs.Excitation(base=base),
                    continuation=rs.ContinuationOptions(max_step=max_step, tol=1e-8,
                                                        max_points=250 if fast else 2500))


def housing_studies(fast: bool) -> dict[str, PeriodicResult]:
    """Figs 3.20-3.26: base excitation at ``k w_vc`` of amplitude ``a`` along y."""
    return {name: sweep(HarmonicBase(a, order=k * vc_order()), fast, 0.2)
            for name, (k, a) in HOUSING.items()}


def radial_ptp(res: PeriodicResult, node: int = 0) -> np.ndarray:
    """Peak-to-peak of the radial displacement ``hypot(ux, uy)`` over a period (P,) [m]."""
    out = np.zeros(len(res))
    for i in range(len(res)):
        x, y = res.orbit(i, node, 256)
        r = np.hypot(x, y)
        out[i] = r.max() - r.min()
    return out


def summary(res: PeriodicResult) -> dict[str, Any]:
    """Reached speed, peak response, unstable points and bifurcations of a branch."""
    ptp = res.amplitude(0, "uy", "peak_to_peak")
    return {"points": len(res), "reached": float(res.parameter[-1]), "reason": res.reason,
            "peak_ptp_y": float(ptp.max()), "peak_speed": float(res.parameter[np.argmax(ptp)]),
            "unstable_points": int(np.sum(~res.stable)),
            "bifurcations": [(b.kind, round(b.parameter, 2)) for b in res.bifurcations],
            "wall_time": float(res.stats["wall_time"])}


SEED_MULTIPLIERS = np.array([0.9874 + 0.1583j, 0.9961 + 0.0887j, -0.9671 + 0.2545j,
                             -0.3990 + 0.9169j, 1.0 + 0j])
"""Seed 002's multipliers at 1000 rad/s (and their conjugates)."""
SEED_Y_HARMONICS = 1e-8 * np.array([16.45858, math.hypot(0.2219, 0.0109),
                                    math.hypot(0.0030, 0.0003), math.hypot(0.0006, 0.001),
                                    math.hypot(0.0003, 0.0001), math.hypot(0.0002, 0.0001),
                                    0.0001, 0.0001, 0.0001, 0.0001])
"""``|A_j - i B_j|`` of the seed's y(t) series at 1000 rad/s, j = 0..9 [m]."""


def _figures(out: Path, data: dict[str, Any]) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    names = []
    for name, draw in (("fig3_1000rads.png", _fig_point), ("fig3_17_18_vc.png", _fig_vc),
                       ("fig3_19_stability.png", _fig_stability),
                       ("fig3_20_26_housing.png", _fig_housing)):
        fig = draw(data)
        fig.savefig(out / name, dpi=110)
        plt.close(fig)
        names.append(name)
    return names


def _fig_point(data: dict[str, Any]) -> Any:
    import matplotlib.pyplot as plt

    p = data["point_1000"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    h = np.arange(p["y_harmonics"].size)
    a.bar(h - 0.27, p["y_harmonics"] * 1e9, 0.27, label="y (vertical), rotorsim")
    a.bar(h, p["z_harmonics"] * 1e9, 0.27, label="z (horizontal), rotorsim")
    a.bar(np.arange(SEED_Y_HARMONICS.size) + 0.27, SEED_Y_HARMONICS * 1e9, 0.27,
          label="y, seed 002 (other rotor data)")
    a.set_yscale("log")
    a.set_xlabel("harmonic of w_vc = Z kappa W")
    a.set_ylabel("|X_h| [nm]")
    a.set_title("1000 rad/s, gravity, undamped: harmonic content")
    a.legend(fontsize=8)
    t = np.linspace(0, 2 * np.pi, 400)
    b.plot(np.cos(t), np.sin(t), color="0.6", lw=0.8)
    for mu, style, label in ((p["multipliers"], "o", "Hill"),
                             (p["hsu"].multipliers[0], "x", "Hsu (N = 128)"),
                             (np.concatenate([SEED_MULTIPLIERS, SEED_MULTIPLIERS.conj()]), "+",
                              "seed 002")):
        b.plot(mu.real, mu.imag, style, ms=8, mfc="none", label=label)
    b.set_aspect("equal")
    b.set_title(f"Floquet multipliers, max |mu| - 1 = {p['max_modulus_hill'] - 1:.1e}")
    b.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _fig_vc(data: dict[str, Any]) -> Any:
    import matplotlib.pyplot as plt

    from rotorsim.plotting.periodic_figures import harmonics_figure

    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    for ax, dof, name in ((axes[0], "uy", "y (Fig. 3.17)"), (axes[1], "ux", "z (Fig. 3.18)")):
        harmonics_figure(data["vc"], ax, node=0, dof=dof, amplitude_units="nm")
        ax.set_title(f"varying-compliance harmonics of {name}, damped")
    fig.tight_layout()
    return fig


def _fig_stability(data: dict[str, Any]) -> Any:
    import matplotlib.pyplot as plt

    from rotorsim.plotting.periodic_figures import multiplier_figure

    fig, (a, b) = plt.subplots(1, 2, figsize=(13, 4.5))
    s = data["stability"]
    a.semilogy(s["speeds"], np.abs(s["max_multiplier"] - 1) + 1e-16, "o-", ms=3, lw=0.8)
    unstable = s["max_multiplier"] > 1 + 1e-5
    a.semilogy(s["speeds"][unstable], s["max_multiplier"][unstable] - 1, "o", color="tab:red",
               ms=4, label="unstable (|mu| > 1 + 1e-5)")
    a.set_xlabel("spin speed [rad/s]")
    a.set_ylabel("| max |mu| - 1 |")
    a.set_title("undamped: one HB point every 10 rad/s (Fig. 3.19)")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
    multiplier_figure(data["vc"], b)
    b.set_title("damped branch (continuation)")
    fig.tight_layout()
    return fig


def _fig_housing(data: dict[str, Any]) -> Any:
    import matplotlib.pyplot as plt

    from rotorsim.plotting.periodic_figures import frequency_response_figure

    fig, axes = plt.subplots(2, 2, figsize=(13, 9))
    colors = {"k1_a1mm": "tab:blue", "k1_a01mm": "tab:orange", "k2_a01mm": "tab:green"}
    for name, res in data["housing"].items():
        k, a = HOUSING[name]
        label = f"k = {k}, a = {a * 1e3:g} mm"
        for ax, dof in ((axes[0, 0], "uy"), (axes[0, 1], "ux")):
            frequency_response_figure(res, ax, node=0, dof=dof, label=label,
                                      color=colors[name])
        axes[1, 0].semilogy(res.parameter, radial_ptp(res) * 1e6, color=colors[name],
                            label=label)
    axes[0, 0].set_title("y (Figs. 3.20-3.22)")
    axes[0, 1].set_title("z (Figs. 3.23-3.25)")
    axes[0, 0].set_yscale("log")
    axes[0, 1].set_yscale("log")
    axes[1, 0].set_title("radial peak-to-peak (Fig. 3.26)")
    axes[1, 0].set_xlabel("spin speed [rad/s]")
    axes[1, 0].set_ylabel("radial peak-to-peak [um]")
    axes[1, 0].grid(alpha=0.3, which="both")
    axes[1, 0].legend(fontsize=8)
    from rotorsim.plotting.periodic_figures import harmonics_figure

    harmonics_figure(data["housing"]["k1_a01mm"], axes[1, 1], node=0, dof="uy")
    axes[1, 1].set_title("harmonics of y, k = 1, a = 0.1 mm")
    fig.tight_layout()
    return fig


def _report(out: dict[str, Any]) -> str:
    p = out["point_1000"]
    lines = ["seed 002 section 3.5.2, rigid rotor on a cylindrical roller bearing",
             f"  1000 rad/s: mean y = {p['mean_y'] * 1e9:.2f} nm (seed {p['seed_mean_y'] * 1e9:.2f}"
             f" nm), first VC harmonic y = {p['y_harmonics'][1] * 1e9:.3f} nm (seed "
             f"{p['seed_vc1_y'] * 1e9:.3f} nm), z = {p['z_harmonics'][1] * 1e9:.3f} nm",
             f"  multipliers: max |mu| - 1 = {p['max_modulus_hill'] - 1:.2e} (Hill), "
             f"{p['max_modulus_hsu'] - 1:.2e} (Hsu); Hill-Hsu {p['hill_hsu_difference']:.1e}"]
    s = out["stability"]
    lines.append(f"  undamped map: {np.sum(s['max_multiplier'] > 1 + 1e-5)} of "
                 f"{s['speeds'].size} speeds unstable")
    for name, numbers in out["summaries"].items():
        lines.append(f"  {name}: {numbers}")
    lines.append(f"  total {out['wall_time']:.1f} s")
    return "\n".join(lines)


def main(fast: bool = False, outdir: str | Path | None = None) -> dict[str, Any]:
    """Run the seed 002 studies, write the figures, return the measured numbers.

    Parameters
    ----------
    fast : bool
        Fewer harmonics, a coarser stability map and branches to 400 rad/s (tests).
    outdir : path, optional
        Folder of the figures; default ``docs/figures/seed002``.

    Returns
    -------
    dict
        ``point_1000`` (harmonic amplitudes, multipliers, comparison numbers), ``stability``
        (speeds, largest multiplier), ``vc`` and ``housing`` (PeriodicResult branches),
        ``summaries`` (per branch: reach, peak, unstable points, bifurcations),
        ``figures`` and ``wall_time`` [s].
    """
    clock = time.perf_counter()
    data: dict[str, Any] = {"point_1000": point_1000(fast), "stability": stability_map(fast),
                            "vc": sweep(None, fast, 0.01), "housing": housing_studies(fast)}
    data["summaries"] = {"vc": summary(data["vc"]),
                         **{k: summary(v) for k, v in data["housing"].items()}}
    data["figures"] = _figures(Path(outdir) if outdir is not None else FIGURES, data)
    data["wall_time"] = time.perf_counter() - clock
    return data


def _cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short ranges, fewer harmonics")
    parser.add_argument("--out", default=None, help="figure folder")
    args = parser.parse_args()
    print(_report(main(fast=args.fast, outdir=args.out)))


if __name__ == "__main__":
    _cli()
