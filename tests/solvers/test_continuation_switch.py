"""Branch switching and extrema on closed-form problems (rotorsim.solvers)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_extrema import locate_extrema
from rotorsim.solvers.continuation_switch import (
    continue_from,
    locate_branch_point,
    scaled_system,
)


def transcritical(x, lam):
    """``x (lam - 1 - x) = 0`` and a decoupled ``z = 0``: the lines ``x = 0`` and
    ``x = lam - 1`` cross at ``lam = 1`` (a transcritical branch point)."""
    r = np.array([x[0] * (lam - 1.0 - x[0]), 2.0 * x[1]])
    J = np.array([[lam - 1.0 - 2 * x[0], 0.0], [0.0, 2.0]])
    return r, J, np.array([x[0], 0.0])


OPTIONS = Continuation(initial_step=0.05, max_step=0.2, lam_min=0.0, lam_max=2.0)


def test_transcritical_branch_point_is_located_and_the_other_line_followed():
    branch = continue_branch(transcritical, [0.0, 0.0], 0.0, OPTIONS)
    i = int(np.flatnonzero(np.diff(branch.det_sign) != 0)[0])
    system, fixed = scaled_system(transcritical, branch.x[0], 0.0, OPTIONS)
    y, width = locate_branch_point(system, fixed, branch.scaled()[i], branch.scaled()[i + 1])
    x, lam = system.from_y(y)
    # the determinant vanishes linearly: Illinois to 1e-10 in scaled arclength
    assert abs(lam - 1.0) < 1e-9 and width < 1e-9
    along = np.append(branch.x[i + 1] - branch.x[i], branch.lam[i + 1] - branch.lam[i])
    up, jump = continue_from(transcritical, x, lam, None, OPTIONS, along=along)
    assert jump.singular_values is not None and jump.singular_values[1] < 1e-9
    # the second branch is the line x = lam - 1, followed from the branch point upwards
    assert np.allclose(up.x[:, 0], up.lam - 1.0, atol=1e-9) and up.lam[-1] == 2.0
    down, _ = continue_from(transcritical, x, lam, None, OPTIONS, along=along, sign=-1)
    assert down.lam[-1] == 0.0 and down.x[-1, 0] == pytest.approx(-1.0)


def test_orientation_chooses_the_way_off_the_start():
    def circle(x, lam):
        return np.array([x[0] ** 2 + lam**2 - 1.0]), np.array([[2 * x[0]]]), np.array([2 * lam])

    opts = Continuation(max_step=0.2, max_points=4)
    ahead = continue_branch(circle, [1.0], 0.0, opts, orientation=[0.0, -1.0])
    assert ahead.lam[-1] < 0.0
    with pytest.raises(ModelError, match="orientation"):
        continue_branch(circle, [1.0], 0.0, opts, orientation=[1.0])


def test_extrema_of_a_measure_along_a_parabola():
    def parabola(x, lam):          # x = 1 - lam^2: x largest at lam = 0
        return np.array([x[0] - 1.0 + lam**2]), np.eye(1), np.array([2 * lam])

    branch = continue_branch(parabola, [0.0], -1.0, Continuation(max_step=0.3, lam_max=1.0))
    [top] = locate_extrema(parabola, branch, lambda x, lam: float(x[0]))
    assert top.kind == "max" and top.located
    assert abs(top.lam) < 1e-9 and top.value == pytest.approx(1.0, abs=1e-12)
