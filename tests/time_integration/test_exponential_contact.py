"""The error estimate of exponential collocation on steps across a contact change (issue 14):
a mass that hits a Hertz contact across a clearance, each accepted step's estimate against
its local error found by integrating the same step in 16 fixed sub-steps."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from test_exponential import LocalSpring

from rotorsim.time_integration.exponential import Exponential
from rotorsim.time_integration.exponential_modes import HarmonicLoad
from rotorsim.time_integration.problem import SecondOrderProblem

M = np.array([[2.0, 0.0], [0.0, 1.0]])
K = np.array([[300.0, -100.0], [-100.0, 100.0]])
C = 0.002 * K
W = 7.0
F = np.array([0.0, 40.0 + 0j])
GAP, STIFFNESS = 0.1, 1e5
"""Two masses on springs driven on the second (as in ``test_exponential.py``); the first
hits a Hertz contact ``STIFFNESS (|q0| - GAP)^1.5`` on either side of a clearance ``GAP``
[m] (a ball's contact across a bearing clearance, reduced to one DOF). Its amplitude, about
0.17 m, closes the contact twice per period of the load: ``rho`` has a kink in its second
derivative wherever the contact closes or opens."""


class ClearanceContact(LocalSpring):
    """The Hertz contact on DOF 0, evaluated in batches as a rotor's bearings are."""

    def __init__(self) -> None:
        super().__init__(0.0, 0.0)

    def batch(self, q, v, t):
        x = q[:, :1]
        pen = np.maximum(np.abs(x) - GAP, 0.0)
        r = STIFFNESS * pen**1.5 * np.sign(x)
        kt = (1.5 * STIFFNESS * np.sqrt(pen))[:, :, None]
        return self.dofs, r, kt, np.zeros_like(kt)


def steps_checked(rtol: float, t_end: float = 2.0) -> list[tuple[float, float, float]]:
    """``(t, estimate, local error)`` of every accepted step, both in units of the local
    tolerance; the local error is the difference to the same step in 16 fixed sub-steps."""
    load = HarmonicLoad(np.zeros(2), F, W)
    problem = SecondOrderProblem(mass=M, stiffness=K, damping=C,
                                 restoring=ClearanceContact(), load=load)
    stepper = Exponential(load, rtol=rtol)
    fine = dataclasses.replace(stepper, fixed=True)
    state = stepper.init(problem, 0.0, np.zeros(2), np.zeros(2), dt=1e-3)
    rows = []
    while state.t < t_end:
        new = stepper.step(problem, state)
        h = new.history_dt
        sub = dataclasses.replace(state, dt=h / 16)
        for _ in range(16):
            sub = dataclasses.replace(fine.step(problem, sub), dt=h / 16)
        scales = new.cache.scales
        local = float((scales.weights * np.abs(new.q - sub.q)).max()) / (
            stepper.local_tol * scales.scale(new.peak))
        rows.append((state.t, float(new.error), local))
        state = new
    return rows


@pytest.mark.parametrize("rtol", [1e-1, 3e-2])
def test_no_step_across_a_contact_change_passes_with_a_low_estimate(rtol):
    rows = steps_checked(rtol)
    # the sub-steps' own error is about 16^-1 of the step's at a kink (and far less where
    # rho is smooth), so the local error found is good to about 10 %; steps whose local
    # error is below a quarter of the tolerance do not matter to the run. The interpolant
    # difference alone (the estimate before the defect check) passed steps with 12 times
    # the local tolerance at rtol 1e-1 and 3.2 at 3e-2, with estimates 45 to 730 times low
    worst = max(local / max(est, 0.25) for _, est, local in rows)
    assert worst <= 3.0, [r for r in rows if r[2] > 3.0 * max(r[1], 0.25)]
