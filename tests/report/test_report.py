"""``rotorsim report MODEL``: one self-contained HTML page per model.

The page must parse as XML after its doctype (every tag closed, every attribute quoted),
embed every figure as a base64 PNG, reference nothing outside itself, show the numbers of
the HDF5 results beside it, and render in a headless browser (Debian's chromium; the
test skips and says why where it is missing)."""

from __future__ import annotations

import base64
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.plotting.figures import DRAWERS

MODELS = Path(__file__).resolve().parents[2] / "models"
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module", params=["compressor", "default"])
def report(request, tmp_path_factory):
    out = tmp_path_factory.mktemp(request.param)
    code = main(["report", str(MODELS / f"{request.param}.toml"), "--out", str(out),
                 "--fast"])
    assert code == 0
    folder = out / request.param
    return request.param, folder / "report.html", folder / "report.h5"


def _tree(path: Path) -> ET.Element:
    text = path.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>\n")
    return ET.fromstring(text.split("\n", 1)[1])


def _sections(root: ET.Element) -> dict[str, list[ET.Element]]:
    """Elements of the body grouped under each ``h2`` (by its id)."""
    body = root.find("body")
    assert body is not None
    out: dict[str, list[ET.Element]] = {}
    current = None
    for element in body:
        if element.tag == "h2":
            current = element.get("id")
            out[current] = []
        elif current is not None:
            out[current].append(element)
    return out


def test_page_is_well_formed_and_self_contained(report):
    _, html, _ = report
    root = _tree(html)
    images = list(root.iter("img"))
    assert images
    for img in images:
        src = img.get("src", "")
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == PNG
    for element in root.iter():
        for key in ("src", "href"):
            value = element.get(key)
            assert value is None or value.startswith(("data:", "#")), value
    assert "http://" not in html.read_text() and "https://" not in html.read_text()


def test_every_figure_is_present(report):
    name, html, h5 = report
    model = rs.load_model(MODELS / f"{name}.toml")
    sections = _sections(_tree(html))
    assert set(model.analyses) <= set(sections)
    results = rs.load(h5)
    for analysis in model.analyses:
        figures = [e for e in sections[analysis] if e.tag == "figure"]
        has_drawer = type(results[analysis]).__name__ in DRAWERS
        assert bool(figures) == has_drawer, analysis
        if type(results[analysis]).__name__ == "ModalResult":
            assert len(figures) == min(4, results[analysis].num_modes)
    assert any(e.tag == "figure" for e in sections["model"])  # the layout
    if model.rolling_bearings:
        assert sum(e.tag == "figure" for e in sections["rolling-bearings"]) == len(
            model.rolling_bearings)


def test_numbers_are_traceable_to_the_hdf5_results(report):
    name, html, h5 = report
    results = rs.load(h5)
    sections = _sections(_tree(html))
    for analysis, elements in sections.items():
        if analysis in results:
            texts = " ".join("".join(e.itertext()) for e in elements)
            assert f"group /results/{analysis}" in texts
    if name == "compressor":
        stability = results["api_stability"]
        texts = " ".join("".join(e.itertext()) for e in sections["api_stability"])
        for value in (f"{stability.q0 / 1e3:.4g}", f"{stability.q_ratio:.4g}",
                      f"{stability.csr:.4g}", f"{stability.log_dec_a:.4g}"):
            assert value in texts
        unbalance = results["api_unbalance"]
        texts = " ".join("".join(e.itertext()) for e in sections["api_unbalance"])
        finite = np.isfinite(unbalance.af)
        assert all(f"{af:.3g}" in texts for af in unbalance.af[finite])


def _chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.skipif(_chromium() is None, reason="no chromium on this machine (Debian "
                    "package 'chromium'; .ci/run installs it): the browser check is skipped")
def test_renders_in_a_headless_browser(report, tmp_path):
    import matplotlib.image as mpimg

    _, html, _ = report
    shot = tmp_path / "shot.png"
    subprocess.run([_chromium(), "--headless", "--no-sandbox", "--disable-gpu",
                    "--hide-scrollbars", f"--screenshot={shot}", "--window-size=1200,2000",
                    html.resolve().as_uri()], check=True, capture_output=True, timeout=120)
    pixels = mpimg.imread(shot)[..., :3]
    # non-blank: text and figures make dark pixels and a spread of grey levels
    assert (pixels.mean(axis=2) < 0.5).mean() > 0.005
    assert pixels.std() > 0.05


def test_bearing_lives_are_traceable_to_the_hdf5_results(report):
    """Every rolling bearing gets its life at the static load, over the transient and along
    the periodic branch over speed, each stored in its own HDF5 group; the table shows the
    stored numbers (4 significant digits, as the page writes them)."""
    from rotorsim.report.bearing_life import life_row

    name, html, h5 = report
    model = rs.load_model(MODELS / f"{name}.toml")
    results = rs.load(h5)
    if not model.rolling_bearings:  # the compressor: journal bearings, no lives
        assert not [k for k in results if "life" in k]
        return
    sections = _sections(_tree(html))
    kinds = {"life": "rolling-bearings", **{
        f"{a}_life": a for a, spec in model.analyses.items()
        if spec.type in ("transient", "periodic")}}
    assert len(kinds) == 3  # the default model has one transient and one periodic branch
    for prefix, section in kinds.items():
        rows = [tuple(td.text or "" for td in tr.iter("td"))
                for e in sections[section] for tr in e.iter("tr")]
        for rolling in model.rolling_bearings:
            key = f"{prefix}_{rolling.tag}"
            life = results[key]
            assert isinstance(life, rs.BearingLifeResult)
            assert 0 < life.L10r < np.inf
            assert life_row(life, rolling.tag, key) in rows
    static = results[f"life_{model.rolling_bearings[0].tag}"]
    assert static.L10r == pytest.approx(static.L10, rel=0.5)  # ISO/TS 16281 near ISO 281
