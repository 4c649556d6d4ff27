"""Craig-Bampton reduction of rotor transients, nonlinear DOFs kept physical."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.statics.nonlinear_static import nominal_tangent
from rotorsim.assembly.reduction import accuracy, craig_bampton
from rotorsim.errors import ModelError

MODELS = Path(__file__).resolve().parents[3] / "models"


@pytest.fixture(scope="module")
def default_rotor():
    model = rs.load_model(MODELS / "default.toml")
    return model.rotor.with_nonlinear(model.rolling_bearings), list(model.loads.unbalance)


def test_all_interior_modes_reproduce_the_full_system(default_rotor):
    rotor, _ = default_rotor
    system = rs.assemble(rotor)
    b = system.nonlinear.dofs
    full = craig_bampton(system, b, system.n_free - b.size)
    check = accuracy(system, full, nominal_tangent(system), n_check=10)
    # With every interior mode the basis spans the whole space, so the frequencies agree to
    # the eigensolvers' accuracy. Each dense solve errs by ~eps (w_max / w_min)^2 relative
    # in w_min^2 (1.1e-10 for this model, where (w_max / w_min)^2 = 5e5), times a modest
    # factor from the conditioning of the two pencils: seen 2e-10 to 1.1e-9 across
    # OpenBLAS kernels. 1e-8 keeps a margin and is still 500x below the error of a
    # truncated basis (5e-6 with 16 modes, below).
    assert check["max_relative_error"] < 1e-8
    few = accuracy(system, craig_bampton(system, b, 8), nominal_tangent(system), n_check=6)
    more = accuracy(system, craig_bampton(system, b, 16), nominal_tangent(system), n_check=6)
    assert more["max_relative_error"] < few["max_relative_error"] < 1e-2


def test_static_vectors_are_m_orthonormal_and_keep_the_loads_span(default_rotor):
    # the static responses are orthogonalised against the modes by block Gram-Schmidt
    # applied twice ("twice is enough"): what they add to the basis must be M-orthonormal
    # to the modes and to each other, and with the modes span the responses themselves
    rotor, unbalance = default_rotor
    system = rs.assemble(rotor)
    b = np.unique(system.nonlinear.dofs)
    n = system.n_free
    loads = [np.zeros(n) for _ in range(3)]
    loads[0][1::6] = -9.81  # a gravity-like load on every uy
    node = int(unbalance[0][0])
    loads[1][6 * node + 1], loads[2][6 * node + 2] = 1.0, 1.0
    basis = craig_bampton(system, b, 12, static_loads=loads)
    inner = np.setdiff1d(np.arange(n), b)
    M = system.matrices(0.0).M
    M_ii = (M.toarray() if hasattr(M, "toarray") else np.asarray(M))[np.ix_(inner, inner)]
    X = basis.T[inner, b.size:]  # the modes, then the static vectors
    G = X.T @ M_ii @ X
    # orthonormal to round-off of the products (entries of M_ii up to ~1e1 kg, X of 1e1)
    assert basis.n_static == 3
    assert np.max(np.abs(G - np.eye(G.shape[0]))) < 1e-10
    K = system.matrices(0.0).K
    K_ii = (K.toarray() if hasattr(K, "toarray") else np.asarray(K))[np.ix_(inner, inner)]
    for f in loads:
        s = np.linalg.solve(K_ii, f[inner])
        coef = np.linalg.lstsq(X, s, rcond=None)[0]
        assert np.linalg.norm(X @ coef - s) <= 1e-10 * np.linalg.norm(s)


def test_a_pair_of_equal_frequencies_is_never_cut(default_rotor):
    """The default rotor is axisymmetric: its fixed-interface modes come in x/y pairs, and
    16 modes would end inside the pair at 6165 rad/s. Cutting there would keep a direction
    of the pair's eigenspace that differs between LAPACK builds (it made the reduced
    transient differ by 0.25 N between OpenBLAS kernels), so the pair is kept whole."""
    rotor, _ = default_rotor
    system = rs.assemble(rotor)
    b = system.nonlinear.dofs
    w16 = craig_bampton(system, b, 16).frequencies
    w17 = craig_bampton(system, b, 17).frequencies
    assert w16.size == 17
    # eigensolver accuracy: ~eps (w_max / w_min)^2, and other subset sizes take other paths
    np.testing.assert_allclose(w16, w17, rtol=1e-8)
    assert w16[-1] == pytest.approx(w16[-2], rel=1e-6)
    assert craig_bampton(system, b, 2).frequencies.size == 2  # a whole pair: kept as asked
    assert craig_bampton(system, b, 3).frequencies.size == 3  # a single mode ends the cut


@pytest.mark.verification
def test_reduced_transient_matches_the_full_one(default_rotor):
    rotor, unbalance = default_rotor
    kw = dict(speed=300.0, unbalance=unbalance, nodes=[8, 16])
    full = rs.transient(rotor, 0.03, 1e-4, **kw)
    red = rs.transient(rotor, 0.03, 1e-4, reduction=16, **kw)
    report = red.options["reduction"]
    assert report["requested_modes"] == 16 and report["fixed_interface_modes"] == 17
    assert report["size"] < full.dof_map.n_free / 4 and report["max_relative_error"] < 1e-4
    np.testing.assert_allclose(red.q[0], full.q[0], rtol=0, atol=1e-12)  # static start exact
    for node in (8, 16):
        y, y_ref = red.displacement(node, "uy"), full.displacement(node, "uy")
        assert np.abs(y - y_ref).max() < 1e-3 * np.ptp(y_ref)
    np.testing.assert_allclose(red.bearing_loads, full.bearing_loads, rtol=0,
                               atol=1e-3 * np.abs(full.bearing_loads).max())


def test_reduction_needs_nonlinear_dofs_and_a_valid_mode_count(default_rotor):
    rotor, _ = default_rotor
    with pytest.raises(ModelError, match="nonlinear"):
        rs.transient(rotor.linear_part().with_bearings(
            [rs.BearingElement(n=0, kxx=1e8), rs.BearingElement(n=24, kxx=1e8)]),
            0.001, 1e-4, reduction=4, excitation=rs.Excitation(gravity=None), initial="zero")
    with pytest.raises(ModelError, match="num_modes"):
        rs.transient(rotor, 0.001, 1e-4, reduction=10_000)


def _three_equal_spans():
    """A shaft of three equal spans on four ball bearings: its fixed-interface modes come
    in clusters of six (x and y bending of three identical spans)."""
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    from rotorsim.elements.rolling.ball.bearing import BallBearing
    from rotorsim.elements.rolling.element import RollingBearing

    ball = BallBearing(n_balls=8, pitch_diameter=0.035, ball_diameter=0.007, Kn=8e9,
                       diametral_clearance=10e-6, f_i=0.52, f_o=0.52)
    shaft = [rs.ShaftElement(L=0.04, idl=0.0, odl=0.03, material=steel) for _ in range(12)]
    bearings = [RollingBearing(ball, n=n) for n in (0, 4, 8, 12)]
    return rs.assemble(rs.Rotor(shaft).with_nonlinear(bearings))


def test_repeated_fixed_interface_frequencies_are_all_found_by_the_sparse_path(monkeypatch):
    # ARPACK from a symmetric start vector found 4 of a 6-fold cluster on such a rotor
    # (benchmarks/bench_transient.py rotor1000); the block subspace check completes it.
    import scipy.linalg as sl
    import scipy.sparse as sp

    import rotorsim.assembly.reduction as red

    system = _three_equal_spans()
    inner = np.setdiff1d(np.arange(system.n_free), system.nonlinear.dofs)
    mats = system.matrices(0.0)
    K = sp.csr_matrix(mats.K)[inner][:, inner]
    M = sp.csr_matrix(mats.M)[inner][:, inner]
    exact = np.sqrt(sl.eigh(K.toarray(), M.toarray(), eigvals_only=True,
                            subset_by_index=(0, 11)))
    monkeypatch.setattr(red, "DENSE_EIGEN", 10)  # force the sparse (ARPACK) path
    w, phi = red.fixed_interface_modes(K, M, 8)
    # eigenvalues of well separated clusters: shift-invert converges to round-off; 1e-8
    # leaves room for the clustered copies' conditioning
    np.testing.assert_allclose(w[:12], exact[:w[:12].size], rtol=1e-8)
    np.testing.assert_allclose(phi.T @ (M @ phi), np.eye(w.size), atol=1e-9)
