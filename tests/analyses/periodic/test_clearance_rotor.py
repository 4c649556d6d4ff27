"""The clearance rotor of issue 16 (``models/clearance_rotor.toml``): a harmonic-balance
branch through a sharp clearance resonance.

A 0.8 m, 40 mm shaft with a 250 mm disk at mid-span on two 9-ball bearings with 5 um
radial clearance, gravity and an unbalance of 1e-4 kg m, damped only by the contact damping
of the balls. Before issue 16 the branch from 100 rad/s crawled through the resonance with
steps scaled to the static sag and stalled at the first contact-onset point (the corrector
stuck at a scaled residual of about 1e-8: ``beta_c K(delta) delta'`` is not Lipschitz where
an AFT sample meets the contact onset), after reporting about 30 "bifurcations" in a few
rad/s. It must now reach 400 rad/s, report only confirmed events, and list the sign changes
it rejected.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs

MODEL = Path(__file__).resolve().parents[3] / "models" / "clearance_rotor.toml"
DISK = 10


@pytest.fixture(scope="module")
def branch():
    model = rs.load_model(MODEL)
    return rs.periodic(model, start=100.0, stop=400.0, harmonics=8,
                       unbalance=[(DISK, 1e-4, 0.0)], nodes=[0, DISK, 20])


def test_the_branch_passes_the_clearance_resonance(branch):
    assert branch.status == rs.Status.OK and branch.parameter[-1] == 400.0
    # the resonance is passed with steps that grow with the response: the whole branch
    # takes a few hundred points, not the 500 that ended it near 353 rad/s before
    assert len(branch) < 400
    amp = branch.amplitude(DISK, "uy", "peak_to_peak")
    assert amp.max() > 20 * amp[0]          # a sharp resonance, passed
    # every point converged (within the stall tolerance at contact-onset points)
    assert np.all(branch.residuals <= 1e-6)


def test_the_hysteresis_folds_are_found(branch):
    """The hardening resonance turns twice: up to about 343.6 rad/s, back to about
    342.0 rad/s, and up again. (A fold at a contact onset is a corner of the branch: the
    extended system may not converge there, and the fold is located on its test function
    instead; its probes accept a corrector stalled within ``stall_tol``, as the branch's
    points do, or they were refused and the fold stayed unlocated.)"""
    folds = sorted(branch.events("fold"), key=lambda f: f.index)
    assert len(folds) == 2 and all(f.located for f in folds)
    up, down = (f.parameter for f in folds)
    assert 340.0 < down < up < 346.0
    i, j = (f.index for f in folds)
    lam = branch.parameter
    assert np.all(np.diff(lam[: i + 1]) > 0) and np.all(np.diff(lam[i + 1: j + 1]) < 0)


def test_only_confirmed_events_are_reported_and_rejected_ones_say_why(branch):
    """Dozens of sign changes near the resonance are artefacts of the discretisation
    (a sample crossing a contact onset, multipliers of nearly undamped modes moved by the
    Floquet method's error): they go to ``unresolved`` with the interval and the reason,
    never to ``bifurcations``. Only the two hysteresis folds and the two axial pitchforks
    are resolved (docs/validation.md case 26, addendum "only resolved events")."""
    assert sorted((b.kind, round(b.parameter)) for b in branch.bifurcations) == [
        ("branch_point", 353), ("branch_point", 354), ("fold", 342), ("fold", 344)]
    stats = branch.stats
    assert stats["confirmed"] == len(branch.bifurcations)
    assert stats["candidates"] >= stats["confirmed"] + len(branch.unresolved)
    assert len(branch.bifurcations) <= 8            # not the ~30 of a raw test-function scan
    assert branch.unresolved                        # the rejected ones are listed ...
    for u in branch.unresolved:                     # ... with where and why
        assert not u.located and u.method.startswith("unresolved between ")
        assert "sign change" in u.method or "jumps" in u.method or "steeply" in u.method \
            or "window" in u.method or "does not converge with" in u.method
    # the summary printed by the CLI counts them
    from rotorsim.cli.summaries import periodic_summary
    assert "did not survive confirmation" in periodic_summary(branch)


def test_a_branch_started_near_the_resonance_steps_over_its_singular_point():
    """Started at 330 rad/s the steps arrive at the contact-onset point near 342.56 rad/s
    (amplitude 2.02e-4 m) in another phase than from 100 rad/s: every step was cut and
    accepted shorter than the last (the tangent turns like the square root of the distance
    there), and the branch crawled back and stopped at ``min_step`` after 295 points. The
    stepper now steps over the point after three such steps (``SHRINKS_TO_STEP_OVER``)."""
    model = rs.load_model(MODEL)
    res = rs.periodic(model, start=330.0, stop=360.0, harmonics=8,
                      unbalance=[(DISK, 1e-4, 0.0)], nodes=[DISK], stability=None)
    assert res.status == rs.Status.OK and res.parameter[-1] == 360.0
    assert len(res) < 200
    lam = res.parameter
    turns = np.flatnonzero(np.sign(np.diff(lam[1:])) != np.sign(np.diff(lam[:-1]))) + 1
    # the same two hysteresis turns as from 100 rad/s, and no spurious third one
    assert len(turns) == 2
    assert 343.5 < lam[turns[0]] < 343.8 and 341.9 < lam[turns[1]] < 342.1
    # the two branch points that bound the unstable window near 353 rad/s (an axial
    # pitchfork, real multiplier 1.09: docs/validation.md case 25) are located. Before, the
    # tangent-cone guard refused the probes next to them (the bordered Jacobian is nearly
    # singular at a branch point) and, located to 1e-7 of the bracket, the probes' noise
    # made them look steep
    window = [b for b in res.events("branch_point") if 352.0 < b.parameter < 355.0]
    assert len(window) == 2 and all(b.located for b in window)
    lo, hi = sorted(b.parameter for b in window)
    assert 353.0 < lo < 353.25 and 353.6 < hi < 353.85



def test_time_integration_confirms_the_axial_pitchforks_near_353_rad_s():
    """A short transient on each side of the unstable window between the branch points near
    353.1 and 353.7 rad/s, on the full model (``rs.transient``, average acceleration,
    T / 200: no code shared with harmonic balance or Floquet but the element forces),
    from the HB state with the whole rotor shifted 0.1 um axially. Inside the window the
    shift grows (Floquet: a real multiplier 1.093, an axial pitchfork, docs/validation.md
    case 25); outside it the rigid axial oscillation stays bounded (Floquet 1.000)."""
    from rotorsim.verification.period_map import PeriodMap
    from rotorsim.verification.periodic_events import _excitation, _system

    model = rs.load_model(MODEL)
    res = rs.periodic(model, start=346.0, stop=356.0, harmonics=8,
                      unbalance=[(DISK, 1e-4, 0.0)], nodes=None)
    edges = sorted(b.parameter for b in res.events("branch_point"))
    assert len(edges) == 2
    system = _system(model)
    shift = 1e-7                                   # [m], 1/50 of the clearance
    growth = {}
    for speed in (edges[0] - 0.5, 0.5 * (edges[0] + edges[1]), edges[1] + 0.5):
        i = res.nearest(speed)
        pm = PeriodMap(system, float(res.speed[i]), 2.0 * np.pi / float(res.fundamental[i]),
                       _excitation(res), phi0=float(res.options.get("shaft_angle", 0.0)),
                       steps=200)
        q0, v0 = res.state(i, 0.0)
        dq = np.zeros_like(q0)
        dq[2::6] = shift
        q, _ = pm.flow(q0 + dq, v0, 20)
        growth[speed] = (q[:, 2::6].mean(axis=1) / shift, float(res.max_multiplier[i]))
    below, inside, above = growth.values()
    assert inside[1] > 1.05 and below[1] < 1.01 and above[1] < 1.01   # Floquet's verdicts
    # inside: the shift more than doubles in 20 periods, growing every period of the last 10
    assert inside[0][-1] > 2.0 and np.all(np.diff(inside[0][10:]) > 0)
    # at a rate within 30 % (in log) of Floquet's: the shift is not the pure eigenvector
    # (it also starts the neutral rigid axial oscillation), so 10 periods bias the estimate
    rate = (inside[0][-1] / inside[0][-11]) ** 0.1
    assert abs(np.log(rate) / np.log(inside[1]) - 1.0) < 0.3
    # outside: bounded by the initial shift (the axial oscillation is neutral there)
    assert np.abs(below[0]).max() <= 1.05 and np.abs(above[0]).max() <= 1.05
