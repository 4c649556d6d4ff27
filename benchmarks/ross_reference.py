"""Recompute the ROSS reference numbers of ``tests/validation/reference_ross.py``.

ROSS (Rotordynamic Open Source Software, https://github.com/petrobras/ross) is an
independent code. It is never imported by rotorsim or by its tests: this script runs
offline, in a separate virtual environment that has ROSS, and writes the numbers into a
plain Python module that the validation tests read.

Setup (ROSS 3.1.0 needs Python >= 3.13; older interpreters only get ROSS 2.3.0)::

    bash benchmarks/setup_ross_env.sh        # -> .venv-ross, or by hand:
    python3.13 -m venv /tmp/rossenv313
    /tmp/rossenv313/bin/pip install "ross-rotordynamics==3.1.0"

Run from the repository root::

    .venv-ross/bin/python benchmarks/ross_reference.py \
        --write tests/validation/reference_ross.py

Without ``--write`` the module text is printed. The models are the rotorsim rotors of
``examples/textbook_rotors.py`` translated element by element (length, diameters at both
ends, material constants, disk mass and inertias, bearing coefficients), so ROSS and
rotorsim solve the identical model. ROSS options: ``shear_method_calc="cowper"``,
``run_modal(speed, num_modes=..., sparse=False)`` (dense eigen-solution, rigid-body
modes removed by ROSS); only modes that ROSS classifies as ``Lateral`` are kept (its 6-DOF
elements also give axial and torsional modes).
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import math
import os
import pprint
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

RPM = math.pi / 30.0
N_LATERAL = 10  # lateral modes stored per case and speed

CASES = {
    # name: (builder name in examples.textbook_rotors, kwargs, speeds [rpm])
    "friswell_5_9_1": ("friswell_5_9_1", {}, (0.0, 4000.0)),
    "friswell_5_9_2": ("friswell_5_9_2", {}, (0.0, 4000.0)),
    "friswell_5_9_5": ("friswell_5_9_5", {}, (0.0, 4000.0)),
    "friswell_5_9_9": ("friswell_5_9_9", {}, (0.0, 4000.0)),
    "tapered_8": ("tapered_rotor", {"n_elements": 8}, (0.0, 4000.0)),
    "tapered_8_eb": ("tapered_rotor", {"n_elements": 8, "shear_effects": False},
                     (0.0, 4000.0)),
    "tapered_64": ("tapered_rotor", {"n_elements": 64}, (0.0, 4000.0)),
}


def to_ross(rotor):
    """Translate a rotorsim Rotor into a ROSS Rotor, element by element."""
    import ross as rs

    materials = {}

    def material(m):
        key = (m.E, m.G_s, m.rho)
        if key not in materials:
            materials[key] = rs.Material(name=f"mat{len(materials)}", rho=m.rho, E=m.E,
                                         G_s=m.G_s)
        return materials[key]

    shaft = []
    for el in rotor.shaft_elements:
        if el.shear_coefficient is not None or el.axial_force or el.alpha or el.beta:
            raise ValueError(f"{el.label}: option without a ROSS counterpart here")
        shaft.append(rs.ShaftElement(
            L=el.L, idl=el.idl, odl=el.odl, idr=el.idr, odr=el.odr, n=el.n,
            material=material(el.material), shear_effects=el.shear_effects,
            rotary_inertia=el.rotary_inertia, gyroscopic=el.gyroscopic,
            shear_method_calc="cowper",
        ))
    disks = [rs.DiskElement(n=d.n, m=d.m, Id=d.Id, Ip=d.Ip) for d in rotor.disk_elements]
    bearings = []
    for b in rotor.bearing_elements:
        if b.speed_dependent or b.n_link is not None:
            raise ValueError(f"{b.label}: only constant bearings to ground are translated")
        c = {k: float(b.coefficient(k, 0.0)) for k in
             ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx", "kzz", "czz", "krr")}
        if c.pop("krr"):
            raise ValueError(f"{b.label}: ROSS BearingElement has no tilting stiffness")
        bearings.append(rs.BearingElement(n=b.n, **c))
    return rs.Rotor(shaft_elements=shaft, disk_elements=disks, bearing_elements=bearings)


def lateral_modes(ross_rotor, speed: float) -> dict[str, list]:
    """First ``N_LATERAL`` lateral modes of ROSS at ``speed`` [rad/s], ROSS order (by wd)."""
    modal = ross_rotor.run_modal(speed, num_modes=8 * N_LATERAL, sparse=False)
    keep = [j for j, s in enumerate(modal.shapes) if s.mode_type == "Lateral"][:N_LATERAL]
    whirl = modal.whirl_direction()
    return {
        "eigenvalues": [complex(modal.evalues[j]) for j in keep],
        "wd": [float(modal.wd[j]) for j in keep],
        "log_dec": [float(modal.log_dec[j]) for j in keep],
        "whirl": [str(whirl[j]).lower() for j in keep],
    }


@contextlib.contextmanager
def _stdout_to_stderr():
    """Send file descriptor 1 to stderr (C libraries write there directly)."""
    sys.stdout.flush()
    saved = os.dup(1)
    os.dup2(2, 1)
    try:
        yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)


def compute() -> dict[str, dict[float, dict[str, list]]]:
    import examples.textbook_rotors as textbook

    with _stdout_to_stderr():  # ROSS's CoolProp prints a REFPROP notice on import
        import ross  # noqa: F401

    out: dict[str, dict[float, dict[str, list]]] = {}
    for name, (builder, kwargs, speeds) in CASES.items():
        ross_rotor = to_ross(getattr(textbook, builder)(**kwargs))
        out[name] = {rpm: lateral_modes(ross_rotor, rpm * RPM) for rpm in speeds}
        print(f"{name}: done", file=sys.stderr)
    return out


def module_text(data) -> str:
    import numpy
    import ross
    import scipy

    models = "\n".join(
        f"- ``{name}``: ``{builder}({', '.join(f'{k}={v!r}' for k, v in kwargs.items())})`` at "
        f"{', '.join(f'{rpm:g}' for rpm in speeds)} rpm"
        for name, (builder, kwargs, speeds) in CASES.items()
    )
    header = f'''"""ROSS reference numbers for the validation tests (generated: do not edit).

Produced by ``benchmarks/ross_reference.py`` with ROSS {ross.__version__} (numpy
{numpy.__version__}, scipy {scipy.__version__}, Python {sys.version.split()[0]}) on
{datetime.date.today().isoformat()}. Models: the rotors of ``examples/textbook_rotors.py``
translated element by element into ROSS (``shear_method_calc="cowper"``,
``run_modal(speed, sparse=False)``), lateral modes only, in ROSS order (increasing
damped frequency). Rerun the script in an environment with ROSS to regenerate.

``ROSS[case][speed_rpm]`` holds ``eigenvalues`` (complex, rad/s), ``wd`` (rad/s),
``log_dec`` and ``whirl`` of the first {N_LATERAL} lateral modes. Cases (builders of
``examples.textbook_rotors``):

{models}
"""

ROSS_VERSION = "{ross.__version__}"
GENERATED_ON = "{datetime.date.today().isoformat()}"

'''
    return header + "ROSS = " + pprint.pformat(data, width=96, sort_dicts=False) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", type=Path, help="write the module to this path")
    args = parser.parse_args()
    text = module_text(compute())
    if args.write:
        args.write.write_text(text)
        print(f"wrote {args.write}", file=sys.stderr)
    else:
        print(text)


if __name__ == "__main__":
    main()
