"""Stability of a quasi-periodic solution by the quasi-periodic Hill method: the
characteristic exponents of the variational equation along the torus, from the eigenvalues
of its Hill matrix with a selection of the eigenvalues that belong to the exponents.

A perturbation ``y`` of the torus obeys (:mod:`~.lyapunov`)

    M y'' + (D + Ct(theta)) y' + (K + Kt(theta)) y = 0,     theta = (w1 t, w2 t),

``D = C + W G``, ``Kt`` and ``Ct`` the nonlinear force's tangents on the torus. With the
Floquet-type ansatz ``y = e^{lam t} p(theta)``, ``p`` on a box of tones ``k1 w1 + k2 w2``,
``|k1| <= a``, ``|k2| <= b``, and ``y' = e^{lam t} u(theta)``, with ``Y`` and ``V`` the
real cosine-sine coefficients of ``p`` and ``u`` (the harmonic balance's layout),
balancing every tone gives the real eigenproblem

    lam Y = V - Dm Y,
    lam M V = -K Y - D V - M Dm V - T(Kt) Y_N - T(Ct) V_N,

``Dm`` the derivative of the coefficients (``d/dt`` of a tone) and ``T(Kt)`` the product
with the sampled tangent, projected on the box (exactly the harmonic balance Jacobian's
operator, :meth:`~rotorsim.harmonic_balance.quasi.aft.TorusAFT.jacobian`). In real
arithmetic this costs a quarter of the equivalent complex form. Each
exponent ``lam`` of the untruncated problem appears once per tone, shifted by ``i
Omega_m`` with its eigenvector shifted by ``m``; the truncation adds spurious eigenvalues
at the edge of the box. The *selection* keeps the eigenvalues whose eigenvector lies inside the
box, with little of its norm on the edge tones (a shifted copy of a true exponent away
from the edge has the exponent's real part; Guillot, Lazarus, Thomas, Vergez, Cochelin,
*J. Comput. Phys.* 416 (2020) 109477, sort Hill eigenvalues by their eigenvectors too). A
copy straddling two tones (a parametric resonance, ``Im lam`` half a tone) is kept as
well, which a "largest block on the central tone" rule would drop. The torus is
asymptotically stable when every selected exponent has a negative real part; both base
frequencies are imposed, so no exponent is neutral.

Unlike the Lyapunov estimate, whose resolution is ``1 / T`` of its horizon, the exponents'
real parts are resolved whatever the damping, so a lightly damped rotor (``-zeta w`` near
-0.1 1/s) gets its sign. The box of the stability tones can be smaller than that of the
solution (a truncated Hill matrix), which the tests compare against the Lyapunov exponent
and time integration.

References
----------
G. W. Hill, *Acta Math.* 8 (1886) 1-36 (the method); A. Lazarus, O. Thomas, *C. R. Mec.*
338 (2010) 510-517 (its rotor form); L. Guillot et al., *J. Comput. Phys.* 416 (2020)
109477 (eigenvalue selection by the eigenvectors); issue 17 part 2.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi.aft import TorusAFT
from rotorsim.harmonic_balance.quasi.harmonics import TorusHarmonics
from rotorsim.harmonic_balance.quasi.residual import QuasiProblem
from rotorsim.solvers.threads import blas_threads_for

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
MAX_ROWS = 4000
"""Largest Hill matrix (dense eigenproblem) accepted."""
EDGE_SHARE = 0.1
"""Largest share of an eigenvector's displacement norm on the edge tones of the box for its
eigenvalue to count as an exponent (spurious eigenvalues of the truncation live there)."""


@dataclass(frozen=True, eq=False)
class TorusExponents:
    """Characteristic exponents of a torus from the quasi-periodic Hill method.

    Attributes
    ----------
    exponents : complex array (r,)
        The selected exponents [1/s], by decreasing real part (``r`` is about ``2 n``).
    box : (int, int)
        The stability tones ``|k1| <= a``, ``|k2| <= b``.
    edge_share : array (r,)
        Share of each selected eigenvector's displacement norm on the edge tones of the
        box (near 0 for a weakly modulated torus; a value near :data:`EDGE_SHARE` or above
        warns that the box is too small for the modulation).
    """

    exponents: ComplexArray
    box: tuple[int, int]
    edge_share: FloatArray

    @property
    def largest(self) -> float:
        """The largest real part [1/s] (negative: stable)."""
        return float(self.exponents.real.max()) if self.exponents.size else float("nan")

    @property
    def stable(self) -> bool:
        """Every selected exponent has a negative real part."""
        return self.largest < 0.0

    @property
    def critical_frequency(self) -> float:
        """``|Im lam|`` [rad/s] of the exponent with the largest real part (modulo the
        tones): the frequency at which the least stable perturbation oscillates."""
        return float(abs(self.exponents[0].imag)) if self.exponents.size else float("nan")


def hill_exponents(problem: QuasiProblem, X_nl: FloatArray, aft: TorusAFT, w1: float,
                   w2: float, box: tuple[int, int] = (2, 1)) -> TorusExponents:
    """Characteristic exponents of the torus with nonlinear-DOF coefficients ``X_nl``.

    Parameters
    ----------
    problem : QuasiProblem
        The linear part (full or reduced; ``problem.nl_dofs`` locate the nonlinear DOFs)
        and the nonlinear force whose tangents enter.
    X_nl : array (rows, d)
        Coefficients of the nonlinear DOFs on ``aft``'s harmonic set [m, rad].
    aft : TorusAFT
        Harmonic set and torus grid of the solution (the tangents are sampled on it).
    w1, w2 : float
        Base frequencies [rad/s].
    box : (int, int)
        Stability tones ``|k1| <= a``, ``|k2| <= b``.

    Raises
    ------
    ModelError
        A box with negative orders, a grid too coarse for its tone differences (``N1 >
        4 a``, ``N2 > 4 b``), or a Hill matrix above :data:`MAX_ROWS` rows.

    Examples
    --------
    A damped oscillator whose stiffness is modulated on a torus: its exponents are close to
    those of the mean system ``-zeta w +- i w sqrt(1 - zeta^2)``.

    >>> from rotorsim.harmonic_balance.quasi import TorusHarmonics
    >>> def force(q, v, t1, t2):
    ...     k = 0.1 * (np.cos(t1) + np.cos(t2))
    ...     return k[:, None] * q, k[:, None, None], None
    >>> pb = QuasiProblem(np.eye(1), 0.2 * np.eye(1), np.eye(1), nl_dofs=np.array([0]),
    ...                   force=force)
    >>> aft = TorusAFT(TorusHarmonics.box(2, 2))
    >>> ex = hill_exponents(pb, np.zeros((aft.harmonics.rows, 1)), aft, 3.1, 7.3)
    >>> round(ex.largest, 2), ex.stable
    (-0.1, True)
    """
    a, b = (int(v) for v in box)
    if a < 0 or b < 0 or (a, b) == (0, 0):
        raise ModelError(f"box {box!r}: need orders >= 0, not both 0", "hill_exponents.box")
    n1, n2 = aft.grid
    if n1 <= 4 * a or n2 <= 4 * b:   # the differences k - l (up to 2a, 2b) stay distinct
        raise ModelError(f"the torus grid {aft.grid} cannot resolve the tone differences of "
                         f"the box {box} (need N1 > 4 a, N2 > 4 b)", "hill_exponents.box")
    n = problem.n
    stab = TorusAFT(TorusHarmonics.box(a, b), samples=aft.grid)
    rows = stab.harmonics.rows
    if 2 * n * rows > MAX_ROWS:
        raise ModelError(f"the Hill matrix would have {2 * n * rows} rows (> {MAX_ROWS}): "
                         "reduce the model or the box", "hill_exponents")
    A = _hill_matrix(problem, X_nl, aft, stab, w1, w2)
    with blas_threads_for(A.shape[0]):       # threads only for a large Hill matrix
        lam, vec = sl.eig(A, check_finite=False, overwrite_a=True)
    return _select(lam, vec, stab.harmonics.k, n)


def _hill_matrix(problem: QuasiProblem, X_nl: FloatArray, aft: TorusAFT, stab: TorusAFT,
                 w1: float, w2: float) -> FloatArray:
    """The real first-order Hill matrix ``(2 n rows, 2 n rows)`` on the stability tones
    ``stab`` (module docstring, in the real cosine-sine basis: ``d/dt`` is
    :meth:`TorusAFT.derivative_matrix`, the product with a sampled tangent is
    :meth:`TorusAFT.jacobian`), harmonic-major with ``[Y_r, V_r]`` per coefficient row."""
    n, rows = problem.n, stab.harmonics.rows
    M, D, K = (_dense(X) for X in (problem.M, problem.damping(w1), problem.K))
    nl = np.asarray(problem.nl_dofs, dtype=np.int64)
    d = nl.size
    Minv = sl.solve(M, np.eye(n), assume_a="sym", check_finite=False)
    Dm = stab.derivative_matrix(w1, w2)
    eye = np.eye(n)
    A = np.zeros((rows, 2, n, rows, 2, n))
    A[:, 0, :, :, 0, :] = -np.einsum("rs,ij->risj", Dm, eye)
    A[:, 1, :, :, 1, :] = -np.einsum("rs,ij->risj", Dm, eye)
    r = np.arange(rows)
    A[r, 0, :, r, 1, :] += eye
    A[r, 1, :, r, 0, :] -= Minv @ K
    A[r, 1, :, r, 1, :] -= Minv @ D
    if problem.force is not None and d:
        q = aft.to_samples(X_nl)
        v = aft.to_samples(aft.derivative_matrix(w1, w2) @ X_nl)
        _, dfdq, dfdv = problem.force(q, v, *aft.angles)
        ME = Minv[:, nl]
        for tangent, part in ((dfdq, 0), (dfdv, 1)):
            if tangent is None:
                continue
            J = stab.jacobian(np.asarray(tangent)).reshape(rows, d, rows, d)
            couple = np.einsum("ia,rasb->risb", ME, J)            # (rows, n, rows, d)
            block = A[:, 1, :, :, part, :]                      # a view (rows, n, rows, n)
            block[..., nl] -= couple
    return A.reshape(2 * n * rows, 2 * n * rows)


def _select(lam: ComplexArray, vec: ComplexArray, k: NDArray[np.int64], n: int
            ) -> TorusExponents:
    """Eigenvalues whose eigenvector lies inside the box (module docstring): a share of its
    displacement norm on the box's edge tones of at most :data:`EDGE_SHARE`, or, when fewer
    than ``2 n`` qualify (a box too small for the modulation), the ``2 n`` with the
    smallest edge share."""
    a, b = (int(v) for v in np.abs(k).max(axis=0))
    share = _edge_share(vec, k, n)
    keep = share <= EDGE_SHARE
    if np.count_nonzero(keep) < 2 * n:
        keep = np.zeros(lam.size, dtype=bool)
        keep[np.argsort(share, kind="stable")[:2 * n]] = True
    exponents, shares = lam[keep], share[keep]
    order = np.argsort(-exponents.real, kind="stable")
    return TorusExponents(exponents[order], (a, b), shares[order])


def _edge_share(vec: ComplexArray, k: NDArray[np.int64], n: int) -> FloatArray:
    """Share of each eigenvector's (columns) displacement norm on the box's edge tones (rows
    ``[a_0, c_1, s_1, ...]`` of the wave vectors ``k``)."""
    a, b = (int(v) for v in np.abs(k).max(axis=0))
    edge = ((np.abs(k[:, 0]) == a) & (a > 0)) | ((np.abs(k[:, 1]) == b) & (b > 0))
    rows = 2 * k.shape[0] + 1
    Y = vec.reshape(rows, 2 * n, -1)[:, :n, :]
    weight = np.sum(np.abs(Y) ** 2, axis=1)                       # (rows, r)
    on_edge = weight[1::2][edge] + weight[2::2][edge]
    return np.sqrt(on_edge.sum(axis=0) / np.maximum(weight.sum(axis=0), 1e-300))


def _dense(A: Any) -> FloatArray:
    return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)
