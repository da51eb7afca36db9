"""Statistics more than one script reports: the library's Wilson intervals
over arrays, and the permutation test of failure against a binned input."""

from __future__ import annotations

import numpy as np
import rtw


def wilson(k: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Wilson score 95 % intervals of k successes in n trials, elementwise:
    rtw-scan's own (rtw.wilson), as in its summaries."""
    lo_hi = np.array([rtw.wilson(int(ki), int(ni)) for ki, ni in zip(np.asarray(k), np.asarray(n))]).reshape(-1, 2)
    return lo_hi[:, 0], lo_hi[:, 1]


def permutation_p(bins: np.ndarray, failed: np.ndarray, nbins: int, rounds: int, seed: int) -> tuple[float, float]:
    """χ² of failure against bin, and its permutation p-value (failure labels shuffled)."""

    def chi2(f: np.ndarray) -> float:
        n = np.bincount(bins, minlength=nbins).astype(float)
        k = np.bincount(bins, weights=f, minlength=nbins)
        p = f.mean()
        expected_k, expected_ok = n * p, n * (1 - p)
        m = n > 0
        return float((((k - expected_k) ** 2 / expected_k)[m]).sum() + (((n - k - expected_ok) ** 2 / expected_ok)[m]).sum())

    observed = chi2(failed)
    rng = np.random.default_rng(seed)
    more = sum(chi2(rng.permutation(failed)) >= observed for _ in range(rounds))
    return observed, (more + 1) / (rounds + 1)
