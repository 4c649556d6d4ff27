"""Model files (TOML): load a rotor with its loads and named analyses, and save one back.

A model file lists ``[model]``, ``[[materials]]``, ``[[shaft]]`` segments, ``[[disks]]``,
``[[bearings]]``, ``[[rolling_bearings]]``, ``[[point_masses]]``, ``[[fixed]]``, ``[loads]``
and named ``[analyses.<name>]``; the reference is ``docs/model_files.md``. Rolling bearings
stay out of ``Model.rotor``: the analyses run on :meth:`Model.linearized`, the rotor with
each rolling bearing linearised (by default at its static load). Values are SI numbers or
strings with units (``"50 mm"``, ``"1 MN/m"``, ``"3000 rpm"``).

Every problem in a file raises one :class:`~rotorsim.errors.ModelError` whose message
starts with the key path (``shaft[3].od: must be > id (0.06 m)``); TOML syntax errors give
the line and column.

pydantic (and pint, for unit strings) is imported when a file is read, so importing this
module stays light. This module is the entry point: :class:`Model` and
:func:`model_from_dict` are defined in :mod:`rotorsim.io.model`, :func:`run_analysis` in
:mod:`rotorsim.io.analysis_runners`, and are importable from here.

Examples
--------
>>> import tempfile, pathlib
>>> text = '''
... [[materials]]
... name = "steel"
... E = "211 GPa"
... G_s = "81.2 GPa"
... rho = "7810 kg/m^3"
...
... [[shaft]]
... length = "1.5 m"
... n_elements = 6
... od = "50 mm"
... material = "steel"
...
... [[bearings]]
... z = 0
... kxx = "1 MN/m"
...
... [[bearings]]
... z = "1.5 m"
... kxx = "1 MN/m"
...
... [analyses.modes]
... type = "modal"
... num_modes = 4
... '''
>>> path = pathlib.Path(tempfile.mkdtemp()) / "shaft.toml"
>>> _ = path.write_text(text)
>>> model = load_model(path)
>>> model.name, model.rotor.n_nodes, [b.n for b in model.rotor.bearing_elements]
('shaft', 7, [0, 6])
>>> result = run_analysis(model, "modes")
>>> result.wn.size
4
"""

from __future__ import annotations

import os
import tempfile
import tomllib
from pathlib import Path

from rotorsim.errors import ModelError
from rotorsim.io.analysis_runners import run_analysis
from rotorsim.io.model import Model, model_from_dict
from rotorsim.io.model_writer import model_to_dict, toml_text
from rotorsim.io.output_folder import prepare_folder
from rotorsim.model.rotor import Rotor

__all__ = ["Model", "load_model", "model_from_dict", "run_analysis", "save_model"]


def load_model(path: str | os.PathLike[str]) -> Model:
    """Read a TOML model file.

    Parameters
    ----------
    path : str or path-like
        The ``.toml`` file.

    Returns
    -------
    Model

    Raises
    ------
    ModelError
        Missing or unreadable file, TOML syntax error (with line and column), or an invalid
        model; the message starts with the key path of the first problem.
    """
    path = Path(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except OSError as err:
        raise ModelError(f"cannot read the file: {err.strerror or err}", str(path)) from None
    except UnicodeDecodeError as err:
        raise ModelError(f"not a UTF-8 text file ({err.reason} at byte {err.start})",
                         str(path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ModelError(f"invalid TOML: {err}", str(path)) from None
    return model_from_dict(data, source=path)


def save_model(model: Model | Rotor, path: str | os.PathLike[str]) -> Path:
    """Write a rotor or a model as a TOML model file in SI numbers.

    Shaft elements are written as one ``[[shaft]]`` segment per run of identical
    consecutive elements (tapered elements one by one), disks with ``m, Id, Ip``, bearings
    with every coefficient that differs from its default and their tables over
    ``frequency``. Loading the file rebuilds identical element matrices, loads and analyses.
    The file is written to a temporary name and renamed, so it is never left half-written.

    Parameters
    ----------
    model : Model or Rotor
        What to write; a bare Rotor gets default loads and no analyses.
    path : str or path-like
        Output file; missing folders are created.

    Returns
    -------
    Path
        ``path``.
    """
    if isinstance(model, Rotor):
        model = Model(name=model.tag, rotor=model)
    if not isinstance(model, Model):
        raise ModelError(f"expected a Model or Rotor, got {type(model).__name__}", "save_model")
    path = Path(path)
    text = toml_text(model_to_dict(model))
    prepare_folder(path, "save_model")
    handle, tmp = tempfile.mkstemp(dir=path.parent or ".", prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
