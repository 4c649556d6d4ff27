"""Load vectors: consistent gravity, rotating unbalance, point loads, and their validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.assembly.loads import (
    STANDARD_GRAVITY,
    gravity_load,
    gravity_load_all_dofs,
    nodal_load,
    unbalance_load,
)
from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.model.material import steel
from rotorsim.model.rotor import Rotor


def _rotor(n_el: int = 3, **kwargs) -> Rotor:
    shaft = [ShaftElement(L=0.3, idl=0.0, odl=0.04, material=steel) for _ in range(n_el)]
    disks = [DiskElement(n=1, m=7.0, Id=0.02, Ip=0.04)]
    bearings = [BearingElement(n=0, kxx=1e7, mxx=5.0, n_link=n_el + 1),
                BearingElement(n=n_el + 1, kxx=1e8), BearingElement(n=n_el, kxx=1e7)]
    return Rotor(shaft, disks, bearings, [PointMass(n=n_el + 1, m=3.0)], **kwargs)


def test_gravity_total_weight_excludes_bearing_added_mass():
    rotor = _rotor()
    system = assemble(rotor)
    f = system.dof_map.expand(gravity_load(system)).reshape(-1, 6)
    weight = STANDARD_GRAVITY * (rotor.m + 3.0)  # shaft + disk + point mass, not mxx = 5 kg
    assert f[:, 1].sum() == pytest.approx(-weight, rel=1e-12)
    assert np.abs(f[:, [0, 2]]).max() == 0.0


def test_gravity_consistent_nodal_values_of_one_element():
    # Consistent load of a uniform beam element under q = rho A g: q L / 2 at each node and
    # end moments q L^2 / 12 (exact for the interdependent Timoshenko interpolation too).
    el = ShaftElement(L=0.4, idl=0.01, odl=0.05, material=steel)
    f = gravity_load(assemble(Rotor([el]))).reshape(-1, 6)
    q = el.mass / el.L * STANDARD_GRAVITY
    np.testing.assert_allclose(f[:, 1], [-q * el.L / 2] * 2, rtol=1e-12)
    # rx = -duy/dz, so a downward load gives +q L^2/12 on rx at the left end
    np.testing.assert_allclose(f[:, 3], [q * el.L**2 / 12, -q * el.L**2 / 12], rtol=1e-10)


def test_gravity_from_rotor_equals_system_without_fixed_dofs_and_direction_is_normalised():
    rotor = _rotor()
    system = assemble(rotor)
    np.testing.assert_allclose(gravity_load(system, rotor=rotor), gravity_load(system),
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(gravity_load(system, direction=(0.0, -3.0, 0.0)),
                               gravity_load(system), rtol=1e-12)
    fx = system.dof_map.expand(gravity_load(system, g=2.0, direction=(1.0, 0.0, 0.0)))
    fx = fx.reshape(-1, 6)
    assert fx[:, 0].sum() == pytest.approx(2.0 * (rotor.m + 3.0), rel=1e-12)


def test_gravity_from_rotor_keeps_coupling_to_fixed_dofs():
    rotor = _rotor().with_fixed([(0, "uy")])
    system = assemble(rotor)
    exact = gravity_load(system, rotor=rotor)
    full = gravity_load_all_dofs(rotor)
    np.testing.assert_allclose(exact, full[system.dof_map.free], rtol=1e-12)
    assert full.reshape(-1, 6)[:, 1].sum() == pytest.approx(
        -STANDARD_GRAVITY * (rotor.m + 3.0), rel=1e-12)
    # the free-block formula alone misses the mass coupling of node 1 to the fixed uy of
    # node 0 (consistent mass M[uy0, uy1] = 54/420 of the element mass, shear adds a little)
    i = system.dofs_of(1, ("uy",))[0]
    el = rotor.shaft_elements[0]
    missing = gravity_load(system)[i] - exact[i]
    assert missing == pytest.approx(STANDARD_GRAVITY * el.mass * 54 / 420, rel=0.05)


def test_unbalance_is_a_forward_rotating_force():
    system = assemble(_rotor())
    me, a, W = 2e-4, 0.8, 300.0
    f = unbalance_load(system, [(2, me, a), (2, me, a + math.pi / 2)], W)
    fx, fy = f[system.dofs_of(2, ("ux", "uy"))]
    t = np.linspace(0.0, 0.05, 7)
    expected = me * W**2 * (np.exp(1j * (W * t + a)) + np.exp(1j * (W * t + a + math.pi / 2)))
    np.testing.assert_allclose((fx * np.exp(1j * W * t)).real, expected.real, atol=1e-12)
    np.testing.assert_allclose((fy * np.exp(1j * W * t)).real, expected.imag, atol=1e-12)
    others = np.delete(f, system.dofs_of(2, ("ux", "uy")))
    assert np.abs(others).max() == 0.0


def test_nodal_load():
    system = assemble(_rotor().without_axial_torsion())
    f = nodal_load(system, 1, "ry", 12.5)
    assert f[system.dofs_of(1, ("ry",))[0]] == 12.5
    assert np.count_nonzero(f) == 1


@pytest.mark.parametrize(
    ("unbalance", "words"),
    [
        ([(1, 1e-4, 0.0), (99, 1e-4, 0.0)], ("unbalance[1]", "node 99")),
        ([(1, float("nan"), 0.0)], ("unbalance[0]", "magnitude", "node 1")),
        ([(2, 1e-4, float("inf"))], ("unbalance[0]", "phase", "node 2")),
        ([(1, -1e-4, 0.0)], ("unbalance[0]", ">= 0")),
        ([(1, 1e-4)], ("unbalance[0]", "expected (node")),
        ([], ("non-empty",)),
    ],
)
def test_unbalance_validation_names_item_and_node(unbalance, words):
    system = assemble(_rotor())
    with pytest.raises(ModelError) as err:
        unbalance_load(system, unbalance, 100.0)
    for word in words:
        assert word in str(err.value)


def test_loads_on_fixed_or_unknown_dofs_are_rejected():
    system = assemble(_rotor().with_fixed([(2, "ux")]))
    with pytest.raises(ModelError, match=r"unbalance\[0\].*ux of node 2 is fixed"):
        unbalance_load(system, [(2, 1e-4, 0.0)], 10.0)
    with pytest.raises(ModelError, match="unknown DOF 'uq' at node 1"):
        nodal_load(system, 1, "uq", 1.0)
    with pytest.raises(ModelError, match=r"loads\[3\].*must be finite"):
        nodal_load(system, 1, "uy", float("nan"), where="loads[3]")
    with pytest.raises(ModelError, match="direction"):
        gravity_load(system, direction=(0.0, 0.0, 0.0))
