"""Property test: random mutations of valid model files either load or raise ModelError.

Each example takes a valid model (a file from ``models/`` or a small model using every
section), applies 1-3 random mutations at random key paths (delete a key or item, replace a
value by a random number, NaN, infinity, negative, string, unit string, list or table, add
an unknown key) and loads the result both as a dict and through a TOML file. Anything but
success or a one-line :class:`ModelError` fails the test.

Set ``ROTORSIM_HYPOTHESIS_EXAMPLES`` to run more examples than the fast default.
"""

from __future__ import annotations

import copy
import os
import tempfile
import tomllib
from pathlib import Path
from typing import Any

import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model, model_from_dict

MODELS = Path(__file__).resolve().parents[2] / "models"
EXAMPLES = int(os.environ.get("ROTORSIM_HYPOTHESIS_EXAMPLES", "150"))

EVERY_SECTION: dict[str, Any] = {
    "model": {"name": "every_section", "description": "uses every table"},
    "materials": [{"name": "steel", "E": "210 GPa", "rho": 7850, "nu": 0.3}],
    "shaft": [
        {"length": "0.4 m", "n_elements": 4, "od": "40 mm", "material": "steel"},
        {"element_length": 0.1, "n_elements": 2, "idl": 0.0, "odl": 0.04, "odr": 0.03,
         "material": "steel", "shear_effects": False, "alpha": 0.1, "beta": 1e-6,
         "axial_force": "1 kN", "tag": "cone"},
    ],
    "disks": [{"z": "0.2 m", "m": 5.0, "Id": 0.02, "Ip": 0.04},
              {"node": 5, "width": 0.02, "i_d": 0.03, "o_d": 0.2, "material": "steel"}],
    "bearings": [
        {"node": 0, "kxx": "10 MN/m", "cxx": "1 kN s/m", "n_link": 7},
        {"z": 0.6, "frequency": {"values": [0, 3000], "unit": "rpm"},
         "kxx": [1e7, 2e7], "kxy": ["1 MN/m", 0], "cyy": 200.0, "krr": 100.0, "mxx": 0.1},
        {"node": 7, "kxx": 1e9},
    ],
    "point_masses": [{"node": 7, "m": "30 kg", "mz": 0.0}],
    "fixed": [{"node": 7, "dofs": ["uz", "rz"]}],
    "loads": {"gravity": True, "gravity_direction": [0, -1, 0],
              "unbalance": [{"z": 0.2, "magnitude": "10 g mm", "phase": "90 deg"}],
              "point_loads": [{"node": 3, "dof": "uy", "value": "-100 N"}]},
    "analyses": {
        "modes": {"type": "modal", "num_modes": 4, "speed": "1000 rpm"},
        "campbell": {"type": "campbell", "speeds": {"start": 0, "stop": 3000, "num": 4,
                                                     "unit": "rpm"}, "harmonics": [1, 2]},
        "crit": {"type": "critical_speeds", "whirl": "forward"},
        "map": {"type": "critical_speed_map", "bearings": [0, 1], "num_modes": 2,
                "stiffness": {"start": 1e6, "stop": 1e8, "num": 3}},
        "unb": {"type": "unbalance", "speeds": [10, 20, 30], "nodes": [2],
                "unbalance": [{"node": 2, "magnitude": 1e-5}]},
        "frf": {"type": "frequency_response", "frequencies": [1.0, 2.0],
                "inputs": [{"node": 3, "dof": "ux"}], "speed": 0},
        "static": {"type": "static", "units": "Hz"},
    },
}


def _bases() -> list[dict[str, Any]]:
    out = [EVERY_SECTION]
    for name in ("default", "compressor"):
        with open(MODELS / f"{name}.toml", "rb") as stream:
            out.append(tomllib.load(stream))
    return out


BASES = _bases()

UNIT_STRINGS = ["50 mm", "50 kg", "3000 rpm", "1 MN/m", "-1 m", "nan m", "inf", "0.1 g m",
                "1e999 m", "5 foo", "", " ", "steel", "campbell", "ux", "rpm", "log",
                "1 kg m^2", "2 kN s/m", "90 deg", "10 m/s^2", "[1, 2]", "{a}", "1 (", "forward"]
SCALARS = st.one_of(
    st.integers(min_value=-3, max_value=30),
    st.sampled_from([0, -1, 10**6, 2**40]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    st.text(max_size=8),
    st.sampled_from(UNIT_STRINGS),
)
VALUES = st.recursive(
    SCALARS,
    lambda children: st.lists(children, max_size=4)
    | st.dictionaries(st.sampled_from(["start", "stop", "num", "values", "unit", "node", "z",
                                       "x", "type", "dof", "magnitude"]), children,
                      max_size=3),
    max_leaves=6,
)


def _paths(node: Any, prefix: tuple = ()) -> list[tuple]:
    """Every key path into a nested dict/list (the root excluded)."""
    out = []
    items = node.items() if isinstance(node, dict) else enumerate(node) \
        if isinstance(node, list) else ()
    for key, child in items:
        out.append((*prefix, key))
        out.extend(_paths(child, (*prefix, key)))
    return out


def _mutate(data: dict[str, Any], draw: Any) -> None:
    path = draw(st.sampled_from(_paths(data)))
    parent: Any = data
    for key in path[:-1]:
        parent = parent[key]
    last = path[-1]
    op = draw(st.sampled_from(["delete", "replace", "replace", "add"]))
    if op == "delete":
        del parent[last]
    elif op == "replace":
        parent[last] = draw(VALUES)
    else:
        target = parent[last] if isinstance(parent[last], dict) else parent
        if isinstance(target, dict):
            target[draw(st.sampled_from(["kxz", "odd", "Type", "speed", "nodes", "x"]))] = \
                draw(VALUES)
        else:
            target.append(draw(VALUES))


def _check(load: Any) -> None:
    try:
        load()
    except ModelError as err:
        assert "\n" not in str(err), str(err)
        assert str(err).split(": ")[0], str(err)


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(st.data())
def test_mutated_models_load_or_raise_model_error(data):
    model = copy.deepcopy(data.draw(st.sampled_from(BASES)))
    for _ in range(data.draw(st.integers(min_value=1, max_value=3))):
        if not _paths(model):
            break
        _mutate(model, data.draw)
    _check(lambda: model_from_dict(model))
    try:
        text = tomli_w.dumps(model)
    except (TypeError, ValueError):  # not representable in TOML (e.g. None)
        return
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "mutated.toml"
        path.write_text(text)
        _check(lambda: load_model(path))


def test_the_unmutated_bases_load():
    for base in BASES:
        model = model_from_dict(copy.deepcopy(base))
        assert model.analyses
