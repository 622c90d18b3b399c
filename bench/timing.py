"""The one timing helper every bench file uses: the median of repeated single calls (timeit)."""

from __future__ import annotations

import statistics
import timeit


def median_seconds(fn, runs: int = 50) -> float:
    """Median wall time of one call of fn, after one warm-up call (caches, lazy imports)."""
    fn()
    return statistics.median(timeit.repeat(fn, number=1, repeat=runs))
