"""The public harmonic-balance layer ``rs.hb``: elements, system input, scaling, verbs.

References: closed forms (linear and single-harmonic Duffing responses), finite differences
of each element's force, and periodic orbits from scipy's DOP853 at rtol 1e-10
(:mod:`shooting_reference`), none of which use rotorsim.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.optimize as so

import rotorsim as rs
from rotorsim.errors import ModelError, Status
from rotorsim.hb.elements import (
    BilateralGap,
    CoulombFriction,
    CubicSpring,
    HertzContact,
    UnilateralSpring,
)
from rotorsim.hb.response import discretize
from rotorsim.hb.scaling import linear_guess, unknown_scales
from rotorsim.solvers.continuation import Continuation, continue_branch

sys.path.insert(0, str(Path(__file__).parent))
from shooting_reference import first_order, fundamental, periodic_orbit

M_, C_, K_, K3, P = 1.0, 0.05, 1.0, 0.1, 0.18
"""Duffing of /work/shared/reference (and NLvib example 01)."""


def duffing(force: float = P, k3: float = K3) -> rs.hb.System:
    return rs.hb.System(M_, K_, C_, forcing=[force], elements=[CubicSpring(0, k3=k3)])


def single_harmonic_peak() -> tuple[float, float]:
    """Largest amplitude of ``[(k - m W^2 + 3/4 k3 A^2)^2 + (c W)^2] A^2 = P^2`` (m = 1):
    ``dA/dW = 0`` gives ``k - W^2 + 3/4 k3 A^2 = c^2 / 2`` and ``A^2 (c^4/4 + c^2 W^2) =
    P^2``, one equation in ``u = A^2``. The shared reference prints 2.84162 at 1.26663."""
    kap = 0.75 * K3

    def eq(u):
        return u * (C_**4 / 4 + C_**2 * (K_ + kap * u - C_**2 / 2)) - P**2

    u = so.brentq(eq, 1.0, 20.0, xtol=1e-15, rtol=1e-15)
    return math.sqrt(K_ + kap * u - C_**2 / 2), math.sqrt(u)


# ----------------------------------------------------------------------------- elements
ELEMENTS = [
    CubicSpring(0, k3=2.5),
    CubicSpring(0, k3=-0.7, other=1),
    UnilateralSpring(0, stiffness=40.0, gap=0.3),
    UnilateralSpring(1, stiffness=40.0, gap=0.2, other=0, side=-1),
    BilateralGap(0, stiffness=15.0, gap=0.25),
    BilateralGap(0, stiffness=15.0, gap=0.0, other=1),
    HertzContact(0, stiffness=7.0, gap=0.1),
    HertzContact(1, stiffness=7.0, gap=0.1, exponent=10 / 9, other=0, side=-1),
    CoulombFriction(0, limit_force=1.3, eps=0.05),
    CoulombFriction(1, limit_force=1.3, eps=0.05, other=0),
]


@pytest.mark.parametrize("element", ELEMENTS, ids=lambda e: f"{type(e).__name__}{e.dofs}")
def test_element_tangents_match_central_differences(element):
    """Exact tangents against central differences (relative step 1e-6: truncation and
    round-off both below 1e-7 of the largest tangent), at random samples kept 1e-3 away
    from the switching points of piecewise laws (contact onset at u = +-gap)."""
    rng = np.random.default_rng(7)
    d = len(element.dofs)
    q, v = rng.uniform(-1.5, 1.5, (400, d)), rng.uniform(-0.3, 0.3, (400, d))
    w = np.array([1.0] if d == 1 else [1.0, -1.0])
    gap = getattr(element, "gap", None)
    if gap is not None:
        u = q @ w
        keep = np.min(np.abs(np.abs(u)[:, None] - np.array([[gap]])), axis=1) > 1e-3
        q, v = q[keep], v[keep]
    f, dfdq, _ = element.evaluate(q, v)
    assert f.shape == q.shape and dfdq.shape == (q.shape[0], d, d)
    assert rs.hb.check_tangents(element, q, v) < 1e-7
    # action and reaction: the forces on the two DOFs cancel
    if d == 2:
        np.testing.assert_array_equal(f[:, 0], -f[:, 1])


def test_element_laws_at_hand_computed_points():
    q = np.array([[-2.0], [-0.5], [0.2], [1.5]])
    v = np.zeros_like(q)
    f = UnilateralSpring(0, stiffness=10.0, gap=1.0).evaluate(q, v)[0].ravel()
    assert f.tolist() == [0.0, 0.0, 0.0, 5.0]
    f = UnilateralSpring(0, stiffness=10.0, gap=1.0, side=-1).evaluate(q, v)[0].ravel()
    assert f.tolist() == [-10.0, 0.0, 0.0, 0.0]
    f = BilateralGap(0, stiffness=10.0, gap=1.0).evaluate(q, v)[0].ravel()
    assert f.tolist() == [-10.0, 0.0, 0.0, 5.0]
    f = HertzContact(0, stiffness=2.0, gap=0.5).evaluate(q, v)[0].ravel()
    assert f[:3].tolist() == [0.0, 0.0, 0.0] and f[3] == pytest.approx(2.0)
    f = CoulombFriction(0, limit_force=3.0, eps=1e-3).evaluate(v, q)[0]
    np.testing.assert_allclose(f.ravel(), [-3.0, -3.0, 3.0, 3.0], rtol=1e-12)


class QuadraticDamper:
    """A user element through the protocol: ``f = d v |v|`` (NLvib's quadraticDamper
    family, here on one DOF)."""

    dofs = (0,)

    def __init__(self, d: float) -> None:
        self.d = d

    def evaluate(self, q, v):
        return (self.d * v * np.abs(v), np.zeros((q.shape[0], 1, 1)),
                (2 * self.d * np.abs(v))[:, :, None])


def test_user_element_follows_the_protocol_and_matches_shooting():
    element = QuadraticDamper(0.4)
    assert isinstance(element, rs.hb.Element)
    assert rs.hb.check_tangents(element, np.zeros((20, 1)),
                                np.linspace(0.1, 2.0, 20)[:, None]) < 1e-7
    system = rs.hb.System(1.0, 1.0, 0.02, forcing=[0.3], elements=[element])
    point = rs.hb.solve(system, 0.9, harmonics=15, samples=256)
    rhs = first_order(1.0, 0.02, 1.0, lambda q, v: 0.4 * v * np.abs(v),
                      lambda t: np.array([0.3 * math.cos(0.9 * t)]))
    T = 2 * math.pi / 0.9
    y, _ = periodic_orbit(rhs, _state(point), T)
    # |v| v has a jump in its second derivative: H = 15 leaves 1.6e-8 (measured)
    assert point.amplitude(0) == pytest.approx(fundamental(rhs, y, T, 0), rel=1e-6)


def _state(point):
    """``[q(0), q'(0)]`` of a Point."""
    X = point.coefficients
    h = np.arange(1, point.harmonics + 1)[:, None]
    return np.concatenate([X[0] + X[1::2].sum(axis=0),
                           point.omega * np.sum(h * X[2::2], axis=0)])


@pytest.mark.parametrize("element, force, omega, rel", [
    (HertzContact(0, stiffness=5.0, gap=0.2), lambda q, v: 5.0 * max(q[0] - 0.2, 0) ** 1.5,
     1.1, 1e-6),
    (BilateralGap(0, stiffness=3.0, gap=0.3),
     lambda q, v: 3.0 * (q[0] - 0.3 * np.sign(q[0])) * (abs(q[0]) > 0.3), 1.2, 1e-5),
    (CoulombFriction(0, limit_force=0.05, eps=0.02), lambda q, v: 0.05 * np.tanh(v / 0.02),
     0.95, 1e-3),
], ids=["hertz", "bilateral_gap", "friction"])
def test_element_responses_match_shooting(element, force, omega, rel):
    """One-DOF oscillator ``q'' + 0.05 q' + q + f = 0.2 cos(W t)`` per element, HB with
    H = 25, N = 512 against shooting (DOP853, rtol 1e-10). The truncation error of H = 25
    depends on the smoothness of the law: measured 6e-8 for Hertz (``d^1.5``: a jump in
    the second derivative), 1.2e-6 for the gap (a jump in the stiffness) and 1.4e-4 for
    the friction (``tanh(v / 0.02)`` switches within 1.5 % of the velocity amplitude);
    each bound is ten times that."""
    system = rs.hb.System(1.0, 1.0, 0.05, forcing=[0.2], elements=[element])
    frf = rs.hb.frequency_response(system, 0.6, omega, harmonics=25, samples=512,
                                   stability=None, bifurcations=False)
    assert frf.status == Status.OK and frf.omega[-1] == omega
    point = rs.hb.solve(system, omega, harmonics=25, samples=512, x0=frf.branch.x[-1])
    rhs = first_order(1.0, 0.05, 1.0, lambda q, v: np.array([force(q, v[0])]).reshape(1),
                      lambda t: np.array([0.2 * math.cos(omega * t)]))
    T = 2 * math.pi / omega
    y, _ = periodic_orbit(rhs, _state(point), T)
    assert point.amplitude(0) == pytest.approx(fundamental(rhs, y, T, 0), rel=rel)


# ------------------------------------------------------------------------------- input
@pytest.mark.parametrize("make, where", [
    (lambda: rs.hb.System(np.eye(2), np.eye(2), elements=[CubicSpring(2, k3=1.0)]),
     "hb.System.elements[0] (CubicSpring): DOF 2 is outside [0, 2)"),
    (lambda: rs.hb.System(np.eye(2), np.eye(2), elements=[
        CubicSpring(0, k3=1.0), UnilateralSpring(0, stiffness=1.0, other=-1)]),
     "hb.System.elements[1] (UnilateralSpring): DOF -1 is outside"),
    (lambda: rs.hb.System(np.eye(2), np.eye(2), forcing=[rs.hb.Forcing(3, 1.0)]),
     "hb.System.forcing[0]: DOF 3 is outside [0, 2)"),
    (lambda: rs.hb.System(np.eye(2), np.eye(2), forcing=[1.0, 2.0, 3.0]),
     "hb.System.forcing: a force vector needs 2 finite entries"),
    (lambda: rs.hb.System(np.ones((2, 3)), np.eye(2)), "hb.System.mass: must be square"),
    (lambda: rs.hb.System(np.eye(2), np.ones((2, 3))), "hb.System.stiffness: must be square"),
    (lambda: rs.hb.System(np.eye(2), np.eye(3)),
     "hb.System.stiffness: shape (3, 3) differs from the mass matrix (2, 2)"),
    (lambda: rs.hb.System(np.eye(2), np.eye(2), damping=[[1.0, np.nan], [0.0, 1.0]]),
     "hb.System.damping: contains NaN"),
    (lambda: rs.hb.System(np.eye(2), np.eye(2), elements=[object()]),
     "hb.System.elements[0] (object): is not an element"),
    (lambda: UnilateralSpring(0, stiffness=10.0, gap=-0.1),
     "UnilateralSpring.gap: must be >= 0 (a clearance), got -0.1"),
    (lambda: BilateralGap(0, stiffness=10.0, gap=-1.0), "BilateralGap.gap: must be >= 0"),
    (lambda: HertzContact(0, stiffness=-1.0), "HertzContact.stiffness: must be > 0"),
    (lambda: HertzContact(0, stiffness=1.0, exponent=0.5), "HertzContact.exponent"),
    (lambda: CoulombFriction(0, limit_force=1.0, eps=0.0), "CoulombFriction.eps: must be > 0"),
    (lambda: CubicSpring(1, k3=1.0, other=1), "CubicSpring: other = dof = 1"),
    (lambda: CubicSpring(0.5, k3=1.0), "CubicSpring: dof must be an integer"),
    (lambda: rs.hb.Forcing(0, 1.0, harmonic=-1), "Forcing.harmonic: must be an integer"),
])
def test_bad_input_names_what_and_where(make, where):
    with pytest.raises(ModelError) as info:
        make()
    assert where in str(info.value)


def test_bad_verb_arguments():
    system = duffing()
    with pytest.raises(ModelError, match=r"hb\.start: must be a positive finite"):
        rs.hb.frequency_response(system, -1.0, 2.0)
    with pytest.raises(ModelError, match="start = stop"):
        rs.hb.frequency_response(system, 1.0, 1.0)
    with pytest.raises(TypeError, match="unknown stability 'floquet'"):
        rs.hb.frequency_response(system, 0.5, 1.0, stability="floquet")
    with pytest.raises(ModelError, match="forcing at harmonic 3 needs harmonics >= 3"):
        rs.hb.solve(rs.hb.System(1.0, 1.0, forcing=[rs.hb.Forcing(0, 1.0, 3)]), 1.0,
                    harmonics=2)
    with pytest.raises(ModelError, match="DOF 4 is outside"):
        rs.hb.amplitude(np.zeros((3, 1)), 4)
    bad = rs.hb.System(1.0, 1.0, elements=[_WrongShape()], forcing=[1.0])
    with pytest.raises(ModelError, match=r"elements\[0\] \(_WrongShape\): returned f of shape"):
        rs.hb.solve(bad, 1.0, harmonics=1)


class _WrongShape:
    dofs = (0,)

    def evaluate(self, q, v):
        return np.zeros(q.shape[0]), np.zeros((q.shape[0], 1, 1)), None


# ----------------------------------------------------------------------------- scaling
def test_continuation_auto_scale_at_a_zero_start_is_the_newton_step():
    """``x_scale="auto"`` at ``x0 = 0`` takes ``max |dx|`` of the Newton step from 0,
    here the linear response 2e-3 / (1 - 0.04) (it used to be 1)."""
    def linear(x, lam):
        return (1 - lam**2) * x - 2e-3, np.diag(np.full(1, 1 - lam**2)), -2 * lam * x

    b = continue_branch(linear, [0.0], 0.2, Continuation(x_scale="auto", r_scale="auto",
                                                         lam_max=0.5))
    assert b.x_scale[0] == pytest.approx(2e-3 / 0.96, rel=1e-12)
    nonzero = continue_branch(linear, [3e-3], 0.2, Continuation(x_scale="auto", lam_max=0.5))
    assert nonzero.x_scale[0] == 3e-3                  # unchanged rule: max |x0|


def test_hb_scales_come_from_the_linear_response():
    frf_system = duffing()
    residual = discretize(frf_system, 3)
    guess = linear_guess(residual, 0.5)
    linear = P / math.hypot(K_ - 0.25, C_ * 0.5)       # |Q_1| of the linear oscillator
    assert np.hypot(*guess[1:3]) == pytest.approx(linear, rel=1e-12)
    np.testing.assert_allclose(unknown_scales(residual, guess), np.abs(guess[1:3]).max())


def test_a_micrometre_system_traces_like_the_unit_one():
    """The Duffing in micrometres (forces x 1e-6, k3 x 1e12) is the same curve scaled by
    1e-6: with automatic scales the continuation takes the same steps (a fixed scale of
    1 would see a straight line in frequency)."""
    unit = rs.hb.frequency_response(duffing(), 0.5, 1.6, harmonics=3, stability=None)
    micro = rs.hb.frequency_response(duffing(P * 1e-6, K3 * 1e12), 0.5, 1.6, harmonics=3,
                                     stability=None)
    assert len(micro) == len(unit) and micro.status == Status.OK
    np.testing.assert_allclose(micro.omega, unit.omega, rtol=1e-8)
    np.testing.assert_allclose(micro.amplitude(0) * 1e6, unit.amplitude(0), rtol=1e-7)
    assert [b.kind for b in micro.bifurcations] == ["fold", "fold"]


# ------------------------------------------------------------------------------- verbs
def test_linear_system_matches_the_closed_form():
    system = rs.hb.System(2.0, 8.0, 0.4, forcing=[rs.hb.Forcing(0, 0.5, phase=0.3)])
    frf = rs.hb.frequency_response(system, 1.0, 3.0, harmonics=2, max_step=0.1)
    w = frf.omega
    exact = 0.5 / np.hypot(8.0 - 2.0 * w**2, 0.4 * w)
    np.testing.assert_allclose(frf.amplitude(0), exact, rtol=1e-9)
    assert frf.status == Status.OK and frf.stable.all() and frf.bifurcations == ()
    peak = frf.peak(0)        # |dA/dW| = 0 at W^2 = k/m - c^2 / (2 m^2)
    assert peak.omega == pytest.approx(math.sqrt(4.0 - 0.4**2 / 8.0), rel=1e-6)


def test_duffing_in_five_lines_matches_the_single_harmonic_closed_form():
    duffing_system = rs.hb.System(mass=1, stiffness=1, damping=0.05, forcing=[0.18],
                                  elements=[rs.hb.CubicSpring(0, k3=0.1)])
    frf = rs.hb.frequency_response(duffing_system, start=0.5, stop=1.6, harmonics=1)
    peak = frf.peak(0)
    w_ref, a_ref = single_harmonic_peak()
    assert (round(a_ref, 5), round(w_ref, 5)) == (2.84162, 1.26663)   # shared reference
    # the peak is refined by Brent on the branch to |ds| 1e-9: error ~ solve tolerance
    assert peak.refined and peak.amplitude == pytest.approx(a_ref, rel=1e-9)
    assert peak.omega == pytest.approx(w_ref, rel=1e-7)
    assert frf.status == Status.OK and frf.omega[-1] == 1.6
    assert [b.kind for b in frf.bifurcations] == ["fold", "fold"]
    # along the branch: stable up to the first fold, unstable between the folds (the
    # middle branch), stable after the second
    first, second = (b.index for b in frf.bifurcations)
    assert frf.stable[:first + 1].all() and frf.stable[second + 1:].all()
    assert not frf.stable[first + 1:second + 1].any()


def test_measures_and_point_helpers():
    point = rs.hb.solve(duffing(), 1.0, harmonics=5)
    t, q = point.time_response(512)
    assert point.amplitude(0, "peak") == pytest.approx(np.abs(q).max(), rel=1e-3)
    assert point.amplitude(0, "rms") == pytest.approx(np.sqrt(np.mean(q[:, 0] ** 2)),
                                                      rel=1e-12)
    assert point.amplitude(0, "harmonic", 3) < 0.05 * point.amplitude(0)
    assert t[-1] < 2 * math.pi / point.omega
    with pytest.raises(TypeError, match="unknown measure 'max'"):
        point.amplitude(0, "max")


def test_plot_draws_the_curve(tmp_path):
    pytest.importorskip("matplotlib")
    frf = rs.hb.frequency_response(duffing(), 0.8, 1.4, harmonics=3)
    fig = frf.plot(0)
    fig.savefig(tmp_path / "frf.png")
    assert (tmp_path / "frf.png").stat().st_size > 10000
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert {"stable", "unstable", "fold"} <= set(labels)


def test_sparse_and_gyroscopic_systems():
    """Sparse ``M, K`` and a gyroscopic ``G`` scaled by ``W = Omega`` (``spin_ratio=1``),
    linear: the harmonic-1 coefficients solve ``(K - W^2 M + i W (C + W G)) Q = p`` with
    ``q = Re(Q e^{i W t})``, ``Q = Q_c - i Q_s``."""
    import scipy.sparse as sparse

    g = 0.3
    G = sparse.csr_matrix([[0.0, g], [-g, 0.0]])
    forcing = [rs.hb.Forcing(0, 0.1), rs.hb.Forcing(1, 0.1, phase=-math.pi / 2)]
    system = rs.hb.System(sparse.identity(2), 2.0 * sparse.identity(2), 0.1 * np.eye(2),
                          G, forcing=forcing, spin_ratio=1.0)
    point = rs.hb.solve(system, 1.2, harmonics=1)
    X = point.coefficients
    w = 1.2
    A = np.array([[2.0 - w**2 + 1j * w * 0.1, 1j * w * w * g],
                  [-1j * w * w * g, 2.0 - w**2 + 1j * w * 0.1]])
    Q = np.linalg.solve(A, [0.1, -0.1j])
    np.testing.assert_allclose(X[1] - 1j * X[2], Q, rtol=1e-10)
