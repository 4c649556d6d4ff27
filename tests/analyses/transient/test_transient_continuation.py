"""Continued transients (``initial=previous``): equal to an uninterrupted run, also from a
results file and after a Craig-Bampton reduction; mismatches refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.transient.speed_profile import LinearSpeed
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model

T_END, DT = 0.004, 2e-5
ADAMS_T_END, ADAMS_DT = 0.001, 2e-6  # the Adams iteration needs small steps on this model
UNBALANCE = [(5, 1e-5, 0.0)]


@pytest.fixture(scope="module")
def rotor() -> rs.Rotor:
    model = load_model("models/rolling_ball.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings)


def _split_runs(rotor, method, speed, t_end, dt, **extra):
    kw = dict(speed=speed, nodes=[5], unbalance=UNBALANCE, method=method, **extra)
    full = rs.transient(rotor, t_end, dt, **kw)
    half = rs.transient(rotor, t_end / 2, dt, **kw)
    rest = rs.transient(rotor, t_end, dt, initial=half, **kw)
    return full, half, rest


# The continued run restores the stepper state exactly, but its inputs differ from the
# uninterrupted run's by round-off: the uninterrupted run reaches T/2 by adding dt 100
# times (the continuation starts at T/2 exactly) and computes the angle as
# I(t) - I(0) instead of phi(T/2) + I(t) - I(T/2). Each Newton solve then stops at a
# slightly different iterate within its stopping test |dq| <= 1e-10 max |q| (Newmark; the
# Adams iteration has the same form). The samples agree to that level, not bitwise;
# measured: 6e-15 .. 1.5e-14 of the motion.
NEWTON_LEVEL = 1e-9


@pytest.mark.parametrize("method, t_end, dt", [("newmark", T_END, DT),
                                               ("adams", ADAMS_T_END, ADAMS_DT)])
@pytest.mark.parametrize("speed", ["constant", "run-up"])
def test_continued_run_equals_the_uninterrupted_one(rotor, method, t_end, dt, speed):
    schedule = 300.0 if speed == "constant" else LinearSpeed(0.0, 500.0, 0.0, t_end)
    full, half, rest = _split_runs(rotor, method, schedule, t_end, dt)
    after = full.t >= t_end / 2 - 0.25 * dt
    assert rest.options["initial"] == "continued" and rest.t[0] == half.t[-1] == t_end / 2
    np.testing.assert_allclose(rest.t, full.t[after], rtol=0, atol=1e-12 * t_end)
    # the angle continues: phi(t0) of the continuation is the previous final angle
    assert rest.angle[0] == half.final.angle == half.angle[-1]
    np.testing.assert_allclose(rest.angle, full.angle[after], rtol=1e-14)
    scale = np.abs(full.q).max()
    np.testing.assert_allclose(rest.q, full.q[after], rtol=0, atol=NEWTON_LEVEL * scale)
    # Hertz loads ~ deflection^1.5, the deflections of the order of the motion
    loads = np.abs(full.bearing_loads).max()
    np.testing.assert_allclose(rest.bearing_loads, full.bearing_loads[after], rtol=0,
                               atol=10 * NEWTON_LEVEL * loads)
    for name in ("q", "v"):  # the final states of all free DOFs
        a, b = getattr(rest.final, name), getattr(full.final, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=NEWTON_LEVEL * np.abs(b).max())
    assert rest.stats["steps"] == round(t_end / 2 / dt)  # counts of this call only


def test_final_state_holds_all_free_dofs(rotor):
    res = rs.transient(rotor, T_END / 4, DT, speed=300.0, nodes=[5], unbalance=UNBALANCE)
    final, system = res.final, rs.assemble(rotor)
    assert final.q.shape == final.v.shape == final.a.shape == (system.n_free,)
    assert final.t == res.t[-1] and final.method == res.method and final.reduction == 0
    kept = system.dof_map.full_to_free[res.dofs]
    np.testing.assert_array_equal(final.q[kept], res.q[-1])
    assert final.speed == 300.0 and final.angle == res.angle[-1]


def test_continue_from_a_results_file(rotor, tmp_path):
    kw = dict(speed=300.0, nodes=[5], unbalance=UNBALANCE)
    half = rs.transient(rotor, T_END / 2, DT, **kw)
    rs.save(half, tmp_path / "half.h5")
    loaded = rs.load(tmp_path / "half.h5")
    from_file = rs.transient(rotor, T_END, DT, initial=loaded, **kw)
    in_memory = rs.transient(rotor, T_END, DT, initial=half, **kw)
    # the file holds every float64 bit of the state: the same computation
    np.testing.assert_array_equal(from_file.q, in_memory.q)


def test_reduced_run_continues_from_its_reduced_state(rotor):
    full, half, rest = _split_runs(rotor, "newmark", 300.0, T_END, DT, reduction=8)
    assert half.final.reduction == half.options["reduction"]["size"]
    system = rs.assemble(rotor)
    assert half.final.q.shape == (system.n_free,)  # expanded to the physical DOFs
    kept = system.dof_map.full_to_free[half.dofs]
    # the physical state is T x: equal to the expanded samples up to round-off of T x
    np.testing.assert_allclose(half.final.q[kept], half.q[-1], rtol=0,
                               atol=1e-12 * np.abs(half.q).max())
    after = full.t >= T_END / 2 - 0.25 * DT
    np.testing.assert_allclose(rest.q, full.q[after], rtol=0,
                               atol=NEWTON_LEVEL * np.abs(full.q).max())  # as above


@pytest.mark.parametrize("change, where, match", [
    (dict(t_end=(0.001, 0.004)), "t_end", "starts there"),
    (dict(t_end=0.001), "t_end", "after the end"),
    (dict(method="adams"), "method", "same method"),
    (dict(speed=400.0), "speed", "continues it"),
    (dict(reduction=8), "reduction", "same reduction"),
])
def test_continuation_refuses_a_mismatch(rotor, change, where, match):
    kw = dict(speed=300.0, nodes=[5], unbalance=UNBALANCE)
    half = rs.transient(rotor, T_END / 2, DT, **kw)
    args = dict(t_end=T_END, dt=DT, initial=half, **kw)
    args.update(change)
    with pytest.raises(ModelError, match=rf"transient\.{where}: .*{match}"):
        rs.transient(rotor, **args)


def test_continuation_refuses_another_model(rotor):
    half = rs.transient(rotor, T_END / 2, DT, speed=300.0, nodes=[5])
    softer = rotor.with_nonlinear([dataclasses.replace(b, bearing=dataclasses.replace(
        b.bearing, Kn=0.5 * b.bearing.Kn)) for b in rotor.nonlinear_elements])
    stiffer_shaft = rs.Rotor(
        [dataclasses.replace(e, odl=1.01 * e.odl) for e in rotor.shaft_elements],
        rotor.disk_elements, rotor.bearing_elements).with_nonlinear(rotor.nonlinear_elements)
    with pytest.raises(ModelError, match=r"transient\.initial: the model differs"):
        rs.transient(stiffer_shaft, T_END, DT, speed=300.0, nodes=[5], initial=half)
    n = len(rotor.shaft_elements) - 1
    shorter = rs.Rotor(rotor.shaft_elements[:-1], rotor.disk_elements,
                       [rs.BearingElement(n=0, kxx=1e7), rs.BearingElement(n=n, kxx=1e7)])
    with pytest.raises(ModelError, match=r"transient\.initial: .* free DOFs"):
        rs.transient(shorter, T_END, DT, speed=300.0, initial=half,
                     excitation=rs.Excitation(gravity=None))
    # the bearing model itself is not part of the matrices: a continuation on softer
    # contacts is the user's choice (documented), and runs
    assert rs.transient(softer, 0.0021, DT, speed=300.0, nodes=[5], initial=half).t[0] \
        == half.t[-1]


def test_a_result_without_final_state_cannot_be_continued(rotor):
    half = rs.transient(rotor, T_END / 4, DT, speed=300.0, nodes=[5])
    with pytest.raises(ModelError, match=r"transient\.initial: .*no final state"):
        rs.transient(rotor, T_END, DT, speed=300.0, initial=dataclasses.replace(
            half, final=None))


def test_a_state_from_an_older_fingerprint_is_refused_by_name(rotor):
    half = rs.transient(rotor, T_END / 4, DT, speed=300.0, nodes=[5])
    assert half.final is not None
    older = dataclasses.replace(half.final, problem=half.final.problem[2:])  # no "2-"
    with pytest.raises(ModelError, match=r"transient\.initial: .*older rotorsim"):
        rs.transient(rotor, T_END, DT, speed=300.0, initial=older)


def test_the_fingerprint_tells_dense_matrices_apart_by_any_entry():
    from rotorsim.time_integration.problem import content_digest
    A = np.diag([1.0, 2.0, 3.0])
    B = A.copy()
    B[0, 2] = 1e-300  # a new non-zero entry, however small
    C = A.copy()
    C[1, 1] = np.nextafter(2.0, 3.0)  # one value one ulp off
    digests = {content_digest(X) for X in (A, B, C, A.reshape(3, 3)[:, ::-1])}
    assert len(digests) == 4 and content_digest(A.copy()) == content_digest(A)
