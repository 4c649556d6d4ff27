"""Materials, shaft lines (``lines``: machines of several shafts), system damping
(``damping``) and the rotor model (``rotor``)."""
