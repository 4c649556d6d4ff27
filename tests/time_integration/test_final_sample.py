"""The samples of a time integration always end with the state at ``t_end`` (issue 12):
the last step is shortened when ``dt`` does not divide the span, and ``every`` never drops
the final state."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.output import OutputSpec
from rotorsim.time_integration.problem import SecondOrderProblem


def oscillator() -> SecondOrderProblem:
    return SecondOrderProblem(mass=np.eye(1), stiffness=4.0 * np.eye(1))


@pytest.mark.parametrize(("dt", "every", "steps", "times"), [
    (0.3, 5, 4, [0.0, 1.0]),            # 0.3, 0.6, 0.9, 1.0: 4 steps, none a 5th
    (0.1, 3, 10, [0.0, 0.3, 0.6, 0.9, 1.0]),
    (0.25, 2, 4, [0.0, 0.5, 1.0]),      # a multiple of every: nothing added twice
])
def test_every_keeps_the_final_state_at_t_end(dt, every, steps, times):
    res = integrate(oscillator(), Newmark(), (0.0, 1.0), [1.0], [0.0], dt=dt,
                    output=OutputSpec(every=every))
    assert res.stats["steps"] == steps
    # the times are sums of dt (round-off of a few ulps), the last one is set to t_end
    np.testing.assert_allclose(res.t, times, rtol=0, atol=1e-12)
    assert res.t[-1] == 1.0 == res.state.t
    assert np.array_equal(res.q[-1], res.state.q) and np.array_equal(res.v[-1], res.state.v)


def test_resuming_a_finished_run_keeps_the_final_state_once(tmp_path):
    path = tmp_path / "run.h5"
    args = (oscillator(), Newmark(), (0.0, 1.0), [1.0], [0.0])
    spec = OutputSpec(every=5)
    whole = integrate(*args, dt=0.3, output=spec, checkpoint=path, checkpoint_every=4)
    again = integrate(*args, dt=0.3, output=spec, resume=path)
    assert np.array_equal(whole.t, again.t) and np.array_equal(whole.q, again.q)
    assert whole.t.tolist() == [0.0, 1.0]


def test_rotor_transient_reaches_t_end_with_every():
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel)] * 4
    rotor = rs.Rotor(shaft, bearing_elements=[rs.BearingElement(n=0, kxx=1e7, cxx=1e3),
                                              rs.BearingElement(n=4, kxx=1e7, cxx=1e3)])
    res = rs.transient(rotor, 1.0, 0.3, output=rs.Output(every=5), initial="zero", nodes=[2],
                       unbalance=[(2, 1e-4, 0.0)], speed=50.0)
    assert res.t.tolist() == [0.0, 1.0] and res.stats["steps"] == 4
    assert res.speed.shape == (2,) and res.q.shape == (2, 6)
    assert np.any(res.q[-1] != 0.0)  # the state at t_end, not a copy of the start


def test_on_failure_stop_keeps_the_run_up_to_the_failed_step(tmp_path):
    def load(t):
        return np.array([np.nan if t > 1.01 else 0.0])

    problem = SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1), load=load)
    args = (problem, Newmark(), (0.0, 5.0), [1.0], [0.0])
    with pytest.raises(rs.ConvergenceError, match="not finite"):
        integrate(*args, dt=0.05)
    path = tmp_path / "run.h5"
    res = integrate(*args, dt=0.05, output=OutputSpec(every=7), on_failure="stop",
                    checkpoint=path, checkpoint_every=100)
    assert res.status == rs.Status.NOT_CONVERGED and "not finite" in res.message
    assert res.state.step == 20 and res.t[-1] == res.state.t == pytest.approx(1.0)
    assert np.array_equal(res.q[-1], res.state.q)  # the last accepted state is kept
    assert res.t.size == 4  # 0, steps 7 and 14, and step 20
    from rotorsim.time_integration.checkpoint import load_checkpoint

    assert load_checkpoint(path)[0].step == 20
    with pytest.raises(rs.ModelError, match="on_failure must be 'raise' or 'stop'"):
        integrate(*args, dt=0.05, on_failure="record")
