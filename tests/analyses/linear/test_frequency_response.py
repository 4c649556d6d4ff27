"""Unbalance response and receptances against the Jeffcott rotor and structural identities."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.analyses.linear.frequency_response import frequency_response, unbalance_response
from rotorsim.analyses.statics.static import static
from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.material import Material, steel
from rotorsim.model.rotor import Rotor

# Jeffcott rotor: disk of mass M_DISK at midspan of a (nearly) massless Euler-Bernoulli shaft on
# rigid supports. Its lateral stiffness is 48 E I / L^3 in series with the two support springs.
LIGHT = Material(name="massless", E=211e9, G_s=81.2e9, rho=1e-6)
L_SHAFT, D_SHAFT, M_DISK, K_SUPPORT = 1.0, 0.03, 10.0, 1e14
K_SHAFT = 48 * LIGHT.E * (math.pi * D_SHAFT**4 / 64) / L_SHAFT**3
K_EFF = 1.0 / (1.0 / K_SHAFT + 1.0 / (2.0 * K_SUPPORT))
W_N = math.sqrt(K_SHAFT / M_DISK)
# Jeffcott references: the model error (shaft mass ratio 7e-11 over 2 zeta) is <= 1.6e-9;
# 1e-8 leaves margin for round-off (the solve's condition ~ K_SUPPORT / K_SHAFT = 2.5e8
# does not reach the disk DOF: its spread across BLAS kernels is 1e-15)
TOL_JEFFCOTT = 1e-8


def jeffcott(extra_kx: float = 0.0, extra_ky: float = 0.0, c: float = 0.0) -> Rotor:
    """Jeffcott rotor; a spring/damper at the disk adds ``extra_k*`` and damping ``c``."""
    shaft = [ShaftElement(L=L_SHAFT / 2, idl=0.0, odl=D_SHAFT, material=LIGHT,
                          shear_effects=False, rotary_inertia=False, gyroscopic=False)
             for _ in range(2)]
    bearings = [BearingElement(n=0, kxx=K_SUPPORT), BearingElement(n=2, kxx=K_SUPPORT),
                BearingElement(n=1, kxx=extra_kx, kyy=extra_ky, cxx=c)]
    disk = DiskElement(n=1, m=M_DISK, Id=0.0, Ip=0.0)
    return Rotor(shaft, [disk], bearings).without_axial_torsion()


def gyroscopic_rotor() -> Rotor:
    """A steel rotor with shaft mass, two disks, gyroscopics and damped bearings."""
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [DiskElement(n=2, m=15.0, Id=0.1, Ip=0.2), DiskElement(n=5, m=8.0, Id=0.06,
                                                                    Ip=0.11)]
    bearings = [BearingElement(n=0, kxx=2e7, kyy=3e7, cxx=400.0, cyy=300.0, kzz=1e7, czz=50.0),
                BearingElement(n=6, kxx=1e7, cxx=200.0, krr=1e4)]
    return Rotor(shaft, disks, bearings).with_fixed([(n, "rz") for n in range(7)])


@pytest.mark.validation
def test_jeffcott_unbalance_amplitude_phase_and_forward_circular_orbit():
    # Reference: Jeffcott rotor, x = me W^2 e^{ia} / (k - m W^2 + i c W) (Friswell et al. 2010,
    # section 3.3; Genta 2005, ch. 4). The model differs from the 1-DOF reference only by
    # the shaft mass (7e-10 kg against 10 kg, amplified by at most 1 / (2 zeta) at the
    # resonance) and the support compliance, which K_EFF includes; the FE shaft stiffness
    # is exact at the nodes for EB elements. Measured: amplitude 1.8e-10, phase 3.3e-10
    # rad, the same under every BLAS kernel tried; tolerance 1e-8 (TOL_JEFFCOTT).
    c = 2 * 0.05 * math.sqrt(K_SHAFT * M_DISK)
    speeds = np.linspace(0.05, 3.0, 120) * W_N
    me, a = 2e-4, 0.7
    r = unbalance_response(jeffcott(c=c), speeds, [(1, me, a)])
    W = speeds
    denom = K_EFF - M_DISK * W**2 + 1j * c * W
    np.testing.assert_allclose(r.amplitude(1, "ux"), me * W**2 / np.abs(denom),
                               rtol=TOL_JEFFCOTT)
    phase = a - np.arctan2(c * W, K_EFF - M_DISK * W**2)
    np.testing.assert_allclose(np.exp(1j * r.phase(1, "ux")), np.exp(1j * phase),
                               atol=TOL_JEFFCOTT)
    orbit = r.orbit(1)
    np.testing.assert_allclose(orbit.whirl_ratio, 1.0, atol=1e-9)  # forward circle
    np.testing.assert_allclose(orbit.minor, orbit.major, rtol=1e-9)
    assert r.stats["factorizations"] == speeds.size
    assert r.status is Status.OK and r.response.shape == (speeds.size, 18, 1)


def test_unbalance_peak_and_deflected_shape():
    # Peak of the unbalance amplitude at W = wn / sqrt(1 - 2 zeta^2) (displacement of a
    # rotating-unbalance-forced SDOF, Friswell et al. 2010 eq. 3.36): the grid spacing bounds it.
    zeta = 0.1
    c = 2 * zeta * math.sqrt(K_SHAFT * M_DISK)
    speeds = np.linspace(0.5, 1.5, 1001) * W_N
    r = unbalance_response(jeffcott(c=c), speeds, [(1, 1e-4, 0.0)])
    w_peak, amp = r.peak(1, "ux")
    assert w_peak == pytest.approx(W_N / math.sqrt(1 - 2 * zeta**2), abs=speeds[1] - speeds[0])
    assert amp == pytest.approx(r.amplitude(1, "ux").max())
    shape = r.deflected_shape(frequency=w_peak)
    assert shape.speed == w_peak
    assert shape.ux[1] == r.complex(1, "ux")[np.argmax(r.amplitude(1, "ux"))]
    assert shape.major[1] == pytest.approx(amp, rel=1e-9)  # circular orbit: major = |X|
    # the stiff supports deflect by the spring force K_EFF |X| shared by two supports
    assert shape.major[0] == pytest.approx(K_EFF * amp / (2 * K_SUPPORT), rel=1e-6)
    with pytest.raises(ModelError, match="exactly one"):
        r.deflected_shape()


@pytest.mark.validation
def test_anisotropic_supports_backward_whirl_between_criticals():
    # Classic result (Friswell et al. 2010 section 3.5): with kx < ky the orbit is an ellipse,
    # forward below wx = sqrt(kx/m) and above wy = sqrt(ky/m), backward between them.
    # X = me W^2 / (kx - m W^2 + i c W), Y = -i me W^2 / (ky - m W^2 + i c W).
    # Measured 1.6e-10 (X), 1.6e-9 (Y: zeta = 1e-3 at 0.99 wy amplifies the shaft-mass
    # model error of the Jeffcott test).
    kx, ky = K_EFF + 1e5, K_EFF + 4e5
    c = 20.0  # light damping
    wx, wy = math.sqrt(kx / M_DISK), math.sqrt(ky / M_DISK)
    speeds = np.array([0.5 * wx, 0.9 * wx, 0.5 * (wx + wy), 0.99 * wy, 1.1 * wy, 2 * wy])
    r = unbalance_response(jeffcott(1e5, 4e5, c), speeds, [(1, 1e-4, 0.0)])
    W = speeds
    X = 1e-4 * W**2 / (kx - M_DISK * W**2 + 1j * c * W)
    Y = -1j * 1e-4 * W**2 / (ky - M_DISK * W**2 + 1j * c * W)
    np.testing.assert_allclose(r.complex(1, "ux"), X, rtol=TOL_JEFFCOTT)
    np.testing.assert_allclose(r.complex(1, "uy"), Y, rtol=TOL_JEFFCOTT)
    orbit = r.orbit(1)
    expected = np.where((W > wx) & (W < wy), -1, 1)
    np.testing.assert_array_equal(np.sign(orbit.whirl_ratio), expected)
    assert np.all(orbit.minor < 0.999 * orbit.major)  # an ellipse, not a circle
    # whirl sense from the sampled orbit itself: sign of x y' - y x' over one period
    t = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)[:, None] / W
    x = (r.complex(1, "ux") * np.exp(1j * W * t)).real
    y = (r.complex(1, "uy") * np.exp(1j * W * t)).real
    vx = (1j * W * r.complex(1, "ux") * np.exp(1j * W * t)).real
    vy = (1j * W * r.complex(1, "uy") * np.exp(1j * W * t)).real
    np.testing.assert_array_equal(np.sign((x * vy - y * vx).mean(axis=0)), expected)


@pytest.mark.validation
def test_receptance_of_sdof_like_model():
    # Receptance of a 1-DOF system H = 1 / (k - m w^2 + i c w) (Ewins 2000, ch. 2);
    # tolerance as in the Jeffcott test (measured 4.3e-10).
    c = 150.0
    w = np.linspace(0.0, 2.5, 60) * W_N
    h = frequency_response(jeffcott(c=c), w, [(1, "ux"), (1, "uy")], speed=0.0)
    H = 1.0 / (K_EFF - M_DISK * w**2 + 1j * c * w)
    np.testing.assert_allclose(h.complex(1, "ux", input=0), H, rtol=TOL_JEFFCOTT)
    np.testing.assert_allclose(h.complex(1, "uy", input=1), H, rtol=TOL_JEFFCOTT)
    assert np.abs(h.complex(1, "uy", input=0)).max() < 1e-12 * np.abs(H).max()
    assert h.stats["factorizations"] == w.size
    assert h.stats["solves"] == w.size  # all inputs in one solve per frequency
    assert h.inputs == ("unit force ux at node 1", "unit force uy at node 1")


def _receptance_matrix(rotor: Rotor, w, dofs, speed):
    h = frequency_response(rotor, w, dofs, speed=speed)
    rows = [h.dof_map.index(n, d) for n, d in dofs]
    return h.response[:, rows, :], h


_TURN_SIGN = {"ux": -1.0, "uy": 1.0, "uz": -1.0, "rx": -1.0, "ry": 1.0, "rz": -1.0}
"""Turning the rotor end for end (rotation by pi about y: x -> -x, z -> -z) maps each DOF to
itself at the mirrored node with these signs, and spin at -W to spin at +W."""


def _turned_gyroscopic_rotor() -> Rotor:
    """:func:`gyroscopic_rotor` seen from its other end (node n -> 6 - n); it has no
    cross-coupled bearing terms, which would change sign."""
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [DiskElement(n=4, m=15.0, Id=0.1, Ip=0.2), DiskElement(n=1, m=8.0, Id=0.06,
                                                                    Ip=0.11)]
    bearings = [BearingElement(n=6, kxx=2e7, kyy=3e7, cxx=400.0, cyy=300.0, kzz=1e7, czz=50.0),
                BearingElement(n=0, kxx=1e7, cxx=200.0, krr=1e4)]
    return Rotor(shaft, disks, bearings).with_fixed([(n, "rz") for n in range(7)])


def test_reciprocity_non_rotating_and_reversed_spin():
    # Maxwell-Betti reciprocity H_ij = H_ji holds for symmetric M, C, K (W = 0). With spin
    # the skew gyroscopic matrix gives H(W)^T = H(-W) instead (Lund's reciprocity for
    # gyroscopic systems, since (K - w^2 M + i w (C + W G))^T = K - w^2 M + i w (C - W G)).
    # Speeds are >= 0 by convention, so H(-W) is the receptance of the rotor turned end for
    # end spinning at +W, with the DOFs mapped back.
    rotor = gyroscopic_rotor()
    dofs = [(2, "ux"), (2, "uy"), (5, "ry"), (3, "rx"), (4, "uz"), (6, "ux")]
    w = np.array([50.0, 400.0, 1500.0])
    H0, _ = _receptance_matrix(rotor, w, dofs, 0.0)
    np.testing.assert_allclose(H0, np.swapaxes(H0, 1, 2), rtol=1e-10,
                               atol=1e-10 * np.abs(H0).max())
    Hp, _ = _receptance_matrix(rotor, w, dofs, 600.0)
    turned = [(6 - n, d) for n, d in dofs]
    sign = np.array([_TURN_SIGN[d] for _, d in dofs])
    Hm = _receptance_matrix(_turned_gyroscopic_rotor(), w, turned, 600.0)[0] * np.outer(sign,
                                                                                        sign)
    np.testing.assert_allclose(Hp, np.swapaxes(Hm, 1, 2), rtol=1e-10,
                               atol=1e-10 * np.abs(Hp).max())
    asym = np.abs(Hp - np.swapaxes(Hp, 1, 2)).max() / np.abs(Hp).max()
    assert asym > 1e-3  # the gyroscopic term is really in the dynamic stiffness


def test_synchronous_receptance_reproduces_unbalance_response():
    # Superposition: unbalance me at angle a on node n is the force me W^2 e^{ia} (1, -i) on
    # (ux, uy), so X = me W^2 e^{ia} (H_ux - i H_uy) with synchronous receptances (W = w).
    rotor = gyroscopic_rotor()
    speeds = np.linspace(100.0, 2000.0, 9)
    me, a = 3e-4, -1.1
    u = unbalance_response(rotor, speeds, [(5, me, a)])
    h = frequency_response(rotor, speeds, [(5, "ux"), (5, "uy")])
    np.testing.assert_allclose(h.speeds, speeds)
    expected = me * speeds[:, None] ** 2 * np.exp(1j * a) * (
        h.response[:, :, 0] - 1j * h.response[:, :, 1])
    np.testing.assert_allclose(u.response[:, :, 0], expected, rtol=1e-9,
                               atol=1e-9 * np.abs(expected).max())
    # a fixed spin speed differs from synchronous excitation when gyroscopics matter
    fixed = frequency_response(rotor, speeds, [(5, "ux")], speed=0.0)
    assert not np.allclose(fixed.response[:, :, 0], h.response[:, :, 0], rtol=1e-3)


def test_speed_dependent_bearings_evaluated_at_each_speed():
    rotor = gyroscopic_rotor()
    table = BearingElement(n=0, kxx=[1e7, 5e7], kyy=[2e7, 6e7], cxx=[100.0, 900.0],
                           frequency=[0.0, 1000.0])
    varying = rotor.with_bearings([table, rotor.bearing_elements[1]])
    speeds = np.array([200.0, 700.0])
    r = unbalance_response(assemble(varying), speeds, [(2, 1e-4, 0.0)])
    assert r.stats["factorizations"] == 2
    for i, W in enumerate(speeds):
        k = lambda s, W=W: float(table.coefficient(s, W))  # noqa: E731
        frozen = BearingElement(n=0, kxx=k("kxx"), kyy=k("kyy"), cxx=k("cxx"))
        ref = unbalance_response(rotor.with_bearings([frozen, rotor.bearing_elements[1]]),
                                 [W], [(2, 1e-4, 0.0)])
        np.testing.assert_allclose(r.response[i], ref.response[0], rtol=1e-10, atol=1e-18)


@pytest.mark.filterwarnings("ignore::scipy.linalg.LinAlgWarning")
def test_static_point_with_free_rigid_motions_is_solved_or_refused():
    # Without axial/torsional restraint K is singular at w = 0 (rigid-body motion). A
    # lateral load does no work on those motions: the receptance at w = 0 is the static
    # compliance (issue 12: it used to raise "matrix is singular"). An axial load moves the
    # free axial translation: the static response is unbounded, raised or recorded.
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel) for _ in range(3)]
    rotor = Rotor(shaft, [], [BearingElement(n=0, kxx=1e7), BearingElement(n=3, kxx=1e7)])
    h = frequency_response(rotor, [0.0, 100.0], [(1, "ux")], speed=0.0)
    static_ux = static(rotor, gravity=None, loads=[(1, "ux", 1.0)]).displacement
    # one LU solve against another of the same (restrained) matrix: round-off only
    np.testing.assert_allclose(h.response[0, :, 0].real, static_ux, rtol=1e-9,
                               atol=1e-12 * np.abs(static_ux).max())
    assert np.all(h.response[0].imag == 0) and h.status is Status.OK
    with pytest.raises(ConvergenceError, match=r"point 0.*unbounded.*z \(translation\)"):
        frequency_response(rotor, [0.0, 100.0], [(1, "uz")], speed=0.0)
    r = frequency_response(rotor, [0.0, 100.0], [(1, "uz")], speed=0.0, on_failure="record")
    assert r.point_status.tolist() == [Status.FAILED, Status.OK]
    assert np.isnan(r.response[0]).all() and np.isfinite(r.response[1]).all()
    assert r.status is Status.FAILED
    with pytest.raises(TypeError, match="on_failure"):
        frequency_response(rotor, [1.0], [(1, "ux")], on_failure="ignore")


def test_unbalance_response_from_zero_speed_with_free_axial_and_torsion():
    # The unbalance force me W^2 vanishes at W = 0, so the response is exactly zero there;
    # sweeps starting at 0 are the normal case (issue 12: "matrix is singular" at W = 0).
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel) for _ in range(3)]
    rotor = Rotor(shaft, [], [BearingElement(n=0, kxx=1e7, cxx=1e3),
                              BearingElement(n=3, kxx=1e7, cxx=1e3)])
    speeds = np.array([0.0, 50.0, 100.0])
    u = unbalance_response(rotor, speeds, [(1, 1e-4, 0.3)])
    assert u.status is Status.OK and np.all(u.response[0] == 0)
    later = unbalance_response(rotor, speeds[1:], [(1, 1e-4, 0.3)])
    np.testing.assert_array_equal(u.response[1:], later.response)  # same solves, same bits
    assert u.stats["factorizations"] == 2  # no solve where the force is zero


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda r: unbalance_response(r, [10.0], [(1, 1e-4, 0.0), (7, 1e-4, 0.0)]),
         ("unbalance[1]", "node 7")),
        (lambda r: unbalance_response(r, [10.0], [(1, float("nan"), 0.0)]),
         ("unbalance[0]", "magnitude", "node 1")),
        (lambda r: unbalance_response(r, [], [(1, 1e-4, 0.0)]), ("speeds", "non-empty")),
        (lambda r: unbalance_response(r, [10.0, -5.0], [(1, 1e-4, 0.0)]),
         ("speeds", "index 1")),
        (lambda r: unbalance_response(r, [10.0, np.inf], [(1, 1e-4, 0.0)]),
         ("speeds", "index 1")),
        (lambda r: frequency_response(r, [10.0], [(1, "ux"), (1, "rz")]),
         ("inputs[1]", "rz of node 1 is fixed")),
        (lambda r: frequency_response(r, [10.0], [(1, "uq")]), ("inputs[0]", "'uq'")),
        (lambda r: frequency_response(r, [10.0], []), ("inputs", "non-empty")),
        (lambda r: frequency_response(r, [10.0], [(1, "ux")], speed=float("nan")),
         ("speed",)),
    ],
)
def test_bad_input_names_the_culprit(call, words):
    with pytest.raises(ModelError) as err:
        call(jeffcott(c=1.0))
    for word in words:
        assert word in str(err.value)
