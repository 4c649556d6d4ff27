"""``rotorsim bearing``: tables on stdout, HDF5 results and figures per rolling bearing; the
linearisation table of ``run``; one-line errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import EXIT_BAD_INPUT, main
from rotorsim.io.model_file import load_model

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_bearing_writes_results_and_figures(tmp_path, capsys):
    assert main(["bearing", str(MODELS / "rolling_ball.toml"), "--out", str(tmp_path),
                 "--fast"]) == 0
    out = capsys.readouterr().out
    folder = tmp_path / "rolling_ball"
    linear = load_model(MODELS / "rolling_ball.toml").linearized()
    for i, tag in enumerate(("DE", "NDE")):
        result = rs.load(folder / f"bearing_{tag}.h5")
        assert type(result).__name__ == "BearingEquilibriumResult"
        np.testing.assert_array_equal(result.load, linear.loads[i])
        np.testing.assert_array_equal(result.stiffness, linear.bearings[i].stiffness_matrix)
        variation = rs.load(folder / f"bearing_{tag}_pass.h5")
        assert variation.stiffness.shape == (6, 5, 5)
        for name in (f"bearing_{tag}.png", f"bearing_{tag}_pass.png"):
            assert (folder / name).stat().st_size > 10_000
    assert "rolling bearings linearised at their static loads" in out
    assert "bearing 'DE' (BallBearing, 9 elements): loaded 3/9" in out
    assert "stiffness matrix K_ij" in out and "Mx [N m]" in out
    assert "stiffness over one element pass (6 positions)" in out
    life = rs.load(folder / "bearing_DE_life.h5")
    assert type(life).__name__ == "BearingLifeResult" and life.source == "equilibrium"
    assert (folder / "bearing_DE_life.png").stat().st_size > 10_000
    assert f"L10r = {life.L10r:.4g} Mrev" in out and "max Hertz pressure inner" in out
    # the element table of DE: one row per ball with the loads of the result file
    lines = out.splitlines()
    start = lines.index(next(line for line in lines if line.startswith("element  angle")))
    rows = [line.split() for line in lines[start + 2:start + 11]]
    de = rs.load(folder / "bearing_DE.h5")
    np.testing.assert_allclose([float(r[2]) for r in rows], de.element_load, atol=5e-4)
    np.testing.assert_allclose([float(r[3]) for r in rows], np.degrees(de.contact_angle),
                               atol=5e-4)


RATING = """
[rolling_bearings.rating]
C = "14.8 kN"
C0 = "7.8 kN"
viscosity_ratio = 1.5
contamination = 0.5
fatigue_load_limit = "335 N"
reliability = 95
shoulder_heights = ["1.5 mm", "1.5 mm"]
"""


def test_rating_table_of_a_model_file(tmp_path, capsys):
    """``[rolling_bearings.rating]`` of the DE bearing: catalogue ratings and the a_ISO
    inputs reach the life; the NDE bearing (no table) is rated from its geometry."""
    text = (MODELS / "rolling_ball.toml").read_text()
    marker = 'damping_factor = "20 us"\n'
    head, tail = text.split(marker, 1)
    path = tmp_path / "rated.toml"
    path.write_text(head + marker + RATING + tail)
    model = load_model(path)
    assert model.ratings[0].C == 14.8e3 and model.ratings[1] is None
    assert model.ratings[0].shoulder_heights == (1.5e-3, 1.5e-3)
    assert main(["bearing", str(path), "--out", str(tmp_path), "--no-plots", "--fast"]) == 0
    de = rs.load(tmp_path / "rolling_ball" / "bearing_DE_life.h5")
    nde = rs.load(tmp_path / "rolling_ball" / "bearing_NDE_life.h5")
    assert de.rating_source == "catalogue" and de.C == 14.8e3 and de.a1 == 0.64
    assert de.a_iso > 1 and not np.isnan(de.shoulder_margin).any()
    assert nde.rating_source.startswith("ISO 281 geometry")
    bad = path.read_text().replace('contamination = 0.5\n', "")
    path.write_text(bad)
    with pytest.raises(rs.ModelError, match=r"rating\.contamination: a_ISO needs"):
        load_model(path)


def test_bearing_tag_selects_one(tmp_path, capsys):
    assert main(["bearing", str(MODELS / "rolling_tapered.toml"), "--tag", "B", "--out",
                 str(tmp_path), "--no-plots", "--fast"]) == 0
    files = sorted(p.name for p in (tmp_path / "rolling_tapered").iterdir())
    assert files == ["bearing_B.h5", "bearing_B_life.h5", "bearing_B_pass.h5"]
    out = capsys.readouterr().out
    assert "bearing 'B' (ReversedBearing, 17 elements): loaded 17/17" in out


@pytest.mark.parametrize(("argv", "fragment"), [
    (["bearing", "{models}/rolling_ball.toml", "--tag", "XX"],
     "--tag: no rolling bearing tagged 'XX'; the model has DE, NDE"),
    (["bearing", "{models}/friswell_5_9_1.toml"],
     "friswell_5_9_1: the model has no [[rolling_bearings]]"),
])
def test_bearing_bad_input(argv, fragment, tmp_path, capsys):
    argv = [a.format(models=MODELS) for a in argv] + ["--out", str(tmp_path)]
    assert main(argv) == EXIT_BAD_INPUT
    err = capsys.readouterr().err.strip()
    assert err == f"rotorsim: error: {fragment}"


def test_run_and_info_name_the_rolling_bearings(tmp_path, capsys):
    assert main(["info", str(MODELS / "rolling_tapered.toml")]) == 0
    assert "rolling_bearings" in capsys.readouterr().out
    assert main(["run", str(MODELS / "rolling_tapered.toml"), "static", "--out",
                 str(tmp_path), "--fast"]) == 0
    out = capsys.readouterr().out
    assert "rolling bearings linearised at their static loads" in out
    static = rs.load(tmp_path / "rolling_tapered" / "static.h5")
    assert static.options["rolling_bearings"]["tags"] == ["A", "B"]
    # the 400 N thrust: the axial reactions of both bearings balance it
    assert static.bearing_forces[:, 2].sum() == pytest.approx(-400.0, rel=1e-6)
    assert (tmp_path / "rolling_tapered" / "layout.png").stat().st_size > 5000
