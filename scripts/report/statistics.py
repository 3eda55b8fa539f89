"""Averages, ratios and their 95% intervals by a bootstrap over repeats (independent simulations).

The unit of independence is the repeat, not the frame: frames of one simulation follow each other and
are correlated, the repeats (seed + k) are not. So a cell's average is the mean over repeats of each
repeat's mean over its frames, and its interval comes from resampling whole repeats with replacement.
A ratio between two strategies resamples the same repeats for numerator and denominator: repeat k of
either is the same simulation (same seed), so the pairing keeps what the two share out of the spread.

Resampling is seeded per repeat count, so the same data give the same intervals on every run and in
any order of cells; every cell with n repeats draws the same n-index resamples.
"""

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

RESAMPLES = 2000
SEED = 20240612
LEVEL = 0.95


@dataclass(frozen=True)
class Estimate:
    """A point value with its 95% bootstrap interval (lo, hi), or without one (`why` says why)."""
    value: float
    lo: float = None
    hi: float = None
    repeats: int = 0
    why: str = ""

    @property
    def has_interval(self):
        return self.lo is not None and self.hi is not None

    def position(self, x):
        """Where x lies against the interval: 'inside', 'above' or 'below'; None without an interval."""
        if not self.has_interval or x is None:
            return None
        return "above" if x > self.hi else "below" if x < self.lo else "inside"

    def overlaps(self, other):
        """False only when both have intervals and they are disjoint."""
        if not (self.has_interval and other.has_interval):
            return True
        return not (self.hi < other.lo or other.hi < self.lo)


def no_interval_reason(repeats):
    return f"no interval ({repeats} repeat{'s' if repeats != 1 else ''})" if repeats < 2 else ""


@lru_cache(maxsize=None)
def resample_indices(n):
    """RESAMPLES rows of n repeat indices drawn with replacement, the same for every call with this n."""
    rng = np.random.default_rng([SEED, n])
    return rng.integers(0, n, size=(RESAMPLES, n))


def _percentiles(samples):
    tail = (1 - LEVEL) / 2 * 100
    samples = samples[np.isfinite(samples)]
    if samples.size == 0:
        return None, None
    lo, hi = np.percentile(samples, [tail, 100 - tail])
    return float(lo), float(hi)


def mean_estimate(repeat_means):
    """Mean over repeats of per-repeat means, with its bootstrap interval over repeats."""
    values = np.asarray(repeat_means, dtype=float)
    n = values.size
    value = float(values.mean())
    if n < 2:
        return Estimate(value, repeats=n, why=no_interval_reason(n))
    lo, hi = _percentiles(values[resample_indices(n)].mean(axis=1))
    return Estimate(value, lo, hi, n)


def ratio_estimate(numerator, denominator):
    """mean(numerator) / mean(denominator) of paired per-repeat means (index k = repeat k of both),
    with the interval from resampling the same repeats for both; None when the denominator is 0."""
    top, bottom = np.asarray(numerator, dtype=float), np.asarray(denominator, dtype=float)
    if top.shape != bottom.shape or bottom.size == 0 or bottom.mean() <= 0:
        return None
    n = top.size
    value = float(top.mean() / bottom.mean())
    if n < 2:
        return Estimate(value, repeats=n, why=no_interval_reason(n))
    idx = resample_indices(n)
    with np.errstate(divide="ignore", invalid="ignore"):
        lo, hi = _percentiles(top[idx].mean(axis=1) / bottom[idx].mean(axis=1))
    return Estimate(value, lo, hi, n)


def mean_ratio_estimate(pairs):
    """Mean over columns of per-column ratios, `pairs` a list of (numerator, denominator) per-repeat
    arrays all over the same repeats; each resample draws the same repeats in every column (repeat k is
    seed + k at every resolution or object count). None without a usable column."""
    pairs = [(np.asarray(t, dtype=float), np.asarray(b, dtype=float)) for t, b in pairs]
    pairs = [(t, b) for t, b in pairs if t.shape == b.shape and b.size and b.mean() > 0]
    if not pairs:
        return None
    value = float(np.mean([t.mean() / b.mean() for t, b in pairs]))
    sizes = {t.size for t, _ in pairs}
    n = min(sizes)
    if len(sizes) > 1:
        return Estimate(value, repeats=n, why="no interval (columns differ in their repeats)")
    if n < 2:
        return Estimate(value, repeats=n, why=no_interval_reason(n))
    idx = resample_indices(n)
    with np.errstate(divide="ignore", invalid="ignore"):
        boot = np.mean([t[idx].mean(axis=1) / b[idx].mean(axis=1) for t, b in pairs], axis=0)
    lo, hi = _percentiles(boot)
    return Estimate(value, lo, hi, n)


def paired(a, b):
    """The per-repeat means of two cells ({repeat: mean}) over the repeats both have, in repeat order."""
    common = sorted(set(a) & set(b))
    return [a[k] for k in common], [b[k] for k in common]
