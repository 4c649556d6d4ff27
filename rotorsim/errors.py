"""Exceptions and status codes shared by the whole package.

Every error names *where* the problem is (element, key, step) so that a user can
fix the model without reading a traceback.
"""

from __future__ import annotations

import enum

_CONTROL = {**{i: f"\\x{i:02x}" for i in (*range(32), 127)}, 9: "\\t", 10: "\\n", 13: "\\r"}


def one_line(text: str) -> str:
    """``text`` with control characters escaped, so that a message stays on one line even
    when a user's name or tag holds a newline.

    Examples
    --------
    >>> print(one_line("Material 'a\\nb': E must be > 0"))
    Material 'a\\nb': E must be > 0
    """
    return text.translate(_CONTROL)


class RotorsimError(Exception):
    """Base class of all rotorsim errors."""


class ModelError(RotorsimError, ValueError):
    """Invalid model input.

    Parameters
    ----------
    message : str
        What is wrong.
    where : str, optional
        The culprit, e.g. ``"ShaftElement[3].odl"`` or ``"bearing 'B1'"``.
    """

    def __init__(self, message: str, where: str | None = None) -> None:
        self.where = where
        super().__init__(one_line(f"{where}: {message}" if where else message))


class InconsistentModelError(ModelError):
    """A model that changed in a way the analysis cannot follow, e.g. a varied parameter
    whose rotor has other nodes or nonlinear DOFs. Solvers never retry it with a smaller
    step: it propagates at once."""


class ResultsFileError(ModelError):
    """A results file, or a value to be written to one, does not fit the rotorsim layout.

    ``where`` names the file and HDF5 path (or the field) at fault.
    """


class CheckpointError(RotorsimError, ValueError):
    """A checkpoint cannot be read or belongs to another run.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The checkpoint file.
    """

    def __init__(self, message: str, path: str | None = None) -> None:
        self.path = path
        super().__init__(f"checkpoint {path}: {message}" if path else message)


class ConvergenceError(RotorsimError, RuntimeError):
    """A single solve failed to converge.

    Parameters
    ----------
    message : str
        What failed.
    where : str, optional
        Which analysis or solve.
    step, iteration : int, optional
        Step (speed point, time step) and iteration at failure.
    residual : float, optional
        Residual norm at failure.
    """

    def __init__(
        self,
        message: str,
        where: str | None = None,
        step: int | None = None,
        iteration: int | None = None,
        residual: float | None = None,
    ) -> None:
        self.where = where
        self.step = step
        self.iteration = iteration
        self.residual = residual
        parts = [message]
        if step is not None:
            parts.append(f"step {step}")
        if iteration is not None:
            parts.append(f"iteration {iteration}")
        if residual is not None:
            parts.append(f"residual {residual:.3e}")
        text = ", ".join(parts)
        super().__init__(one_line(f"{where}: {text}" if where else text))


class Status(enum.IntEnum):
    """Outcome of one point of a sweep or of a whole analysis."""

    OK = 0
    NOT_CONVERGED = 1
    FAILED = 2
    SKIPPED = 3
