"""How a rotor's harmonic-balance residual varies with a model parameter ``p``.

:func:`parametric_residual` turns the HB problem of :func:`rotorsim.periodic` at a fixed
fundamental into a residual whose parameter ``p`` is a model parameter, given by
``vary(p)``:

* **nonlinear elements** (``vary(p)`` returns them, same nodes and kinds): only the force
  callback changes, one :class:`~rotorsim.assembly.nonlinear.NonlinearAssembly` per value
  (cached); the condensation of the linear part is shared by every ``p``;
* **a whole rotor** (``vary(p)`` returns a :class:`~rotorsim.model.rotor.Rotor` with the
  same nodes, constraints and nonlinear DOFs): any parameter of the linear part as well (a
  damper coefficient, a bearing stiffness, a disk mass, a shaft diameter). Each value is
  assembled and its HB problem rebuilt with the same loads, excitation plan and held DOFs
  (:attr:`RotorPeriodicProblem.rebuild`), then condensed on the nonlinear DOFs (the last
  :data:`CACHED_VALUES` values are kept: a corrector iterate and its two differences).

In both cases the periodic forcing is the full one (the rotor problem's own parameter, the
forcing reduction, stays 0) and ``dR/dp`` is a central difference of the residual with the
step ``6e-6 max(|p|, scale)``: for the whole rotor, of the *condensed* residual, whose
dependence on ``p`` through the Schur complements is part of what is differentiated.
:func:`static_load_residual` makes ``p`` the size of the static point loads instead
(``dR/dp`` is then exact: the load enters harmonic 0 linearly).

Changing the varying-compliance orders (number of rolling elements, cage speed ratio) with
``p`` would change the fundamental at a fixed speed; both variants refuse it.
"""

from __future__ import annotations

import dataclasses
from collections import OrderedDict
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.problem import RotorForce, RotorPeriodicProblem
from rotorsim.analyses.varying_compliance import vc_orders
from rotorsim.assembly.loads import nodal_load
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.errors import InconsistentModelError, ModelError
from rotorsim.harmonic_balance.fourier import AFT, FloatArray, IntArray
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import HBEvaluation, HBResidual, make_residual
from rotorsim.model.rotor import Rotor
from rotorsim.solvers.stats import Stats

WHERE = "periodic_parameter"
CACHED_VALUES = 6
"""Parameter values whose assembled and condensed problems :class:`RotorFamilyResidual`
keeps."""
RELATIVE_STEP = 6e-6
"""Central-difference step of ``dR/dp`` relative to ``max(|p|, scale)``."""


def parametric_residual(rp: RotorPeriodicProblem, system: RotorSystem,
                        vary: Callable[[float], Any], harmonics: int, samples: int | None,
                        scale: float, at: float) -> HBResidual:
    """The HB residual of ``rp`` (full forcing) whose parameter ``p`` is the model
    parameter of ``vary`` (module docstring); ``at`` is a value of ``p`` used to tell the
    two kinds of ``vary`` apart, ``scale`` the typical size of ``p``.

    Raises
    ------
    ModelError
        When ``vary(at)`` is neither a Rotor nor nonlinear elements, or changes the nodes,
        the nonlinear DOFs or the varying-compliance orders.
    """
    template = rp.problem.force
    if not isinstance(template, RotorForce) or system.nonlinear is None:
        raise ModelError("the rotor has no nonlinear DOFs to vary", WHERE)
    probe = vary(float(at))
    if isinstance(probe, Rotor):
        return RotorFamilyResidual(rp, system, vary, harmonics, samples, float(scale))
    force = _ParametricForce(template, vary, system)
    force.at(float(at))  # checks the elements now, with the offending value in the error
    problem = dataclasses.replace(rp.problem, force=force,
                                  excitation=_FullForcing(rp.problem.excitation),
                                  param_scale=float(scale))
    return make_residual(problem, harmonics, samples=samples, condense=True)


def static_load_residual(rp: RotorPeriodicProblem, system: RotorSystem,
                         loads: Sequence[tuple[int, str, float]], at: float, harmonics: int,
                         samples: int | None, scale: float) -> HBResidual:
    """The HB residual of ``rp`` (built with the point loads ``at * loads``) whose
    parameter ``p`` multiplies the point loads ``loads`` instead (full periodic forcing)."""
    unit = np.zeros(system.n_free)
    for i, (node, dof, value) in enumerate(loads):
        unit += nodal_load(system, int(node), str(dof), float(value), where=f"loads[{i}]")
    if not np.any(unit):
        raise ModelError("vary='loads' needs nonzero point loads (node, dof, value)", WHERE)
    problem = dataclasses.replace(
        rp.problem, param_scale=float(scale),
        excitation=_ScaledStaticLoad(rp.problem.excitation, unit[rp.active], float(at)))
    return make_residual(problem, harmonics, samples=samples, condense=True)


@dataclasses.dataclass(frozen=True, eq=False)
class _FullForcing:
    """The rotor's external load with the full periodic forcing for every ``p``."""

    loads: Any

    def __call__(self, omega: float, param: float) -> Any:
        return self.loads(omega, 0.0)


@dataclasses.dataclass(frozen=True, eq=False)
class _ScaledStaticLoad:
    """The rotor's external load with the point loads ``p * unit`` instead of
    ``at * unit`` (harmonic 0)."""

    loads: Any
    unit: FloatArray
    at: float

    def __call__(self, omega: float, param: float) -> Any:
        out = np.array(self.loads(omega, 0.0), dtype=float)
        out[0] += (param - self.at) * self.unit
        return out


def _check_orders(elements: Sequence[Any], reference: list[float], value: float) -> None:
    if vc_orders(elements) != reference:
        raise InconsistentModelError(f"vary({value!r}) changed the varying-compliance orders "
                         f"{reference} -> {vc_orders(elements)}: at a fixed speed the "
                         "fundamental would change with the parameter", WHERE)


class _ParametricForce:
    """The rotor force callback with the nonlinear elements of ``vary(p)`` (cached)."""

    def __init__(self, template: RotorForce, vary: Callable[[float], Sequence[Any]],
                 system: RotorSystem) -> None:
        self.template, self.vary = template, vary
        self.full_to_free = system.dof_map.full_to_free
        self.n_nodes = system.dof_map.n_nodes
        assert system.nonlinear is not None
        self.dofs = system.nonlinear.dofs
        self.orders = vc_orders(system.nonlinear.elements)
        self.cache: dict[float, RotorForce] = {}

    def at(self, p: float) -> RotorForce:
        key = float(p)
        if key not in self.cache:
            if len(self.cache) > 64:
                self.cache.clear()
            elements = self.vary(key)
            if isinstance(elements, Rotor):
                raise InconsistentModelError(f"vary({key!r}) returned a Rotor where it returned "
                                 "nonlinear elements before", WHERE)
            elements = tuple(elements)
            assembly = NonlinearAssembly.build(elements, self.full_to_free, self.n_nodes)
            if not np.array_equal(assembly.dofs, self.dofs):
                raise InconsistentModelError(
                    f"vary({key!r}) changed the nonlinear DOFs: keep the nodes", WHERE)
            _check_orders(elements, self.orders, key)
            self.cache[key] = dataclasses.replace(self.template, assembly=assembly)
        return self.cache[key]

    def __call__(self, q: Any, v: Any, tau: Any, omega: float, param: float) -> Any:
        return self.at(param)(q, v, tau, omega, 0.0)


class RotorFamilyResidual:
    """HB residual of the rotors ``vary(p)``: linear and nonlinear parts both vary
    (module docstring). Same interface as the condensed residual
    (:class:`~rotorsim.harmonic_balance.residual.HBResidual`); ``problem`` is the problem of
    the first rotor, :meth:`at` the residual of the rotor at ``p``.

    Parameters
    ----------
    rp, system : RotorPeriodicProblem, RotorSystem
        The problem and system of the rotor at the first value (its nodes, constraints,
        nonlinear DOFs and excitation plan are those of every ``p``).
    vary : callable
        ``vary(p) -> Rotor``.
    harmonics, samples : int, int or None
        HB discretisation.
    scale : float
        Typical size of ``p`` (central-difference step ``6e-6 max(|p|, scale)``).
    """

    def __init__(self, rp: RotorPeriodicProblem, system: RotorSystem,
                 vary: Callable[[float], Any], harmonics: int, samples: int | None,
                 scale: float) -> None:
        if not (np.isfinite(scale) and scale > 0):
            raise ModelError(f"the parameter scale must be positive, got {scale!r}", WHERE)
        self.rp, self.vary, self.scale = rp, vary, float(scale)
        self.base = make_residual(rp.problem, harmonics, samples=samples, condense=True)
        self.free = system.dof_map.free
        assert system.nonlinear is not None
        self.nl_dofs = system.nonlinear.dofs
        self.orders = vc_orders(system.nonlinear.elements)
        self.cache: OrderedDict[float, HBResidual] = OrderedDict()

    @property
    def problem(self) -> HBProblem:
        return self.base.problem

    @property
    def harmonics(self) -> int:
        return self.base.harmonics

    @property
    def samples(self) -> int:
        return self.base.samples

    @property
    def aft(self) -> AFT:
        return self.base.aft

    @property
    def size(self) -> int:
        return self.base.size

    @property
    def dofs(self) -> IntArray:
        return self.base.dofs

    def at(self, p: float) -> HBResidual:
        """The condensed residual of the rotor ``vary(p)`` (cached)."""
        key = float(p)
        if key in self.cache:
            self.cache.move_to_end(key)
            return self.cache[key]
        rotor = self.vary(key)
        if not isinstance(rotor, Rotor):
            raise InconsistentModelError(
                f"vary({key!r}) returned {type(rotor).__name__}, not a Rotor", WHERE)
        system = assemble(rotor)
        if not np.array_equal(system.dof_map.free, self.free):
            raise InconsistentModelError(
                f"vary({key!r}) changed the nodes or constraints of the rotor "
                f"({system.n_free} free DOFs instead of {self.free.size})", WHERE)
        if system.nonlinear is None or not np.array_equal(system.nonlinear.dofs,
                                                          self.nl_dofs):
            raise InconsistentModelError(
                f"vary({key!r}) changed the nonlinear DOFs: keep the nonlinear elements on "
                "the same nodes", WHERE)
        _check_orders(system.nonlinear.elements, self.orders, key)
        rebuilt = self.rp.rebuild(system)
        problem = dataclasses.replace(rebuilt.problem,
                                      excitation=_FullForcing(rebuilt.problem.excitation))
        out = make_residual(problem, self.harmonics, samples=self.samples, condense=True)
        self.cache[key] = out
        while len(self.cache) > CACHED_VALUES:
            self.cache.popitem(last=False)
        return out

    def evaluate(self, x: Any, omega: float, param: float = 0.0, *, jacobian: bool = True,
                 d_omega: bool = False, d_param: bool = False,
                 stats: Stats | None = None) -> HBEvaluation:
        """Residual and derivatives at ``x``, ``omega`` and ``p = param``."""
        ev = self.at(param).evaluate(x, omega, 0.0, jacobian=jacobian, d_omega=d_omega,
                                     stats=stats)
        dp = None
        if d_param:
            h = RELATIVE_STEP * max(abs(float(param)), self.scale)
            up = self.at(param + h).evaluate(x, omega, 0.0, jacobian=False, stats=stats).r
            down = self.at(param - h).evaluate(x, omega, 0.0, jacobian=False, stats=stats).r
            dp = (up - down) / (2.0 * h)
        return HBEvaluation(ev.r, ev.jacobian, ev.d_omega, dp, ev.terms)

    def expand(self, x: Any, omega: float, param: float = 0.0) -> FloatArray:
        """Coefficients (2H + 1, n) of all DOFs of the rotor at ``p = param``."""
        return self.at(param).expand(x, omega, 0.0)

    def restrict(self, X: Any) -> FloatArray:
        return self.base.restrict(X)

    def with_discretization(self, harmonics: int | None = None,
                            samples: int | None = None) -> RotorFamilyResidual:
        """The same family on another ``(H, N)``."""
        base = self.base.with_discretization(harmonics, samples)
        out = RotorFamilyResidual.__new__(RotorFamilyResidual)
        out.__dict__.update(self.__dict__, base=base, cache=OrderedDict())
        return out
