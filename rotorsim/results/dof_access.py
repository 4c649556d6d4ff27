"""DOF access shared by the results that keep some DOFs (transient, periodic): their
``dofs`` (indices among all DOFs, ``6 * node + local``) label and locate the columns of
their arrays."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap


class KeptDofs:
    """Mixin of a result dataclass with the fields ``dofs`` (int array (m,)) and
    ``dof_map``."""

    dofs: NDArray[np.int64]
    dof_map: DofMap

    @property
    def dof_labels(self) -> list[str]:
        """Label of each kept DOF, ``"node 8 uy"`` as in results files
        (:func:`~rotorsim.assembly.dof_map.dof_label`)."""
        return [self.dof_map.label(i) for i in self.dofs]

    def column(self, node: int, dof: str) -> int:
        """Column of ``(node, dof)`` among the kept DOFs.

        Raises
        ------
        ModelError
            When that DOF was not kept (the message lists the kept nodes).
        """
        return self.dof_map.column(self.dofs, node, dof, type(self).__name__)
