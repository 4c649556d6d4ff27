"""API Level I stability: Q0 of a Jeffcott rotor against the closed form, Q0 of the
compressor model against an independent eigenvalue computation, the sweep's content, and
the errors on bad input.

Closed form. A disk of mass m on an isotropic spring k and damper c, with cross-coupling
``kxy = Q, kyx = -Q`` at the disk: in ``z = x + i y``, ``m z'' + c z' + (k - i Q) z = 0``.
A root ``lam = i w`` on the imaginary axis needs ``-m w^2 + k = 0`` and ``c w - Q = 0``:
the threshold is ``Q0 = c wn``, ``wn = sqrt(k / m)``, whatever the spin speed (the disk's
tilt, where the gyroscopic terms act, is uncoupled from its translation).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

import rotorsim as rs
from rotorsim.assembly.system import assemble

MODELS = Path(__file__).resolve().parents[3] / "models"
RPM = math.pi / 30.0


def _jeffcott(m: float, k: float, c: float) -> rs.Rotor:
    disk = rs.DiskElement(n=0, m=m, Id=0.2 * m * 0.01, Ip=0.4 * m * 0.01)
    bearing = rs.BearingElement(n=0, kxx=k, cxx=c, kzz=k, krr=0.05 * k)
    return rs.Rotor([], [disk], [bearing]).without_axial_torsion()


@pytest.mark.validation
@pytest.mark.parametrize(("m", "k", "c", "speed"), [
    (100.0, 1e7, 2e3, 1000.0), (35.0, 4e6, 500.0, 300.0), (250.0, 8e7, 1.5e4, 2000.0)])
def test_jeffcott_threshold_is_c_times_wn(m, k, c, speed):
    """Q0 = c wn. Brent's method stops at rtol 1e-10 on Q; the log decrement it zeroes is
    computed by the eigen solver to about 1e-12 relative, so 1e-8 is a safe bound."""
    stage = rs.ApiStage(node=0, power=5e4, diameter=0.3, flow_height=0.02)
    result = rs.api_level1(_jeffcott(m, k, c), speed, [stage], apply_at="stages",
                           q_max=2 * c * math.sqrt(k / m), rtol=1e-10)
    assert result.q0 == pytest.approx(c * math.sqrt(k / m), rel=1e-8)
    # the tracked mode is the translational one at wn (damped: wd < wn)
    assert result.frequency[0] == pytest.approx(math.sqrt(k / m - (c / (2 * m)) ** 2),
                                                rel=1e-9)


def _state_matrix_log_dec(system, speed: float, node: int, q: float) -> float:
    """Log decrement of the lowest forward-whirling mode from scipy's dense eig of the
    first-order form, built here from the assembled matrices plus the cross-coupling
    entries: independent of rotorsim's modal solver and mode classification."""
    mats = system.matrices(speed)
    M, K = mats.M.toarray(), mats.K.toarray()
    D = (mats.C + speed * mats.G).toarray()
    free = system.dof_map.free
    ix = int(np.flatnonzero(free == 6 * node)[0])
    iy = int(np.flatnonzero(free == 6 * node + 1)[0])
    K[ix, iy] += q
    K[iy, ix] -= q
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K),
                                                  -np.linalg.solve(M, D)]])
    lam, vec = scipy.linalg.eig(A)
    keep = lam.imag > 1.0
    lam, vec = lam[keep], vec[:n, keep]
    fwd = np.abs(vec[ix] + 1j * vec[iy]) > np.abs(vec[ix] - 1j * vec[iy])  # x + i y whirl
    j = np.flatnonzero(fwd)[np.argmin(np.abs(lam[fwd]))]
    return float(-2 * math.pi * lam[j].real / lam[j].imag)


@pytest.mark.validation
def test_compressor_q0_against_an_independent_eigen_solution():
    """The compressor model with its stages: Q0 from api_level1 zeroes the log decrement
    that scipy's dense eig of the state matrix gives (|log dec| at Q0 below 1e-6, the
    resolution of Q0 times the slope of the curve), and both agree at Q_A to 1e-6."""
    model = rs.load_model(MODELS / "compressor.toml")
    spec = model.analyses["api_stability"]
    result = rs.run_analysis(model, "api_stability")
    system = assemble(model.rotor)
    [node] = result.stations.tolist()
    assert abs(_state_matrix_log_dec(system, spec.mcs, node, result.q0)) < 1e-6
    assert _state_matrix_log_dec(system, spec.mcs, node, result.q_a) == pytest.approx(
        result.log_dec_a, abs=1e-6)


def test_sweep_content_and_screening():
    model = rs.load_model(MODELS / "compressor.toml")
    result = rs.run_analysis(model, "api_stability")
    assert result.applied[0] == 0 and result.applied[10] == pytest.approx(10 * result.q_a)
    assert np.all(np.diff(result.log_dec[:11]) < 0)  # the cross-coupling destabilises
    assert result.q_ratio == pytest.approx(result.q0 / result.q_a)
    assert 1 < result.csr < 3
    expected, reasons = rs.level1_screening(result.q_ratio, result.log_dec_a, result.csr,
                                            result.density)
    assert result.level2_required == expected and result.reasons == reasons
    assert result.stage_q.sum() == pytest.approx(result.q_a)


def test_stage_stations_share_q_a():
    model = rs.load_model(MODELS / "compressor.toml")
    spec = model.analyses["api_stability"]
    stages = [rs.ApiStage(s.node, s.power, s.diameter, s.flow_height, s.density_ratio)
              for s in spec.stages]
    result = rs.api_level1(model.rotor, spec.mcs, stages, apply_at="stages", num=4)
    assert result.stations.tolist() == sorted(s.node for s in spec.stages)
    assert result.station_share.sum() == pytest.approx(1.0)


@pytest.mark.parametrize(("change", "match"), [
    (dict(stages=[]), "machine data"), (dict(mcs=-10.0), "mcs"),
    (dict(machine="pump"), "machine"), (dict(apply_at="bearings"), "apply_at"),
    (dict(q_max=-1.0), "q_max")])
def test_bad_input_raises_model_error(change, match):
    args = dict(rotor=_jeffcott(100.0, 1e7, 2e3), mcs=1000.0,
                stages=[rs.ApiStage(node=0, power=5e4, diameter=0.3, flow_height=0.02)])
    args.update(change)
    with pytest.raises(rs.ModelError, match=match):
        rs.api_level1(**args)


@pytest.mark.parametrize("bad", [dict(power=-5e4), dict(diameter=0.0),
                                 dict(density_ratio=math.inf), dict(node=-1)])
def test_bad_stage_data(bad):
    args = dict(node=0, power=5e4, diameter=0.3, flow_height=0.02)
    args.update(bad)
    with pytest.raises(rs.ModelError):
        rs.ApiStage(**args)


def test_machines_of_several_lines_are_refused():
    """API 617's mid-span, anti-nodes and CSR are those of one rotor: a two-spool machine
    is refused by name rather than analysed as if its lines were one shaft."""
    model = rs.load_model(MODELS / "two_spool.toml")
    stage = rs.ApiStage(node=2, power=5e4, diameter=0.3, flow_height=0.02)
    with pytest.raises(rs.ModelError, match="one shaft line"):
        rs.api_level1(model.rotor, 1000.0, [stage])
    # the unbalance check is made per spool (tests/analyses/standards/test_api_spools.py):
    # without one named it is refused by name too
    with pytest.raises(rs.ModelError, match="name the spool"):
        rs.api_unbalance(model.rotor, np.linspace(10.0, 1000.0, 20), min_speed=500.0,
                         mcs=600.0)
