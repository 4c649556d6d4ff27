"""A transient analysis driven by torques in a model file: the ``drive`` table, its units,
its errors, the run against the closed-form spin-up, and the round trip through
save_model (issue 14, part 5)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.io.analysis_runners import run_analysis
from rotorsim.io.long_specs import DriveSpec
from rotorsim.io.model_file import load_model, save_model

MODEL = """
[model]
name = "driven"

[[materials]]
name = "steel"
E = "211 GPa"
G_s = "81.2 GPa"
rho = "7810 kg/m^3"

[[shaft]]
length = "1 m"
n_elements = 4
od = "50 mm"
material = "steel"

[[disks]]
z = "500 mm"
m = "10 kg"
Id = "0.05 kg m^2"
Ip = "0.1 kg m^2"

[[bearings]]
z = "0 m"
kxx = "10 MN/m"
cxx = "1 kN s/m"

[[bearings]]
z = "1 m"
kxx = "10 MN/m"
cxx = "1 kN s/m"

[[fixed]]
node = 0
dofs = ["uz"]

[loads]
gravity = false

[analyses.start]
type = "transient"
t_end = "0.2 s"
dt = "1 ms"
speed = "20 rad/s"
initial = "zero"
nodes = [2]
{drive}
"""

DRIVE = """
[analyses.start.drive]
node = 0
motor = { type = "constant", torque = "40 N m" }
loads = [{ z = "1 m", type = "quadratic", coefficient = 0.0 }]
friction = [{ node = 4, type = "constant", torque = "0 N m" }]
"""


def _model(tmp_path: Path, drive: str = DRIVE) -> Path:
    path = tmp_path / "driven.toml"
    path.write_text(MODEL.replace("{drive}", drive))
    return path


def test_drive_table_becomes_a_spec_in_si(tmp_path):
    spec = load_model(_model(tmp_path)).analyses["start"]
    assert isinstance(spec.drive, DriveSpec)
    assert spec.drive.node == 0 and spec.drive.motor == {"type": "constant", "torque": 40.0}
    assert spec.drive.loads == ((4, {"type": "quadratic", "coefficient": 0.0}),)
    assert spec.speed == 20.0


@pytest.mark.verification
def test_model_file_spin_up_matches_closed_form(tmp_path):
    """W = W0 + T t / J_p with J_p = rho pi d^4/32 L + Ip of the disk (SPIN_TOL of the API
    test: rtol 1e-10 integration)."""
    res = run_analysis(load_model(_model(tmp_path)), "start")
    J = 7810 * math.pi * 0.05**4 / 32 * 1.0 + 0.1
    assert res.options["speed"]["kind"] == "torque"
    np.testing.assert_allclose(res.speed, 20.0 + 40.0 * res.t / J, rtol=1e-8)


def test_drive_round_trips_through_save_model(tmp_path):
    model = load_model(_model(tmp_path, DRIVE.replace(
        'type = "constant", torque = "40 N m" }',
        'type = "induction", breakdown_torque = "60 N m", breakdown_slip = 0.2, '
        'synchronous_speed = "1500 rpm", ripple = { amplitude = "2 N m", order = 2 } }')
        + 'inertia = "0.2 kg m^2"\ntorque_damping = false\n'))
    again = load_model(save_model(model, tmp_path / "again.toml"))
    a, b = model.analyses["start"].drive, again.analyses["start"].drive
    assert a.to_toml() == b.to_toml()
    assert b.motor["synchronous_speed"] == pytest.approx(1500 * 2 * math.pi / 60)
    assert b.motor["ripple"] == {"amplitude": 2.0, "order": 2.0, "phase": 0.0}
    assert (b.inertia, b.torque_damping) == (0.2, False)


@pytest.mark.parametrize(("change", "match"), [
    (('type = "constant", torque = "40 N m"', 'type = "constant", torque = "40 m"'),
     r"drive\.motor\.torque"),
    (('type = "constant", torque = "40 N m"', 'type = "induction", breakdown_torque = 5'),
     r"drive\.motor.*breakdown_slip"),
    (('type = "quadratic", coefficient = 0.0', 'type = "quadratic", torque = 1.0'),
     r"drive\.loads\[0\].*'torque' is not a key of a quadratic law"),
    (('{ node = 4, type', '{ node = 9, type'), r"drive\.friction\[0\]"),
    (("node = 0\nmotor", "motor"), r"drive.*give node or z"),
])
def test_bad_drive_tables_name_the_key(tmp_path, change, match):
    with pytest.raises(ModelError, match=match):
        load_model(_model(tmp_path, DRIVE.replace(*change)))


def test_drive_excludes_a_speed_ramp(tmp_path):
    path = _model(tmp_path)
    path.write_text(path.read_text().replace('speed = "20 rad/s"',
                                             'speed = "20 rad/s"\nspeed_stop = "30 rad/s"'))
    with pytest.raises(ModelError, match=r"analyses\.start\.drive: a drive sets the speed"):
        load_model(path)
