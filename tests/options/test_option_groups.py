"""The option groups of rotorsim.options: validation naming the field, shortcut values,
verb defaults, shortcut keywords given twice, and the layering of the package."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

import rotorsim as rs
from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.errors import ModelError
from rotorsim.options import OptionError
from rotorsim.options.group import OptionGroup

GROUPS = (rs.Excitation, rs.Harmonics, rs.ContinuationOptions, rs.StabilityOptions,
          rs.Output, rs.Checkpointing)


@pytest.mark.parametrize("group", GROUPS)
def test_groups_are_frozen_documented_dataclasses(group):
    value = group()
    with pytest.raises(dataclasses.FrozenInstanceError):
        value.x = 1  # type: ignore[attr-defined]
    for f in dataclasses.fields(group):
        assert f.metadata["help"], f"{group.__name__}.{f.name} has no help text"
        assert f"    {f.name} : " in (group.__doc__ or ""), \
            f"{group.__name__}.{f.name} is not in the docstring"
    assert value.given() == {}


def test_excitation_default_gravity_is_standard_gravity():
    assert rs.Excitation().gravity == STANDARD_GRAVITY


@pytest.mark.parametrize(("build", "where", "reason"), [
    (lambda: rs.Harmonics(0), "Harmonics.count", "must be a positive integer"),
    (lambda: rs.Harmonics(2.5), "Harmonics.count", "must be a positive integer"),
    (lambda: rs.Harmonics(2, samples=3), "Harmonics.samples", r"integer >= 2 H \+ 1 = 5"),
    (lambda: rs.Harmonics(fundamental=-1.0), "Harmonics.fundamental", "positive"),
    (lambda: rs.ContinuationOptions(step=0.0), "ContinuationOptions.step", "positive"),
    (lambda: rs.ContinuationOptions(max_points=1), "ContinuationOptions.max_points", ">= 2"),
    (lambda: rs.ContinuationOptions(tol=float("nan")), "ContinuationOptions.tol", "positive"),
    (lambda: rs.ContinuationOptions(solver=rs.Harmonics()), "ContinuationOptions.solver",
     "expected"),
    (lambda: rs.StabilityOptions(modes=-3), "StabilityOptions.modes", "integer"),
    (lambda: rs.StabilityOptions(tol=-1.0), "StabilityOptions.tol", ">= 0"),
    (lambda: rs.Output(every=0), "Output.every", "positive integer"),
    (lambda: rs.Output(nodes=["a"]), "Output.nodes", "node numbers"),
    (lambda: rs.Output(times=[0.0, float("inf")]), "Output.times", "finite"),
    (lambda: rs.Checkpointing(every=0), "Checkpointing.every", "positive integer"),
    (lambda: rs.Checkpointing(path=5), "Checkpointing.path", "file path"),
    (lambda: rs.Excitation(forces=1.0), "Excitation.forces", "callable"),
    (lambda: rs.Excitation(unbalance=5), "Excitation.unbalance", "sequence"),
])
def test_bad_fields_are_refused_by_name(build, where, reason):
    with pytest.raises(OptionError, match=rf"^{where}: .*{reason}") as info:
        build()
    assert info.value.where == where and isinstance(info.value, ModelError)


def test_unknown_stability_method_lists_the_valid_ones():
    with pytest.raises(TypeError, match="unknown stability method 'lyapunov'; valid: auto"):
        rs.StabilityOptions("lyapunov")


def test_a_solver_excludes_the_steps():
    from rotorsim.solvers.continuation import Continuation

    with pytest.raises(OptionError, match=r"ContinuationOptions\.solver: give the solver or "
                                          r"max_step, not both"):
        rs.ContinuationOptions(max_step=0.1, solver=Continuation())


def test_shortcut_values_fill_one_field_and_errors_name_the_keyword():
    assert rs.Harmonics.coerce(6, "periodic.harmonics") == rs.Harmonics(6)
    assert rs.StabilityOptions.coerce(None, "v.stability").method is None
    assert rs.Checkpointing.coerce("a.h5", "v.checkpoint").path == "a.h5"
    assert rs.Output.coerce(None, "v.output") == rs.Output()
    with pytest.raises(ModelError, match=r"^periodic\.harmonics: must be a positive integer"):
        rs.Harmonics.coerce(0, "periodic.harmonics")
    with pytest.raises(ModelError, match=r"^v\.output: expected rs\.Output or None, got int"):
        rs.Output.coerce(3, "v.output")
    with pytest.raises(ModelError, match=r"^v\.harmonics: expected rs\.Harmonics, got Output"):
        rs.Harmonics.coerce(rs.Output(), "v.harmonics")


def test_verb_defaults_fill_only_the_fields_left_at_none():
    defaults = rs.ContinuationOptions(max_step=0.02, max_points=500)
    got = rs.ContinuationOptions(max_points=7).resolved(defaults)
    assert (got.step, got.max_step, got.max_points, got.tol) == (None, 0.02, 7, 1e-10)


def test_a_shortcut_keyword_and_its_field_cannot_both_be_given():
    both = rs.Excitation(unbalance=[(2, 1e-4, 0.0)])
    with pytest.raises(ModelError, match=r"^transient\.unbalance: given twice"):
        both.merged("transient", unbalance=[(3, 1e-4, 0.0)])
    assert both.merged("transient", unbalance=()) is both
    assert rs.Output().merged("v", nodes=[]).nodes == ()      # [] keeps no node, not all
    with pytest.raises(ModelError, match=r"^v\.nodes: expected node numbers"):
        rs.Output().merged("v", nodes=["x"])


def test_fields_a_verb_does_not_use_are_refused():
    with pytest.raises(ModelError, match=r"^periodic\.output\.every: not an option of "
                                         r"periodic"):
        rs.Output(every=2).refuse(("every",), "periodic.output", "periodic")


def test_the_package_imports_nothing_of_rotorsim_but_the_errors():
    folder = Path(rs.__file__).parent / "options"
    for path in folder.glob("*.py"):
        tree = ast.parse(path.read_text())
        runtime = [n for n in tree.body if isinstance(n, ast.ImportFrom) and n.module]
        for node in runtime:
            assert node.module.startswith(("rotorsim.errors", "rotorsim.options", "__future__",
                                           "collections", "dataclasses", "typing", "math",
                                           "numbers", "os")), f"{path.name}: {node.module}"
    assert issubclass(rs.Harmonics, OptionGroup)


def test_resolution_keeps_the_nones_that_mean_something():
    from rotorsim.solvers.continuation import Continuation

    assert rs.StabilityOptions(None).resolved(rs.StabilityOptions(tol=1e-5)).method is None
    assert rs.Output(nodes=None).resolved(rs.Output(every=1)) == rs.Output(every=1)
    expert = rs.ContinuationOptions(solver=Continuation(max_step=0.5))
    assert expert.resolved(rs.ContinuationOptions(max_step=0.02, max_points=500)) is expert


def test_periodic_verbs_resolve_their_groups_with_their_own_defaults():
    from rotorsim.analyses.periodic import parameter, periodic
    from rotorsim.analyses.periodic.arguments import periodic_options
    from rotorsim.solvers.continuation import Continuation

    keywords = dict(harmonics=4, unbalance=[(1, 1e-4, 0.0)], excitation=None,
                    continuation=None, stability=None, nodes=[1], output=None,
                    checkpoint="a.h5")
    own = periodic_options("periodic", periodic.DEFAULTS, **keywords)
    assert (own.continuation.max_step, own.continuation.max_points) == (0.05, 1000)
    assert own.checkpoint_every == 25 and own.checkpoint.path == "a.h5"
    assert own.stability.method is None and own.stability.tol == 1e-5
    assert own.output.nodes == (1,) and own.excitation.unbalance == ((1, 1e-4, 0.0),)
    other = periodic_options("periodic_parameter", parameter.DEFAULTS, **keywords)
    assert (other.continuation.max_step, other.continuation.max_points) == (0.05, 200)
    solver = Continuation(max_step=0.5)
    expert = periodic_options("periodic", periodic.DEFAULTS, **{
        **keywords, "continuation": rs.ContinuationOptions(solver=solver, tol=1e-9)})
    stepping = expert.stepping()
    assert stepping.given is solver and stepping.tol == 1e-9
    with pytest.raises(ModelError, match=r"^periodic_parameter\.harmonics\.condense: not an "
                                         r"option of periodic_parameter"):
        periodic_options("periodic_parameter", parameter.DEFAULTS, **{
            **keywords, "harmonics": rs.Harmonics(4, condense=False)})
    with pytest.raises(ModelError, match=r"^periodic\.excitation\.base: expected "
                                         r"rs\.HarmonicBase, got BaseExcitation"):
        periodic_options("periodic", periodic.DEFAULTS, **{
            **keywords, "excitation": rs.Excitation(base=rs.BaseExcitation(lambda t: 0.0))})


def test_transient_checks_its_base_and_shortcuts():
    rotor = rs.Rotor([rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=rs.Material(
        name="steel", E=211e9, G_s=81.2e9, rho=7810))] * 2,
        bearing_elements=[rs.BearingElement(n=0, kxx=1e7), rs.BearingElement(n=2, kxx=1e7)])
    with pytest.raises(ModelError, match=r"^transient\.excitation\.base: expected "
                                         r"rs\.BaseExcitation, got HarmonicBase"):
        rs.transient(rotor, 0.01, 1e-3, excitation=rs.Excitation(base=rs.HarmonicBase(1e-6)))
    with pytest.raises(ModelError, match=r"^transient\.nodes: given twice"):
        rs.transient(rotor, 0.01, 1e-3, nodes=[1], output=rs.Output(nodes=[2]))
    with pytest.raises(TypeError, match=r"^transient: 'checkpoint_every' moved to "
                                        r"checkpoint=rs\.Checkpointing\(every=\.\.\.\)$"):
        rs.transient(rotor, 0.01, 1e-3, checkpoint_every=5)
