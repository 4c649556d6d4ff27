"""Two more clearance rotors of issue 16 ("What it must show"): their harmonic-balance
branches reach their stop speeds, and every bifurcation they report is confirmed by time
integration next to it (``rs.verify_events(..., measure="floquet")``: a short free
transient along the event's critical Floquet mode on each side, docs/validation.md case
26, addendum "two more clearance rotors").

- ``models/clearance_rotor_damped.toml``: 2 um clearance, a 27 kg disk at mid-span on two
  8-ball bearings, a linear damper of 150 N s/m on the disk and light contact damping.
  Its damped resonance peaks next to the linearised critical speed, and the lightly damped
  axial mode is excited parametrically near twice its frequency (a period-doubling pair).
- ``models/clearance_rotor_structural.toml``: 8 um clearance, a lighter 9.4 kg disk at
  mid-span, half the unbalance, structural damping in the shaft and an axial damper, no
  contact damping. Its resonance, between the backward and forward whirls, turns
  twice inside a stretch made unstable by a period doubling. Both period doublings are
  confirmed by the free transients; the two folds are not (along the fold's real
  multiplier above 1 on the middle sheet, 1.021 and 1.028, the free transient does not
  grow measurably in 6 periods), but shooting on the full model confirms them: the
  monodromy of the time-integrated model's own orbits has the fold's real multiplier
  crossing +1 (docs/validation.md case 26, addendum "two more clearance rotors").
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.verification.event_modes import critical_mode

MODELS = Path(__file__).resolve().parents[3] / "models"


def _passes(branch, stop):
    """The branch reached ``stop`` with every point converged (within the stall tolerance
    at contact-onset points) and passed a resonance (20x its first amplitude at the disk)."""
    assert branch.status == rs.Status.OK and branch.parameter[-1] == stop
    assert np.all(branch.residuals <= 1e-6)
    amp = branch.amplitude(10, "uy", "peak_to_peak")
    assert amp.max() > 20 * amp[0]


def _doubling_confirmed(check):
    """A period doubling confirmed at Floquet's numbers on both sides."""
    assert check.confirmed, check.reason
    stable, unstable = sorted((check.before, check.after), key=lambda s: abs(s.mode))
    assert unstable.mode.imag == 0.0 and unstable.mode.real < -1.01
    # the integration's rate within 1 % of Floquet's multiplier: both are the same
    # linearised period map, measured to the scheme's ~1e-5 per period (case 26)
    assert abs(unstable.measured.real / unstable.mode.real - 1.0) < 0.01
    # the stable side: the same measurement, at Floquet's modulus (below 1, or 0.9995
    # next to the structural rotor's doubling at 392.26 rad/s)
    assert abs(abs(stable.measured) / abs(stable.mode) - 1.0) < 0.01


# ------------------------------------------------------------------------ damped rotor
@pytest.fixture(scope="module")
def damped():
    """The branch 200 -> 360 rad/s with all nodes (``verify_events`` needs full states),
    steps of at most 0.02 of the range (3.2 rad/s: with the default 0.05 the 6.3 rad/s
    period-doubling window holds a single point, at ``|mu| = 1.017``, below the 1.02 the
    verification counts as measurably unstable), and the disk's orbit peak located. Each
    event checked with 2 x 6 free periods per side (about 13 s for the branch and 6 s for
    the checks on the shared machine)."""
    model = rs.load_model(MODELS / "clearance_rotor_damped.toml")
    branch = rs.periodic(model, start=200.0, stop=360.0, harmonics=8,
                         unbalance=[(10, 5e-5, 0.0)], nodes=None,
                         continuation=rs.ContinuationOptions(max_step=0.02),
                         peaks=[(10, "orbit")])
    return model, branch, rs.verify_events(model, branch, periods=6, measure="floquet")


def test_the_damped_rotors_branch_reaches_its_stop(damped):
    _passes(damped[1], 360.0)


def test_every_event_of_the_damped_rotor_is_confirmed(damped):
    """The branch reports the period-doubling pair that bounds the axial parametric
    resonance, and both are confirmed: on the unstable side the critical mode alternates
    in sign at Floquet's real multiplier below -1 (measured -1.023 and -1.022 against
    Floquet's -1.023 and -1.022), on the stable side it does not grow."""
    _, branch, verified = damped
    assert [b.kind for b in branch.bifurcations] == ["period_doubling"] * 2
    assert all(b.located for b in branch.bifurcations)
    assert verified.all_confirmed, verified.summary()
    for check in verified.checks:
        _doubling_confirmed(check)


def test_the_damped_rotors_peak_and_parametric_resonance_sit_where_the_linear_rotor_puts_them(
        damped):
    """Against the rotor with its bearings linearised at the static load (``rs.modal``,
    an eigenvalue problem that shares nothing with harmonic balance but the bearing
    model): the disk's orbit peaks within 1 % of the first forward critical speed (the
    damper keeps the response near the linear one; measured 280.05 against 280.51 rad/s),
    and the period-doubling window
    brackets twice the axial natural frequency (the principal parametric resonance of the
    axial mode: 344.0 rad/s in the window 340.9-347.1 rad/s)."""
    model, branch, _ = damped
    linear = rs.modal(model.linearized().rotor, speed=280.0, num_modes=6)
    forward = next(w for w, k, s in zip(linear.wn, linear.kind, linear.whirl, strict=True)
                   if k == "lateral" and s == "forward")
    axial = next(w for w, k in zip(linear.wn, linear.kind, strict=True) if k == "axial")
    (peak,) = [p for p in branch.peaks if p.kind == "max"]
    assert peak.located and abs(peak.parameter / forward - 1.0) < 0.01
    lo, hi = sorted(b.parameter for b in branch.bifurcations)
    assert lo < 2.0 * axial < hi and hi - lo < 0.05 * 2.0 * axial


# -------------------------------------------------------------------- structural rotor
@pytest.fixture(scope="module")
def structural():
    """The branch 250 -> 500 rad/s with all nodes, default steps, the disk's orbit peak
    located; each event checked with 2 x 6 free periods per side (about 10 s for the branch
    and 16 s for the checks on the shared machine)."""
    model = rs.load_model(MODELS / "clearance_rotor_structural.toml")
    branch = rs.periodic(model, start=250.0, stop=500.0, harmonics=8,
                         unbalance=[(10, 5e-5, 0.0)], nodes=None, peaks=[(10, "orbit")])
    return model, branch, rs.verify_events(model, branch, periods=6, measure="floquet")


def test_the_structural_rotors_branch_reaches_its_stop(structural):
    _passes(structural[1], 500.0)


def test_the_structural_rotors_period_doublings_are_confirmed(structural):
    """The two period doublings that bound the unstable stretch 392.3-432.3 rad/s: the
    critical mode alternates at Floquet's multiplier on the unstable side (measured -1.021
    and -1.020 against -1.021 and -1.020) and decays on the stable side."""
    _, branch, verified = structural
    assert [b.kind for b in branch.bifurcations] == [
        "period_doubling", "fold", "fold", "period_doubling"]
    for check in verified.checks:
        if check.event.kind == "period_doubling":
            _doubling_confirmed(check)


def test_the_folds_are_followed_along_their_own_multiplier(structural):
    """The folds lie where a period-doubling multiplier (-1.32 ... -1.37) dominates on both
    sides; the check follows the fold's real multiplier crossing +1 (the largest of the
    event's kind outside ``1 + margin``), not the doubling's (before, both folds were
    reported as "the unstable side's is a period doubling")."""
    _, _, verified = structural
    for check in verified.checks:
        if check.event.kind != "fold":
            continue
        for side in (check.before, check.after):
            assert side.mode.imag == 0.0 and 0.95 < side.mode.real < 1.05
            assert side.floquet > 1.3                 # the doubling's multiplier dominates
        assert "period doubling" not in check.reason


def test_the_structural_rotors_folds_are_confirmed_by_shooting_on_the_full_model(structural):
    """Along the fold's real multiplier on the middle sheet (Floquet 1.021 and 1.028) the
    free transients do not grow measurably (1.009 and 0.994 per period over 6 periods:
    ``measure="floquet"`` leaves both folds unconfirmed). Shooting on the full model
    (``measure="shooting"``) finds the time-integrated model's own orbits next to the
    branch's and computes their multipliers from the monodromy matrix: the fold's real
    multiplier is 0.964 on the lower sheet and 1.012 on the middle one (first fold), 1.011
    on the middle sheet and 0.993 on the upper one (second fold), each resolved by more
    than its error estimate (half the change between 200 and 400 steps per period). The
    points right next to the folds have no orbit of the full model nearby (the truncated
    series moves the folds by a few 0.01 rad/s) and are skipped; the orbits used lie within
    10 % of the branch's (``defect``)."""
    model, branch, _ = structural
    folds = [k for k, b in enumerate(branch.bifurcations) if b.kind == "fold"]
    checked = rs.verify_events(model, branch, events=folds, measure="shooting")
    assert checked.all_confirmed, checked.summary()
    for check in checked.checks:
        inside, outside = sorted((check.before, check.after), key=lambda s: abs(s.measured))
        assert inside.measured.imag == 0.0 and outside.measured.imag == 0.0
        assert 0.9 < inside.measured.real < 1.0 - inside.accuracy
        assert 1.0 + outside.accuracy < outside.measured.real < 1.05
        assert inside.accuracy < 0.01 and outside.accuracy < 0.01
        assert inside.defect < 0.1 and outside.defect < 0.1


def test_the_structural_rotors_resonance_lies_between_its_linear_critical_speeds(
        structural):
    """Against the rotor with its bearings linearised at the static load (``rs.modal``):
    the bearings carry the gravity load vertically, so their stiffness is anisotropic and
    the unbalance excites the backward whirl (394.7 rad/s) as well as the forward one
    (425.2 rad/s). Every located maximum of the disk's orbit (six, 403.5-416.0 rad/s: the
    orbit changes shape between the two whirls) lies between them; at the largest (404.4
    rad/s) the journals move by more than the 8 um radial clearance (peak-to-peak,
    vertically), so the clearance is crossed. Both folds lie within 2 rad/s of a peak and
    inside the period-doubling window."""
    model, branch, _ = structural
    linear = rs.modal(model.linearized().rotor, speed=410.0, num_modes=6)
    lateral: dict[str, float] = {}
    for w, k, s in zip(linear.wn, linear.kind, linear.whirl, strict=True):
        if k == "lateral":
            lateral.setdefault(s, float(w))                 # the lowest of each whirl
    backward, forward = lateral["backward"], lateral["forward"]
    peaks = [p for p in branch.peaks if p.kind == "max"]
    assert len(peaks) >= 2 and all(p.located for p in peaks)
    assert all(backward < p.parameter < forward for p in peaks)
    top = max(peaks, key=lambda p: p.amplitude)
    journal = branch.amplitude(0, "uy", "peak_to_peak")[top.index]
    assert journal > 8e-6
    folds = [b.parameter for b in branch.events("fold")]
    doublings = sorted(b.parameter for b in branch.events("period_doubling"))
    assert all(min(abs(f - p.parameter) for p in peaks) < 2.0 for f in folds)
    assert doublings[0] < min(folds) and max(folds) < doublings[1]


# ------------------------------------------------------------------- the mode followed
def test_the_critical_mode_is_the_largest_of_the_events_kind():
    """``critical_mode``: the first multiplier (by decreasing modulus) outside ``1 + margin``
    of the event's kind; the largest when none is (the kind check then rejects the event)."""
    mu = np.array([-1.35, 1.03, 0.9 + 0.5j, 0.9 - 0.5j, 0.5])
    assert critical_mode(mu, "fold", 0.02) == 1
    assert critical_mode(mu, "branch_point", 0.02) == 1
    assert critical_mode(mu, "period_doubling", 0.02) == 0
    assert critical_mode(mu, "neimark_sacker", 0.02) == 2      # |0.9 + 0.5i| = 1.0296
    assert critical_mode(np.array([-1.35, 1.1 + 0.2j, 1.1 - 0.2j]), "neimark_sacker",
                         0.02) == 1
    assert critical_mode(mu, "fold", 0.05) == 0                 # 1.03 inside 1 + margin
