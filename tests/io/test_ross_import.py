"""ROSS rotor files (``ross.Rotor.save``) read into rotorsim (:func:`rotorsim.from_ross`).

The files in data/ross were written by ROSS 3.1.0 (data/ross/ross_reference.py) from its
example rotors and a rotor on pedestals; ROSS's damped natural frequencies and log
decrements of them (``Rotor.run_modal``, printed by that script) are recorded below. Both
codes build Timoshenko elements with Cowper's shear coefficient on 6 DOFs per node, so a
rotor rotorsim represents exactly has the same eigenvalues up to the 9 digits recorded:
``REL_EXACT``. The compressor has mass-only sleeves on its shaft, which rotorsim lumps on
their nodes (one shaft element per node pair): against ROSS's consistent sleeves the
frequencies differ by up to 0.37 % (``REL_LUMPED``), and against ROSS computing the same
lumped rotor (``compressor_lumped``) they agree like the exact cases at a table speed of the
bearings and seals.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.io.ross_import import RossImportError, from_ross

DATA = Path(__file__).parent / "data" / "ross"
REL_EXACT = 1e-7
"""Same matrices: the 9 significant digits recorded, with room for two eigen-solvers."""
REL_LUMPED = 5e-3
"""Sleeves lumped on their nodes instead of ROSS's consistent mass: measured 0.37 % at most
on the first 10 modes of the compressor (0.05 % on the first four)."""
REL_TABLE = 5e-5
"""Between table points rotorsim interpolates linearly between 8 samples of ROSS's cubic per
interval, and extends the table by ROSS's end slopes (``speed_range``): measured 1.0e-5
(9e-4 with the table points only, 3 % at 1250 rad/s with the end values held)."""
LOG_DEC_ABS = 2e-5
"""Log decrements are recorded to 6 significant digits (undamped ones as 0)."""

ROSS_3_1_0 = {
    ("rotor_example", 500.0): (
         [91.5603507, 96.4566397, 265.406, 305.353455, 658.346552, 774.349678, 821.325359,
          1062.92066, 1107.64546, 1819.21054],
         [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    ("rotor_example_6dof", 500.0): (
         [47.6215566, 91.6141511, 96.5202855, 265.746881, 305.912429, 659.009498, 774.349678,
          822.918031, 1070.72506, 1115.0056],
         [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    ("rotor_example_with_damping", 500.0): (
         [179.31296, 189.760419, 538.099222, 582.449167, 939.21902, 952.165632, 993.065793,
          1689.82552, 2155.15004, 2569.10418],
         [0.14755, 0.142629, 0.0986382, 0.0600663, 0.0564356, 0.133841, 0.062846, 0.168378,
          0.141073, 0.0991141]),
    ("compressor_example", 628.3185307179587): (
         [979.019559, 984.599741, 1010.90673, 1038.35183, 1280.94747, 1310.06128, 2201.99864,
          2288.96839, 3341.04127, 3660.32944],
         [10.4572, 9.95755, 1.62271, 0.976553, 6.98584, 7.23112, 0.747427, 0.665566, 0.0,
          1.09522]),
    ("compressor_example", 900.0): (
         [1007.98359, 1039.42653, 1530.37512, 1559.56663, 1673.16911, 1700.11458, 2192.12736,
          2312.8115, 3341.04126, 3767.20461],
         [1.75635, 0.763399, 4.98582, 4.94578, 3.39982, 3.5302, 0.821121, 0.667763, 0.0, 1.0016]),
    ("compressor_example", 1250.0): (
         [1020.29543, 1051.3697, 1798.44441, 1815.71086, 1839.05086, 1861.13459, 2200.11928,
          2345.956, 3341.04127, 3843.33297],
         [1.89168, 0.477022, 3.36287, 1.94557, 3.27338, 2.24432, 0.941839, 0.658114, 0.0,
          0.885674]),
    ("pedestal_example", 500.0): (
         [382.166331, 393.73966, 1434.00678, 1681.04324, 1940.32981, 2349.02689, 2496.56227,
          2878.68984, 3304.10182, 3731.02484],
         [0.00503216, 0.00218765, 0.0658074, 0.0476138, 0.103686, 0.0801513, 0.0963176,
          0.0802375, 0.13461, 0.10366]),
    ("compressor_lumped", 628.3185307179587): (
         [978.915955, 984.429424, 1010.49285, 1037.87746, 1280.31344, 1309.13471, 2199.26603,
          2286.98859, 3339.7964, 3646.95785],
         [10.4367, 9.94018, 1.62003, 0.974177, 6.97856, 7.22461, 0.752699, 0.670114, 0.0,
          1.10541]),
    ("compressor_lumped", 900.0): (
         [1007.61197, 1038.97377, 1529.12017, 1558.13918, 1673.51802, 1700.12479, 2189.4333,
          2311.22802, 3339.7964, 3756.31474],
         [1.75406, 0.761443, 4.98751, 4.94822, 3.39159, 3.52219, 0.829071, 0.673453, 0.0,
          1.01287]),
    ("compressor_lumped", 1250.0): (
         [1019.90143, 1050.89815, 1797.63011, 1814.6888, 1838.09936, 1860.30248, 2198.75129,
          2345.09381, 3339.7964, 3834.50001],
         [1.88976, 0.475446, 3.36551, 1.93219, 3.27638, 2.235, 0.953834, 0.664703, 0.0,
          0.895587]),
}
"""ROSS 3.1.0: ``(rotor, speed [rad/s]) -> (the 10 lowest damped natural frequencies [rad/s]
of the underdamped modes, their log decrements)``."""


def _modes(rotor: rs.Rotor, speed: float, count: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` lowest underdamped modes (ROSS leaves out rigid-body and overdamped
    ones, whose damped frequency is 0)."""
    m = rs.modal(rotor, speed=speed, num_modes=30)
    keep = m.wd > 1.0
    order = np.argsort(m.wd[keep])[:count]
    return m.wd[keep][order], m.log_dec[keep][order]


@pytest.mark.parametrize("name", ["rotor_example", "rotor_example_6dof",
                                  "rotor_example_with_damping", "pedestal_example"])
def test_rotors_rotorsim_represents_exactly_have_ross_frequencies(name):
    rotor = from_ross(DATA / f"{name}.toml")
    wd_ross, ld_ross = ROSS_3_1_0[(name, 500.0)]
    wd, ld = _modes(rotor, 500.0, len(wd_ross))
    np.testing.assert_allclose(wd, wd_ross, rtol=REL_EXACT)
    np.testing.assert_allclose(ld, ld_ross, rtol=1e-5, atol=LOG_DEC_ABS)


@pytest.fixture(scope="module")
def compressor():
    return from_ross(DATA / "compressor_example.toml", speed_range=(400.0, 1300.0))


def test_compressor_matches_ross_with_its_sleeves_lumped(compressor):
    """At a table speed of every bearing and seal: exact against ROSS's lumped rotor,
    within the lumping error against ROSS's own."""
    speed = 628.3185307179587
    wd, ld = _modes(compressor, speed, 10)
    np.testing.assert_allclose(wd, ROSS_3_1_0[("compressor_lumped", speed)][0], rtol=REL_EXACT)
    np.testing.assert_allclose(ld, ROSS_3_1_0[("compressor_lumped", speed)][1], rtol=1e-5,
                               atol=LOG_DEC_ABS)
    np.testing.assert_allclose(wd, ROSS_3_1_0[("compressor_example", speed)][0],
                               rtol=REL_LUMPED)
    sleeves = [d for d in compressor.disk_elements if d.tag.startswith("ross_layers_")]
    assert len(sleeves) == 44  # 36 sleeve elements in 8 runs of adjacent ones: 44 nodes
    assert len(compressor.shaft_elements) == 55


@pytest.mark.parametrize("speed", [900.0, 1250.0])
def test_compressor_bearing_tables_follow_ross_interpolation(compressor, speed):
    """900 rad/s lies between table points (ROSS: pchip), 1250 rad/s beyond the bearing
    tables (ROSS: linear extrapolation with the end slopes)."""
    wd, ld = _modes(compressor, speed, 10)
    wd_ross, ld_ross = ROSS_3_1_0[("compressor_lumped", speed)]
    np.testing.assert_allclose(wd, wd_ross, rtol=REL_TABLE)
    np.testing.assert_allclose(ld, ld_ross, rtol=1e-4, atol=1e-4)  # measured 2.7e-5


def test_cli_writes_a_model_file_with_the_same_frequencies(tmp_path):
    out = tmp_path / "pedestal.toml"
    assert main(["import-ross", str(DATA / "pedestal_example.toml"), "--out", str(out)]) == 0
    model = rs.load_model(out)
    wd, _ = _modes(model.rotor, 500.0, 10)
    np.testing.assert_allclose(wd, ROSS_3_1_0[("pedestal_example", 500.0)][0], rtol=REL_EXACT)
    direct, _ = _modes(from_ross(DATA / "pedestal_example.toml"), 500.0, 10)
    np.testing.assert_array_equal(wd, direct)  # the model file rebuilds the same rotor


def _shaft(n: int, **extra) -> dict:
    return {"L": 0.2, "idl": 0.0, "odl": 0.05, "n": n,
            "material": {"name": "steel", "E": 211e9, "G_s": 81.2e9, "rho": 7810.0}, **extra}


BASE = {"ross_version": "3.1.0", "parameters": {"alpha": 0.0, "beta": 0.0},
        "ShaftElement_S0": _shaft(0), "ShaftElement_S1": _shaft(1),
        "BearingElement_B0": {"n": 0, "kxx": [1e6], "kyy": [1e6]},
        "BearingElement_B1": {"n": 2, "kxx": [1e6], "kyy": [1e6]}}


@pytest.mark.parametrize(("extra", "match"), [
    ({"MagneticBearingElement_M0": {"n": 1, "g0": 1e-3}}, "class 'MagneticBearingElement'"),
    ({"BearingElement_W": {"n": 1, "kxx": [1e6, 2e6], "frequency": [0.0, 100.0]}},
     "whirl frequency"),
    ({"ShaftElement_S1": _shaft(1, torque=10.0)}, "torque"),
    ({"ShaftElement_S1": _shaft(1, shear_method_calc="hutchinson")}, "hutchinson"),
    ({"ShaftElement_L": _shaft(1, idl=0.05, odl=0.08)}, "both carry load"),
    ({"ShaftElement_S1": _shaft(2)}, "nodes 0, 1, 2"),
    ({"BearingElement_Z": {"n": 1, "kxx": [1e6], "mzz": [1.0]}}, "mzz"),
])
def test_unsupported_ross_content_is_named(extra, match):
    with pytest.raises(RossImportError, match=match):
        from_ross({**BASE, **extra})


def test_a_mass_only_layer_is_lumped_with_its_mass():
    sleeve = _shaft(1, idl=0.05, odl=0.1)
    sleeve["material"] = {"name": "soft", "E": 6894.75, "G_s": 6894.75, "rho": 7800.0}
    rotor = from_ross({**BASE, "ShaftElement_L": sleeve})
    mass = 7800.0 * np.pi / 4 * (0.1**2 - 0.05**2) * 0.2
    lumps = [d for d in rotor.disk_elements]
    assert [d.n for d in lumps] == [1, 2]
    assert sum(d.m for d in lumps) == pytest.approx(mass, rel=1e-12)
    assert sum(d.Ip for d in lumps) == pytest.approx(mass * (0.05**2 + 0.025**2) / 2,
                                                     rel=1e-12)


def test_json_files_and_non_ross_files(tmp_path):
    """ROSS saves .json with the same tables; a file without ROSS elements is refused."""
    import json
    import tomllib

    data = tomllib.loads((DATA / "rotor_example.toml").read_text())
    path = tmp_path / "rotor_example.json"
    path.write_text(json.dumps({"_note": "written by ROSS", **data}))
    wd, _ = _modes(from_ross(path), 500.0, 10)
    np.testing.assert_allclose(wd, ROSS_3_1_0[("rotor_example", 500.0)][0], rtol=REL_EXACT)
    model_file = Path(__file__).resolve().parents[2] / "models" / "default.toml"
    with pytest.raises(rs.ModelError, match="no ROSS elements"):
        from_ross(model_file)
