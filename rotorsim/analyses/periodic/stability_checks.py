"""Per-point checks of a branch's Floquet multipliers, as stored in the result.

The checks and the shooting fallback themselves are rotor-agnostic
(:mod:`rotorsim.harmonic_balance.floquet_check`); this module only gathers their records
over the points of a branch into the arrays of ``PeriodicResult.stability_checks`` and
projects the excitation onto a Craig-Bampton stability model (shooting integrates the
forced trajectory of that model).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.floquet_check import FloquetCheck
from rotorsim.harmonic_balance.fourier import FloatArray
from rotorsim.harmonic_balance.problem import HBProblem


class CheckedModel(Protocol):
    """What :func:`check_arrays` needs of a stability model."""

    def check(self, x: FloatArray, omega: float, param: float = 0.0) -> FloquetCheck:
        """The check record of a branch point."""
        ...


def check_arrays(model: CheckedModel | None, points: Any, lam: Any) -> dict[str, np.ndarray]:
    """``stability_checks`` of a branch (empty without a stability model).

    Keys (arrays over the P points): ``method`` (str: method of the stored multipliers,
    "" where Floquet failed), ``passed`` (bool: the first method passed the Liouville and
    tangent-jump checks), ``liouville_error`` (float, NaN: not applicable),
    ``tangent_jumps`` (int), ``fallback_liouville_error`` (float, NaN without shooting).
    """
    if model is None:
        return {}
    records: list[FloquetCheck | None] = []
    for x, w in zip(points, lam, strict=True):
        try:
            records.append(model.check(np.asarray(x, dtype=float), float(w)))
        except (ModelError, ConvergenceError, np.linalg.LinAlgError):
            records.append(None)
    nan = float("nan")
    return {
        "method": np.array([r.method if r else "" for r in records], dtype=str),
        "passed": np.array([bool(r and r.passed) for r in records], dtype=bool),
        "liouville_error": np.array([r.liouville_error if r else nan for r in records]),
        "tangent_jumps": np.array([r.tangent_jumps if r else 0 for r in records],
                                  dtype=np.int64),
        "fallback_liouville_error": np.array([r.fallback_liouville_error if r else nan
                                              for r in records]),
    }


def projected_excitation(problem: HBProblem, T: FloatArray) -> dict[str, Any]:
    """``excitation`` and ``load`` of ``problem`` in the coordinates ``q = T z``
    (``T^T f``), as keyword arguments of the reduced :class:`HBProblem`."""
    out: dict[str, Any] = {}
    coeff, load = problem.excitation, problem.load
    if coeff is not None:
        if callable(coeff):
            source: Callable[[float, float], Any] = coeff
            out["excitation"] = lambda w, p: np.asarray(source(w, p), dtype=float) @ T
        else:
            out["excitation"] = np.asarray(coeff, dtype=float) @ T
    if load is not None:
        sampled = load
        out["load"] = lambda tau, w, p: np.asarray(sampled(tau, w, p), dtype=float) @ T
    return out
