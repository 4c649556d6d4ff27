"""Resume of a periodic branch whose checkpoint became its results file.

``periodic(..., checkpoint=path)`` rewrites ``path`` during the run and at its end; a
finished run is resumed from it like a transient: nothing is left to compute and the result
is the finished branch. Users often save the result under the same name
(``rs.save(result, path)``), which replaces the checkpoint by a results file. Resuming from
such a file returns the stored result when it was computed by the same run: the options of
the call (:func:`~rotorsim.analyses.periodic.periodic.periodic`'s ``result.options``) and the
identity of the start (size and hash of the first point, as stored in continuation
checkpoints) must match, else :class:`~rotorsim.errors.CheckpointError`
lists what differs. A results file holding anything but a periodic branch is refused too.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from rotorsim.errors import CheckpointError
from rotorsim.io.checkpoint_file import compare_config, file_format
from rotorsim.results.periodic import PeriodicResult

RESULTS_FORMAT = "rotorsim-results"
"""``format`` attribute of a file written by :func:`rotorsim.io.hdf5.save`."""

IGNORED = ("stability_model_modes", "fold_map")
"""Result options that are outputs of the run, not inputs to compare."""


def finished_result(path: str | os.PathLike[str]) -> PeriodicResult | None:
    """The periodic result stored in ``path`` when it is a results file, None when it is
    anything else (a checkpoint: read by the continuation, which checks it).

    Raises
    ------
    CheckpointError
        For a results file that does not hold one periodic result.
    """
    source = Path(path)
    if file_format(source) != RESULTS_FORMAT:
        return None
    from rotorsim.io.hdf5 import load

    result = load(source)
    if not isinstance(result, PeriodicResult):
        raise CheckpointError(f"a results file with a {type(result).__name__}, not a periodic "
                              "branch to resume", str(source))
    return result


def resumed(result: PeriodicResult, options: dict[str, Any],
            path: str | os.PathLike[str]) -> PeriodicResult:
    """``result`` when it was computed with ``options`` (this call's), else
    CheckpointError naming the differing options."""
    stored = _normal({k: v for k, v in result.options.items() if k not in IGNORED})
    current = _normal({k: v for k, v in options.items() if k not in IGNORED})
    try:
        compare_config(stored, current)
    except CheckpointError as exc:
        raise CheckpointError(f"results file {exc}", str(path)) from exc
    return result


def _normal(values: dict[str, Any]) -> dict[str, Any]:
    """JSON form (tuples as lists) so that stored and fresh options compare equal."""
    out: dict[str, Any] = json.loads(json.dumps(values, sort_keys=True, default=str))
    return out
