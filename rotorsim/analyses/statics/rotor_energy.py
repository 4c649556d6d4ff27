"""Static equilibrium of a rotor on rolling bearings as a minimum of its potential energy.

Seed 000 finds a bearing's equilibrium as the minimum of its potential energy (eqs 12-26).
For the complete rotor the total potential energy is

    Pi(q) = 1/2 q^T K q - f^T q + sum_b E_b(delta_b(q), psi_b),

the shaft strain energy, minus the work of the constant loads, plus the energy stored in the
rolling-element contacts of each bearing at the relative displacement ``delta_b`` of its
rings. Its gradient is the residual ``K q + r(q) - f`` and its Hessian the tangent
``K + P K_t P^T``, so a trust-region Newton minimiser (``scipy.optimize.minimize``,
``trust-exact`` up to a few hundred unknowns, ``trust-krylov`` with sparse products above)
converges from far away without the line-search heuristics of a root finder: ``Pi`` is
convex where every loaded contact stays loaded and bounded below by the support.
"""

from __future__ import annotations

import inspect
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.errors import ConvergenceError, ModelError

DENSE_LIMIT = 400
"""Up to this many unknowns the Hessian is dense (``trust-exact``)."""
HANDOVER = 1e-4
"""A minimiser stopped by round-off in the energy (its differences reach ``sqrt(eps)``)
is accepted when its gradient is below ``HANDOVER * max(|f|, 1 N)``: Newton's method
finishes from there in one or two iterations."""


def element_energy(element: Any, u: FloatArray, phi: FloatArray, speed: FloatArray
                   ) -> FloatArray:
    """Potential energy [J] of a nonlinear element at element DOFs ``u`` (S, n).

    Raises
    ------
    ModelError
        When the element's model has no energy (e.g. EHL damping only).
    """
    if hasattr(element, "energy"):
        return np.asarray(element.energy(u, phi, speed), dtype=float)
    bearing = getattr(element, "bearing", None)
    if bearing is None or not hasattr(bearing, "energy") or not hasattr(element, "relative"):
        raise ModelError("this element has no potential energy; use the Newton solver",
                         str(getattr(element, "label", element)))
    delta = element.relative(u)
    psi = bearing.element_angles(phi)
    if "speed" in inspect.signature(bearing.energy).parameters:
        return np.asarray(bearing.energy(delta, psi, speed), dtype=float)
    return np.asarray(bearing.energy(delta, psi), dtype=float)


@dataclass(frozen=True, eq=False)
class EnergyEquilibrium:
    """Minimum of the rotor's potential energy on the free DOFs.

    Attributes
    ----------
    q : array (n_free,)
        Displacements [m, rad].
    energy : float
        ``Pi`` at the minimum [J].
    iterations : int
        Minimiser iterations.
    gradient : float
        ``max |K q + r - f|`` at the minimum [N, N m].
    hessian_min : float
        Smallest eigenvalue of the Hessian on the free (not held) DOFs (dense case; NaN
        otherwise): positive at a strict minimum.
    """

    q: FloatArray
    energy: float
    iterations: int
    gradient: float
    hessian_min: float


class RotorEnergy:
    """``Pi(q)``, its gradient and Hessian on the kept free DOFs (module docstring)."""

    def __init__(self, system: RotorSystem, f: FloatArray, speed: float, phi: float,
                 keep: NDArray[np.int64]) -> None:
        if system.nonlinear is None:
            raise ModelError("the system has no nonlinear elements", "rotor energy")
        self.system, self.nl = system, system.nonlinear
        self.K = system.matrices(speed).K
        self.f, self.speed, self.phi, self.keep = f, speed, phi, keep
        full_to_free = system.dof_map.full_to_free
        self.element_dofs = [full_to_free[(DOFS_PER_NODE * np.asarray(el.nodes)[:, None]
                                           + np.arange(DOFS_PER_NODE)).ravel()]
                             for el in self.nl.elements]
        self.base = np.zeros(system.n_free)

    def full(self, x: FloatArray) -> FloatArray:
        q = self.base.copy()
        q[self.keep] = x
        return q

    def value(self, x: FloatArray) -> float:
        q = self.full(x)
        total = 0.5 * float(q @ (self.K @ q)) - float(self.f @ q)
        one, zero = np.array([self.phi]), np.array([self.speed])
        for el, dofs in zip(self.nl.elements, self.element_dofs, strict=True):
            u = np.where(dofs >= 0, q[np.maximum(dofs, 0)], 0.0)[None, :]
            total += float(element_energy(el, u, one, zero)[0])
        return total

    def gradient_and_tangent(self, x: FloatArray) -> tuple[FloatArray, FloatArray]:
        q = self.full(x)
        out = self.nl.evaluate(q[self.nl.dofs], np.zeros(self.nl.k), self.phi, self.speed)
        r = np.zeros_like(q)
        r[self.nl.dofs] = out.f[0]
        return (self.K @ q + r - self.f)[self.keep], out.K[0]

    def hessian(self, kt: FloatArray) -> sp.csr_matrix:
        n, dofs = self.system.n_free, self.nl.dofs
        rows, cols = np.repeat(dofs, dofs.size), np.tile(dofs, dofs.size)
        H = sp.csr_matrix(self.K + sp.csr_matrix((kt.ravel(), (rows, cols)), shape=(n, n)))
        return H[self.keep][:, self.keep]


def energy_equilibrium(system: RotorSystem, f: FloatArray, *, speed: float = 0.0,
                       phi: float = 0.0, q0: FloatArray | None = None,
                       held: Sequence[int] = (), gtol: float = 1e-7, max_iter: int = 500
                       ) -> EnergyEquilibrium:
    """Minimise the rotor's potential energy (module docstring).

    Parameters
    ----------
    system : RotorSystem
        Assembled with its nonlinear elements (each with a potential energy).
    f : array (n_free,)
        Constant loads [N, N m].
    speed, phi : float
        Spin speed [rad/s] and shaft angle [rad].
    q0 : array (n_free,), optional
        Start (default zero); held DOFs keep its values.
    held : sequence of int
        Free DOFs held fixed (free rigid motions: torsion, axial motion on rollers).
    gtol : float
        Converged when ``max |gradient| <= gtol * max(|f|, 1 N)``. Differences of the
        energy reach round-off near ``sqrt(eps)`` of the gradient scale, so polish a tighter
        solution with Newton's method
        (:func:`~rotorsim.analyses.statics.nonlinear_static.nonlinear_equilibrium` from ``q``).
    max_iter : int
        Minimiser iterations.

    Raises
    ------
    ConvergenceError
        When the minimiser stops above the tolerance (message with the gradient).
    """
    from scipy.optimize import minimize

    n = system.n_free
    keep = np.setdiff1d(np.arange(n), np.asarray(held, dtype=np.int64))
    problem = RotorEnergy(system, f, float(speed), float(phi), keep)
    if q0 is not None:
        problem.base = np.array(q0, dtype=float)
    x0 = problem.base[keep].copy()
    cache: dict[bytes, tuple[FloatArray, FloatArray]] = {}

    def grad_and_tangent(x: FloatArray) -> tuple[FloatArray, FloatArray]:
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = problem.gradient_and_tangent(x)
        return cache[key]

    scale = max(float(np.max(np.abs(f), initial=0.0)), 1.0)
    options: dict[str, Any] = {"gtol": gtol * scale, "maxiter": max_iter}
    if keep.size <= DENSE_LIMIT:
        res = minimize(problem.value, x0, method="trust-exact",
                       jac=lambda x: grad_and_tangent(x)[0],
                       hess=lambda x: problem.hessian(grad_and_tangent(x)[1]).toarray(),
                       options=options)
    else:
        res = minimize(problem.value, x0, method="trust-krylov",
                       jac=lambda x: grad_and_tangent(x)[0],
                       hessp=lambda x, p: problem.hessian(grad_and_tangent(x)[1]) @ p,
                       options=options)
    grad, kt = grad_and_tangent(res.x)
    worst = float(np.max(np.abs(grad), initial=0.0))
    if not np.isfinite(worst) or (worst > HANDOVER * scale and not res.success):
        raise ConvergenceError(f"energy minimisation stopped with gradient {worst:.3e} N "
                               f"({res.message})", "rotor energy", iteration=int(res.nit),
                               residual=worst)
    h_min = float("nan")
    if keep.size <= DENSE_LIMIT:
        h_min = float(np.linalg.eigvalsh(problem.hessian(kt).toarray())[0])
    return EnergyEquilibrium(problem.full(res.x), float(res.fun), int(res.nit), worst, h_min)
