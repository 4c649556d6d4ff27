"""The rigid-ring roller bearing (cylindrical and tapered, whole roller or sliced):
``bearing`` (``RollerBearing``), ``profile`` (straight, crowned, logarithmic), ``checks``
(input checks), ``line_load`` (the line load along the rollers, tilt integral or slices),
``integrals`` (its assembly into force and tangent) and ``centrifugal`` (roller state under
centrifugal loads).

May import: ``rolling.contact`` and the shared ``rolling`` modules.
"""
