"""The torus residual as a function of the speed, for pseudo-arclength continuation.

A rotor's torus depends on the speed ``W`` through both base frequencies (``w1 = W``,
``w2 = Z kappa W``), the gyroscopic and speed-dependent linear terms, the unbalance
``m e W^2`` and the bearings' own speed terms (centrifugal loads, cage speed). Natural
steps in ``W`` stop where the branch folds: a lightly damped resonance on Hertzian
contacts bends over (the default model's first critical speed). Pseudo-arclength
continuation (:func:`~rotorsim.solvers.continuation.continue_branch`) passes such folds;
it needs ``R(x, W)``, ``dR/dx`` and ``dR/dW``.

``x`` are the coefficients of the bearing DOFs on the torus (the condensed unknowns). The
condensation is redone at every new ``W`` (one sparse LU per tone; the last two speeds
are cached, since the corrector evaluates each speed with and without its Jacobian).
``dR/dW`` is analytic for the linear part (the chain rule through the condensation,
:func:`~rotorsim.harmonic_balance.quasi.residual.speed_derivative`, including the
unbalance's ``W^2``) and a central difference with step :data:`DW_REL` ``W`` of the
bearing forces alone (their velocities and own speed terms). With speed-dependent linear
bearings the whole residual is differenced (two more condensations).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.problem import (
    RotorQuasiProblem,
    TorusBearingForce,
    forcing_rows,
    torus_plan,
)
from rotorsim.assembly.system import RotorSystem
from rotorsim.harmonic_balance.quasi import QuasiProblem, TorusAFT
from rotorsim.harmonic_balance.quasi.residual import (
    CondensedTones,
    LinearBlocks,
    condense,
    residual,
    speed_derivative,
)

FloatArray = NDArray[np.float64]
DW_REL = 1e-6
"""Relative speed step of the central difference ``dR/dW``."""
CACHE = 4
"""Speeds whose condensation is kept."""


class SpeedResidual:
    """``fun(x, W) -> (R, dR/dx, dR/dW)`` of the torus at speed ``W`` [rad/s] (module
    docstring), from the problem ``base`` built at one speed."""

    def __init__(self, system: RotorSystem, base: RotorQuasiProblem, aft: TorusAFT,
                 unbalance: Sequence[tuple[int, float, float]]) -> None:
        self.system, self.base, self.aft = system, base, aft
        self.unbalance = tuple(unbalance)
        self.active = base.active
        pb = base.problem
        self.rows, self.d = aft.harmonics.rows, int(np.size(pb.nl_dofs))
        self.constant = np.asarray(pb.excitation)[0].copy()
        plan = base.plan if base.plan is not None else torus_plan(system, unbalance)
        self.forcing = forcing_rows(system, plan, aft.harmonics, self.active)
        self.speed_dependent = bool(system.variable_bearings)
        self._cache: OrderedDict[float, tuple[QuasiProblem, CondensedTones]] = OrderedDict()
        self.blocks = None if self.speed_dependent else LinearBlocks.of(pb)

    def problem_at(self, speed: float) -> QuasiProblem:
        """The quasi-periodic problem at ``speed`` (no static solve: the held DOFs and the
        bearing DOFs are those of ``base``)."""
        pb = self.base.problem
        P = np.zeros((self.rows, self.active.size))
        P[0] = self.constant
        for row, U in self.forcing:
            P[row] += U.real * speed**2
            P[row + 1] += -U.imag * speed**2
        f = pb.force
        assert isinstance(f, TorusBearingForce)
        force = replace(f, speed=float(speed))
        changes: dict[str, Any] = {"excitation": P, "force": force, "spin": float(speed)}
        if self.speed_dependent:
            mats = self.system.matrices(speed)
            ix = np.ix_(self.active, self.active)
            changes.update(M=sp.csr_matrix(mats.M)[ix], C=sp.csr_matrix(mats.C)[ix],
                           K=sp.csr_matrix(mats.K)[ix])
        return replace(pb, **changes)

    def tones_at(self, speed: float) -> tuple[QuasiProblem, CondensedTones]:
        key = float(speed)
        if key not in self._cache:
            problem = self.problem_at(key)
            self._cache[key] = (problem, condense(problem, self.aft, key,
                                                  self.base.vc_order * key, self.blocks))
            while len(self._cache) > CACHE:
                self._cache.popitem(last=False)
        return self._cache[key]

    def value(self, x: FloatArray, speed: float, jacobian: bool
              ) -> tuple[FloatArray, FloatArray | None]:
        problem, tones = self.tones_at(speed)
        return residual(problem, self.aft, tones, float(speed),
                        self.base.vc_order * float(speed),
                        np.asarray(x).reshape(self.rows, self.d), jacobian=jacobian)

    def __call__(self, x: FloatArray, speed: float
                 ) -> tuple[FloatArray, FloatArray, FloatArray]:
        W = float(speed)
        r, J = self.value(x, W, True)
        assert J is not None
        h = DW_REL * abs(W)
        if self.blocks is None:        # speed-dependent bearings: difference everything
            up, _ = self.value(x, W + h, False)
            down, _ = self.value(x, W - h, False)
            return r, J, (up - down) / (2 * h)
        Y = np.asarray(x).reshape(self.rows, self.d)
        problem, tones = self.tones_at(W)
        harmonics = self.aft.harmonics
        orders = np.concatenate([[0.0], harmonics.frequencies(1.0, self.base.vc_order)])
        dF = np.zeros((orders.size, self.active.size), dtype=complex)
        for row, U in self.forcing:
            dF[(row + 1) // 2] += 2.0 * W * U                     # d(me (r W)^2)/dW
        linear = speed_derivative(self.blocks, tones, orders, W, Y, dF)
        return r, J, (linear + (self._force(problem, Y, W + h) -
                                self._force(problem, Y, W - h)) / (2 * h)).ravel()

    def _force(self, problem: QuasiProblem, Y: FloatArray, speed: float) -> FloatArray:
        """Coefficients of the bearing forces at ``speed`` (its velocities and its own speed
        terms) for fixed coefficients ``Y``."""
        f = problem.force
        assert isinstance(f, TorusBearingForce)
        q = self.aft.to_samples(Y)
        v = self.aft.to_samples(self.aft.derivative_matrix(speed, self.base.vc_order * speed)
                                @ Y)
        values, _, _ = replace(f, speed=speed)(q, v, *self.aft.angles)
        return self.aft.to_coefficients(values)

    def full(self, x: FloatArray, speed: float) -> FloatArray:
        """Coefficients of all active DOFs ``(rows, n)`` at a branch point."""
        from rotorsim.harmonic_balance.quasi.residual import full_coefficients

        problem, tones = self.tones_at(speed)
        return full_coefficients(problem, tones, np.asarray(x).reshape(self.rows, self.d))
