"""A dual rotor against a hand-derived closed form (issue 15, docs/validation.md, case 28).

The issue asks for a published dual-rotor or rotor-casing example reproduced with its
numbers. No source whose full data *and* result numbers could be read was found (case 28
lists the sources tried and what each lacked), so this file holds the closest independent
check instead, labelled as such: a two-spool machine whose exact critical speeds and
unbalance response follow from equations written here, not from rotorsim's assembly.

The model: each spool is a rigid disk (``m``, ``Id``, ``Ip``) on a line of its own with no
beam elements, the two disks at the same axial station. Each disk sits on an isotropic
support to ground (lateral ``k``, tilt ``kr``) and an inter-shaft bearing joins them
(lateral ``kc``, tilt ``krc``). LP turns at the reference speed ``W``, HP at ``r W``,
co-rotating (``r = 1.45``) or counter-rotating (``r = -1.3``); with ``r = 0`` the second
body is a rigid casing that does not turn, the LP rotor sitting in it on the "inter-shaft"
bearing (a rotor-casing machine). With the disks at one station, translation and tilt
decouple (Friswell et al. 2010, section 3.5, for one disk):

- translation, at any speed: ``det([[k1 + kc - m1 w^2, -kc], [-kc, k2 + kc - m2 w^2]]) =
  0``, a quadratic in ``w^2``;
- tilt, whirling at the signed frequency ``lam`` in the fixed frame: disk ``i`` turning at
  ``r_i W`` adds ``Ip_i r_i W lam`` to its tilt stiffness. Excited by spool ``k``'s ``1X``
  with sense ``s`` (``lam = s |r_k| W``), ``W lam = s lam^2 / |r_k|`` and the determinant
  ``(a1 - b1 lam^2)(a2 - b2 lam^2) - krc^2 = 0`` with ``a_i = kr_i + krc`` and
  ``b_i = Id_i - s Ip_i r_i / |r_k|`` is again a quadratic in ``lam^2``.

Tolerances: the model has no mesh (rigid disks, springs), so rotorsim's answer is exact up
to the eigensolver. Dense QZ on this 12-DOF pencil is accurate to ~1e-13 relative; 1e-9 is
asserted, whatever the BLAS. Campbell crossings are located on a cubic through grid points
5 rad/s apart: better than 1e-4 relative (as in case 27).
"""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.model.lines import ShaftLine

pytestmark = pytest.mark.validation

M1, ID1, IP1 = 30.0, 0.9, 0.5     # LP disk [kg, kg m^2]
M2, ID2, IP2 = 12.0, 0.25, 0.15   # HP disk
K1, KR1 = 4e6, 2e5                # LP support [N/m, N m/rad]
K2, KR2 = 6e6, 1.5e5              # HP support
KC, KRC = 2e6, 8e4                # inter-shaft bearing
KZ = 1e10                         # axial springs: axial modes above 18000 rad/s, out of range
RATIOS = (1.45, -1.3, 0.0)        # HP speed ratio: co-, counter-rotating, casing
RTOL = 1e-9                       # dense QZ on a 12-DOF pencil: ~1e-13 relative


def machine(ratio: float, damping: float = 0.0) -> rs.Rotor:
    """LP (node 0) and HP (node 1) disks at one station, on supports and an inter-shaft
    bearing; ``damping`` [N s/m] on the lateral motion of the three springs."""
    lines = [ShaftLine("LP", []), ShaftLine(_second(ratio), [], speed_ratio=ratio)]
    disks = [rs.DiskElement(n=0, m=M1, Id=ID1, Ip=IP1, tag="LP disk"),
             rs.DiskElement(n=1, m=M2, Id=ID2, Ip=IP2, tag=f"{_second(ratio)} body")]
    bearings = [
        rs.BearingElement(n=0, kxx=K1, krr=KR1, kzz=KZ, cxx=damping, tag="LP support"),
        rs.BearingElement(n=1, kxx=K2, krr=KR2, kzz=KZ, cxx=damping,
                          tag=f"{_second(ratio)} support"),
        rs.BearingElement(n=1, n_link=0, kxx=KC, krr=KRC, cxx=damping, tag="inter-shaft"),
    ]
    return rs.Rotor([], disks, bearings, lines=lines)


def _quadratic_roots(a: float, b: float, c: float) -> np.ndarray:
    """Both roots of ``a x^2 + b x + c = 0`` (real, distinct here), without cancellation."""
    q = -(b + np.copysign(np.sqrt(b * b - 4.0 * a * c), b)) / 2.0
    return np.array([q / a, c / q])


def translation_modes() -> tuple[np.ndarray, np.ndarray]:
    """Squared frequencies [rad^2/s^2] of the two-mass translation and the mode shapes
    ``(phi_LP, phi_HP)`` as columns, from its first row ``(K1 + KC - M1 w^2) phi_LP =
    KC phi_HP``."""
    w2 = _quadratic_roots(M1 * M2, -((K1 + KC) * M2 + (K2 + KC) * M1),
                          (K1 + KC) * (K2 + KC) - KC**2)
    return w2, np.vstack([np.full(2, KC), K1 + KC - M1 * w2])


def tilt_critical_speeds(ratio: float, spool_ratio: float) -> np.ndarray:
    """Reference speeds [rad/s] where a tilt mode whirls at ``|r_k| W``, both senses."""
    out = []
    a1, a2 = KR1 + KRC, KR2 + KRC
    for s in (1.0, -1.0):
        b1 = ID1 - s * IP1 * 1.0 / abs(spool_ratio)
        b2 = ID2 - s * IP2 * ratio / abs(spool_ratio)
        lam2 = _quadratic_roots(b1 * b2, -(a1 * b2 + a2 * b1), a1 * a2 - KRC**2)
        assert np.all(lam2 > 0)  # b1, b2 > 0 for these inertias: four real crossings
        out.extend(np.sqrt(lam2) / abs(spool_ratio))
    return np.array(out)


def expected_critical_speeds(ratio: float, spool_ratio: float) -> np.ndarray:
    """All lateral critical speeds for spool ``k``'s 1X: each translation mode twice (it
    whirls both ways at the same frequency) and four tilt crossings, sorted."""
    w2, _ = translation_modes()
    cylindrical = np.repeat(np.sqrt(w2) / abs(spool_ratio), 2)
    return np.sort(np.concatenate([cylindrical, tilt_critical_speeds(ratio, spool_ratio)]))


def _second(ratio: float) -> str:
    """Name of the second line: a spool, or a casing when it does not turn."""
    return "HP" if ratio else "casing"


def _spools(ratio: float) -> list[tuple[str, float, int]]:
    """(name, speed ratio, disk node) of each turning line."""
    return [("LP", 1.0, 0)] + ([("HP", ratio, 1)] if ratio else [])


@pytest.mark.parametrize("ratio", RATIOS)
def test_critical_speeds_of_each_spool_match_the_two_disk_closed_form(ratio: float) -> None:
    rotor = machine(ratio)
    for spool, spool_ratio, _ in _spools(ratio):
        lateral = rs.critical_speeds(rotor, spool=spool, num_modes=12).select(kind="lateral")
        expected = expected_critical_speeds(ratio, spool_ratio)
        assert lateral.speed.size == expected.size == 8
        np.testing.assert_allclose(np.sort(lateral.speed), expected, rtol=RTOL)


@pytest.mark.parametrize("ratio", RATIOS)
def test_spool_excitation_follows_the_closed_form_mode_shapes(ratio: float) -> None:
    """A static unbalance on a spool's disk drives only the translation modes whirling with
    that spool, in proportion ``|phi_k| / max|phi|`` of the two-mass mode shape; the tilt
    modes and the translation modes whirling against the spool get nothing."""
    w2, phi = translation_modes()
    for spool, spool_ratio, node in _spools(ratio):
        cs = rs.critical_speeds(machine(ratio), spool=spool, num_modes=12).select(
            kind="lateral")
        assert cs.excitation is not None
        sense = "forward" if spool_ratio > 0 else "backward"
        for j in range(2):
            at = np.isclose(cs.speed, np.sqrt(w2[j]) / abs(spool_ratio), rtol=RTOL)
            assert at.sum() == 2
            driven = at & (cs.whirl == sense)
            assert driven.sum() == 1
            share = abs(phi[node, j]) / np.abs(phi[:, j]).max()
            # the measure is a ratio of mode-shape entries: as accurate as the shape
            np.testing.assert_allclose(cs.excitation[driven], share, rtol=1e-8)
            assert np.all(cs.excitation[at & ~driven] < 1e-9)
        tilt = ~np.isclose(cs.speed[:, None], np.sqrt(w2)[None, :] / abs(spool_ratio),
                           rtol=RTOL).any(axis=1)
        assert tilt.sum() == 4 and np.all(cs.excitation[tilt] < 1e-12)


@pytest.mark.parametrize("ratio", RATIOS)
def test_campbell_crossings_of_each_spool_match_the_closed_form(ratio: float) -> None:
    speeds = np.linspace(0.0, 3000.0, 601)
    campbell = rs.campbell(machine(ratio), speeds, num_modes=12)
    for spool, spool_ratio, _ in _spools(ratio):
        crossings = campbell.critical_speeds(spool=spool).speed
        crossings = crossings[crossings > 1.0]  # the free torsion of the disks: 0 rad/s
        exact = expected_critical_speeds(ratio, spool_ratio)
        exact = exact[exact < 0.97 * speeds[-1]]
        assert exact.size >= 6
        # the local cubic through grid points 5 rad/s apart: better than 1e-4 relative
        for w in exact:
            assert np.min(np.abs(crossings - w)) < 1e-4 * w
        for w in crossings[crossings < 0.97 * speeds[-1]]:
            assert np.min(np.abs(exact - w)) < 1e-4 * w  # no crossing the closed form lacks


@pytest.mark.parametrize("ratio", RATIOS)
def test_unbalance_response_of_each_spool_matches_the_closed_form(ratio: float) -> None:
    """Each spool's unbalance ``me`` on its disk, at its own frequency ``w = r W``: the
    disks translate in circles of radius ``|X|``, ``X = (K - w^2 M + i |w| C)^-1 F`` on the
    two-mass system (no tilt: a static unbalance at the common station), ``F = me w^2``
    on the unbalanced disk."""
    c, me = 800.0, 2e-4
    W = np.linspace(50.0, 1200.0, 47)
    spools = _spools(ratio)
    result = rs.unbalance_response(machine(ratio, damping=c), W,
                                   [(node, me, 0.0) for _, _, node in spools])
    if len(spools) > 1:
        assert result.input_ratios is not None
        np.testing.assert_array_equal(result.input_ratios, [1.0, ratio])
    mass = np.diag([M1, M2])
    stiffness = np.array([[K1 + KC, -KC], [-KC, K2 + KC]])
    damping = np.array([[2 * c, -c], [-c, 2 * c]])
    for column, (_, spool_ratio, node) in enumerate(spools):
        w = abs(spool_ratio) * W
        dynamic = (stiffness[None] - w[:, None, None] ** 2 * mass[None]
                   + 1j * w[:, None, None] * damping[None])
        force = np.zeros((W.size, 2))
        force[:, node] = me * w**2
        closed = np.abs(np.linalg.solve(dynamic, force[:, :, None])[:, :, 0])
        for n in (0, 1):
            # one LU solve of a 12-DOF complex system per speed: ~1e-13 relative
            np.testing.assert_allclose(result.amplitude(n, "ux", column), closed[:, n],
                                       rtol=RTOL)
            np.testing.assert_allclose(result.amplitude(n, "rx", column), 0.0,
                                       atol=1e-12 * closed.max())
