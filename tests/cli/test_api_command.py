"""``rotorsim api MODEL``: the API checks a model file names, their HDF5 results, figures
and tables; a model without them is bad input; model-file errors name the key."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import EXIT_BAD_INPUT, main

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_api_runs_the_checks_and_writes_hdf5(tmp_path, capsys):
    assert main(["api", str(MODELS / "compressor.toml"), "--out", str(tmp_path)]) == 0
    folder = tmp_path / "compressor"
    stability = rs.load(folder / "api_stability.h5")
    unbalance = rs.load(folder / "api_unbalance.h5")
    assert type(stability).__name__ == "ApiLevel1Result"
    assert type(unbalance).__name__ == "ApiUnbalanceResult"
    direct = rs.run_analysis(rs.load_model(MODELS / "compressor.toml"), "api_stability")
    assert stability.q0 == direct.q0 and np.array_equal(stability.log_dec, direct.log_dec)
    assert unbalance.clearance_tags[0] == "eye seal 1"
    for name in ("api_stability", "api_unbalance"):
        assert (folder / f"{name}.png").stat().st_size > 5000
    out = capsys.readouterr().out
    assert "Q0/QA" in out and "SM actual [%]" in out
    assert "campbell" not in [p.stem for p in folder.glob("*.h5")]  # only the API checks


def test_api_without_checks_is_bad_input(tmp_path, capsys):
    code = main(["api", str(MODELS / "friswell_5_9_1.toml"), "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "api_stability" in capsys.readouterr().err


@pytest.mark.parametrize(("edit", "message"), [
    ({"power": "-400 kW"}, "stages[0].power"),
    ({"diameter": None}, "stages[0].diameter"),
])
def test_model_file_errors_name_the_key(tmp_path, edit, message):
    import tomllib

    data = tomllib.loads((MODELS / "compressor.toml").read_text())
    stage = data["analyses"]["api_stability"]["stages"][0]
    for key, value in edit.items():
        if value is None:
            del stage[key]
        else:
            stage[key] = value
    with pytest.raises(rs.ModelError, match=message.replace("[", r"\[").replace("]", r"\]")):
        from rotorsim.io.model import model_from_dict

        model_from_dict(data)


def test_mcs_outside_the_analysed_speeds_is_refused():
    import tomllib

    from rotorsim.io.model import model_from_dict

    data = tomllib.loads((MODELS / "compressor.toml").read_text())
    data["analyses"]["api_unbalance"]["mcs"] = "14000 rpm"
    model = model_from_dict(data)
    with pytest.raises(rs.ModelError, match="MCS outside the analysed range"):
        rs.run_analysis(model, "api_unbalance")
