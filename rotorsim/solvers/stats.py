"""Cost counters carried by every result (DESIGN section 6)."""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field


@dataclass
class Stats:
    """Mutable counters filled while an analysis runs; frozen into a dict in the result."""

    factorizations: int = 0
    solves: int = 0
    eigen_solves: int = 0
    iterations: int = 0
    residual_evaluations: int = 0
    rejected_steps: int = 0
    wall_time: float = 0.0
    _t0: float = field(default_factory=time.perf_counter, repr=False)

    def finish(self) -> dict[str, float]:
        """Stop the clock and return the counters as a plain dict."""
        self.wall_time = time.perf_counter() - self._t0
        out = asdict(self)
        out.pop("_t0")
        return out
