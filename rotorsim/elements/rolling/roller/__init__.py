"""The rigid-ring roller bearing (cylindrical and tapered, whole roller or sliced):
``bearing`` (``RollerBearing``), ``profile`` (straight, crowned, logarithmic), ``checks``
(input checks), ``integrals`` (slice sums) and ``centrifugal`` (roller state under
centrifugal loads).

May import: ``rolling.contact`` and the shared ``rolling`` modules.
"""
