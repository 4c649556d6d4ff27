"""PeriodicResult.stability_checks: the per-point Liouville and tangent-jump checks of a
rotor branch, saved and loaded; results files written before the field existed still load.

The rotor is the Jeffcott rotor on 9-ball Hertz bearings of ``test_periodic.py`` (Hsu on
the full system): Hertz contacts have continuous tangents, so no point falls back.
"""

from __future__ import annotations

import json

import h5py
import numpy as np
from test_periodic import UNBALANCE, fast, jeffcott

import rotorsim as rs
from rotorsim.analyses.periodic.periodic import periodic


def test_a_smooth_branch_records_passed_checks_that_survive_save_and_load(tmp_path):
    result = periodic(jeffcott(), start=1200.0, stop=1204.0, unbalance=UNBALANCE,
                      stability=rs.StabilityOptions("hsu", bifurcations=False), **fast())
    checks = result.stability_checks
    P = len(result)
    assert set(checks) == {"method", "passed", "liouville_error", "tangent_jumps",
                           "fallback_liouville_error"}
    assert checks["method"].tolist() == ["hsu"] * P and checks["passed"].all()
    assert (checks["tangent_jumps"] == 0).all()
    assert np.isnan(checks["fallback_liouville_error"]).all()
    path = tmp_path / "branch.h5"
    rs.save(result, path)
    loaded = rs.load(path)
    for key, value in checks.items():
        np.testing.assert_array_equal(loaded.stability_checks[key], value)
    # a file from before the field: drop it from the stored field list
    with h5py.File(path, "r+") as f:
        group = next(g for g in f.values() if isinstance(g, h5py.Group)
                     and "fields" in g.attrs) if "fields" not in f.attrs else f
        kinds = json.loads(group.attrs["fields"])
        del kinds["stability_checks"], group["stability_checks"]
        group.attrs["fields"] = json.dumps(kinds)
    assert rs.load(path).stability_checks == {}
