"""NLvib's examples 01-03 with ``rs.hb``: Duffing, 2-DOF cubic chain, unilateral contact.

The systems and analysis settings are those of NLvib 1.3's example scripts (M. Krack,
J. Gross, *Harmonic Balance for Nonlinear Vibration Problems*, Springer 2019;
github.com/maltekrack/NLvib, ``EXAMPLES/01``-``03``):

01. Duffing ``q'' + 0.05 q' + q + 0.1 q^3 = 0.18 cos(W t)``, ``H = 7``, ``N = 29``,
    ``W = 0.5 -> 1.6``; amplitude: the fundamental ``|Q_1|``.
02. Chain ``m = (1, 0.05)``, springs ``k = (1, 0.0453, 0)`` and dampers
    ``d = (0.002, 0.013, 0)`` (ground-mass 1, mass 1-mass 2, mass 2-ground), a grounded
    cubic spring ``1 q_1^3`` and ``0.0042 (q_1 - q_2)^3`` between the masses, forcing
    ``0.11 cos(W t)`` on mass 1, ``H = 7``, ``N = 29``, ``W = 0.8 -> 1.4``; amplitude: the
    RMS of ``q_1``. NLvib finds two Neimark-Sacker points by shooting.
03. Chain ``m = (1, 1)``, ``k = (0, 1, 1)``, ``d = 0.03 k``, a unilateral spring of
    stiffness 100 after a gap of 1 on mass 1, forcing ``0.1 cos(W t)`` on mass 2,
    ``H = 21``, ``N = 1024``, ``W = 0.8 -> 0.5``; amplitude: ``|Q_1|`` of ``q_2``.

:data:`NLVIB` holds NLvib's own numbers for the same settings, from running its scripts in
GNU Octave 7.3 (``docs/validation.md`` says how); their points are converged to about
1e-5 (fsolve's default tolerances) and spaced by NLvib's step (``ds = 0.01-0.02``), so a
peak read from its points is a lower bound of the true one.

Run: ``python examples/nlvib_examples.py [--fast] [--out DIR]`` (figures and a summary).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402

NLVIB = {
    "duffing": {"peak": (1.26870094, 2.8301978), "folds": (1.26960161, 1.11571931),
                "points": 192},
    "two_dof_cubic": {"peak_rms": (1.02774281, 0.41848809), "folds": (1.21461003, 1.20622941),
                      "neimark_sacker": ((1.1077742, 1.1166947), (1.1896171, 1.1968355)),
                      "points": 83},
    "unilateral_contact": {"peak": (0.751553175, 0.93722160),
                           "folds": (0.655011795, 0.755638091), "points": 127},
}
"""NLvib 1.3 in Octave 7.3 (module docstring): ``(W, amplitude)`` of the largest point,
the turning points of ``W`` along its branch, and for example 02 the brackets of the
stability changes its shooting run finds (Floquet multipliers leaving the unit circle as a
complex pair: Neimark-Sacker)."""


def chain(masses: Any, dampers: Any, springs: Any) -> tuple[np.ndarray, ...]:
    """``M, D, K`` of a chain: ``springs[0]`` ground-mass 0, ``springs[i]`` mass i-1 to
    mass i, ``springs[-1]`` last mass-ground (NLvib's ``ChainOfOscillators``)."""
    m, d, k = (np.asarray(v, dtype=float) for v in (masses, dampers, springs))

    def tridiagonal(c: np.ndarray) -> np.ndarray:
        return np.diag(c[:-1] + c[1:]) - np.diag(c[1:-1], -1) - np.diag(c[1:-1], 1)

    return np.diag(m), tridiagonal(d), tridiagonal(k)


def duffing(harmonics: int = 7) -> rs.hb.FrequencyResponse:
    """Example 01: the Duffing oscillator (five lines of user code)."""
    system = rs.hb.System(mass=1.0, stiffness=1.0, damping=0.05, forcing=[0.18],
                          elements=[rs.hb.CubicSpring(0, k3=0.1)])
    return rs.hb.frequency_response(system, start=0.5, stop=1.6, harmonics=harmonics,
                                    samples=4 * harmonics + 1)


def two_dof_cubic() -> rs.hb.FrequencyResponse:
    """Example 02: two masses, a grounded cubic spring and one between them."""
    M, D, K = chain([1.0, 0.05], [0.002, 0.013, 0.0], [1.0, 0.0453, 0.0])
    system = rs.hb.System(M, K, D, forcing=[0.11, 0.0],
                          elements=[rs.hb.CubicSpring(0, k3=1.0),
                                    rs.hb.CubicSpring(0, k3=0.0042, other=1)])
    return rs.hb.frequency_response(system, start=0.8, stop=1.4, harmonics=7, samples=29)


def unilateral_contact(stability: bool = False) -> rs.hb.FrequencyResponse:
    """Example 03: two masses, a unilateral spring after a gap on mass 1 (``H = 21``).

    Stability and bifurcations are off by default: at the contact resonance the branch of
    this non-smooth problem zigzags in steps of 1e-5 rad/s (issue 16), and HB-based
    Floquet multipliers of a stiffness step are unreliable there.
    """
    M, D, K = chain([1.0, 1.0], [0.0, 0.03, 0.03], [0.0, 1.0, 1.0])
    system = rs.hb.System(M, K, D, forcing=[0.0, 0.1],
                          elements=[rs.hb.UnilateralSpring(0, stiffness=100.0, gap=1.0)])
    return rs.hb.frequency_response(system, start=0.8, stop=0.5, harmonics=21, samples=1024,
                                    stability=stability, bifurcations=stability)


def turning_points(omega: np.ndarray) -> np.ndarray:
    """Frequencies where the branch turns (sign changes of ``dW`` between points)."""
    d = np.sign(np.diff(omega))
    return omega[np.flatnonzero(d[1:] != d[:-1]) + 1]


def main(fast: bool = False, out: str | Path | None = None) -> dict[str, Any]:
    """Run the three examples, print a comparison with :data:`NLVIB`, and write the
    figures to ``out`` (none when None). ``fast`` skips example 03 (the longest)."""
    runs: dict[str, Any] = {}
    clock = time.perf_counter()
    runs["duffing"] = duffing()
    runs["two_dof_cubic"] = two_dof_cubic()
    if not fast:
        runs["unilateral_contact"] = unilateral_contact()
    lines = []
    for name, frf in list(runs.items()):
        dof, measure = {"duffing": (0, "fundamental"), "two_dof_cubic": (0, "rms"),
                        "unilateral_contact": (1, "fundamental")}[name]
        peak = frf.peak(dof, measure)
        ref = NLVIB[name]["peak_rms" if measure == "rms" else "peak"]
        events = ", ".join(f"{b.kind} {b.omega:.6f}" for b in frf.bifurcations)
        lines.append(f"{name}: {len(frf)} points, {frf.reason}; peak {peak.amplitude:.6f} at "
                     f"{peak.omega:.6f} rad/s (NLvib's largest point {ref[1]:.6f} at "
                     f"{ref[0]:.6f}); events: {events or 'not computed'}")
        if out is not None:
            folder = Path(out)
            folder.mkdir(parents=True, exist_ok=True)
            fig = frf.plot(dof, measure)
            fig.savefig(folder / f"nlvib_{name}.png", dpi=110)
            runs[f"{name}_figure"] = folder / f"nlvib_{name}.png"
    runs["summary"] = "\n".join(lines)
    runs["wall_time"] = time.perf_counter() - clock
    return runs


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="skip example 03")
    parser.add_argument("--out", default="results/examples", help="folder of the figures")
    args = parser.parse_args()
    result = main(fast=args.fast, out=args.out)
    print(result["summary"])
    print(f"total {result['wall_time']:.1f} s")
