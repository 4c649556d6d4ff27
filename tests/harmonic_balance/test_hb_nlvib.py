"""NLvib's examples 01-03 (``examples/nlvib_examples.py``) against NLvib's own numbers
and against periodic orbits from scipy's DOP853 at rtol 1e-10 (:mod:`shooting_reference`).

NLvib's numbers come from running its example scripts (NLvib 1.3) in GNU Octave 7.3 with
the scripts' settings (docs/validation.md): ``examples.nlvib_examples.NLVIB``. Its points
are converged to about 1e-5 (fsolve's default tolerances; re-solving its points with
rotorsim moves their coefficients by 1e-7 to 1e-4) and spaced by its continuation step,
so its largest point is a lower bound of the peak and its turning points bound the folds
from inside.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.errors import Status

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).parent))

from shooting_reference import first_order, fundamental, periodic_orbit  # noqa: E402

from examples import nlvib_examples as ex  # noqa: E402

CONVERGED = 2e-5
"""How far NLvib's amplitudes may sit from the exact HB solution (its fsolve tolerance;
measured up to 1e-5 on the amplitudes of examples 01-03)."""


def initial_state(point: rs.hb.Point) -> np.ndarray:
    """``[q(0), q'(0)]`` of a solved point."""
    X = point.coefficients
    h = np.arange(1, point.harmonics + 1)[:, None]
    return np.concatenate([X[0] + X[1::2].sum(axis=0),
                           point.omega * np.sum(h * X[2::2], axis=0)])


@pytest.fixture(scope="module")
def duffing():
    return ex.duffing()


@pytest.fixture(scope="module")
def two_dof():
    return ex.two_dof_cubic()


def test_01_duffing_peak_and_folds_match_nlvib(duffing):
    ref = ex.NLVIB["duffing"]
    assert duffing.status == Status.OK and duffing.omega[-1] == 1.6
    peak = duffing.peak(0)
    # NLvib's largest point (2.8301978 at 1.26870) lies on the same curve 0.003 rad/s
    # before the refined peak: lower by at most the curvature there, 3e-6
    assert ref["peak"][1] - CONVERGED <= peak.amplitude <= ref["peak"][1] + 1e-5
    assert abs(peak.omega - ref["peak"][0]) < 0.005
    folds = sorted((b.omega for b in duffing.events("fold")), reverse=True)
    assert len(folds) == 2 and len(duffing.bifurcations) == 2
    # NLvib's turning points lie inside the folds by O(ds^2) (measured 1e-6 and 2e-5)
    for mine, theirs, side in zip(folds, ref["folds"], (1, -1), strict=True):
        assert 0 <= side * (mine - theirs) < 1e-4


def test_01_duffing_peak_matches_shooting(duffing):
    """At the refined peak the H = 7 orbit equals the exact one: ``|Q_1|`` to 1e-9
    (measured 2e-10; the H = 7 truncation of a cubic at this amplitude is below 1e-9)."""
    peak = duffing.peak(0)
    system = rs.hb.System(1.0, 1.0, 0.05, forcing=[0.18],
                          elements=[rs.hb.CubicSpring(0, k3=0.1)])
    point = rs.hb.solve(system, peak.omega, harmonics=7, samples=29,
                        x0=duffing.branch.x[peak.index])
    assert point.amplitude(0) == pytest.approx(peak.amplitude, rel=1e-10)
    T = 2 * math.pi / peak.omega
    rhs = first_order(1.0, 0.05, 1.0, lambda q, v: 0.1 * q**3,
                      lambda t: np.array([0.18 * math.cos(peak.omega * t)]))
    y, monodromy = periodic_orbit(rhs, initial_state(point), T)
    assert fundamental(rhs, y, T, 0) == pytest.approx(peak.amplitude, rel=1e-9)
    # the peak is on the stable branch, as Hill's method says
    assert duffing.stable[peak.index] and np.abs(np.linalg.eigvals(monodromy)).max() < 1


def test_02_two_dof_cubic_matches_nlvib(two_dof):
    ref = ex.NLVIB["two_dof_cubic"]
    assert two_dof.status == Status.OK and two_dof.omega[-1] == 1.4
    peak = two_dof.peak(0, "rms")
    assert ref["peak_rms"][1] - CONVERGED <= peak.amplitude <= ref["peak_rms"][1] + 1e-4
    assert abs(peak.omega - ref["peak_rms"][0]) < 0.005
    kinds = [b.kind for b in two_dof.bifurcations]
    assert kinds == ["neimark_sacker", "neimark_sacker", "fold", "fold"]
    # the Neimark-Sacker points lie in the brackets of NLvib's shooting stability change
    for event, (lo, hi) in zip(two_dof.events("neimark_sacker"), ref["neimark_sacker"],
                               strict=True):
        assert lo < event.omega < hi and abs(abs(event.multiplier) - 1) < 1e-6
        assert abs(event.multiplier.imag) > 0.4               # a complex pair
    folds = sorted((b.omega for b in two_dof.events("fold")), reverse=True)
    for mine, theirs, side in zip(folds, ref["folds"], (1, -1), strict=True):
        assert 0 <= side * (mine - theirs) < 1e-4
    # unstable exactly between the two Neimark-Sacker points
    first, second = (b.index for b in two_dof.events("neimark_sacker"))
    assert not two_dof.stable[first + 1:second + 1].any()
    assert two_dof.stable[first] and two_dof.stable[second + 1]


def test_02_two_dof_cubic_matches_shooting_and_its_multipliers(two_dof):
    """An unstable point between the Neimark-Sacker points: the H = 7 orbit against the
    exact one (measured 4e-11 relative: the truncation of H = 7), and Hill's multipliers
    against the eigenvalues of the monodromy matrix of the exact orbit (central
    differences of the flow with step 1e-6: accurate to about 1e-8; measured 1e-9)."""
    i = int(np.argmin(np.abs(two_dof.omega - 1.15)))
    M, D, K = ex.chain([1.0, 0.05], [0.002, 0.013, 0.0], [1.0, 0.0453, 0.0])
    omega = float(two_dof.omega[i])
    point = two_dof.point(i)

    def force(q, v):
        d = q[0] - q[1]
        return np.array([q[0] ** 3 + 0.0042 * d**3, -0.0042 * d**3])

    rhs = first_order(M, D, K, force, lambda t: np.array([0.11 * math.cos(omega * t), 0.0]))
    T = 2 * math.pi / omega
    y, monodromy = periodic_orbit(rhs, initial_state(point), T)
    assert point.amplitude(0) == pytest.approx(fundamental(rhs, y, T, 0), rel=1e-9)
    exact = np.sort_complex(np.linalg.eigvals(monodromy))
    hill = np.sort_complex(two_dof.multipliers[i])
    assert not two_dof.stable[i] and np.abs(exact).max() > 1
    np.testing.assert_allclose(np.sort(np.abs(hill)), np.sort(np.abs(exact)), atol=1e-6)


@pytest.mark.slow
def test_03_unilateral_contact_matches_nlvib_and_shooting():
    """H = 21, N = 1024 as NLvib. The branch passes the contact resonance (NLvib in Octave
    stops at 0.58 rad/s there) and reaches 0.5. Against the exact orbit at 0.635 rad/s
    the HB amplitude differs by 9e-4 relative (measured): the truncation of a stiffness
    step at H = 21, which the 2e-3 bound below covers."""
    ref = ex.NLVIB["unilateral_contact"]
    frf = ex.unilateral_contact()
    assert frf.status == Status.OK and frf.omega[-1] == 0.5
    peak = frf.peak(1)
    assert ref["peak"][1] - CONVERGED <= peak.amplitude <= ref["peak"][1] + 1e-3
    assert abs(peak.omega - ref["peak"][0]) < 0.005
    # the folds: the first turning point (lower fold, the branch turns up into the
    # resonance) and the largest W (upper fold; the branch zigzags by 1e-5 rad/s there,
    # issue 16). NLvib's turning points lie inside them (within its step, 0.002 rad/s
    # in W near the lower fold)
    lower = ex.turning_points(frf.omega)[0]
    assert 0 <= ref["folds"][0] - lower < 2e-3
    top = ex.turning_points(frf.omega).max()
    assert -CONVERGED <= top - ref["folds"][1] < 1e-4
    omega = 0.635
    M, D, K = ex.chain([1.0, 1.0], [0.0, 0.03, 0.03], [0.0, 1.0, 1.0])
    system = rs.hb.System(M, K, D, forcing=[0.0, 0.1],
                          elements=[rs.hb.UnilateralSpring(0, stiffness=100.0, gap=1.0)])
    nearest = int(np.argmin(np.abs(frf.omega - omega)))
    point = rs.hb.solve(system, omega, harmonics=21, samples=1024, x0=frf.branch.x[nearest])
    rhs = first_order(M, D, K, lambda q, v: np.array([100.0 * max(q[0] - 1.0, 0.0), 0.0]),
                      lambda t: np.array([0.0, 0.1 * math.cos(omega * t)]))
    T = 2 * math.pi / omega
    y, _ = periodic_orbit(rhs, initial_state(point), T)
    assert point.amplitude(1) == pytest.approx(fundamental(rhs, y, T, 1), rel=2e-3)
    assert np.abs(point.time_response()[1][:, 0]).max() > 1.0      # in contact


def test_example_main_runs_fast(tmp_path):
    pytest.importorskip("matplotlib")
    out = ex.main(fast=True, out=tmp_path)
    assert "duffing: 191 points" in out["summary"]
    assert out["duffing_figure"].stat().st_size > 10000
    assert "unilateral_contact" not in out
