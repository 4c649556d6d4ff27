"""Multi-start global search for every local minimum of an energy (seed 000 section 4).

Many starts spread over a box (scrambled Sobol points) are iterated *at once* by a batched
trust-region Newton method (:func:`trust_region_batch`, one vectorised energy call per
iteration for every start); the converged points are clustered into distinct minima, and
stationary points whose Hessian has a negative eigenvalue (saddles) are rejected.
Rotor-agnostic (DESIGN section 1).

References
----------
Seed 000 section 3 and Fig. 4; Nocedal & Wright, *Numerical Optimization* (2006), ch. 4.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError
from rotorsim.solvers.minimize import BatchEnergyFunction, FloatArray, LocalMinimum, scales
from rotorsim.solvers.stats import Stats


@dataclass(frozen=True, eq=False)
class BatchOutcome:
    """Final points of :func:`trust_region_batch`, arrays over the ``S`` starts (scaled).

    ``status``: 0 converged, 1 iteration limit or stagnation, 2 left the bound box.
    """

    x: FloatArray
    energy: FloatArray
    gradient: FloatArray
    hessian: FloatArray
    status: NDArray[np.int64]
    iterations: NDArray[np.int64]


def trust_region_batch(fun: BatchEnergyFunction, x0: FloatArray, *, tol: float = 1e-10,
                       max_iter: int = 100, bound: float = np.inf, radius: float = 1.0,
                       stats: Stats | None = None) -> BatchOutcome:
    """Minimise from every row of ``x0`` (S, n) at once, in already scaled variables.

    Each start has its own trust radius; the step is the exact solution of the
    trust-region subproblem ``min g.p + p.H p/2, |p| <= radius`` in the eigenbasis of
    ``H`` (Moré-Sorensen secular equation, batched; "hard case" completed along the
    lowest eigenvector). Starts stop when ``max |g| <= tol`` with a positive semidefinite
    ``H`` (converged), after ``max_iter`` iterations or when the radius collapses
    (status 1), or when ``max |x| > bound`` (status 2).
    """
    x = np.array(x0, dtype=float)
    n_start = x.shape[0]
    e, g, h = _call(fun, x, stats)
    delta = np.full(n_start, float(radius))
    status = np.full(n_start, -1)
    iterations = np.zeros(n_start, dtype=np.int64)
    for _ in range(max_iter + 1):
        _update_status(status, x, e, g, h, delta, tol, bound)
        active = np.flatnonzero(status < 0)
        if active.size == 0 or iterations.max(initial=0) >= max_iter:
            break
        iterations[active] += 1
        if stats is not None:
            stats.iterations += 1
        p, pred = _subproblem(g[active], h[active], delta[active])
        e_t, g_t, h_t = _call(fun, x[active] + p, stats)
        actual = e[active] - e_t
        noise = 1e-13 * np.maximum(np.abs(e[active]), 1e-300)
        rho = np.where(pred > noise, actual / np.maximum(pred, 1e-300),
                       np.where(actual >= -noise, 1.0, -1.0))
        rho = np.where(np.isfinite(e_t), rho, -1.0)
        accept = rho > 1e-4
        if stats is not None:
            stats.rejected_steps += int((~accept).sum())
        step = np.abs(p).max(axis=1)
        delta[active] = np.where(rho < 0.25, 0.25 * step,
                                 np.where((rho > 0.75) & (step > 0.99 * delta[active]),
                                          2.0 * delta[active], delta[active]))
        idx = active[accept]
        x[idx] += p[accept]
        e[idx], g[idx], h[idx] = e_t[accept], g_t[accept], h_t[accept]
    status[status < 0] = 1
    return BatchOutcome(x, e, g, h, status, iterations)


def _call(fun: BatchEnergyFunction, x: FloatArray,
          stats: Stats | None) -> tuple[FloatArray, FloatArray, FloatArray]:
    if stats is not None:
        stats.residual_evaluations += 1
    e, g, h = fun(x)
    return (np.array(e, dtype=float), np.array(g, dtype=float), np.array(h, dtype=float))


def _update_status(status: NDArray[np.int64], x: FloatArray, e: FloatArray, g: FloatArray,
                   h: FloatArray, delta: FloatArray, tol: float, bound: float) -> None:
    open_ = status < 0
    gmax = np.abs(g).max(axis=1)
    wmin = np.linalg.eigvalsh(h)[:, 0]
    hscale = np.abs(h).max(axis=(1, 2))
    converged = (gmax <= tol) & (wmin >= -1e-9 * np.maximum(hscale, 1e-300))
    status[open_ & converged] = 0
    status[open_ & ~converged & (np.abs(x).max(axis=1) > bound)] = 2
    status[open_ & ~converged & ((delta < 1e-14) | ~np.isfinite(e))] = 1


def _subproblem(g: FloatArray, h: FloatArray, delta: FloatArray
                ) -> tuple[FloatArray, FloatArray]:
    """Exact trust-region steps ``p`` (S, n) and their predicted decrease (S,)."""
    w, v = np.linalg.eigh(h)
    gh = np.einsum("sji,sj->si", v, g)
    gnorm = np.sqrt((gh * gh).sum(axis=1))
    floor = np.maximum(0.0, -w[:, 0])
    lam = floor + gnorm / delta  # |p(lam)| <= delta here: Newton on the secular equation
    newton = (w[:, 0] > 0) & (_norm(gh, w, 0.0) <= delta)
    lam = np.where(newton, 0.0, lam)
    for _ in range(50):
        shift = w + lam[:, None]
        shift = np.where(shift > 0, shift, np.inf)
        pn = np.sqrt(((gh / shift) ** 2).sum(axis=1))
        dn = ((gh * gh) / shift**3).sum(axis=1)
        # Newton on 1/delta - 1/|p(lam)| (concave): from |p| <= delta it decreases lam
        # monotonically to the root, or to the floor in the "hard case"
        done = newton | (pn == 0) | (np.abs(pn - delta) <= 1e-9 * delta)
        upd = np.where(done, 0.0, (pn - delta) / delta * pn * pn / np.maximum(dn, 1e-300))
        lam = np.maximum(lam + upd, floor * (1.0 + 1e-14))
        if np.all(done):
            break
    shift = w + lam[:, None]
    coeff = np.where(shift > 0, -gh / np.where(shift > 0, shift, 1.0), 0.0)
    # hard case: |p| < delta on the floor of an indefinite H -> add the lowest eigenvector
    short = ~newton & (w[:, 0] < 0) & (np.sqrt((coeff**2).sum(axis=1)) < 0.999 * delta)
    extra = np.sqrt(np.maximum(delta**2 - (coeff**2).sum(axis=1), 0.0))
    coeff[:, 0] += np.where(short, extra * np.where(gh[:, 0] > 0, -1.0, 1.0), 0.0)
    p = np.einsum("sij,sj->si", v, coeff)
    pred = -(np.einsum("si,si->s", gh, coeff) + 0.5 * np.einsum("si,si->s", w * coeff, coeff))
    return p, pred


def _norm(gh: FloatArray, w: FloatArray, lam: float) -> FloatArray:
    shift = w + lam
    safe = np.where(shift > 0, shift, 1.0)
    return np.where((shift > 0).all(axis=1), np.sqrt(((gh / safe) ** 2).sum(axis=1)), np.inf)


@dataclass(frozen=True, eq=False)
class GlobalMinima:
    """Distinct local minima found by :class:`GlobalSearch`, lowest energy first.

    ``n_starts`` starts were run: ``n_converged`` reached a minimum, ``n_saddles`` stopped
    on a stationary point with a negative curvature, ``n_escaped`` left the bound box and
    ``n_failed`` reached the iteration limit.
    """

    minima: tuple[LocalMinimum, ...]
    n_starts: int
    n_converged: int
    n_saddles: int
    n_escaped: int
    n_failed: int


@dataclass(frozen=True)
class GlobalSearch:
    """Multi-start search of every local minimum in a box.

    Parameters
    ----------
    n_starts : int
        Sobol starts in the box (plus any ``extra_starts`` given to :meth:`run`).
    tol : float
        Scaled gradient tolerance of each local solve.
    max_iter : int
        Iterations of the batched trust-region solver.
    cluster_tol : float
        Converged points closer than this (scaled max-norm) are one minimum.
    bound : float
        Starts that leave ``|x / x_scale| <= bound * box`` are abandoned (status escaped).
    seed : int
        Seed of the scrambled Sobol sequence (results are reproducible).

    Examples
    --------
    >>> def f(X):  # two wells at x = +-1
    ...     x = X[:, 0]
    ...     return (x**2 - 1) ** 2, (4 * x * (x**2 - 1))[:, None], (12 * x**2 - 4)[:, None, None]
    >>> found = GlobalSearch(n_starts=16).run(f, [-2.0], [2.0])
    >>> sorted(round(float(m.x[0]), 6) for m in found.minima), found.n_saddles
    ([-1.0, 1.0], 0)
    """

    n_starts: int = 64
    tol: float = 1e-10
    max_iter: int = 100
    cluster_tol: float = 1e-6
    bound: float = 4.0
    seed: int = 0

    def run(self, fun: BatchEnergyFunction, lower: ArrayLike, upper: ArrayLike, *,
            x_scale: ArrayLike | None = None, energy_scale: float = 1.0,
            extra_starts: ArrayLike | None = None, stats: Stats | None = None,
            where: str = "global search") -> GlobalMinima:
        """Search the box ``lower <= x <= upper`` (unscaled) for every local minimum."""
        lo = np.atleast_1d(np.asarray(lower, dtype=float))
        hi = np.atleast_1d(np.asarray(upper, dtype=float))
        if lo.shape != hi.shape or lo.ndim != 1 or not np.all(hi > lo):
            raise ModelError("need 1-D lower < upper of equal length", where)
        xs = scales(lo.size, x_scale, energy_scale, where)
        starts = self._starts(lo, hi, extra_starts) / xs
        box = float(np.max(np.abs(np.concatenate([lo, hi]) / np.tile(xs, 2))))

        def scaled(y: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
            e, g, h = fun(y * xs)
            return (np.asarray(e) / energy_scale, np.asarray(g) * xs / energy_scale,
                    np.asarray(h) * np.outer(xs, xs) / energy_scale)

        out = trust_region_batch(scaled, starts, tol=self.tol, max_iter=self.max_iter,
                                 bound=self.bound * box, radius=0.25 * box, stats=stats)
        eig = np.asarray(np.linalg.eigvalsh(out.hessian), dtype=float)
        saddle = (out.status == 0) & (eig[:, 0] < -1e-9 * np.abs(eig).max(axis=1))
        good = (out.status == 0) & ~saddle
        minima = _cluster(out, eig, good, xs, energy_scale, self.cluster_tol)
        return GlobalMinima(minima, len(starts), int(good.sum()), int(saddle.sum()),
                            int((out.status == 2).sum()), int((out.status == 1).sum()))

    def _starts(self, lo: FloatArray, hi: FloatArray,
                extra: ArrayLike | None) -> FloatArray:
        if self.n_starts < 1:
            raise ModelError(f"n_starts must be >= 1, got {self.n_starts}", "GlobalSearch")
        from scipy.stats import qmc  # scipy.stats takes ~0.4 s to import: on first use

        m = int(np.ceil(np.log2(self.n_starts)))
        unit = qmc.Sobol(lo.size, scramble=True, seed=self.seed).random_base2(m)
        points = lo + unit[: self.n_starts] * (hi - lo)
        if extra is not None:
            points = np.vstack([np.atleast_2d(np.asarray(extra, dtype=float)), points])
        return points


def _cluster(out: BatchOutcome, eig: FloatArray, good: NDArray[np.bool_], xs: FloatArray,
             energy_scale: float, cluster_tol: float) -> tuple[LocalMinimum, ...]:
    """Group converged points closer than ``cluster_tol`` (scaled); lowest energy first."""
    order = [i for i in np.argsort(out.energy) if good[i]]
    reps: list[int] = []
    hits: list[int] = []
    for i in order:
        for k, j in enumerate(reps):
            if np.max(np.abs(out.x[i] - out.x[j])) <= cluster_tol:
                hits[k] += 1
                break
        else:
            reps.append(int(i))
            hits.append(1)
    return tuple(LocalMinimum(out.x[j] * xs, float(out.energy[j]) * energy_scale,
                              out.gradient[j] * energy_scale / xs, eig[j],
                              int(out.iterations[j]), hits[k])
                 for k, j in enumerate(reps))
