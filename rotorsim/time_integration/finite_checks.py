"""Input and NaN/Inf checks shared by the steppers: state vectors of the right size, and a
:class:`~rotorsim.errors.ConvergenceError` that names the time, step and first non-finite
DOF of a residual, correction or tangent.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.base import FloatArray
from rotorsim.time_integration.local_tangent import LocalMatrix


def finite_vector(x: ArrayLike, n: int, name: str) -> FloatArray:
    """``x`` as a float vector of ``n`` finite numbers; :class:`ModelError` naming ``name``."""
    arr = np.array(x, dtype=float).reshape(-1)
    if arr.shape != (n,) or not np.all(np.isfinite(arr)):
        raise ModelError(f"must be {n} finite numbers, got shape {np.shape(x)}", name)
    return arr


def first_nonfinite_row(T: object) -> int:
    """Row of the first NaN/Inf entry of a dense or sparse matrix (-1 if none or None)."""
    if T is None:
        return -1
    if isinstance(T, LocalMatrix):
        bad_rows = ~np.isfinite(T.block).all(axis=-1)
        return int(T.dofs[np.argmax(bad_rows)]) if bad_rows.any() else -1
    if sp.issparse(T):
        coo = sp.coo_matrix(T)
        bad = ~np.isfinite(coo.data)
        return int(coo.row[np.argmax(bad)]) if bad.any() else -1
    rows = ~np.isfinite(np.asarray(T, dtype=float)).all(axis=-1)
    return int(np.argmax(rows)) if rows.any() else -1


def check_finite(x: FloatArray, what: str, where: str, t: float, step: int,
                 iteration: int) -> None:
    """Raise ConvergenceError naming the first non-finite DOF of ``x``."""
    bad = ~np.isfinite(x)
    if bad.any():
        dof = int(np.argmax(bad))
        raise ConvergenceError(f"{what} is not finite at t = {t:.9g} s (DOF {dof})", where,
                               step=step, iteration=iteration, residual=float("nan"))
