"""Parameter sweeps: one model evaluated over a grid or a random sample of parameters.

- ``sweep``: the ``rs.sweep`` verb (serial, process pool or dask; resumable store).
- ``functions``: ready-made, picklable model changes and evaluations.

May import every other analysis family, the model layers, ``results`` and the sweep store
of ``rotorsim.io``.
"""
