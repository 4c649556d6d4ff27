"""A rotor's periodic-response problem as a rotor-agnostic :class:`HBProblem`.

:func:`build_problem` turns an assembled :class:`~rotorsim.assembly.system.RotorSystem`
into ``M q'' + (C + W G) q' + K q + r(q_nl, q_nl', phi, W) = f(t)`` on its *active* DOFs:
the free DOFs minus one DOF per free rigid-body motion that no element restrains (torsion;
axial motion on cylindrical rollers), which are held at zero as in the static analysis
(their harmonic-0 equation would be singular). The fundamental ``omega`` and the shaft
angle follow :class:`~rotorsim.analyses.periodic.excitation.ExcitationPlan`:

* ``parameter="speed"``: ``W = omega / f``, ``phi = phi0 + tau / f`` (or ``phi0`` with
  frozen rolling elements); ``HBProblem(spin_ratio=1 / f)``;
* ``parameter="frequency"``: fixed ``W``, ``phi = phi0``, ``omega`` the base-excitation
  frequency; ``HBProblem(spin=W, spin_ratio=0)``.

External load (harmonic coefficients, ``excitation(omega, p)``): constant gravity and point
loads in harmonic 0, unbalance ``me W^2`` in harmonic ``1 / f``, housing excitation
``M e a (b W)^2`` in harmonic ``b / f`` (seed 002 eq 3.43). Their ``omega`` dependence is a
callable, so :mod:`rotorsim.harmonic_balance.residual` differentiates it (``dR/domega`` of
speed continuation contains ``d(W^2)/domega``). The force callback gathers the bearings on the
nonlinear DOFs in one batched call per period (DESIGN section 4); a bearing whose force
depends on ``W`` (EHL damping, centrifugal loading) makes ``force_uses_omega`` true.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.periodic.excitation import (
    ExcitationPlan,
    HarmonicBase,
    rotating_coefficients,
)
from rotorsim.analyses.statics.static_start import static_start
from rotorsim.assembly.loads import (
    gravity_load,
    nodal_load,
    rigid_translation,
    spool_groups,
    unbalance_amplitudes,
)
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import default_samples, whole
from rotorsim.harmonic_balance.memory import check_memory
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.solvers.stats import Stats

IntArray = NDArray[np.int64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class PeriodicLoads:
    """``excitation(omega, p)``: coefficients (2m + 1, n_active) of the external load [N].

    The HB parameter ``p`` scales the periodic forcing (unbalance, base) by ``1 - p``: the
    analysis runs at ``p = 0``; the start homotopy goes from ``p = 1`` (static) to 0.
    ``constant`` (gravity, point loads), ``unbalance`` per unit ``W^2`` (complex, shaft
    angle 0), ``mass_direction = M e`` of the base motion [kg]; ``order`` ``f`` (0: the
    frequency is the parameter and ``speed`` is fixed).
    """

    constant: FloatArray
    unbalance: ComplexArray | None
    mass_direction: FloatArray | None
    base: HarmonicBase | None
    plan: ExcitationPlan
    phi0: float

    @property
    def rows(self) -> int:
        return 2 * max(self.plan.unbalance_harmonic, self.plan.base_harmonic) + 1

    def __call__(self, omega: float, param: float) -> FloatArray:
        plan = self.plan
        out = np.zeros((self.rows, self.constant.size))
        out[0] = self.constant
        scale = 1.0 - param   # p = 1 removes the periodic forcing (start homotopy)
        if self.unbalance is not None:
            # the spool's unbalance turns at r W with the angle r phi; backwards (r < 0) it
            # is Re(U e^{-i |r| W t}) = Re(conj(U) e^{i |r| W t})
            r = plan.unbalance_ratio
            W = omega / plan.order
            U = self.unbalance * (scale * np.exp(1j * r * self.phi0) * (r * W) ** 2)
            U = U if r > 0 else U.conj()
            out += rotating_coefficients(U, plan.unbalance_harmonic, self.rows)
        if self.base is not None and self.mass_direction is not None:
            b = self.base
            if plan.order:   # locked to the speed: order b, phase b phi0 + phase
                w_b, psi = b.order * omega / plan.order, b.order * self.phi0 + b.phase
            else:            # the frequency is the parameter
                w_b, psi = omega, b.phase
            U = self.mass_direction * (scale * b.amplitude * w_b**2 * np.exp(1j * psi))
            out += rotating_coefficients(U, plan.base_harmonic, self.rows)
        return out


@dataclass(frozen=True, eq=False)
class RotorForce:
    """``force(q, v, tau, omega, p)`` of the rotor's nonlinear elements on the active
    nonlinear DOFs (held DOFs at zero, their reactions dropped)."""

    assembly: NonlinearAssembly
    positions: IntArray          # active nonlinear DOFs among assembly.dofs
    plan: ExcitationPlan
    phi0: float
    speed: float | None          # fixed W (frequency parameter)
    damped: bool

    def angle_speed(self, tau: FloatArray, omega: float) -> tuple[FloatArray, float]:
        """Shaft angle (N,) [rad] and spin speed [rad/s] at the phases ``tau``."""
        plan = self.plan
        W = self.speed if self.speed is not None else omega / plan.order
        if plan.moving_elements:
            return self.phi0 + tau / plan.order, W
        return np.full(tau.shape, self.phi0), W

    def __call__(self, q: FloatArray, v: FloatArray, tau: FloatArray, omega: float,
                 param: float) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        phi, W = self.angle_speed(tau, omega)
        return self.assembly.evaluate_on(self.positions, q, v, phi, W, self.damped)


@dataclass(frozen=True, eq=False)
class RotorPeriodicProblem:
    """The HB problem of a rotor with the maps back to its DOFs.

    Attributes
    ----------
    problem : HBProblem
        On the active DOFs (``n_active``).
    active : int array (n_active,)
        Free-DOF index of each active DOF.
    held : int array
        Free DOFs held at zero (free rigid motions).
    static : array (n_free,)
        Static equilibrium under the constant loads at the first speed [m, rad] (zero when
        built with given ``held`` DOFs).
    loads : PeriodicLoads
    rebuild : callable
        ``rebuild(system, **changes)``: the same problem (plan, loads, held DOFs, no static
        solve) for another assembled system, e.g. the rotor at another value of a model
        parameter; ``changes`` override keyword arguments of :func:`build_problem`.
    """

    problem: HBProblem
    active: IntArray
    held: IntArray
    static: FloatArray
    loads: PeriodicLoads
    rebuild: Callable[..., RotorPeriodicProblem]


def build_problem(system: RotorSystem, plan: ExcitationPlan, *, speed0: float,
                  fixed_speed: float | None, phi0: float,
                  unbalance: Sequence[tuple[int, float, float]], gravity: float | None,
                  direction: Any, loads: Sequence[tuple[int, str, float]],
                  base: HarmonicBase | None, stats: Stats,
                  held: IntArray | None = None, x0: FloatArray | None = None
                  ) -> RotorPeriodicProblem:
    """Assemble the periodic problem of ``system`` (module docstring) and its static start
    at the speed ``speed0`` [rad/s] and shaft angle ``phi0`` [rad], its Newton iteration
    started from ``x0`` (n_free,) when given; with ``held`` given the static solve is
    skipped (``static`` zero) and those free DOFs are held."""
    if system.variable_bearings and fixed_speed is None:
        tags = [b.label for _, b in system.variable_bearings]
        raise ModelError(f"speed-dependent linear bearings {tags} need a fixed speed: use "
                         "parameter='frequency'", "periodic")
    W = speed0 if fixed_speed is None else fixed_speed
    mats = system.matrices(W)
    f_const = np.zeros(system.n_free)
    if gravity is not None:
        f_const += gravity_load(system, gravity, direction)
    for i, (node, dof, value) in enumerate(loads):
        f_const += nodal_load(system, int(node), str(dof), float(value), where=f"loads[{i}]")
    if held is None:
        static, held = static_start(system, mats.K, f_const, W, phi0, stats, x0)
    else:
        static = np.zeros(system.n_free)
    active = np.setdiff1d(np.arange(system.n_free), held).astype(np.int64)
    ix = np.ix_(active, active)
    mass_direction = None
    if base is not None:
        e = rigid_translation(system.dof_map.n_nodes, base.direction)[system.dof_map.free]
        mass_direction = np.asarray(mats.M @ e)[active]
    if unbalance and spool_ratio(system, unbalance) != plan.unbalance_ratio:
        raise ModelError("the excitation plan was made for another spool's unbalance",
                         "periodic.unbalance")
    unb = unbalance_amplitudes(system, unbalance)[active] if unbalance else None
    periodic_loads = PeriodicLoads(f_const[active], unb, mass_direction, base, plan, phi0)
    force, nl_dofs, uses_speed = _force(system, active, plan, phi0, fixed_speed)
    G = sp.csr_matrix(mats.G)[ix] if mats.G.nnz else None
    problem = HBProblem(
        sp.csr_matrix(mats.M)[ix], sp.csr_matrix(mats.K)[ix], sp.csr_matrix(mats.C)[ix], G,
        nl_dofs=nl_dofs, force=force, excitation=periodic_loads,
        spin=0.0 if fixed_speed is None else fixed_speed,
        spin_ratio=1.0 / plan.order if fixed_speed is None else 0.0,
        force_uses_omega=uses_speed and fixed_speed is None)
    recipe = functools.partial(_rebuild, dict(
        plan=plan, speed0=speed0, fixed_speed=fixed_speed, phi0=phi0, unbalance=unbalance,
        gravity=gravity, direction=direction, loads=loads, base=base, stats=stats, held=held))
    return RotorPeriodicProblem(problem, active, held, static, periodic_loads, recipe)


def spool_ratio(system: RotorSystem, unbalance: Any) -> float:
    """Speed ratio of the spool that carries ``unbalance`` (1 without lines or unbalance).

    The unbalances of two spools turning at different speeds force two incommensurate
    frequencies in general: the response is quasi-periodic (a 2-torus), which the
    two-frequency harmonic balance computes (``rs.periodic`` dispatches it before this
    plan); here it is refused. One spool's unbalance at a ratio ``r``
    is periodic at ``|r| W``.
    """
    if not unbalance:
        return 1.0
    ratios = [float(r) for r in spool_groups(system, unbalance)]
    if len(ratios) > 1:
        raise ModelError(f"unbalances on spools turning at {', '.join(f'{r:g}' for r in ratios)}"
                         " times the reference speed force incommensurate frequencies: the "
                         "response is quasi-periodic, which periodic() does not compute; "
                         "give the unbalance of one spool", "periodic.unbalance")
    return ratios[0]


def check_discretization(harmonics: Any, samples: Any, plan: ExcitationPlan,
                         system: RotorSystem, condense: bool, where: str) -> None:
    """Refuse ``harmonics`` that is not an integer ``>= 1`` or below the harmonic of a
    forcing (the forcing would be dropped), ``samples`` that is not an integer
    ``>= 2 H + 1``, and a discretisation whose estimated memory is above the limit of
    :func:`~rotorsim.harmonic_balance.memory.check_memory` (before any solve)."""
    if not whole(harmonics, 1):
        raise ModelError(f"must be a positive integer (harmonics of the fundamental), got "
                         f"{harmonics!r}", f"{where}.harmonics")
    for name, h in (("unbalance", plan.unbalance_harmonic),
                    ("base excitation", plan.base_harmonic)):
        if h > harmonics:
            raise ModelError(f"{harmonics} harmonics drop the {name}, which is harmonic {h} "
                             f"of the fundamental: use harmonics >= {h}", f"{where}.harmonics")
    if samples is not None and not whole(samples, 2 * harmonics + 1):
        raise ModelError(f"must be an integer >= 2 H + 1 = {2 * harmonics + 1}, got "
                         f"{samples!r}", f"{where}.samples")
    nl = system.nonlinear
    k = 0 if nl is None else int(nl.dofs.size)
    balls = 0 if nl is None else sum(int(getattr(el, "n_elements", 0))
                                     for el in nl.elements)
    check_memory(int(harmonics), int(samples or default_samples(int(harmonics))), k,
                 system.n_free, condense=condense and k > 0, rolling_elements=balls,
                 where=f"{where}.harmonics")


def _rebuild(settings: dict[str, Any], system: RotorSystem, **changes: Any
             ) -> RotorPeriodicProblem:
    """:func:`build_problem` of ``system`` with the settings of an earlier build."""
    return build_problem(system, **{**settings, **changes})


def _force(system: RotorSystem, active: IntArray, plan: ExcitationPlan, phi0: float,
           fixed_speed: float | None) -> tuple[RotorForce | None, IntArray, bool]:
    nl = system.nonlinear
    if nl is None:
        return None, np.zeros(0, dtype=np.int64), False
    keep = np.isin(nl.dofs, active)
    positions = np.flatnonzero(keep).astype(np.int64)
    nl_dofs = np.searchsorted(active, nl.dofs[keep]).astype(np.int64)
    damped = any(getattr(el, "contact_damping", "unknown") != "none" for el in nl.elements)
    uses_speed = any(_uses_speed(el) for el in nl.elements)
    return RotorForce(nl, positions, plan, phi0, fixed_speed, damped), nl_dofs, uses_speed


def _uses_speed(element: Any) -> bool:
    """Whether the element's force depends on the spin speed (unknown kinds: yes)."""
    if not hasattr(element, "contact_damping"):
        return True
    return bool(getattr(element, "centrifugal", False)) or element.contact_damping == "ehl"
