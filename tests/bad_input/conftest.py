"""The bad-input corpus (issue 12): every case is an input that must be refused with a
one-line, named error that says what is wrong and where, never a traceback from numpy or
scipy, a hang or a silently wrong number.

- ``test_element_corpus.py``: materials, shaft elements, disks, point masses, linear bearings
  and the rotor's node bookkeeping (``ModelError`` naming element and field).
- ``test_rolling_corpus.py``: ball, roller and flexible-ring bearings and bearing statics.
- ``test_analysis_corpus.py``: arguments of the analyses (``ModelError`` naming the argument)
  and unknown keywords (``TypeError`` listing the valid ones).
- ``test_model_file_corpus.py``: model files (``ModelError.where`` is the key path).
- ``test_cli_corpus.py``: command lines (exit code 2, one line on stderr).

Shared checks and small models are in ``corpus_checks.py``, made importable here.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))
