"""Monte Carlo of critical speeds under bearing-stiffness scatter.

The rotor of Friswell et al. (2010) example 5.9.1 (two disks, bearings of 1 MN/m at both
ends, undamped) is built with each bearing's stiffness drawn independently from a
normal distribution of mean 1 MN/m and standard deviation 5 % (so about 95 % of the
bearings lie within +-10 %). A seeded sample of the first two forward synchronous
critical speeds is evaluated by a sweep and compared with two independent predictions:

* the nominal critical speeds ``Wc``: the sample mean differs from them by sampling error
  and a small second-order bias ``sum_i d2Wc/dk_i2 sigma_k^2 / 2`` (negative: the critical
  speeds grow slower than linearly with the stiffness), and
* the first-order (delta-method) standard deviation ``sqrt(sum_i (dWc/dk_i sigma_k)^2)``,
  the derivatives from central finite differences on the nominal model.

Run: ``python examples/monte_carlo_critical_speeds.py [--out DIR] [--fast] [--workers N]``.
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

from examples.textbook_rotors import friswell_5_9_1  # noqa: E402
from rotorsim.analyses.linear.critical_speeds import critical_speeds  # noqa: E402
from rotorsim.analyses.sweep.sweep import (  # noqa: E402
    Normal,
    Sample,
    chain,
    critical_speeds_eval,
    set_bearing_stiffness,
    sweep,
)
from rotorsim.elements.linear_bearing import BearingElement  # noqa: E402
from rotorsim.results.sweep import SweepResult  # noqa: E402

NOMINAL_K = 1e6
"""Nominal bearing stiffness of example 5.9.1 [N/m]."""
SCATTER = 0.05
"""Relative standard deviation of each bearing stiffness."""
SEED = 591
NUM_MODES = 2


def forward_critical_speeds(k0: float, k1: float) -> np.ndarray:
    """First two forward critical speeds [rad/s] with bearing stiffnesses ``k0``, ``k1``."""
    bearings = [BearingElement(n=0, kxx=k0), BearingElement(n=6, kxx=k1)]
    found = critical_speeds(friswell_5_9_1().with_bearings(bearings), 1, NUM_MODES,
                            whirl="forward", sparse=False)
    return found.speed[:NUM_MODES]


def delta_method(h: float = 1e-2 * NOMINAL_K) -> tuple[np.ndarray, np.ndarray]:
    """Second-order mean and first-order standard deviation of the critical speeds
    [rad/s] for independent stiffnesses of standard deviation ``sigma``:
    ``mean = Wc + sum_i d2Wc/dk_i2 sigma^2 / 2`` and ``std = sqrt(sum_i (dWc/dk_i sigma)^2)``,
    with central finite differences of step ``h`` [N/m] on the nominal model."""
    sigma = SCATTER * NOMINAL_K
    centre = forward_critical_speeds(NOMINAL_K, NOMINAL_K)
    mean, variance = centre.copy(), np.zeros_like(centre)
    for step in np.eye(2) * h:
        up = forward_critical_speeds(*(NOMINAL_K + step))
        down = forward_critical_speeds(*(NOMINAL_K - step))
        mean += (up - 2 * centre + down) / h**2 * sigma**2 / 2
        variance += ((up - down) / (2 * h) * sigma) ** 2
    return mean, np.sqrt(variance)


def monte_carlo(out: Path, n: int, executor: Any = "serial",
                max_workers: int | None = None, progress: bool = False) -> SweepResult:
    """Run (or resume) the sample of ``n`` rotors, stored in ``out/monte_carlo_<n>.h5``."""
    out.mkdir(parents=True, exist_ok=True)
    scatter = Normal(NOMINAL_K, SCATTER * NOMINAL_K)
    space = Sample(n, {"k_B0": scatter, "k_B1": scatter}, seed=SEED)
    apply = chain(set_bearing_stiffness(0, "k_B0"), set_bearing_stiffness(1, "k_B1"))
    evaluate = critical_speeds_eval(1.0, NUM_MODES, whirl="forward", sparse=False)
    return sweep(friswell_5_9_1(), space, apply, evaluate, store=out / f"monte_carlo_{n}.h5",
                 executor=executor, max_workers=max_workers, progress=progress)


def statistics(result: SweepResult) -> dict[str, np.ndarray]:
    """Sample mean, standard deviation, standard error and stiffness correlation."""
    speeds = result.outputs["critical_speeds"][result.ok]
    k_sum = (result.parameter("k_B0") + result.parameter("k_B1"))[result.ok]
    n = speeds.shape[0]
    std = speeds.std(axis=0, ddof=1)
    return {"n": np.array(n), "mean": speeds.mean(axis=0), "std": std,
            "std_error": std / np.sqrt(n),
            "correlation": np.array([np.corrcoef(k_sum, s)[0, 1] for s in speeds.T])}


def draw(result: SweepResult, nominal: np.ndarray, path: Path) -> None:
    """Histogram of each critical speed with the nominal value and the sample mean."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    speeds = result.outputs["critical_speeds"][result.ok]
    fig, axes = plt.subplots(1, NUM_MODES, figsize=(9, 3.5))
    for j, ax in enumerate(axes):
        ax.hist(speeds[:, j], bins="auto", color="tab:blue", alpha=0.75)
        ax.axvline(nominal[j], color="k", lw=2, label="nominal")
        ax.axvline(speeds[:, j].mean(), color="tab:red", ls="--", label="sample mean")
        ax.set_xlabel(f"forward critical speed {j + 1} [rad/s]")
        ax.set_ylabel("count")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{speeds.shape[0]} rotors, bearing stiffness N(1 MN/m, 5 %)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(fast: bool = False, out: str | Path = "results/examples", executor: Any = "serial",
         max_workers: int | None = None) -> dict[str, Any]:
    """Run the Monte Carlo, draw the histograms and return the statistics."""
    out = Path(out)
    n = 200 if fast else 2000
    result = monte_carlo(out, n, executor, max_workers, progress=not fast)
    nominal = forward_critical_speeds(NOMINAL_K, NOMINAL_K)
    stats = statistics(result)
    second_order_mean, linear = delta_method()
    figure = out / f"monte_carlo_critical_speeds_{n}.png"
    draw(result, nominal, figure)
    print(f"Monte Carlo: {int(stats['n'])} rotors (seed {SEED}), {int(result.stats['evaluated'])}"
          " evaluated now")
    for j in range(NUM_MODES):
        print(f"  forward critical speed {j + 1}: nominal {nominal[j]:.3f} rad/s,"
              f" mean {stats['mean'][j]:.3f} +- {stats['std_error'][j]:.3f}"
              f" (second order {second_order_mean[j]:.3f}),"
              f" std {stats['std'][j]:.3f} (first order {linear[j]:.3f}),"
              f" corr. with k0 + k1 {stats['correlation'][j]:.3f}")
    return {"result": result, "nominal": nominal, "second_order_mean": second_order_mean,
            "linear_std": linear, "figure": figure,
            **stats}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/examples")
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--workers", type=int, default=0, help="local processes (0: serial)")
    args = parser.parse_args()
    main(args.fast, args.out, "process" if args.workers else "serial", args.workers or None)
