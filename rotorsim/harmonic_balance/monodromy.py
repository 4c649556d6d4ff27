"""Monodromy matrix of a harmonic-balance solution: Hsu's method and Newmark integration.

The variational equation of the periodic solution in first-order form, with the state
``y = [q; v]`` (seed 002 eq 3.37 orders it ``[v; q]``; the multipliers are the same), is

    y' = A(t) y,   A = [[0, I], [-M^-1 (K + K_t(t)), -M^-1 (C + W G + C_t(t))]],

where ``K_t``, ``C_t`` are the force tangents on the nonlinear DOFs at the periodic solution.
Its monodromy matrix ``Phi(T)`` has the Floquet multipliers as eigenvalues.

:func:`hsu` -- Hsu's discrete transition matrix (seed 002 eq 3.38): on ``N`` equal steps
``Delta = T / N``, ``A`` is replaced by a constant ``C_j`` per step and
``Phi = prod_j exp(Delta C_j)``. The tangents come from the HB Fourier series evaluated at
the sample phases (one batched force call). ``rule`` chooses ``C_j``:

* ``"average"`` (default): ``(A(t_{j-1}) + A(t_j)) / 2``, the trapezoidal value of the
  seed's ``C_j = 1/Delta int A dt``; second order in ``1 / N``; no extra force calls on the
  HB grid;
* ``"midpoint"``: ``A((t_{j-1} + t_j) / 2)``; second order;
* ``"left"``: ``A(t_{j-1})`` (the right-hand form of eq 3.38); first order per step, but
  over a whole period the first-order error terms sum to ``int A' dt = 0`` (``A`` is
  periodic), and the observed order of the multipliers is two as well.

``expansion="taylor"`` replaces ``exp`` by the seed's truncated series with ``terms``
terms; the default ``"expm"`` is the matrix exponential to round-off (scaling and squaring
of a Taylor series whose degree is chosen from the largest 1-norm of the batch, so the
short steps of Hsu's method cost only a few batched products). The product of the ``N`` factors is
formed by pairwise batched products (``log2 N`` numpy calls).

:func:`variational` -- integrates the ``2n`` variational solutions over one period with a
Newmark stepper of :mod:`rotorsim.time_integration` as one block-diagonal problem of size
``2 n^2`` (the tangents are re-evaluated at each step from the Fourier series): second
order in the step, intended for small ``n`` as an independent check. Jumps of the tangent
in time (contacts) are located first and the steps are aligned with them; before that fix
the contact duration was rounded to whole steps, so two different contacting orbits whose
contact lasted the same number of steps got identical multipliers (issue 16).

All three use the tangents along the *harmonic-balance* orbit. For a non-smooth force
that orbit carries the Gibbs ripple of its truncated series; the monodromy of the real
trajectory is :mod:`~rotorsim.harmonic_balance.shooting`.

References
----------
Seed 002 section 3.5.2.2, eqs 3.37-3.38. C. S. Hsu, J. Appl. Mech. 41 (1974) 1135-1137;
C. S. Hsu, W. H. Cheng, J. Appl. Mech. 40 (1973) 78-86 (the discrete transition matrix).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.floquet import FloquetResult, floquet_result
from rotorsim.harmonic_balance.fourier import AFT, FloatArray, derivative
from rotorsim.harmonic_balance.problem import HBProblem, as_dense
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.harmonic_balance.tangent_switches import TangentJumps, find_jumps
from rotorsim.solvers.linear import DENSE_THRESHOLD, factorize
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.output import OutputSpec
from rotorsim.time_integration.problem import SecondOrderProblem

Rule = Literal["average", "midpoint", "left"]


@dataclass(frozen=True, eq=False)
class PeriodicTangents:
    """The periodic solution's nonlinear tangents, evaluable at any phase.

    Built from the full coefficients ``X`` (2H + 1, n) of a solution at ``omega``,
    ``param``; :meth:`at` returns ``K_t`` and ``C_t`` (S, k, k) at phases ``tau`` (S,).
    """

    problem: HBProblem
    aft: AFT
    X: FloatArray
    omega: float
    param: float

    @classmethod
    def of(cls, residual: HBResidual, x: ArrayLike, omega: float,
           param: float) -> PeriodicTangents:
        """Tangents of the solution ``x`` of ``residual``."""
        return cls(residual.problem, residual.aft, residual.expand(x, omega, param),
                   float(omega), float(param))

    @cached_property
    def _nonlinear_coefficients(self) -> tuple[FloatArray, FloatArray]:
        Xn = self.X[:, self.problem.nl_dofs]
        return Xn, derivative(Xn)

    def at(self, tau: FloatArray) -> tuple[FloatArray, FloatArray | None]:
        """``(K_t, C_t)`` at the phases ``tau`` (``C_t`` None for a velocity-free force)."""
        Xn, dXn = self._nonlinear_coefficients
        G = self.aft.basis(tau)
        q, v = G @ Xn, self.omega * (G @ dXn)
        ev = self.problem.nonlinear(q, v, np.asarray(tau, dtype=float), self.omega,
                                    self.param)
        assert ev.dfdq is not None
        return ev.dfdq, ev.dfdv

    def entries(self, tau: FloatArray) -> FloatArray:
        """``K_t`` and ``C_t`` at the phases ``tau`` flattened to (S, k^2) or (S, 2 k^2)."""
        Kt, Ct = self.at(np.asarray(tau, dtype=float))
        flat = Kt.reshape(Kt.shape[0], -1)
        return flat if Ct is None else np.hstack((flat, Ct.reshape(Ct.shape[0], -1)))

    def jumps(self, samples: int) -> TangentJumps:
        """Jumps of the tangents in time (contacts closing and opening), searched on
        ``samples`` equal steps (:func:`~.tangent_switches.find_jumps`)."""
        tau = 2.0 * np.pi * np.arange(samples) / samples
        return find_jumps(self.entries, tau)


def hsu(residual: HBResidual, x: ArrayLike, omega: float, param: float = 0.0, *,
        samples: int | None = None, rule: Rule = "average",
        expansion: Literal["expm", "taylor"] = "expm", terms: int = 5,
        autonomous: bool = False) -> FloquetResult:
    """Floquet multipliers by Hsu's discrete transition matrix (seed 002 eq 3.38).

    Parameters
    ----------
    residual : HBResidual
    x : array (residual.size,)
        A solution at ``omega`` [rad/s] and ``param``.
    samples : int, optional
        Steps per period (default ``residual.samples``, the HB time grid).
    rule : {"average", "midpoint", "left"}
        Constant value of ``A`` on each step (module docstring).
    expansion : {"expm", "taylor"}
        Exact exponential of each step or the seed's truncated Taylor series.
    terms : int
        Highest power kept by the Taylor series (the seed uses 5).
    autonomous : bool
        Exclude the trivial multiplier from the stability decision.

    Raises
    ------
    ModelError
        If the mass matrix is singular (the first-order form needs ``M^-1``).

    Examples
    --------
    Undamped oscillator ``x'' + x = 0`` seen with period ``2 pi / 0.5``: the multipliers
    are ``exp(+-i 4 pi) = 1``.

    >>> from rotorsim.harmonic_balance.problem import HBProblem, as_dense
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> fl = hsu(make_residual(HBProblem(np.eye(1), np.eye(1)), 1), np.zeros(0), 0.5)
    >>> np.allclose(fl.multipliers, 1.0), fl.kind
    (True, 'fold')
    """
    if rule not in ("average", "midpoint", "left"):
        raise TypeError(f"unknown rule {rule!r}; valid: average, midpoint, left")
    if expansion not in ("expm", "taylor"):
        raise TypeError(f"unknown expansion {expansion!r}; valid: expm, taylor")
    clock = time.perf_counter()
    S = residual.samples if samples is None else int(samples)
    if S < 1:
        raise ModelError(f"samples must be >= 1, got {samples!r}", "hsu")
    T = 2.0 * math.pi / omega
    offset = 0.5 if rule == "midpoint" else 0.0
    tau = 2.0 * np.pi * (np.arange(S) + offset) / S
    A = state_matrices(residual.problem, PeriodicTangents.of(residual, x, omega, param),
                       tau)
    if rule == "average":
        A = 0.5 * (A + np.roll(A, -1, axis=0))
    steps = _exponential(A * (T / S), expansion, terms)
    Phi = ordered_product(steps)
    stats = {"samples": float(S), "wall_time": time.perf_counter() - clock}
    return floquet_result(np.linalg.eigvals(Phi), omega, "hsu", stats,
                          autonomous=autonomous)


def state_matrices(problem: HBProblem, tangents: PeriodicTangents,
                   tau: FloatArray) -> FloatArray:
    """``A(tau)`` (S, 2n, 2n) of the first-order variational equation."""
    n, nl = problem.n, problem.nl_dofs
    try:
        lu = factorize(problem.mass, where="mass matrix")
    except ConvergenceError as exc:
        raise ModelError("the first-order form needs a nonsingular mass matrix; use hill()",
                         "hsu") from exc
    K = as_dense(problem.stiffness)
    D = as_dense(problem.damping_matrix(tangents.omega))
    MK, MD, ME = lu.solve(K), lu.solve(D), lu.solve(np.eye(n)[:, nl])
    Kt, Ct = tangents.at(tau)
    A = np.zeros((len(tau), 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -MK
    A[:, n:, n:] = -MD
    A[:, n:, nl] -= ME @ Kt                       # (n, k) @ (S, k, k) -> (S, n, k)
    if Ct is not None:
        A[:, n:, n + nl] -= ME @ Ct
    return A


def ordered_product(F: FloatArray) -> FloatArray:
    """``F[S-1] @ ... @ F[1] @ F[0]`` by pairwise batched products.

    Examples
    --------
    >>> F = np.array([[[1.0, 1.0], [0.0, 1.0]], [[2.0, 0.0], [0.0, 1.0]], [[0., 1], [1, 0]]])
    >>> np.array_equal(ordered_product(F), F[2] @ F[1] @ F[0])
    True
    """
    F = np.asarray(F)
    while F.shape[0] > 1:
        pairs = F.shape[0] // 2
        merged = F[1: 2 * pairs: 2] @ F[0: 2 * pairs: 2]
        F = np.concatenate((merged, F[2 * pairs:])) if F.shape[0] % 2 else merged
    return F[0]


def variational(residual: HBResidual, x: ArrayLike, omega: float, param: float = 0.0, *,
                steps: int = 1000, stepper: Newmark | None = None,
                autonomous: bool = False) -> FloquetResult:
    """Floquet multipliers by integrating the variational equations over one period.

    Where the tangents jump in time (a contact closing or opening), the period is cut at
    the jumps (located to 1e-12 rad by :mod:`~.tangent_switches`) and each smooth piece
    gets its own whole number of steps (``steps`` shared in proportion to the lengths, at
    least one each), with the tangent taken inside the piece: the contact duration is then
    exact instead of rounded to a whole number of steps.

    Parameters
    ----------
    residual : HBResidual
    x : array (residual.size,)
        A solution at ``omega`` [rad/s] and ``param``.
    steps : int
        Steps per period (fixed; about ``steps`` with jumps).
    stepper : Newmark, optional
        Default: average acceleration (second order, no numerical damping).
    autonomous : bool
        Exclude the trivial multiplier from the stability decision.

    Examples
    --------
    >>> from rotorsim.harmonic_balance.problem import HBProblem, as_dense
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1))
    >>> fl = variational(make_residual(pb, 1), np.zeros(0), 1.0, steps=400)
    >>> s, h = -0.05 + 1j * np.sqrt(1 - 0.05**2), 2 * np.pi / 400   # trapezoidal rule map:
    >>> bool(np.isclose(fl.max_modulus, abs((1 + s * h / 2) / (1 - s * h / 2)) ** 400))
    True
    """
    clock = time.perf_counter()
    pb = residual.problem
    n, copies = pb.n, 2 * pb.n
    tangents = PeriodicTangents.of(residual, x, omega, param)
    dense = copies * n <= DENSE_THRESHOLD
    T = 2.0 * math.pi / omega
    jumps = tangents.jumps(max(int(steps), residual.samples)) if pb.force is not None \
        else None
    cuts = np.zeros(0) if jumps is None else jumps.phases / omega

    def blocks(A: object) -> Any:
        """``I_2n (x) A``: one copy of ``A`` per variational solution."""
        if dense:
            out = np.zeros((copies, n, copies, n))
            out[np.arange(copies), :, np.arange(copies), :] = as_dense(A)
            return out.reshape(copies * n, copies * n)
        return sp.kron(sp.identity(copies, format="csr"), sp.csr_matrix(A), format="csr")

    def restoring_on(a: float, b: float) -> Any:
        """Restoring force with the tangent taken inside ``[a, b]`` (one-sided at jumps)."""
        inset = 0.0 if cuts.size == 0 else min(1e-9 * T, 0.25 * (b - a))

        def restoring(q: FloatArray, v: FloatArray, t: float) -> tuple[FloatArray, Any, Any]:
            t_in = min(max(t, a + inset), b - inset)
            Kt, Ct = tangents.at(np.array([omega * t_in]))
            Kf, Cf = _embed(Kt[0], pb), _embed(None if Ct is None else Ct[0], pb)
            r = q.reshape(copies, n) @ Kf.T + v.reshape(copies, n) @ Cf.T
            return r.reshape(-1), blocks(Kf), blocks(Cf)
        return restoring

    matrices = {"mass": blocks(pb.mass), "stiffness": blocks(pb.stiffness),
                "damping": blocks(pb.damping_matrix(omega))}
    q = np.vstack((np.eye(n), np.zeros((n, n)))).reshape(-1)
    v = np.vstack((np.zeros((n, n)), np.eye(n))).reshape(-1)
    stats: dict[str, float] = {}
    for a, b, count in _pieces(T, cuts, int(steps)):
        problem = SecondOrderProblem(**matrices, restoring=restoring_on(a, b)
                                     if pb.force is not None else None)
        res = integrate(problem, stepper or Newmark.average_acceleration(), (a, b), q, v,
                        dt=(b - a) / count, output=OutputSpec(every=count, velocities=False))
        q, v = res.state.q, res.state.v
        for key, value in res.stats.items():
            stats[key] = stats.get(key, 0.0) + float(value)
    Phi = np.vstack((q.reshape(copies, n).T, v.reshape(copies, n).T))
    stats.update(tangent_jumps=float(cuts.size), wall_time=time.perf_counter() - clock)
    return floquet_result(np.linalg.eigvals(Phi), omega, "variational", stats,
                          autonomous=autonomous)


def _pieces(T: float, cuts: FloatArray, steps: int) -> list[tuple[float, float, int]]:
    """``(start, end, steps)`` of the smooth pieces of ``[0, T]`` between the ``cuts`` [s]:
    ``steps`` shared in proportion to the lengths, at least one per piece."""
    edges = np.unique(np.concatenate(([0.0], cuts[(cuts > 0) & (cuts < T)], [T])))
    lengths = np.diff(edges)
    counts = np.maximum(1, np.rint(steps * lengths / T)).astype(int)
    return [(float(a), float(b), int(c)) for a, b, c in zip(edges[:-1], edges[1:], counts,
                                                             strict=True)]


def _embed(T: FloatArray | None, problem: HBProblem) -> FloatArray:
    """Tangent (k, k) on the nonlinear DOFs as an (n, n) matrix (zeros for None)."""
    out = np.zeros((problem.n, problem.n))
    if T is not None:
        out[np.ix_(problem.nl_dofs, problem.nl_dofs)] = T
    return out


def _exponential(A: FloatArray, expansion: str, terms: int) -> FloatArray:
    """``exp(A[s])`` for each step: to round-off, or by the Taylor series up to
    ``A^terms`` (the seed's form)."""
    if expansion == "taylor":
        return _taylor(A, terms)
    norm = float(np.abs(A).sum(axis=-2).max()) if A.size else 0.0   # largest 1-norm
    squarings = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.5 else 0
    B = A / 2.0**squarings
    b = min(norm, 0.5)
    degree = next(m for m in range(1, 30)
                  if b ** (m + 1) / math.factorial(m + 1) * math.exp(b) < 1e-17)
    E = _taylor(B, degree)
    for _ in range(squarings):
        E = E @ E
    return E


def _taylor(A: FloatArray, terms: int) -> FloatArray:
    """``sum_{j <= terms} A^j / j!`` for a stack of matrices (Horner form)."""
    eye = np.broadcast_to(np.eye(A.shape[-1]), A.shape)
    out = eye + A / terms
    for j in range(terms - 1, 0, -1):
        out = eye + (A @ out) / j
    return out
