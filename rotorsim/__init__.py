"""rotorsim: rotordynamics with finite elements and nonlinear rolling-element bearings.

The workflow is model -> assemble -> analyse -> save/plot::

    import rotorsim as rs

    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [rs.DiskElement.from_geometry(2, steel, width=0.07, i_d=0.05, o_d=0.28)]
    bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=6, kxx=1e6)]
    rotor = rs.Rotor(shaft, disks, bearings)

    modes = rs.modal(rotor, speed=0.0, num_modes=8)       # ModalResult
    system = rs.assemble(rotor)                           # sparse M, C, G, K + DofMap
    run = rs.transient(rotor, 0.5, 1e-4, speed=rs.LinearSpeed(0, 300, 0, 0.5),
                       unbalance=[(2, 1e-4, 0.0)])        # TransientResult (run-up)
    branch = rs.periodic(rotor, start=100, stop=500,
                         unbalance=[(2, 1e-4, 0.0)])      # PeriodicResult (HB branch)

The wide verbs group their options by concern (``rs.Excitation``, ``rs.Harmonics``,
``rs.ContinuationOptions``, ``rs.StabilityOptions``, ``rs.Output``, ``rs.Checkpointing``;
:mod:`rotorsim.options`), e.g. ``rs.transient(rotor, 0.5, 1e-4, excitation=rs.Excitation(
gravity=None), output=rs.Output(every=10))``.

Rolling bearings (``rs.RollingBearing``) go into the rotor beside the linear bearings; the
transient and static analyses use them as they are, the linear analyses after
``rs.linearize_rolling_bearings(rotor)`` at the static load.

All quantities are SI (m, kg, s, N, rad, rad/s).

The public names are listed once, in ``rotorsim/__init__.pyi``, and each is imported on its
first use (:func:`lazy_loader.attach_stub`): ``import rotorsim`` costs almost nothing, and a
script pays only for the parts it uses (``benchmarks/import_time.py``). Set
``EAGER_IMPORT=1`` to import everything at once (the tests do so once, to catch a broken
name).
"""

import lazy_loader

__version__ = "0.1.0"

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
