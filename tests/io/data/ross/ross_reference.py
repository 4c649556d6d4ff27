"""Write the ROSS rotor files of this folder and print ROSS's modes of them.

Run with a Python that has ROSS installed (not part of rotorsim's test suite):
``python tests/io/data/ross/ross_reference.py`` in this folder's parent ``tests/io``'s
``data/ross``. It saves ROSS's example rotors (``rotor_example``, ``rotor_example_6dof``,
``rotor_example_with_damping``, ``compressor_example``) and a rotor on pedestals
(``pedestal_example``: bearings linked to point masses, a bearing tabulated over speed),
then prints the damped natural frequencies and log decrements ROSS computes
(``Rotor.run_modal``), and those of the compressor with its mass-only sleeves lumped on
their nodes as rotorsim's importer lumps them. tests/io/test_ross_import.py records the
numbers printed by ROSS 3.1.0. ROSS is imported inside the functions, so that pytest's
doctest collection can import this file without it.
"""

import warnings

import numpy as np


def pedestal_example():
    import ross as rs
    from ross.materials import steel

    shaft = [rs.ShaftElement(0.2, 0.0, 0.06, material=steel) for _ in range(5)]
    disk = rs.DiskElement.from_geometry(n=3, material=steel, width=0.05, i_d=0.06, o_d=0.3)
    b0 = rs.BearingElement(n=0, n_link=6, kxx=2e7, kyy=3e7, cxx=500.0, tag="B0")
    b1 = rs.BearingElement(n=5, n_link=7, kxx=[1e7, 2e7, 4e7], kyy=[1.5e7, 2.5e7, 4.5e7],
                           kxy=[1e5, 2e5, 3e5], kyx=[-1e5, -2e5, -3e5],
                           cxx=[300.0, 400.0, 500.0], speed=[0.0, 300.0, 600.0], tag="B1")
    p0 = rs.PointMass(n=6, m=10.0, tag="P0")
    p1 = rs.PointMass(n=7, m=12.0, tag="P1")
    s0 = rs.BearingElement(n=6, kxx=5e7, kyy=8e7, cxx=1e3, tag="S0")
    s1 = rs.BearingElement(n=7, kxx=5e7, kyy=8e7, cxx=1e3, tag="S1")
    return rs.Rotor(shaft, [disk], [b0, b1, s0, s1], [p0, p1])


def lumped(rotor):
    """The rotor with each mass-only sleeve (material shaft_mat_2) lumped on its nodes."""
    import ross as rs

    core, disks = [], list(rotor.disk_elements)
    for el in rotor.shaft_elements:
        if el.material.name != "shaft_mat_2":
            core.append(el)
            continue
        half = 0.5 * el.m
        ro, ri = 0.25 * (el.odl + el.odr), 0.25 * (el.idl + el.idr)
        ip = 0.5 * half * (ro**2 + ri**2)
        i_d = half * ((ro**2 + ri**2) / 4 + (0.5 * el.L) ** 2 / 3)
        disks += [rs.DiskElement(n=n, m=half, Id=i_d, Ip=ip, tag=f"lump_{el.tag}_{n}")
                  for n in (el.n, el.n + 1)]
    return rs.Rotor(core, disks, rotor.bearing_elements, rotor.point_mass_elements)


def show(name, rotor, speeds):
    for speed in speeds:
        m = rotor.run_modal(speed, num_modes=24)
        for key, values in (("wd", m.wd), ("ld", m.log_dec)):
            print(name, speed, key, np.array2string(values, precision=9, separator=",",
                                                    max_line_width=400))


def main():
    import ross as rs

    warnings.filterwarnings("ignore")
    print("ROSS", rs.__version__)
    rotors = {"rotor_example": rs.rotor_example(), "rotor_example_6dof": rs.rotor_example_6dof(),
              "rotor_example_with_damping": rs.rotor_example_with_damping(),
              "compressor_example": rs.compressor_example(),
              "pedestal_example": pedestal_example()}
    for name, rotor in rotors.items():
        rotor.save(f"{name}.toml")
        show(name, rs.Rotor.load(f"{name}.toml"),
             (628.3185307179587, 900.0, 1250.0) if name == "compressor_example" else (500.0,))
    show("compressor_lumped", lumped(rotors["compressor_example"]),
         (628.3185307179587, 900.0, 1250.0))


if __name__ == "__main__":
    main()
