"""The option keys of the long model-file analyses (transient, periodic branches) are the
fields of the option groups of rotorsim.options: same names (flat keys), types, bounds,
defaults and help texts in the specs, the model-file schema and the command line."""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import pytest

import rotorsim as rs
from rotorsim.cli.parser import BRANCH_OPTIONS, build_parser
from rotorsim.errors import ModelError
from rotorsim.io.analysis_schema import TABLES
from rotorsim.io.model_file import load_model, model_from_dict, save_model
from rotorsim.io.spec_registry import SPEC_TYPES
from rotorsim.options.flat import flat_key, option_field

MODELS = Path(__file__).resolve().parents[2] / "models"
LONG = ("transient", "periodic", "periodic_parameter")


@pytest.mark.parametrize("kind", LONG)
def test_schema_keys_are_the_group_fields(kind):
    spec = SPEC_TYPES[kind]
    table = TABLES[kind].model_fields
    groups = spec.option_groups()
    for key, (attr, name) in spec.flat_keys().items():
        field = option_field(groups[attr], name)
        default = field.default if field.default is not None else None
        if default is None and "none" not in field.metadata:
            assert not table[key].is_required() and table[key].default is None, key
        else:
            assert table[key].default == default, key
        plain = {f.name for f in dataclasses.fields(spec)} - set(spec.FILE_OPTIONS)
        assert key not in plain, key                  # one meaning per key


def test_flat_keys_of_the_files_fill_the_groups():
    model = load_model(MODELS / "default.toml")
    branch, runup = model.analyses["branch"], model.analyses["runup"]
    assert branch.harmonics == rs.Harmonics(6)
    assert branch.continuation == rs.ContinuationOptions(max_step=0.2, max_points=600)
    assert branch.stability == rs.StabilityOptions()
    assert runup.output == rs.Output(every=2) and runup.checkpointing == rs.Checkpointing()
    assert model.analyses["clearance"].continuation == rs.ContinuationOptions()


def test_groups_round_trip_through_a_saved_file(tmp_path):
    with open(MODELS / "rolling_ball.toml", "rb") as stream:
        raw = tomllib.load(stream)
    raw["analyses"]["branch"] = {"type": "periodic", "start": "300 rpm", "stop": "400 rpm",
                                 "harmonics": 5, "samples": 64, "max_points": 30,
                                 "stability": "none", "checkpoint_every": 7}
    model = model_from_dict(raw, source="m.toml")
    spec = model.analyses["branch"]
    assert spec.harmonics == rs.Harmonics(5, samples=64)
    assert spec.stability.method is None and spec.checkpointing.every == 7
    written = spec.to_toml()
    assert {k: written[k] for k in ("harmonics", "samples", "max_points", "stability",
                                    "checkpoint_every")} == {
        "harmonics": 5, "samples": 64, "max_points": 30, "stability": "none",
        "checkpoint_every": 7}
    assert "max_step" not in written                  # left at the analysis default
    again = load_model(save_model(model, tmp_path / "m.toml")).analyses["branch"]
    assert again.harmonics == spec.harmonics and again.continuation == spec.continuation
    assert again.stability == spec.stability and again.checkpointing == spec.checkpointing
    assert math.isclose(again.start, spec.start)


def test_bad_option_keys_name_the_key_path():
    with open(MODELS / "rolling_ball.toml", "rb") as stream:
        raw = tomllib.load(stream)
    raw["analyses"]["branch"] = {"type": "periodic", "start": "300 rpm", "stop": "400 rpm",
                                 "max_points": 1}
    with pytest.raises(ModelError, match=r"^analyses\.branch\.max_points: must be >= 2"):
        model_from_dict(raw, source="m.toml")
    raw["analyses"]["branch"] = {"type": "periodic", "start": "300 rpm", "stop": "400 rpm",
                                 "stability": "lyapunov"}
    with pytest.raises(ModelError, match=r"^analyses\.branch\.stability: must be one of"):
        model_from_dict(raw, source="m.toml")


def test_command_line_options_are_the_group_fields():
    parser = build_parser()
    sub = parser._subparsers._group_actions[0].choices  # type: ignore[union-attr]
    actions = {a.dest: a for a in sub["periodic"]._actions}
    for group, name in (*BRANCH_OPTIONS, (rs.Checkpointing, "every")):
        meta = option_field(group, name).metadata
        action = actions[flat_key(group, name)]
        assert action.help == meta["help"] and action.type is meta["file"]
    args = parser.parse_args(["periodic", "m.toml", "--harmonics", "3", "--max-points", "9",
                              "--checkpoint-every", "4"])
    assert (args.harmonics, args.max_points, args.checkpoint_every) == (3, 9, 4)
