"""rs.switch_branch and periodic(peaks=...) on a small rotor.

The rotor: a 0.3 m, 40 mm steel shaft (two elements) with a 200 mm disk at mid-span on
two linear bearings (2e6 N/m, 100 N s/m), a hardening spring ``k3 uy^3`` (k3 = 3.6e14
N/m^3) at the disk, turning slowly (10 rad/s) under gravity, its housing shaken
vertically (9 um) at the continued frequency. Gravity preloads the cubic spring, so the
disk's vertical motion about its sag has a quadratic stiffness term: driven near twice its
natural frequency (about 2 x 600 rad/s) its response period-doubles, the rotor version of
the preloaded Duffing oscillator of ``tests/harmonic_balance/test_branch_switching.py``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rotorsim as rs
from rotorsim.elements.base import ElementForce
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.branch_switching import spread_harmonics

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


@dataclass(frozen=True)
class CubicSpring:
    """``f_y = k3 uy^3`` at node ``n`` (a user nonlinear element)."""

    n: int
    k3: float
    contact_damping: str = "none"

    @property
    def nodes(self) -> tuple[int, ...]:
        return (self.n,)

    def force(self, u, v, phi, speed, internal=None):
        S = u.shape[0]
        f, K = np.zeros((S, 6)), np.zeros((S, 6, 6))
        f[:, 1] = self.k3 * u[:, 1] ** 3
        K[:, 1, 1] = 3 * self.k3 * u[:, 1] ** 2
        return ElementForce(f, K, np.zeros((S, 6, 6)))


@dataclass(frozen=True)
class CoupledSpring:
    """Potential ``g (x^4 + y^4) / 4 + b x^2 y^2 / 2`` in ``(ux, uy)`` at node ``n``."""

    n: int
    g: float
    b: float
    contact_damping: str = "none"

    @property
    def nodes(self) -> tuple[int, ...]:
        return (self.n,)

    def force(self, u, v, phi, speed, internal=None):
        S, x, y = u.shape[0], u[:, 0], u[:, 1]
        f, K = np.zeros((S, 6)), np.zeros((S, 6, 6))
        f[:, 0] = self.g * x**3 + self.b * x * y**2
        f[:, 1] = self.g * y**3 + self.b * x**2 * y
        K[:, 0, 0] = 3 * self.g * x**2 + self.b * y**2
        K[:, 1, 1] = 3 * self.g * y**2 + self.b * x**2
        K[:, 0, 1] = K[:, 1, 0] = 2 * self.b * x * y
        return ElementForce(f, K, np.zeros((S, 6, 6)))


def rotor(k3: float = 3.6e14) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    bearings = [rs.BearingElement(n=n, kxx=2e6, kyy=2e6, cxx=100, cyy=100) for n in (0, 2)]
    return rs.Rotor(shaft, [disk], bearings, nonlinear_elements=[CubicSpring(1, k3)])


SHAKER = rs.Excitation(base=rs.HarmonicBase(9e-6))
COMMON = {"parameter": "frequency", "speed": 10.0, "harmonics": 2, "nodes": [1],
          "excitation": SHAKER, "stability": "hsu"}
GRAVITY = 9.80665


@pytest.fixture(scope="module")
def period_one():
    return rs.periodic(rotor(), start=1150.0, stop=1250.0,
                       continuation=rs.ContinuationOptions(max_step=0.1),
                       **{**COMMON, "nodes": None})


def doubling(result: rs.PeriodicResult) -> rs.PeriodicBifurcation:
    """The period doubling of the branch: confirmed, or left unresolved by the screen of
    spurious sign changes (on this coarse branch, 13 points over 100 rad/s, its
    multiplier moves from -0.98 to -1.03 between two points: a genuine, smooth doubling,
    which the switch confirms by the singular odd block)."""
    [pd] = [b for b in (*result.bifurcations, *result.unresolved)
            if b.kind == "period_doubling"]
    return pd


@pytest.fixture(scope="module")
def period_two(period_one):
    return rs.switch_branch(rotor(), period_one, doubling(period_one), stop=1250.0,
                            harmonics=8, stability="hsu",
                            continuation=rs.ContinuationOptions(max_step=0.1))


def test_period_two_branch_from_a_rotor_period_doubling(period_one, period_two):
    res, two = period_one, period_two
    pd = doubling(res)
    assert all(b.kind == "period_doubling" for b in (*res.bifurcations, *res.unresolved))
    assert two.status.name == "OK" and two.parameter[-1] == pytest.approx(1250.0)
    assert two.harmonics == 8 and two.samples == 2 * res.samples
    assert np.allclose(two.fundamental, two.parameter / 2)      # omega / 2
    sw = two.options["switched_from"]
    assert sw["kind"] == "period_doubling" and sw["singular_values"][1] < 1e-10
    # Hsu's multipliers (H = 2, 16 samples) place the doubling within 0.2 % of the odd
    # block of the doubled HB, where the period-2 branch starts (a pitchfork there: the
    # jump of one first step, 0.025 scaled, moves the parameter by O(step^2); measured 1e-5)
    start = sw["doubled_basis_parameter"]
    assert abs(start - pd.parameter) < 2e-3 * pd.parameter
    assert abs(two.parameter[0] - start) < 1e-4 * start
    # the subharmonic (harmonic 1 of omega / 2) grows from ~0 at the doubling
    half = np.abs(two.harmonic(1, "uy", 1))
    assert half[0] < 1e-6 and half[-1] > 3e-5
    # at its first point the even harmonics are the period-1 solution at the doubling
    i = pd.index
    w = (start - res.parameter[i]) / (res.parameter[i + 1] - res.parameter[i])
    C1 = (1 - w) * res.coefficients[i] + w * res.coefficients[i + 1]
    even = spread_harmonics(C1, 2, 4)[0::4]
    assert np.abs(two.coefficients[0][:9][0::4] - even).max() < 1e-2 * np.abs(C1).max()
    assert np.all(two.stable)


@pytest.mark.validation
def test_rotor_period_two_orbit_is_confirmed_by_time_integration(period_two):
    """The rotor's equations written here from its assembled matrices (gravity, the
    housing's inertial load ``M e a w^2 cos(w t)``, the cubic spring), integrated by
    LSODA from the HB state at 1220 rad/s over 20 periods 2T."""
    two = period_two
    i = two.nearest(1220.0)
    w, period = float(two.parameter[i]), 2 * np.pi / float(two.fundamental[i])
    q0, v0 = two.state(i)
    mats = rs.assemble(rotor()).matrices(10.0)
    M, K = mats.M.toarray(), mats.K.toarray()
    D = (mats.C + 10.0 * mats.G).toarray()
    n = M.shape[0]
    e = np.zeros(n)
    e[1::6] = 1.0                                        # rigid vertical translation
    Minv = np.linalg.inv(M)
    f0, fb, uy = -GRAVITY * M @ e, 9e-6 * w**2 * M @ e, 7   # node 1 uy

    def rhs(t, z):
        f = f0 + fb * np.cos(w * t) - D @ z[n:] - K @ z[:n]
        f[uy] -= 3.6e14 * z[uy] ** 3
        return np.concatenate([z[n:], Minv @ f])

    def jac(t, z):
        Kt = K.copy()
        Kt[uy, uy] += 3 * 3.6e14 * z[uy] ** 2
        return np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Kt, -Minv @ D]])

    tau = np.arange(64) / 64
    sol = solve_ivp(rhs, (0.0, 20 * period), np.concatenate([q0, v0]), method="LSODA",
                    rtol=1e-10, atol=1e-14, jac=jac, t_eval=(19 + tau) * period)
    assert sol.success
    hb = two.time_response(i, 64)[1][:, two.column(1, "uy")]
    motion = np.ptp(hb)
    # 8 harmonics of omega / 2 (4 give 3.4e-4: truncation); measured 5e-8 of the motion
    assert np.abs(hb - sol.y[uy]).max() < 1e-6 * motion
    # a period-2 orbit: shifted by T it differs by about its whole motion
    assert np.abs(sol.y[uy] - np.roll(sol.y[uy], 32)).max() > 0.5 * motion


def test_peaks_are_located_on_request_and_cost_nothing_otherwise(period_one):
    assert period_one.peaks == ()
    # a softer spring: the primary resonance (about 577 rad/s) bends a little, and peaks
    res = rs.periodic(rotor(3.6e12), start=450.0, stop=700.0,
                      peaks=[(1, "uy"), (1, "orbit")],
                      continuation=rs.ContinuationOptions(max_step=1.0),
                      **{**COMMON, "stability": None})
    kinds = [(p.node, p.dof, p.kind) for p in res.peaks]
    assert kinds == [(1, "uy", "max"), (1, "orbit", "max")]
    uy, orbit = res.peaks
    assert uy.located and res.parameter[uy.index] <= uy.parameter <= res.parameter[uy.index + 1]
    # the located maximum is above every point's (sampled) amplitude and next to it
    assert uy.amplitude >= res.amplitude(1, "uy").max() * (1 - 1e-9)
    assert uy.amplitude < 1.01 * res.amplitude(1, "uy").max()
    # ux stays 0, so the orbit is the vertical line: the same peak (located to 1e-10)
    assert orbit.amplitude == pytest.approx(uy.amplitude, rel=1e-9)
    assert orbit.parameter == pytest.approx(uy.parameter, rel=1e-8)


def symmetric_rotor() -> rs.Rotor:
    """The rotor with bearings 2.25 times stiffer in x than in y and the coupled spring
    (``b = 4e14``, ``g = b / 10``) at the disk: ``ux = 0`` is invariant; the vertical
    response modulates the horizontal stiffness at twice its frequency."""
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    bearings = [rs.BearingElement(n=n, kxx=4.5e6, kyy=2e6, cxx=72, cyy=72) for n in (0, 2)]
    return rs.Rotor(shaft, [disk], bearings,
                    nonlinear_elements=[CoupledSpring(1, 4e13, 4e14)])


def test_second_branch_through_a_rotor_branch_point():
    """Not turning (speed 0: at any speed the gyroscopic coupling of x and y breaks the
    symmetry, the pitchfork becomes imperfect and has no branch point), no gravity, the
    housing shaken vertically: ``ux = 0`` loses stability in a symmetry-breaking
    pitchfork near the horizontal mode (about 800 rad/s)."""
    common = {**COMMON, "speed": 0.0, "excitation": rs.Excitation(
        gravity=None, base=rs.HarmonicBase(2.2e-5))}
    res = rs.periodic(symmetric_rotor(), start=790.0, stop=812.0,
                      continuation=rs.ContinuationOptions(max_step=0.1), **common)
    assert [b.kind for b in res.bifurcations] == ["branch_point"]
    bp = res.bifurcations[0]
    assert bp.located and np.abs(res.amplitude(1, "ux")).max() == 0.0
    two = rs.switch_branch(symmetric_rotor(), res, bp, stop=806.0, stability="hsu",
                           continuation=rs.ContinuationOptions(max_step=0.1))
    sw = two.options["switched_from"]
    # re-located on the bordered determinant at the recorded point (both to 1e-10 in
    # scaled arclength); a simple branch point: one singular value at round-off
    assert sw["located_parameter"] == pytest.approx(bp.parameter, rel=1e-9)
    assert sw["singular_values"][1] < 1e-10 < 0.1 < sw["singular_values"][0]
    assert two.status.name == "OK" and two.parameter[-1] == pytest.approx(806.0)
    ux = two.amplitude(1, "ux")
    assert ux[0] < 0.05 * ux[-1] and ux[-1] > 3e-5      # grows from the branch point
    assert abs(two.parameter[0] - bp.parameter) < 0.05
    assert np.all(two.stable[:3])                                # supercritical


def test_bad_switch_requests_are_refused(period_one):
    with pytest.raises(ModelError, match="not an index"):
        rs.switch_branch(rotor(), period_one, 5, stop=1250.0)
    with pytest.raises(ModelError, match="must be a PeriodicResult"):
        rs.switch_branch(rotor(), None, 0, stop=1250.0)
    fold = dataclasses.replace(doubling(period_one), kind="fold")
    with pytest.raises(ModelError, match="no second branch"):
        rs.switch_branch(rotor(), period_one, fold, stop=1250.0)
    with pytest.raises(ModelError, match="unknown dof"):
        rs.periodic(rotor(), start=450.0, stop=460.0, peaks=[(1, "uq")], **COMMON)
