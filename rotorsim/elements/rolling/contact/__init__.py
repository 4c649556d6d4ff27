"""Contact laws of one rolling element: Hertz point contacts (``hertz_point``), line-contact
constants (``hertz_line``), the line load integrated along a roller, tilted or sliced
(``line_integrals``), and the EHL film of one contact (``ehl_contact``).

May import: numpy, scipy, ``rotorsim.errors``. Nothing else of ``rotorsim.elements.rolling``.
"""
