"""The public calls that docs and outside checks rely on keep working unchanged.

* The python blocks of ``README.md`` run in document order, in one namespace, in a
  temporary folder that sees the repository's ``models/``.
* The calls of the public API contract (DESIGN section 11) run as written there: the
  reshaping of the package (issue 13: subpackages, option groups, lazy public names) must
  not change a single keyword of them.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs

ROOT = Path(__file__).resolve().parents[1]


def _python_blocks(text: str) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.M | re.S)


def test_readme_python_blocks_run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    blocks = _python_blocks((ROOT / "README.md").read_text())
    assert len(blocks) >= 2
    shutil.copytree(ROOT / "models", tmp_path / "models")
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)
    assert (tmp_path / "campbell.h5").exists() and (tmp_path / "runup.png").exists()
    run = namespace["run"]
    assert isinstance(run, rs.TransientResult) and run.t[-1] == pytest.approx(0.2)


def test_design_section_11_calls_run(tmp_path: Path) -> None:
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel, shear_effects=True,
                             rotary_inertia=True, gyroscopic=True) for _ in range(6)]
    disks = [rs.DiskElement(n=2, m=32.6, Id=0.1, Ip=0.2)]
    bearings = [rs.BearingElement(n=0, kxx=1e6, kyy=1e6, cxx=0, cyy=0),
                rs.BearingElement(n=6, kxx=1e6, kyy=1e6, cxx=0, cyy=0)]
    rotor = rs.Rotor(shaft, disks, bearings)
    speeds = np.linspace(0.0, 400.0, 9)

    m = rs.modal(rotor, speed=0.0, num_modes=12)
    c = rs.campbell(rotor, speeds, num_modes=12)
    u = rs.unbalance_response(rotor, speeds, unbalance=[(2, 1e-4, 0.0)])
    k = rs.critical_speed_map(rotor, (1e5, 1e8))
    s = rs.static(rotor)
    # the rotor floats axially and in torsion (no axial bearing): start from rest
    t = rs.transient(rotor, 0.005, 1e-4, method="newmark", speed=100.0,
                     unbalance=[(2, 1e-4, 0.0)], initial="zero")
    model = rs.load_model(ROOT / "models" / "rolling_ball.toml")
    b = rs.periodic(model.rotor.with_nonlinear(model.rolling_bearings), start=300.0,
                    stop=305.0, harmonics=4, unbalance=[(5, 2e-5, 0.0)])
    rs.save(m, tmp_path / "modes.h5")

    assert isinstance(m, rs.ModalResult) and m.wn.shape == m.wd.shape
    assert len(m.whirl) == m.log_dec.size == m.damping_ratio.size
    assert isinstance(c, rs.CampbellResult) and c.wd.shape[0] == speeds.size
    assert isinstance(c.critical_speeds(harmonic=1), rs.CriticalSpeeds)
    assert u.amplitude(2, "uy").shape == u.phase(2, "uy").shape == speeds.shape
    assert isinstance(k, rs.CriticalSpeedMapResult) and isinstance(s, rs.StaticResult)
    assert isinstance(t, rs.TransientResult) and t.t[-1] == pytest.approx(0.005)
    # unbalance with the balls' varying compliance: the branch of tori (issue 17)
    assert isinstance(b, rs.QuasiPeriodicResult) and b.amplitude(5, "uy").size == b.parameter.size
    assert isinstance(rs.load(tmp_path / "modes.h5"), rs.ModalResult)
    eq = rs.bearing_equilibrium(model.rolling_bearings[0].bearing, [0.0, 500.0, 0.0, 0.0, 0.0])
    assert isinstance(eq, rs.BearingEquilibriumResult)
