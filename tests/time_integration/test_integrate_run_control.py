"""Run control of ``integrate``: continuing from a State, stopping on a predicate, the
reducers (also across a checkpoint resume) and velocities of chosen unknowns."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.time_integration import (
    Adams,
    Newmark,
    OutputSpec,
    Reducer,
    SecondOrderProblem,
    SteadyDetector,
    integrate,
)
from rotorsim.time_integration.base import State

W = 2 * np.pi  # rad/s: period 1 s


def oscillator(damping: float = 0.0, forced: bool = False) -> SecondOrderProblem:
    """Two uncoupled unit oscillators (x, y) with natural frequency W."""
    load = (lambda t: np.array([np.cos(3.0 * t), np.sin(3.0 * t)])) if forced else None
    return SecondOrderProblem(mass=np.eye(2), stiffness=W**2 * np.eye(2),
                              damping=damping * np.eye(2), load=load)


@pytest.mark.parametrize("stepper", [Newmark.average_acceleration(), Adams()],
                         ids=["newmark", "adams"])
def test_continuing_from_the_final_state_equals_one_run(stepper):
    p, q0, v0, dt = oscillator(0.1), [1.0, 0.0], [0.0, 1.0], 0.01
    whole = integrate(p, stepper, (0.0, 2.0), q0, v0, dt=dt)
    first = integrate(p, stepper, (0.0, 1.0), q0, v0, dt=dt)
    second = integrate(p, stepper, (1.0, 2.0), None, None, dt=dt, start=first.state)
    # no time-dependent input: the continued steps are the same operations on the same
    # numbers as in the uninterrupted run, bit for bit
    np.testing.assert_array_equal(second.q, whole.q[100:])
    np.testing.assert_array_equal(second.state.history, whole.state.history)
    assert second.stats["steps"] == 100 and second.state.step == 200


def test_start_is_checked():
    p = oscillator()
    s = integrate(p, Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 0.0], dt=0.1).state
    with pytest.raises(ModelError, match=r"integrate\.start: start is at t = 1\.0"):
        integrate(p, Newmark(), (0.5, 2.0), None, None, dt=0.1, start=s)
    with pytest.raises(ModelError, match=r"integrate\.start: start has 2 unknowns"):
        integrate(SecondOrderProblem(mass=np.eye(3), stiffness=np.eye(3)), Newmark(),
                  (1.0, 2.0), None, None, dt=0.1, start=s)


def test_stop_when_ends_the_run_with_its_reason():
    p = oscillator()
    res = integrate(p, Newmark(), (0.0, 10.0), [1.0, 0.0], [0.0, 0.0], dt=0.01,
                    output=OutputSpec(every=1000),
                    stop_when=lambda s: "far enough" if s.step >= 250 else "")
    assert res.stopped == "far enough" and res.state.t == pytest.approx(2.5)
    assert res.t[-1] == res.state.t and res.status == 0  # the final state is kept


def test_steady_detector_stops_a_damped_forced_oscillator():
    """Forced at 3 rad/s, the free vibration decays as exp(-0.5 c t); the detector stops
    once the peak-to-peak per forcing period has settled."""
    p = oscillator(damping=2.0, forced=True)
    period = 2 * np.pi / 3.0
    stop = SteadyDetector(lambda s: s.t / period, rtol=1e-4, revolutions=2)
    res = integrate(p, Newmark(), (0.0, 100.0), [0.0, 0.0], [0.0, 0.0], dt=period / 200,
                    stop_when=stop)
    # the transient e^{-t} falls below 1e-4 of the orbit by t ~ 10 s; settled for sure when
    # 4 |transient| <= 1e-4 2 |orbit| (the bound of the peak-to-peak change)
    assert res.stopped.startswith("steady") and 4.0 < res.state.t < 16.0
    assert stop.change <= 1e-4 and stop.segment_index == round(res.state.t / period) - 1


def test_reducers_survive_a_checkpoint_resume(tmp_path):
    p = oscillator(0.3, forced=True)
    spec = OutputSpec(every=7, reducers=(
        Reducer("rms", dofs=(0,)), Reducer("max_amplitude", name="amp"),
        Reducer("peak_to_peak", segment=lambda s: s.t / 0.5, segment_label="half"),
        Reducer("peak_to_peak", quantity="v", transform=np.array([[1.0, -1.0]]),
                name="whole", after=1.0)))
    args = (p, Newmark(), (0.0, 3.0), [1.0, 0.0], [0.0, 1.0])
    whole = integrate(*args, dt=0.01, output=spec)
    path = tmp_path / "ck.h5"

    class Stop(Exception):
        pass

    def interrupt(state: State) -> None:
        if state.step == 123:
            raise Stop

    with pytest.raises(Stop):
        integrate(*args, dt=0.01, output=spec, checkpoint=path, checkpoint_every=50,
                  callback=interrupt)
    resumed = integrate(*args, dt=0.01, output=spec, checkpoint=path, resume=path)
    assert list(resumed.reduced) == ["rms_q", "amp", "peak_to_peak_q",
                                     "peak_to_peak_q_half", "whole"]
    for key, value in whole.reduced.items():
        np.testing.assert_array_equal(resumed.reduced[key], value, err_msg=key)
    assert whole.reduced["peak_to_peak_q"].shape == (6, 2)  # half-second segments
    amp = np.hypot(whole.q[:, 0], whole.q[:, 1]).max()  # sampled every 7th step only
    assert whole.reduced["amp"][0] >= amp


def test_velocities_of_chosen_unknowns_only():
    p = oscillator()
    res = integrate(p, Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 1.0], dt=0.01,
                    output=OutputSpec(times=np.linspace(0.1, 1.0, 10), velocities=[1]))
    full = integrate(p, Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 1.0], dt=0.01,
                     output=OutputSpec(times=np.linspace(0.1, 1.0, 10)))
    assert res.v.shape == (10, 1) and res.v_dofs.tolist() == [1]
    np.testing.assert_array_equal(res.v[:, 0], full.v[:, 1])
    none = integrate(p, Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 1.0], dt=0.01,
                     output=OutputSpec(velocities=False))
    assert none.v is None and none.v_dofs is None


def test_reducers_are_checked():
    with pytest.raises(ModelError, match="even number"):
        integrate(oscillator(), Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 0.0], dt=0.1,
                  output=OutputSpec(reducers=(Reducer("max_amplitude", dofs=(0,)),)))
    with pytest.raises(ModelError, match="'dofs' or 'transform'"):
        Reducer(dofs=(0,), transform=np.eye(2))
    with pytest.raises(ModelError, match="peak_to_peak"):
        Reducer("rms", segment=lambda s: s.t)
    with pytest.raises(TypeError, match="unknown reducer kind 'mean'"):
        Reducer("mean")  # type: ignore[arg-type]
