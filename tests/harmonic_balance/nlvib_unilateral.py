"""NLvib's example 03: two masses with a unilateral gap spring, and an independent
reference for its periodic orbits.

The system (NLvib 1.3, EXAMPLES/03_twoDOFoscillator_unilateralSpring, a chain of
oscillators with ``m = [1, 1]``, ``k = [0, 1, 1]``, ``d = 0.03 k``): ``M = I``,
``K = [[1, -1], [-1, 2]]``, ``D = 0.03 K``, the force ``0.1 cos(omega t)`` on the second
mass and a unilateral spring ``f = 100 max(q_1 - 1, 0)`` on the first (stiffness 1e2,
gap 1); NLvib uses ``H = 21`` and ``N = 2^10``. At ``omega = 0.75`` two periodic orbits in
contact have first-harmonic amplitudes ``a1 = |Q_1| = 1.222`` and ``1.310`` of the first
mass (issue 16); :data:`ORBIT_GUESSES` are their states at phase 0 to three digits.

The reference (:func:`reference_monodromy`) integrates with scipy's LSODA at ``rtol =
1e-11`` one smooth segment at a time, each ended by event location where the gap closes
or opens, and forms the monodromy matrix by central finite differences of the end state
(no variational equations, no step control across a switch).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from rotorsim.harmonic_balance.fourier import AFT
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.harmonic_balance.solve import solve_point

M = np.eye(2)
K = np.array([[1.0, -1.0], [-1.0, 2.0]])
D = 0.03 * K
STIFFNESS, GAP, FORCE = 100.0, 1.0, 0.1
H, N = 21, 1024
OMEGA = 0.75
ORBIT_GUESSES = (np.array([-1.261, -0.645, 0.765, -0.163]),      # a1 = 1.222
                 np.array([0.094, -0.207, 0.724, 1.131]))        # a1 = 1.310


def gap_spring(q, v, tau, omega, p):
    """``f = k max(q - g, 0)`` and its tangent (batched HBProblem force)."""
    on = q >= GAP
    return STIFFNESS * (q - GAP) * on, (STIFFNESS * on)[:, :, None], None


def problem() -> HBProblem:
    excitation = np.zeros((3, 2))
    excitation[1, 1] = FORCE
    return HBProblem(M, K, D, nl_dofs=[0], force=gap_spring, excitation=excitation)


def _rhs(contact: bool, omega: float):
    def f(t, y):
        q, v = y[:2], y[2:]
        r = np.array([STIFFNESS * (q[0] - GAP) if contact else 0.0, 0.0])
        a = np.array([0.0, FORCE * np.cos(omega * t)]) - K @ q - D @ v - r
        return np.concatenate((v, a))
    return f


def reference_period(y0, omega: float = OMEGA, rtol: float = 1e-11) -> np.ndarray:
    """``y(T)`` from ``y0``, one event-located smooth segment at a time."""
    T, t, y = 2 * np.pi / omega, 0.0, np.asarray(y0, dtype=float)
    contact = y[0] > GAP or (y[0] == GAP and y[2] > 0)
    while t < T:
        def event(t, y):
            return y[0] - GAP
        event.terminal, event.direction = True, (-1 if contact else 1)
        sol = solve_ivp(_rhs(contact, omega), (t, T), y, method="LSODA", rtol=rtol,
                        atol=1e-13, events=event)
        t, y = sol.t[-1], sol.y[:, -1]
        if sol.status == 1:                        # the gap closed or opened
            contact = not contact
    return y


def reference_monodromy(y0, omega: float = OMEGA, h: float = 1e-5) -> np.ndarray:
    """Central differences of :func:`reference_period` (step ``h`` per state)."""
    cols = [(reference_period(y0 + h * e, omega) - reference_period(y0 - h * e, omega))
            / (2 * h) for e in np.eye(4)]
    return np.column_stack(cols)


def hb_orbit(state, omega: float = OMEGA):
    """HB solution (H, N above, condensed onto q_1) started from the Fourier series of
    the trajectory from ``state``: returns the residual and the converged point."""
    res = make_residual(problem(), H, samples=N)
    tau = 2 * np.pi * np.arange(N) / N
    sol = solve_ivp(_flow(omega), (0, 2 * np.pi / omega), state, method="DOP853",
                    rtol=1e-10, atol=1e-12, t_eval=tau / omega)
    X = AFT(H, N).to_frequency(sol.y[:2].T)
    return res, solve_point(res, omega, res.restrict(X))


def _flow(omega: float):
    def f(t, y):
        contact = y[0] > GAP
        return _rhs(bool(contact), omega)(t, y)
    return f


def first_harmonic(x) -> float:
    """``a1 = |Q_1|`` of the condensed unknowns (q_1's coefficients)."""
    return float(np.hypot(x[1], x[2]))
