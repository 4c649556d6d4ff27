"""The bearing-equilibrium problem behind :mod:`rotorsim.analyses.statics.bearing_statics`: scaled
setup, held (degenerate) DOFs, local and global solves, and the result record."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import as_float_array
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.results.bearing import (
    BEARING_DOFS,
    BearingEquilibriumResult,
    EnergyMinimum,
)
from rotorsim.solvers.global_search import GlobalSearch
from rotorsim.solvers.minimize import minimize_energy
from rotorsim.solvers.newton import Newton, ResidualProblem
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
METHODS = ("newton", "energy", "global")
"""Solution methods of :func:`rotorsim.analyses.statics.bearing_statics.bearing_equilibrium`."""
_HOLD_TOL = 1e-10
"""A DOF is held when its largest probed stiffness is below this fraction of the largest."""


@dataclass(frozen=True, eq=False)
class Setup:
    """One statics problem: the model, element angles, load and scales."""

    bearing: Any
    psi: FloatArray          # (1, N)
    load: FloatArray         # (5,)
    load_stiffness: FloatArray  # (5, 5)
    s: FloatArray            # (5,) length per unit of each DOF: (1, 1, 1, 1/arm, 1/arm)
    free: NDArray[np.bool_]  # (5,)
    held: tuple[tuple[str, str], ...]
    range: float             # physical range, scaled (translations) [m]
    f_ref: float             # load scale [N]
    where: str

    def full(self, xf: FloatArray) -> FloatArray:
        d = np.zeros((xf.shape[0], 5))
        d[:, self.free] = xf
        return d

    def evaluate(self, xf: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Potential energy (S,), its gradient (S, nf), Hessian (S, nf, nf), strain energy."""
        d = self.full(np.atleast_2d(xf))
        st = self.bearing.state(d, self.psi)
        kl = self.load_stiffness
        grad = st.force - self.load - d @ kl.T
        pot = st.energy - d @ self.load - 0.5 * np.einsum("si,ij,sj->s", d, kl, d)
        hess = st.stiffness - kl
        f = self.free
        return pot, grad[:, f], hess[:, f][:, :, f], st.energy

    def residual(self, xf: FloatArray) -> tuple[FloatArray, FloatArray]:
        _, g, h, _ = self.evaluate(xf)
        return g[0], h[0]

    def potential(self, xf: FloatArray) -> tuple[float, FloatArray, FloatArray]:
        e, g, h, _ = self.evaluate(xf)
        return float(e[0]), g[0], h[0]

    def batch(self, xf: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        e, g, h, _ = self.evaluate(xf)
        return e, g, h

    def scaled_size(self, delta: FloatArray) -> float:
        return float(np.max(np.abs(delta / self.s)))


# --------------------------------------------------------------------------- setup
def check_positive(tol: float, max_iter: int, n_starts: int) -> None:
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol > 0):
        raise ModelError(f"tol must be a positive number, got {tol!r}", "bearing statics")
    for name, value in (("max_iter", max_iter), ("n_starts", n_starts)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
            raise ModelError(f"{name} must be an integer >= 1, got {value!r}",
                             "bearing statics")


def _label(bearing: Any) -> str:
    tag = getattr(bearing, "tag", None)
    return f"{type(bearing).__name__} '{tag}'" if tag else type(bearing).__name__


def _geometry(bearing: Any) -> tuple[float, float, float]:
    """Moment arm [m], physical range [m] and a deflection scale [m]."""
    try:
        arm = float(getattr(bearing, "moment_arm", 0.5 * bearing.pitch_diameter))
        diameter = float(getattr(bearing, "ball_diameter", None)
                         or getattr(bearing, "roller_diameter", None)
                         or bearing.effective_length)  # a roller without its diameter
        clearance = abs(float(bearing.clearance))
        kn, n = float(bearing.Kn), float(bearing.exponent)
    except AttributeError as exc:
        raise ModelError(f"not a rolling-bearing model ({exc})", _label(bearing)) from None
    a0 = float(getattr(bearing, "center_distance", 0.0))
    return arm, clearance + a0 + 0.05 * diameter, clearance + (1e3 / kn) ** (1.0 / n)


def make_setup(bearing: Any, load: ArrayLike, psi: FloatArray, load_stiffness: ArrayLike | None,
           max_displacement: float | None,
           held: tuple[tuple[str, str], ...] | None = None) -> Setup:
    where = _label(bearing)
    f = as_float_array(load, "load", where).reshape(-1)
    if f.shape != (5,) or not np.all(np.isfinite(f)):
        raise ModelError(f"load must be 5 finite numbers [Fx, Fy, Fz, Mx, My], got {load!r}",
                         where)
    kl = np.zeros((5, 5)) if load_stiffness is None else np.asarray(load_stiffness, float)
    if kl.shape != (5, 5) or not np.all(np.isfinite(kl)) or not np.allclose(kl, kl.T):
        raise ModelError("load_stiffness must be a finite symmetric (5, 5) matrix", where)
    arm, default_range, probe = _geometry(bearing)
    rng = default_range if max_displacement is None else float(max_displacement)
    if not (math.isfinite(rng) and rng > 0):
        raise ModelError(f"max_displacement must be positive, got {max_displacement!r}", where)
    s = np.array([1.0, 1.0, 1.0, 1.0 / arm, 1.0 / arm])
    if held is None:
        held = _held_dofs(bearing, psi, s, probe)
    free = np.array([d not in dict(held) for d in BEARING_DOFS])
    scaled = np.abs(f * s)
    f_ref = float(scaled.max()) if scaled.max() > 0 else float(bearing.Kn) * probe ** float(
        bearing.exponent)
    for name, reason in held:
        k = BEARING_DOFS.index(name)
        if scaled[k] > 1e-12 * f_ref:
            raise ModelError(f"cannot carry the load component {_LOAD_NAMES[k]} = {f[k]:.6g} "
                             f"{'N' if k < 3 else 'N m'}: {reason}", where)
    return Setup(bearing, psi, f, 0.5 * (kl + kl.T), s, free, held, rng, f_ref, where)


_LOAD_NAMES = ("Fx", "Fy", "Fz", "Mx", "My")


def _held_dofs(bearing: Any, psi: FloatArray, s: FloatArray,
               size: float) -> tuple[tuple[str, str], ...]:
    """DOFs with no stiffness at 20 probe displacements that load every direction."""
    eye = np.eye(5)
    pairs = [eye[i] + eye[j] for i in range(5) for j in range(i + 1, 5)]
    probes = np.vstack([eye, -eye, *pairs]) * (size * s)
    k = bearing.state(probes, psi).stiffness
    diag = np.abs(np.diagonal(k, axis1=1, axis2=2)) * s * s
    peak = diag.max(axis=0)
    if peak.max() <= 0:
        return ()
    alpha = math.degrees(float(getattr(bearing, "contact_angle", float("nan"))))
    held = []
    for i, name in enumerate(BEARING_DOFS):
        if peak[i] <= _HOLD_TOL * peak.max():
            kind = {"z": "axial", "x": "radial", "y": "radial"}.get(name, "tilt")
            held.append((name, f"no contact depends on the {kind} DOF {name} (unloaded "
                               f"contact angle {alpha:.4g} deg; flange and rib contacts "
                               "are not modelled): it has no stiffness and is held at 0"))
    return tuple(held)


# -------------------------------------------------------------------------- solvers
def _ray_start(setup: Setup) -> tuple[FloatArray, float, float]:
    """Displacement on the load ray whose force balances the load's projection.

    Returns the full (5,) start, its scaled size [m] and the ratio of the largest
    projected force within the range to the load (>= 1 when the ray reaches the load).
    """
    target = setup.load * setup.s
    norm = float(np.linalg.norm(target))
    if norm == 0.0:
        return np.zeros(5), 0.0, math.inf
    direction = target / norm
    t = setup.range * 2.0 ** -np.arange(47, -1, -1.0)
    deltas = t[:, None] * (setup.s * direction)[None, :]
    force = setup.bearing.state(deltas, setup.psi).force - deltas @ setup.load_stiffness.T
    proj = (force * setup.s) @ direction
    hit = np.flatnonzero(proj >= norm)
    if hit.size == 0:
        return deltas[-1], float(t[-1]), float(proj.max() / norm)
    i = int(hit[0])
    if i == 0:
        return deltas[0], float(t[0]), 1.0
    w = (norm - proj[i - 1]) / (proj[i] - proj[i - 1])
    size = float(t[i - 1] + w * (t[i] - t[i - 1]))
    return size * setup.s * direction, size, 1.0


def solve_local(setup: Setup, method: str, x0: ArrayLike | None, tol: float,
                 max_iter: int, stats: Stats) -> tuple[FloatArray, int]:
    guess, size, capacity = _ray_start(setup)
    if x0 is not None:
        guess = np.asarray(x0, dtype=float).reshape(5)
        if not np.all(np.isfinite(guess)):
            raise ModelError(f"x0 must be 5 finite numbers, got {x0!r}", setup.where)
        size = max(size, setup.scaled_size(guess))
    size = max(size, 1e-6 * setup.range)
    xf0 = guess[setup.free]
    if not np.any(setup.free):
        return np.zeros(5), 0
    x_scale = size * setup.s[setup.free]
    try:
        if method == "newton":
            problem = ResidualProblem.scaled(setup.residual, xf0.size, x_scale,
                                             setup.f_ref / setup.s[setup.free])
            solver = Newton(tol=tol, max_iter=max_iter, max_step=setup.range / size,
                            where=f"{setup.where} statics")
            state = solver.solve(problem, xf0, stats)
            xf, iterations = state.x, state.iteration
        else:
            found = minimize_energy(setup.potential, xf0, x_scale=x_scale,
                                    energy_scale=setup.f_ref * size, tol=tol,
                                    max_iter=4 * max_iter, stats=stats,
                                    where=f"{setup.where} statics")
            xf, iterations = found.x, found.iterations
    except ConvergenceError as exc:
        _no_equilibrium(setup, capacity, exc)
        raise
    delta = setup.full(xf[None, :])[0]
    if setup.scaled_size(delta) > setup.range:
        _no_equilibrium(setup, capacity, None)
    return delta, iterations


def _no_equilibrium(setup: Setup, capacity: float, exc: Exception | None) -> None:
    """Raise ModelError when the load cannot be balanced within the physical range."""
    if exc is not None and capacity >= 1.0:
        return
    clearance = float(setup.bearing.clearance)
    reach = ("the bearing force along the load direction reaches only "
             f"{100 * capacity:.3g} % of the load there" if capacity < 1.0 else
             "the solution lies outside it")
    raise ModelError(
        f"no equilibrium for the load {setup.load.tolist()} within the physical range "
        f"|translation| <= {setup.range:.4g} m (tilt x pitch radius): {reach}; the rolling "
        f"elements lose contact in the load direction (radial clearance {clearance:.4g} m; "
        "clearance too large, or a load the bearing cannot carry)", setup.where)


def solve_global(setup: Setup, tol: float, max_iter: int, n_starts: int, seed: int,
                  stats: Stats, search: dict[str, int]
                  ) -> tuple[FloatArray, int, tuple[EnergyMinimum, ...]]:
    guess, size, capacity = _ray_start(setup)
    free = setup.free
    if not np.any(free):
        return np.zeros(5), 0, ()
    size = max(size, 1e-3 * setup.range)
    box = setup.range * setup.s[free]
    searcher = GlobalSearch(n_starts=n_starts, tol=tol, max_iter=4 * max_iter,
                          cluster_tol=1e-4, seed=seed)
    found = searcher.run(setup.batch, -box, box, x_scale=size * setup.s[free],
                       energy_scale=setup.f_ref * size,
                       extra_starts=np.vstack([np.zeros(free.sum()), guess[free]]),
                       stats=stats, where=f"{setup.where} global statics")
    search.update(n_starts=found.n_starts, converged=found.n_converged,
                  saddles=found.n_saddles, escaped=found.n_escaped, failed=found.n_failed)
    inside = [m for m in found.minima
              if setup.scaled_size(setup.full(m.x[None, :])[0]) <= setup.range]
    if not inside:
        if capacity < 1.0 or found.n_escaped > 0:
            _no_equilibrium(setup, capacity, None)
        raise ConvergenceError(f"no start converged ({found.n_failed} at the iteration "
                               f"limit, {found.n_saddles} on saddles)",
                               f"{setup.where} global statics")
    minima = tuple(EnergyMinimum(setup.full(m.x[None, :])[0], m.energy,
                                 m.hessian_eigenvalues, m.hits) for m in inside)
    stats.rejected_steps += found.n_starts - found.n_converged
    return minima[0].displacement, inside[0].iterations, minima


# --------------------------------------------------------------------------- result
def make_result(setup: Setup, delta: FloatArray, method: str, phi: float, iterations: int,
            minima: tuple[EnergyMinimum, ...], stats: Stats,
            options: dict[str, Any]) -> BearingEquilibriumResult:
    st = setup.bearing.state(delta[None, :], setup.psi)
    pot, grad, hess, strain = setup.evaluate(delta[setup.free][None, :])
    residual = float(np.max(np.abs(grad[0] * setup.s[setup.free]), initial=0.0)) / setup.f_ref
    arrays = (st.force, st.stiffness, st.element_load, st.contact_angle, st.deflection)
    if not (all(np.all(np.isfinite(a)) for a in arrays) and math.isfinite(residual)):
        raise ConvergenceError("non-finite bearing state at the solution", setup.where)
    notes = _stability_notes(setup, hess[0])
    return BearingEquilibriumResult(
        displacement=delta, load=setup.load, force=st.force[0], method=method, phi=phi,
        element_angles=setup.psi[0].copy(), element_load=st.element_load[0],
        contact_angle=st.contact_angle[0], deflection=st.deflection[0],
        stiffness=st.stiffness[0], energy=float(pot[0]), strain_energy=float(strain[0]),
        residual=residual, iterations=int(iterations),
        held_dofs=tuple(n for n, _ in setup.held),
        hold_reasons=tuple(r for _, r in setup.held), minima=minima, notes=notes,
        options=options, stats=stats.finish(), status=Status.OK,
        summary=bearing_summary(setup.bearing))


def _stability_notes(setup: Setup, hess: FloatArray) -> tuple[str, ...]:
    """Remarks on a singular or indefinite tangent at the equilibrium (free DOFs)."""
    if hess.size == 0:
        return ()
    sf = setup.s[setup.free]
    w = np.linalg.eigvalsh(hess * np.outer(sf, sf))
    top = float(np.abs(w).max())
    if top == 0.0:
        return ("no rolling element is loaded: the displacement is not unique (any "
                "displacement inside the clearance is an equilibrium); 0 is reported",)
    if w[0] < -1e-10 * top:
        return ("unstable equilibrium: the tangent stiffness (minus load_stiffness) has a "
                "negative eigenvalue; use method='global' for the stable ones",)
    if w[0] <= 1e-10 * top:
        return ("the tangent stiffness is singular at the equilibrium: the displacement "
                "is not unique along its null direction",)
    return ()


def bearing_summary(bearing: Any) -> dict[str, Any]:
    return {"bearing": type(bearing).__name__, "tag": getattr(bearing, "tag", None),
            "n_elements": int(bearing.n_elements),
            "contact_angle_deg": math.degrees(float(getattr(bearing, "contact_angle", 0.0))),
            "clearance": float(getattr(bearing, "clearance", 0.0)),
            "Kn": float(bearing.Kn), "exponent": float(bearing.exponent)}
