"""Input and output: model files (TOML schema, builders, writer), analysis specifications
and their runner, results files (HDF5, tagged JSON), the sweep store, checkpoint paths and
VTK export.

Sits downstream of the analyses: it may import every layer but ``cli`` and ``plotting``.
Optional dependencies (``h5py``, ``meshio``) are imported inside the functions that use them.
"""
