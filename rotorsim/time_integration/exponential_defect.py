"""The defect check of an exponential collocation step (:mod:`~.exponential`): the bearing
forces evaluated between the collocation nodes, on the step's own dense output, against
the interpolant the step integrated.

The collocation solution ``y_c`` of a step solves ``y_c' = A y_c + B p(t)``, ``p`` the
interpolant of ``rho`` through its values at the nodes, while the exact solution solves
``y' = A y + B rho(y)``. Their difference obeys ``e' = A e + B (rho(y) - rho(y_c)) +
B d(t)`` with the *defect* ``d = rho(y_c(t)) - p(t)``, zero at the nodes. To first order in
``e`` the local error is the defect's response

    e(t_n + h) ~ int_0^h e^{A (h - s)} B d(t_n + s) ds,

(the variation-of-constants formula of Hochbruck & Ostermann 2010, eq 2.3, applied to the
error). ``d`` is sampled at the midpoints between the nodes (one batch evaluation of the
bearings at ``s`` points) and replaced by its interpolant through those samples and the
zeros at the nodes (degree ``2 s``), whose integral is the same ``phi_k`` weights as a
step's. Where the bearing forces are smooth over the step this is of the size of the true
local error ``O(h^{s+2})``; where a ball's contact closes or opens inside the step, ``rho``
has a kink that the interpolant through the nodes alone cannot see, and the defect shows
it. The stepper's error estimate is the larger of this response and the difference to the
interpolant of degree ``s - 1`` through the stage nodes. That difference estimates the
error of the lower-order interpolant, so it is conservative where ``rho`` is smooth, and it
also covers what the response neglects, the error's feedback through the bearings
(``rho(y) - rho(y_c)``), which dominates when the remainder's stiffness is large against
``1 / h`` (on the forced Duffing oscillator of ``tests/time_integration/test_exponential.py``
at rtol 1e-3 the response alone took 26 steps over 1 s and let the error reach 5.0
``rtol``, doubled 4.6).

Before (issue 14, eighth pass) the difference alone was the estimate, blind to a kink
between the nodes: steps across contact changes passed with estimates up to 42 times below
their local error (``docs/validation.md``).

References
----------
M. Hochbruck, A. Ostermann, *Exponential integrators*, Acta Numerica 19 (2010) 209-286,
sections 2.1-2.3; E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, IV.8
(the defect of a collocation polynomial drives its error).
"""

from __future__ import annotations

import cmath
import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.time_integration.base import FloatArray
from rotorsim.time_integration.exponential_modes import (
    LinearModes,
    StepWeights,
    lagrange_coefficients,
)


@functools.lru_cache(maxsize=8)
def defect_tables(nodes: tuple[float, ...]) -> tuple[FloatArray, FloatArray, FloatArray]:
    """For the nodes ``c_0 .. c_s``: the midpoints ``x`` (s,) between them, the values
    (s, s + 1) of the nodes' Lagrange basis at ``x``, and the monomial coefficients
    (s, 2 s + 1) of the Lagrange basis functions of ``x`` over nodes and midpoints
    together (zero at the nodes). Read-only: every run shares them."""
    c = np.asarray(nodes, dtype=float)
    x = 0.5 * (c[:-1] + c[1:])
    L = lagrange_coefficients(c)
    values = (x[:, None] ** np.arange(c.size)[None, :]) @ L.T
    every = lagrange_coefficients(np.concatenate([c, x]))[c.size:]
    out = (x, values, every)
    for a in out:
        a.setflags(write=False)
    return out


def bearing_maps(bearing_rows: Any, W: Any, Bp: Any, k: int) -> tuple[FloatArray, FloatArray]:
    """The maps (p k, s k) of the stage values of ``rho`` (nodes 1..s) to the bearing
    displacements and velocities at the ``p`` fractions of the weights ``W`` (p, s + 1,
    N): block (i, j) = ``Re(C diag(W_ij) Bp)``, ``C`` the rows of ``V`` on the bearing
    displacements, then velocities (2 k, N)."""
    p, s = W.shape[0], W.shape[1] - 1
    B = np.matmul(bearing_rows, W[:, 1:, :, None] * Bp[None, None]).real
    Hq, Hv = (B[:, :, rows].transpose(0, 2, 1, 3).reshape(p * k, s * k)
              for rows in (slice(0, k), slice(k, 2 * k)))
    return Hq, Hv


@dataclass(frozen=True, eq=False)
class DefectOps:
    """What the defect check of a step of size ``h`` needs: the weights at the midpoints,
    the maps ``Hq``, ``Hv`` of :func:`bearing_maps` there, the values of the nodes' basis
    there (s, s + 1) and the end weights ``G`` (s, N) of the midpoints' basis functions."""

    x: FloatArray
    weights: StepWeights
    Hq: FloatArray
    Hv: FloatArray
    values: FloatArray
    G: Any

    @classmethod
    def of(cls, modes: LinearModes, h: float, nodes: FloatArray, L: FloatArray,
           bearing_rows: Any, shared: StepWeights | None = None) -> DefectOps:
        """The defect check's operators of a step of size ``h``; ``shared``: the weights
        :func:`shared_weights` computed (else computed here)."""
        x, values, every = defect_tables(tuple(float(c) for c in nodes))
        s = x.size
        both = shared_weights(modes, h, nodes, L) if shared is None else shared
        w = both.select(slice(s, 2 * s), L)
        Hq, Hv = bearing_maps(bearing_rows, w.W, modes.Bp, modes.dofs.size)
        # the end weights of the midpoints' basis functions, at the end node c_s = 1
        end = both.select(slice(s - 1, s), every)
        return cls(x, w, Hq, Hv, values, end.W[0])


def shared_weights(modes: LinearModes, h: float, nodes: FloatArray, L: FloatArray
                   ) -> StepWeights:
    """The weights of a step of size ``h`` at the stage nodes ``c_1 .. c_s`` and then at
    the defect's midpoints, with the monomials of the midpoints' basis (degree ``2 s``): one
    call of the ``phi`` functions for the step and its defect check."""
    x, _, every = defect_tables(tuple(float(c) for c in nodes))
    return StepWeights.of(modes, h, np.concatenate([nodes[1:], x]), L,
                          monomials=every.shape[1])


def defect_response(ops: DefectOps, modes: LinearModes, bearing_rows: Any, restoring: Any,
                    z: Any, t: float, h: float, all_rho: FloatArray) -> Any:
    """The modal response ``dz`` (N,) at the end of the step to the defect (module
    docstring) of a converged step from the modal state ``z`` at ``t`` whose ``rho`` at
    the nodes is ``all_rho`` (s + 1, k); ``bearing_rows`` as in :func:`bearing_maps`."""
    k, n = modes.dofs.size, modes.n
    w = ops.weights
    e = cmath.exp(1j * modes.frequency * t)
    base = w.E * z[None, :] + w.const + e * w.plus + np.conj(e) * w.minus + \
        w.W[:, 0, :] * (modes.Bp @ all_rho[0])[None, :]
    stages = all_rho[1:].ravel()
    at = (base @ bearing_rows.T).real
    qb = at[:, :k] + (ops.Hq @ stages).reshape(-1, k)
    vb = at[:, k:] + (ops.Hv @ stages).reshape(-1, k)
    p = ops.x.size
    Q, Vel = np.zeros((p, n)), np.zeros((p, n))
    Q[:, modes.dofs], Vel[:, modes.dofs] = qb, vb
    _, r, _, _ = restoring.batch(Q, Vel, t + ops.x * h)
    defect = qb @ modes.K0.T + vb @ modes.C0.T - r - ops.values @ all_rho
    return (ops.G * (defect @ modes.Bp.T)).sum(axis=0)
