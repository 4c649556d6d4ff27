"""Regression of the rigid-ring rolling-bearing path against outputs saved before the
small-batch optimisation (issue target: 100,000 transient steps of a rotor on two ball
bearings in < 60 s).

The fast paths of ``BallBearing.state``, ``RollerBearing.state``, ``RollingBearing.force``
and ``NonlinearAssembly.evaluate`` (no repeated validation in internal calls, cached
constant arrays, fused sums) must not change any result. ``data/small_batch_reference.npz``
holds random inputs and the outputs of the code *before* that change (the rolling-element
and assembly modules of git 85942ea), for ball and roller bearings (tilt-integral and
slices), with and without clearance, all contact-damping models, centrifugal and mirrored
variants, ground and 2-node elements, overlapping and partly fixed element DOFs in the
assembly, and ``S = 1, 2, 7, 1024`` samples. Every output must agree to round-off: the
largest difference relative to the largest entry of each array is at most ``1e-14``
(about 45 units of double-precision round-off; the saved values are the code's own
earlier output, so this is a regression check, not a validation). The bound is tight on
purpose: with proportional damping the tangent gains a central difference of the tangent
(step 1e-9 m), which amplifies any change of its round-off by ``beta |v| / 2h``, so the
tangents keep their order of operations. The test velocities keep that factor below ~12:
summing the 12 balls in reverse order then changes the outputs by ~2e-15 (by 9e-15 at
five times the velocities), room for another BLAS kernel on another CPU.

The reference was written by :func:`write_reference` with the original code::

    .venv/bin/python tests/elements/rolling/test_small_batch_regression.py --write

Rewrite it only for an intended change of the physics, and say so in the commit.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.lubrication import Lubricant
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import CircularCrown
from rotorsim.elements.shaft import ShaftElement
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

REFERENCE = Path(__file__).parent / "data" / "small_batch_reference.npz"
RTOL = 1e-14  # module docstring
SAMPLES = (1, 2, 7, 1024)
FULL_UP_TO = 7  # larger batches: element outputs as 5x5 blocks, every STRIDE-th sample
STRIDE = 16

_OIL = Lubricant(eta0=0.04, alpha=2.0e-8)
BEARINGS: dict[str, Any] = {
    "ball_radial_clear": BallBearing(n_balls=12, pitch_diameter=0.0585, ball_diameter=0.0119,
                                     Kn=1.2e10, diametral_clearance=10e-6, f_i=0.52,
                                     f_o=0.52),
    "ball_angular": BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3,
                                              ball_diameter=9.525e-3, f_i=0.515, f_o=0.525,
                                              contact_angle=math.radians(25.0),
                                              diametral_clearance=10e-6),
    "ball_preload_linear": BallBearing(n_balls=8, pitch_diameter=0.04, ball_diameter=0.008,
                                       Kn=8e9, A0=0.3e-3, radial_clearance=-2e-6,
                                       exponent=1.0, cage="fixed", psi0=0.1),
    "ball_exp13": BallBearing(n_balls=10, pitch_diameter=0.05, ball_diameter=0.009, Kn=9e9,
                              A0=0.35e-3, exponent=1.3, groove_center_radius=0.0252,
                              contact_angle=0.2),
    "roller_tilt_clear": RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8,
                                       radial_clearance=1.75e-6),
    "roller_tilt_tapered": RollerBearing(16, 50e-3, 8e-3, 12e-3, contact_angle=0.25),
    "roller_tilt_linear": RollerBearing(12, 40e-3, 7e-3, 9e-3, Kn=2e8, exponent=1.0,
                                        radial_clearance=-1e-6, cage="fixed", psi0=0.2),
    "roller_slices_tapered": RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8,
                                           model="slices", contact_angle=math.radians(15.0),
                                           n_slices=9),
    "roller_slices_crown": RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8,
                                         model="slices", n_slices=20,
                                         profile=CircularCrown(crown_drop=3e-6),
                                         diametral_clearance=4e-6),
}
# element: (bearing key or wrapped model, n_link, contact damping, damping factor)
ELEMENTS: dict[str, tuple[Any, int | None, str, float]] = {
    "ball_ground_prop": (BEARINGS["ball_radial_clear"], None, "proportional", 2e-5),
    "ball_link_prop": (BEARINGS["ball_radial_clear"], 7, "proportional", 2e-5),
    "ball_link_none": (BEARINGS["ball_angular"], 7, "none", 0.0),
    "ball_ground_ehl": (BEARINGS["ball_angular"], None, "ehl", 0.0),
    "ball_link_preload": (BEARINGS["ball_preload_linear"], 3, "proportional", 1e-5),
    "roller_link_prop": (BEARINGS["roller_tilt_clear"], 7, "proportional", 2e-5),
    "roller_ground_tapered": (BEARINGS["roller_tilt_tapered"], None, "proportional", 1e-5),
    "roller_ground_slices": (BEARINGS["roller_slices_tapered"], None, "none", 0.0),
    "roller_link_crown_ehl": (BEARINGS["roller_slices_crown"], 7, "ehl", 0.0),
    "roller_ground_tilt_ehl": (BEARINGS["roller_tilt_clear"], None, "ehl", 0.0),
    "ball_centrifugal": (CentrifugalBearing(BEARINGS["ball_radial_clear"],
                                            element_density=7850.0), None, "proportional",
                         2e-5),
    "roller_centrifugal": (CentrifugalBearing(BEARINGS["roller_tilt_clear"],
                                              element_density=7850.0), 7, "none", 0.0),
    "ball_reversed": (ReversedBearing(BEARINGS["ball_angular"]), 7, "proportional", 2e-5),
    "ball_centrifugal_reversed": (CentrifugalBearing(ReversedBearing(BEARINGS["ball_angular"]),
                                                     element_density=7850.0), None, "none",
                                  0.0),
}
LARGE_ELEMENTS = ("ball_ground_prop", "ball_link_prop", "ball_ground_ehl", "roller_link_prop",
                  "roller_ground_slices", "roller_link_crown_ehl", "ball_centrifugal",
                  "roller_centrifugal")  # also checked at S = 1024 (keeps the file small)
# velocities [per s] of a displacement SIZE: beta |v| / 2h stays below ~12, so that a
# reordered sum in the tangent (a few units of round-off) stays well inside RTOL
RATE = 10.0
SIZE = np.array([12e-6, 12e-6, 12e-6, 5e-4, 5e-4, 1.0])  # m, rad per node DOF (rz unused)


def _element(key: str) -> RollingBearing:
    model, link, damping, beta = ELEMENTS[key]
    return RollingBearing(model, n=2, n_link=link, tag=key, contact_damping=damping,
                          damping_factor=beta, lubricant=_OIL if damping == "ehl" else None)


def _displacements(rng: np.random.Generator, n_samples: int, n: int) -> np.ndarray:
    u = rng.normal(size=(n_samples, n)) * np.tile(SIZE, n // 6)
    u[:, 2] += 8e-6  # towards the rings of angular-contact and tapered bearings
    u[:, 1] -= 6e-6
    return u


# ------------------------------------------------------------------------ the cases
def _state_case(key: str, n_samples: int, rng: np.random.Generator
                ) -> tuple[dict[str, np.ndarray], Callable[..., dict[str, np.ndarray]]]:
    b = BEARINGS[key]
    delta = _displacements(rng, n_samples, 6)[:, :5]
    phi = rng.uniform(0.0, 2.0 * math.pi, n_samples)
    inputs = {"delta": delta, "phi": phi}

    def run(delta: np.ndarray, phi: np.ndarray) -> dict[str, np.ndarray]:
        psi = b.element_angles(phi)
        st = b.state(delta, psi)
        out = {name: np.asarray(getattr(st, name)) for name in
               ("force", "stiffness", "energy", "element_load", "contact_angle", "deflection",
                "contact_direction", "element_stiffness")}
        out["psi"] = psi
        out["energy_call"] = b.energy(delta, psi)
        # one shared row of angles for every sample, and a single sample as 1-D arrays
        out["shared_psi_force"] = b.state(delta, psi[0]).force
        out["one_d_stiffness"] = b.state(delta[0], psi[0]).stiffness
        if isinstance(b, RollerBearing):
            loads = b.roller_loads(delta, psi)
            out["roller_load"], out["eccentricity"] = loads.load, loads.eccentricity
            out["slice_deflections"] = b.slice_deflections(delta, psi)
        return out

    return inputs, run


def _element_case(key: str, n_samples: int, rng: np.random.Generator
                  ) -> tuple[dict[str, np.ndarray], Callable[..., dict[str, np.ndarray]]]:
    element = _element(key)
    n = element.n_dofs
    u = _displacements(rng, n_samples, n)
    v = rng.normal(size=(n_samples, n)) * np.tile(SIZE, n // 6) * RATE  # ~0.1 mm/s
    if n_samples > 1:
        v[1] = 0.0  # a sample at rest within a moving batch
    phi = rng.uniform(0.0, 2.0 * math.pi, n_samples)
    speed = rng.uniform(200.0, 900.0, n_samples)
    inputs = {"u": u, "v": v, "phi": phi, "speed": speed}
    block = n_samples > FULL_UP_TO

    def run(u: np.ndarray, v: np.ndarray, phi: np.ndarray, speed: np.ndarray
            ) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        first = element.force(u, v, phi, speed)
        still = element.force(u, np.zeros_like(v), phi[0], float(speed[0]))
        for tag, res in (("", first), ("rest_", still)):
            out[tag + "f"] = res.f[:, :5] if block else res.f
            out[tag + "K"] = res.K[:, :5, :5] if block else res.K
            out[tag + "C"] = res.C[:, :5, :5] if block else res.C
        if first.internal is not None:  # warm start from the previous solution
            again = element.force(u * 1.001, v, phi, speed, first.internal)
            out["internal"] = np.asarray(first.internal)
            out["warm_f"] = again.f[:, :5]
            out["warm_K"] = again.K[:, :5, :5]
        return out

    return inputs, run


def _linearize_case(key: str, n_samples: int, rng: np.random.Generator
                    ) -> tuple[dict[str, np.ndarray], Callable[..., dict[str, np.ndarray]]]:
    element = _element(key)
    inputs = {"d": _displacements(rng, 1, 6)[0, :5]}

    def run(d: np.ndarray) -> dict[str, np.ndarray]:
        lin = element.linearize(displacement=d, phi=0.3, speed=500.0)
        out = {"K": np.asarray(lin.stiffness_matrix)}
        if lin.damping_matrix is not None:
            out["C"] = np.asarray(lin.damping_matrix)
        return out

    return inputs, run


def _rotor_systems() -> dict[str, Any]:
    steel = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [ShaftElement(L=0.04, idl=0.0, odl=0.04, material=steel) for _ in range(20)]
    disks = [DiskElement.from_geometry(n=n, material=steel, width=0.03, i_d=0.04, o_d=0.18)
             for n in (7, 14)]
    ball = BEARINGS["ball_radial_clear"]
    pair = [RollingBearing(ball, n=n, tag=t, contact_damping="proportional",
                           damping_factor=2e-5) for n, t in ((0, "A"), (20, "B"))]
    housing = 21
    rotor2 = Rotor(shaft, disks, [BearingElement(n=housing, kxx=5e8, kzz=5e8, krr=1e6)],
                   [PointMass(n=housing, m=2.0)], fixed=[(housing, "rz")])
    mixed = [RollingBearing(ball, n=0, n_link=housing, tag="A", contact_damping="proportional",
                            damping_factor=2e-5),
             RollingBearing(BEARINGS["roller_tilt_clear"], n=20, tag="B",
                            contact_damping="proportional", damping_factor=1e-5),
             RollingBearing(ball, n=10, tag="C")]
    # two equal bearings on one housing (a group whose DOFs overlap: summed scatter) on a
    # shaft whose axial DOF is fixed at node 0 (an element DOF removed)
    rotor3 = Rotor(shaft, disks, [BearingElement(n=housing, kxx=5e8, kzz=5e8, krr=1e6)],
                   [PointMass(n=housing, m=2.0)], fixed=[(housing, "rz"), (0, "uz")])
    shared = [RollingBearing(BEARINGS["ball_angular"], n=n, n_link=housing, tag=t,
                             contact_damping="proportional", damping_factor=1e-5)
              for n, t in ((0, "A"), (20, "B"))]
    return {"pair": assemble(Rotor(shaft, disks), pair), "mixed": assemble(rotor2, mixed),
            "shared": assemble(rotor3, shared)}


_SYSTEMS: dict[str, Any] = {}


def _assembly_case(key: str, n_samples: int, rng: np.random.Generator
                   ) -> tuple[dict[str, np.ndarray], Callable[..., dict[str, np.ndarray]]]:
    if not _SYSTEMS:
        _SYSTEMS.update(_rotor_systems())
    nl = _SYSTEMS[key].nonlinear
    q = rng.normal(size=(n_samples, nl.k)) * 8e-6
    q[:, 1::3] -= 6e-6
    v = rng.normal(size=(n_samples, nl.k)) * 2e-4  # beta |v| / 2h < ~10
    inputs = {"q": q, "v": v, "phi": rng.uniform(0.0, 6.0, n_samples),
              "speed": rng.uniform(200.0, 900.0, n_samples)}

    def run(q: np.ndarray, v: np.ndarray, phi: np.ndarray, speed: np.ndarray
            ) -> dict[str, np.ndarray]:
        res = nl.evaluate(q, v, phi, speed)
        one = nl.evaluate(q[0], v[0], float(phi[0]), float(speed[0]))
        return {"f": res.f, "K": res.K, "C": res.C,
                "element_forces": np.concatenate(res.element_forces, axis=1),
                "one_f": one.f, "one_K": one.K, "one_C": one.C}

    return inputs, run


def _cases() -> dict[str, tuple[Callable[..., Any], str, int]]:
    cases: dict[str, tuple[Callable[..., Any], str, int]] = {}
    for n_samples in SAMPLES:
        for key in BEARINGS:
            cases[f"state/{key}/{n_samples}"] = (_state_case, key, n_samples)
        for key in ELEMENTS if n_samples <= FULL_UP_TO else LARGE_ELEMENTS:
            cases[f"element/{key}/{n_samples}"] = (_element_case, key, n_samples)
        if n_samples <= FULL_UP_TO:
            for key in ("pair", "mixed", "shared"):
                cases[f"assembly/{key}/{n_samples}"] = (_assembly_case, key, n_samples)
    for key in ("ball_ground_prop", "ball_ground_ehl", "roller_link_prop",
                "roller_link_crown_ehl", "ball_centrifugal"):
        cases[f"linearize/{key}/1"] = (_linearize_case, key, 1)
    return cases


CASES = _cases()


def _build(name: str) -> tuple[dict[str, np.ndarray], Callable[..., dict[str, np.ndarray]]]:
    maker, key, n_samples = CASES[name]
    seed = sum(ord(ch) * (i + 1) for i, ch in enumerate(name))  # stable, distinct per case
    return maker(key, n_samples, np.random.default_rng(seed))


def _kept(name: str, outputs: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The outputs that are saved: of large batches every ``STRIDE``-th sample (all of
    them are computed together, so the batched path is still the one checked)."""
    n_samples = CASES[name][2]
    if n_samples <= FULL_UP_TO:
        return {k: np.asarray(x) for k, x in outputs.items()}
    return {k: np.asarray(x)[::STRIDE] if np.ndim(x) and np.shape(x)[0] == n_samples
            else np.asarray(x) for k, x in outputs.items()}


def write_reference(path: Path = REFERENCE) -> None:
    """Compute every case with the current code and save inputs and outputs."""
    arrays: dict[str, np.ndarray] = {}
    for name in CASES:
        inputs, run = _build(name)
        for k, x in inputs.items():
            arrays[f"{name}/in/{k}"] = x
        for k, x in _kept(name, run(**inputs)).items():
            arrays[f"{name}/out/{k}"] = x
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, **arrays)


# ------------------------------------------------------------------------ the tests
@pytest.fixture(scope="module")
def reference() -> dict[str, np.ndarray]:
    with np.load(REFERENCE) as data:
        return {k: data[k] for k in data.files}


def _relative_error(got: np.ndarray, want: np.ndarray) -> float:
    scale = float(np.abs(want).max()) if want.size else 0.0
    diff = float(np.abs(got - want).max()) if want.size else 0.0
    return diff / scale if scale > 0.0 else diff


@pytest.mark.parametrize("name", list(CASES))
def test_outputs_match_the_saved_reference(name: str, reference: dict[str, np.ndarray]):
    _, run = _build(name)  # the models; the inputs come from the file
    prefix = f"{name}/in/"
    inputs = {k[len(prefix):]: x for k, x in reference.items() if k.startswith(prefix)}
    assert inputs, f"no saved inputs for {name}"
    got = _kept(name, run(**inputs))
    prefix = f"{name}/out/"
    want = {k[len(prefix):]: x for k, x in reference.items() if k.startswith(prefix)}
    assert sorted(got) == sorted(want)
    for key, x in want.items():
        y = np.asarray(got[key])
        assert y.shape == x.shape, (key, y.shape, x.shape)
        assert np.array_equal(np.isnan(y), np.isnan(x)), key
        ok = ~np.isnan(x)
        assert _relative_error(y[ok], x[ok]) <= RTOL, (key, _relative_error(y[ok], x[ok]))


@pytest.mark.parametrize("key", ["ball_link_prop", "roller_link_crown_ehl"])
def test_two_node_blocks_of_large_batches(key: str):
    """Large batches are stored as 5x5 blocks: the rest is the +-delta expansion."""
    element = _element(key)
    u = _displacements(np.random.default_rng(5), 1024, 12)
    out = element.force(u, 1e-3 * u, 0.4, 500.0)
    for mat in (out.K, out.C):
        k5 = mat[:, :5, :5]
        want = np.zeros_like(mat)
        want[:, :5, :5] = want[:, 6:11, 6:11] = k5
        want[:, :5, 6:11] = want[:, 6:11, :5] = -k5
        assert np.array_equal(mat, want)
    assert np.array_equal(out.f[:, 6:11], -out.f[:, :5]) and not np.any(out.f[:, 5::6])


if __name__ == "__main__":
    if sys.argv[1:] == ["--write"]:
        write_reference()
        print(f"wrote {REFERENCE}")
    else:
        print(__doc__)
