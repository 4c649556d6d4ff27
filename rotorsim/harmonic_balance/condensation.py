"""Exact condensation of the harmonic-balance equations onto the nonlinear DOFs.

The nonlinear force acts on the ``k`` DOFs ``N = nl_dofs`` only, so the equations of the
``n_L = n - k`` linear DOFs ``L`` are linear, and harmonic by harmonic. With the complex
amplitudes ``X_h = Q_hc - i Q_hs`` and the dynamic stiffness

    Z_h(w) = K - (h w)^2 M + i h w (C + W(w) G),

harmonic ``h`` of the full residual reads ``Z_h X_h + F_nl,h - F_h = 0``. Eliminating
``X_L,h = Z_LL,h^-1 (F_L,h - Z_LN,h X_N,h)`` leaves ``k`` complex equations per harmonic:

    S_h X_N,h + F_nl,h(X_N) - (F_N,h - Z_NL,h Z_LL,h^-1 F_L,h) = 0,
    S_h = Z_NN,h - Z_NL,h Z_LL,h^-1 Z_LN,h       (Schur complement),

whose solution is *exactly* the one of the full system (no modal truncation). ``Z_LL,h`` is
LU-factorised once per ``(h, omega)`` through :func:`rotorsim.solvers.linear.factorize`
(dense below 120 linear DOFs, SuperLU above) and cached for the last two values of
``omega``. Derivatives of the condensed residual follow from the implicit-function
theorem: ``dR_c = dR_N - Z_NL Z_LL^-1 dR_L`` for ``d/domega`` and ``d/dp`` of the full
residual evaluated at the recovered ``X``.

A singular ``Z_LL,h`` (e.g. a rigid-body mode of the linear part at ``h = 0`` that only
the nonlinear DOFs hold) raises :class:`~rotorsim.errors.ConvergenceError` naming the
harmonic; use the full residual, or add the offending DOFs to ``nl_dofs``.

References
----------
Seed 002 section 3.5.2.1 (HB-AFT in matrix form); the reduction to the nonlinear DOFs is the
usual dynamic condensation of harmonic balance (e.g. M. Krack, J. Gross, *Harmonic Balance
for Nonlinear Vibration Problems*, Springer 2019, section 3.6).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.harmonic_balance.banded_tones import BandedTones
from rotorsim.harmonic_balance.fourier import (
    AFT,
    ComplexArray,
    FloatArray,
    IntArray,
    from_complex,
    to_complex,
)
from rotorsim.harmonic_balance.nonlinear import (
    excitation_derivatives,
    nonlinear_harmonics,
    nonlinear_param_derivative,
)
from rotorsim.harmonic_balance.problem import HBProblem, Matrix
from rotorsim.harmonic_balance.residual import (
    HBEvaluation,
    as_coefficients,
    as_unknowns,
    linear_omega_derivative,
)
from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.solvers.stats import Stats
from rotorsim.time_integration.banded_lu import BandedLU

CACHED_OMEGAS = 2
"""Number of ``omega`` values whose factorisations are kept (a continuation step and its
predictor)."""


@dataclass(frozen=True, eq=False)
class HarmonicFactors:
    """Condensation of all harmonics at one ``omega``.

    Attributes
    ----------
    omega : float
    lu : tuple of Factorization, BandedLU or None
        Factors of ``Z_LL,h``, ``h = 0..H`` (None without linear DOFs; ``solve(b)``).
    coupling : tuple of complex arrays (k, n_L)
        ``Z_NL,h``.
    transfer : complex array (H + 1, n_L, k)
        ``Z_LL,h^-1 Z_LN,h``.
    reduced : array ((2H + 1) k, (2H + 1) k)
        Real block-diagonal form of the Schur complements ``S_h`` (harmonic-major).
    magnitude : array (H + 1, k, k)
        ``|Z_NN,h| + |Z_NL,h| |Z_LL,h^-1 Z_LN,h|``: the size of the terms that cancel in
        ``S_h`` (for the round-off floor of the residual).
    """

    omega: float
    lu: tuple[Factorization | BandedLU | None, ...]
    coupling: tuple[ComplexArray, ...]
    transfer: ComplexArray
    reduced: FloatArray
    magnitude: FloatArray


@dataclass(frozen=True, eq=False)
class CondensedResidual:
    """Harmonic balance condensed onto the nonlinear DOFs: ``size = (2H + 1) k``.

    Same interface as :class:`~rotorsim.harmonic_balance.residual.HarmonicBalanceResidual`
    (see :class:`~rotorsim.harmonic_balance.residual.HBResidual`); the unknowns are the
    coefficients of ``nl_dofs`` in the callback's order and :meth:`expand` recovers all DOFs.

    Examples
    --------
    A linear two-mass chain forced at mass 0 with a "nonlinear" linear spring at mass 1:
    the condensed and full solutions coincide.

    >>> spring = lambda q, v, tau, w, p: (2.0 * q, np.full((len(q), 1, 1), 2.0), None)
    >>> K = np.array([[2.0, -1.0], [-1.0, 1.0]])
    >>> pb = HBProblem(np.eye(2), K, nl_dofs=[1], force=spring,
    ...                excitation=[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    >>> res = CondensedResidual(pb, 1)
    >>> ev = res.evaluate(np.zeros(3), 0.5)
    >>> y = -np.linalg.solve(ev.jacobian, ev.r)   # linear: one Newton step
    >>> Z = K + np.diag([0.0, 2.0]) - 0.25 * np.eye(2)
    >>> np.allclose(res.expand(y, 0.5)[1], np.linalg.solve(Z, [1.0, 0.0]))
    True
    """

    problem: HBProblem
    harmonics: int
    samples: int = 0
    _cache: dict[float, HarmonicFactors] = field(default_factory=dict, init=False,
                                                 repr=False)

    def __post_init__(self) -> None:
        aft = AFT(self.harmonics, self.samples)
        object.__setattr__(self, "harmonics", aft.harmonics)
        object.__setattr__(self, "samples", aft.samples)

    @cached_property
    def aft(self) -> AFT:
        """Transforms of this discretisation."""
        return AFT(self.harmonics, self.samples)

    @property
    def size(self) -> int:
        """Number of unknowns ``(2H + 1) k``."""
        return self.aft.rows * self.problem.k

    @property
    def dofs(self) -> IntArray:
        """DOFs carried by the unknowns (``nl_dofs``)."""
        return self.problem.nl_dofs

    def evaluate(self, x: ArrayLike, omega: float, param: float = 0.0, *,
                 jacobian: bool = True, d_omega: bool = False, d_param: bool = False,
                 stats: Stats | None = None) -> HBEvaluation:
        """Condensed residual and derivatives at ``x`` (size,), ``omega`` and ``param``."""
        pb, aft = self.problem, self.aft
        Y = as_unknowns(x, self.size).reshape(aft.rows, pb.k)
        fac = self.factors(omega, stats)
        if stats is not None:
            stats.residual_evaluations += 1
        F = pb.excitation_coefficients(aft, omega, param)
        nl = nonlinear_harmonics(pb, aft, Y, omega, param, jacobian=jacobian,
                                 d_omega=d_omega)
        forcing, forcing_terms = self._schur_terms(F, fac)
        r = fac.reduced @ Y.reshape(-1) + (nl.force - forcing).reshape(-1)
        Yc = np.abs(to_complex(Y))
        sizes = np.einsum("hij,hj->hi", fac.magnitude, Yc) + forcing_terms \
            + force_size(nl.force)
        terms = np.abs(from_complex(sizes + 1j * sizes)).reshape(-1)
        J = dw = dp = None
        if jacobian:
            assert nl.jacobian is not None
            J = fac.reduced + nl.jacobian
        if d_omega or d_param:
            dfw, dfp = excitation_derivatives(pb, aft, omega, param, d_omega=d_omega,
                                              d_param=d_param)
            if d_omega:
                assert nl.d_omega is not None
                Rw = linear_omega_derivative(pb, self._recover(Y, fac, F), omega) - dfw
                Rw[:, pb.nl_dofs] += nl.d_omega
                dw = self._schur(Rw, fac).reshape(-1)
            if d_param:
                Rp = -dfp
                Rp[:, pb.nl_dofs] += nonlinear_param_derivative(pb, aft, Y, omega, param)
                dp = self._schur(Rp, fac).reshape(-1)
        return HBEvaluation(r, J, dw, dp, terms)

    def expand(self, x: ArrayLike, omega: float, param: float = 0.0) -> FloatArray:
        """Coefficients (2H + 1, n) of all DOFs recovered from the nonlinear ones."""
        pb, aft = self.problem, self.aft
        Y = as_unknowns(x, self.size).reshape(aft.rows, pb.k)
        return self._recover(Y, self.factors(omega), pb.excitation_coefficients(
            aft, omega, param))

    def restrict(self, X: ArrayLike) -> FloatArray:
        """Unknowns (size,): the ``nl_dofs`` columns of ``X`` (2H + 1, n)."""
        X = as_coefficients(X, self.aft.rows, self.problem.n)
        return X[:, self.problem.nl_dofs].reshape(-1).copy()

    def with_discretization(self, harmonics: int | None = None,
                            samples: int | None = None) -> CondensedResidual:
        """Same problem with other ``H`` and/or ``N`` (fresh factorisation cache)."""
        H = self.harmonics if harmonics is None else harmonics
        N = samples if samples is not None else (self.samples if harmonics is None else 0)
        return replace(self, harmonics=H, samples=N)

    def factors(self, omega: float, stats: Stats | None = None) -> HarmonicFactors:
        """Condensation at ``omega`` (cached for the last ``CACHED_OMEGAS`` values)."""
        key = float(omega)
        if key in self._cache:
            return self._cache[key]
        out = self._build(key, stats)
        while len(self._cache) >= CACHED_OMEGAS:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = out
        return out

    def _build(self, omega: float, stats: Stats | None) -> HarmonicFactors:
        pb, H, k = self.problem, self.harmonics, self.problem.k
        nL = pb.linear_dofs.size
        lus: list[Factorization | BandedLU | None] = []
        couplings: list[ComplexArray] = []
        transfer = np.zeros((H + 1, nL, k), dtype=complex)
        reduced = np.zeros((self.aft.rows * k, self.aft.rows * k))
        magnitude = np.zeros((H + 1, k, k))
        for h in range(H + 1):
            S = self._dynamic("NN", h, omega)
            magnitude[h] = np.abs(S)
            couplings.append(self._dynamic("NL", h, omega))
            lu: Factorization | BandedLU | None = None
            if nL:
                where = f"HB condensation, harmonic {h} at omega = {omega:.6g} rad/s"
                if h and self._damped_linear and self._band is not None:
                    # regular by construction: banded LU (harmonic_balance/banded_tones.py)
                    if stats is not None:
                        stats.factorizations += 1
                    lu = self._band.factorize(h * omega, self.problem.spin_speed(omega),
                                              where)
                else:
                    lu = factorize(self._dynamic("LL", h, omega), stats=stats, where=where,
                                   check_condition=not (h and self._damped_linear))
                transfer[h] = lu.solve(self._dynamic("LN", h, omega))
                S = S - couplings[h] @ transfer[h]
                magnitude[h] += np.abs(couplings[h]) @ np.abs(transfer[h])
            lus.append(lu)
            _place(reduced, S, h, k)
        return HarmonicFactors(omega, tuple(lus), tuple(couplings), transfer, reduced,
                               magnitude)

    def _dynamic(self, part: str, h: int, omega: float) -> Any:
        """Block ``part`` of ``Z_h(omega)`` (dense complex, or sparse for a large LL)."""
        b = self._blocks
        out = b["stiffness"][part] - (h * omega) ** 2 * b["mass"][part]
        for name, scale in (("damping", 1.0), ("gyroscopic", self.problem.spin_speed(omega))):
            if name in b and h and scale:
                out = out + (1j * h * omega * scale) * b[name][part]
        return out.astype(complex) if not sp.issparse(out) else sp.csc_matrix(out,
                                                                              dtype=complex)

    @cached_property
    def _damped_linear(self) -> bool:
        """The linear DOFs carry damping. ``Z_LL`` of a harmonic ``h >= 1`` is then singular
        only where an undamped fixed-interface mode sits exactly on ``h omega`` (a
        measure-zero event along a branch), so its LU checks only for a zero or non-finite
        pivot and skips the condition estimate (about 40 % of a condensation). Without
        damping (gyroscopic terms alone) every fixed-interface resonance is crossed and
        the estimate stays."""
        block = self._blocks.get("damping", {}).get("LL")
        if block is None:
            return False
        return bool(block.nnz if sp.issparse(block) else np.any(block != 0))

    @cached_property
    def _band(self) -> BandedTones | None:
        """The ``LL`` blocks in band storage when their band is narrow (a shaft line)."""
        ll = {key: self._blocks[name]["LL"] for key, name in (
            ("K", "stiffness"), ("M", "mass"), ("C", "damping"), ("G", "gyroscopic"))
            if name in self._blocks}
        if "K" not in ll or "M" not in ll:
            return None
        zero = sp.csc_matrix(ll["K"].shape)
        return BandedTones.of({key: ll.get(key, zero) for key in ("K", "M", "C", "G")})

    @cached_property
    def _blocks(self) -> dict[str, dict[str, Matrix]]:
        pb = self.problem
        L, N = pb.linear_dofs, pb.nl_dofs
        sparse_ll = L.size > DENSE_THRESHOLD
        out = {}
        for name in ("mass", "stiffness", "damping", "gyroscopic"):
            A = getattr(pb, name)
            if A is None:
                continue
            if sparse_ll:   # large: slice the sparse matrix, keep LL sparse
                As = sp.csr_matrix(A)
                rows_l, rows_n = As[L], As[N]
                out[name] = {"LL": rows_l[:, L].tocsc(), "LN": rows_l[:, N].toarray(),
                             "NL": rows_n[:, L].toarray(), "NN": rows_n[:, N].toarray()}
            else:           # small: dense slicing is much cheaper than sparse indexing
                D = A.toarray() if sp.issparse(A) else np.asarray(A)
                out[name] = {"LL": D[np.ix_(L, L)], "LN": D[np.ix_(L, N)],
                             "NL": D[np.ix_(N, L)], "NN": D[np.ix_(N, N)]}
        return out

    def _schur(self, R: FloatArray, fac: HarmonicFactors) -> FloatArray:
        """``R_N - Z_NL Z_LL^-1 R_L`` per harmonic for a full-DOF array ``R`` (2H+1, n)."""
        return self._schur_terms(R, fac)[0]

    def _schur_terms(self, R: FloatArray, fac: HarmonicFactors
                     ) -> tuple[FloatArray, FloatArray]:
        """:meth:`_schur` and the size ``|R_N| + |Z_NL| |Z_LL^-1 R_L|`` (H + 1, k) of its
        terms per harmonic."""
        pb = self.problem
        C = to_complex(R)
        out = C[:, pb.nl_dofs]
        size = np.abs(out)
        for h, lu in enumerate(fac.lu):
            rhs = C[h, pb.linear_dofs]
            if lu is not None and np.any(rhs):
                solved = lu.solve(rhs)
                out[h] -= fac.coupling[h] @ solved
                size[h] += np.abs(fac.coupling[h]) @ np.abs(solved)
        return from_complex(out), size

    def _recover(self, Y: FloatArray, fac: HarmonicFactors, F: FloatArray) -> FloatArray:
        """All coefficients (2H + 1, n) from ``Y`` (2H + 1, k) and the excitation ``F``."""
        pb = self.problem
        Yc, Fc = to_complex(Y), to_complex(F)
        Xc = np.zeros((Yc.shape[0], pb.n), dtype=complex)
        Xc[:, pb.nl_dofs] = Yc
        XL = -np.einsum("hlk,hk->hl", fac.transfer, Yc)
        for h, lu in enumerate(fac.lu):
            rhs = Fc[h, pb.linear_dofs]
            if lu is not None and np.any(rhs):
                XL[h] += lu.solve(rhs)
        Xc[:, pb.linear_dofs] = XL
        return from_complex(Xc)


def force_size(force: FloatArray) -> FloatArray:
    """Size (H + 1, k) of the AFT force terms in each harmonic: the sum of the amplitudes
    of all harmonics of each DOF, since the FFT spreads the round-off of every time
    sample over all harmonics."""
    amplitudes = np.abs(to_complex(force))
    return np.broadcast_to(amplitudes.sum(axis=0), amplitudes.shape)


def _place(reduced: FloatArray, S: ComplexArray, h: int, k: int) -> None:
    """Write the real form ``[[Re S, Im S], [-Im S, Re S]]`` of harmonic ``h``."""
    if h == 0:
        reduced[:k, :k] = S.real
        return
    c, s = slice((2 * h - 1) * k, 2 * h * k), slice(2 * h * k, (2 * h + 1) * k)
    reduced[c, c] = reduced[s, s] = S.real
    reduced[c, s] = S.imag
    reduced[s, c] = -S.imag
