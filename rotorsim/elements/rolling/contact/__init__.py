"""Contact laws of one rolling element: Hertz point contacts (``hertz_point``), line contacts
with slicing and crowning (``hertz_line``), and the EHL film of one contact (``ehl_contact``).

May import: numpy, scipy, ``rotorsim.errors``. Nothing else of ``rotorsim.elements.rolling``.
"""
