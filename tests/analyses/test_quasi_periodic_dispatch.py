"""``rs.periodic`` on unbalance with incommensurate varying compliance returns the branch of
tori (issue 17): nothing is frozen, so ``result.approximation`` is gone.

The Jeffcott rotor of ``tests/analyses/periodic/test_periodic.py`` with its cages turning
(``Z kappa = 3.5719``): its torus at 800 rad/s is checked against ``rs.transient`` with the
balls moving in ``test_quasi_periodic_rotor.py``; here the dispatch, the result's
accessors, its file round trip, summary and figure, and the options a torus refuses.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.errors import ModelError
from rotorsim.results.quasi_periodic import QuasiPeriodicResult

sys.path.insert(0, str(Path(__file__).resolve().parent / "periodic"))
from test_periodic import UNBALANCE, jeffcott

ROTOR = jeffcott("rotating")


@pytest.fixture(scope="module")
def branch() -> QuasiPeriodicResult:
    res = rs.periodic(ROTOR, start=790.0, stop=810.0, harmonics=6, unbalance=UNBALANCE,
                      nodes=[1], continuation=rs.ContinuationOptions(max_points=12))
    assert isinstance(res, QuasiPeriodicResult)
    return res


def test_periodic_returns_the_tori_with_nothing_frozen(branch: QuasiPeriodicResult) -> None:
    assert branch.approximation == "" and branch.status == rs.Status.OK
    assert branch.speed[0] == 790.0 and branch.speed[-1] == pytest.approx(810.0, rel=1e-12)
    assert len(branch) <= 12
    assert branch.vc_order == pytest.approx(9 / 2 * (1 - 0.00794 / 0.0385), rel=1e-12)
    np.testing.assert_allclose(branch.vc_frequency, branch.vc_order * branch.speed,
                               rtol=1e-14)
    # H = 6 maps to the box (6, 2): 32 tones
    assert len(branch.tones) == 32 and branch.options["box"] == [6, 2]
    i = len(branch) // 2
    point = rs.quasi_periodic_point(ROTOR, float(branch.speed[i]), unbalance=UNBALANCE,
                                    harmonics=(6, 2), truncation="box")
    one_x = point.amplitude(1, "uy", 1, 0)
    # the continuation's corrector and the point's Newton both converge to 1e-9
    assert abs(branch.tone(1, "uy", 1, 0)[i]) == pytest.approx(one_x, rel=1e-6)
    assert abs(branch.tone(1, "uy", -1, 0)[i]) == pytest.approx(one_x, rel=1e-6)
    freq, amp, k = branch.spectrum(i, 1, "uy")
    one = int(np.flatnonzero((k[:, 0] == 1) & (k[:, 1] == 0))[0])
    assert freq[one] == pytest.approx(branch.speed[i], rel=1e-14)
    assert amp[one] == pytest.approx(one_x, rel=1e-6) and np.all(np.diff(amp) <= 0)
    t = np.linspace(0.0, 0.05, 400)
    np.testing.assert_allclose(branch.time_response(i, t)[:, branch.column(1, "uy")],
                               point.response(t, 1, "uy"),
                               atol=1e-6 * np.ptp(point.response(t, 1, "uy")))


def test_every_torus_has_its_exponents(branch: QuasiPeriodicResult) -> None:
    """5000 N s/m on each journal: the tori are stable, their exponents converged in the
    stability boxes, and no stability change is reported."""
    assert branch.has_stability and branch.stable.all() and not branch.events
    assert branch.exponents_converged.all() and branch.stability_method == "hill"


def test_the_result_is_saved_summarised_and_drawn(branch: QuasiPeriodicResult,
                                                  tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from rotorsim.cli.summaries import summarize

    path = rs.save(branch, tmp_path / "tori.h5")
    back = rs.load(path)
    assert isinstance(back, QuasiPeriodicResult)
    np.testing.assert_array_equal(back.coefficients, branch.coefficients)
    np.testing.assert_array_equal(back.tones, branch.tones)
    np.testing.assert_array_equal(back.exponents, branch.exponents)
    text = summarize(branch)
    assert "quasi-periodic branch" in text and "stable tori" in text
    fig = rs.plot(branch)
    assert len(fig.axes) >= 4


def test_what_a_torus_cannot_do_is_refused_with_the_way_out() -> None:
    for kwargs in ({"peaks": [(1, "uy")]}, {"fold_map": True},
                   {"x0": np.zeros(6 * 3)}):
        with pytest.raises(ModelError, match="varying_compliance=False"):
            rs.periodic(ROTOR, start=790.0, stop=810.0, harmonics=6, unbalance=UNBALANCE,
                        **kwargs)
    frozen = rs.periodic(ROTOR, start=780.0, stop=790.0, harmonics=4, unbalance=UNBALANCE,
                         varying_compliance=False, stability=None, nodes=[1],
                         continuation=rs.ContinuationOptions(max_points=3))
    assert "frozen" in frozen.approximation
