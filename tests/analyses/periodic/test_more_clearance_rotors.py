"""Two more clearance rotors of issue 16 ("What it must show"): their harmonic-balance
branches reach their stop speeds, and every bifurcation they report is confirmed by time
integration next to it (``rs.verify_events(..., measure="floquet")``: a short free
transient along the event's critical Floquet mode on each side, docs/validation.md case
26, addendum "two more clearance rotors").

- ``models/clearance_rotor_damped.toml``: 2 um clearance, a 27 kg disk at mid-span on two
  8-ball bearings, a linear damper of 150 N s/m on the disk and light contact damping.
  Its damped resonance peaks next to the linearised critical speed, and the lightly damped
  axial mode is excited parametrically near twice its frequency (a period-doubling pair).
- ``models/clearance_rotor_overhung.toml``: see its fixture below.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs

MODELS = Path(__file__).resolve().parents[3] / "models"


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
    _, branch, _ = damped
    assert branch.status == rs.Status.OK and branch.parameter[-1] == 360.0
    assert np.all(branch.residuals <= 1e-6)
    amp = branch.amplitude(10, "uy", "peak_to_peak")
    assert amp.max() > 20 * amp[0]                 # a resonance, passed


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
        stable, unstable = sorted((check.before, check.after), key=lambda s: abs(s.mode))
        assert unstable.mode.imag == 0.0 and unstable.mode.real < -1.01
        # the integration's rate within 1 % of Floquet's multiplier: both are the same
        # linearised period map, measured to the scheme's ~1e-5 per period (case 26)
        assert abs(unstable.measured.real / unstable.mode.real - 1.0) < 0.01
        assert abs(stable.measured) < 1.0


def test_the_damped_rotors_peak_and_parametric_resonance_sit_where_the_linear_rotor_puts_them(
        damped):
    """Against the rotor with its bearings linearised at the static load (``rs.modal``,
    an eigenvalue problem that shares nothing with harmonic balance but the bearing
    model): the disk's orbit peaks within 1 % of the first forward critical speed (the 2 um
    clearance closes at the static load, so the bearings stay near their linearised
    stiffness; measured 280.05 against 280.51 rad/s), and the period-doubling window
    brackets twice the axial natural frequency (the principal parametric resonance of the
    axial mode: 344.0 rad/s in the window 340.9-347.1 rad/s)."""
    model, branch, _ = damped
    linear = rs.modal(model.linearized().rotor, speed=280.0, num_modes=6)
    forward = [w for w, k, s in zip(linear.wn, linear.kind, linear.whirl)
               if k == "lateral" and s == "forward"][0]
    axial = [w for w, k in zip(linear.wn, linear.kind) if k == "axial"][0]
    (peak,) = [p for p in branch.peaks if p.kind == "max"]
    assert peak.located and abs(peak.parameter / forward - 1.0) < 0.01
    lo, hi = sorted(b.parameter for b in branch.bifurcations)
    assert lo < 2.0 * axial < hi and hi - lo < 0.05 * 2.0 * axial
