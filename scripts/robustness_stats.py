"""The statistics of the robustness study (scripts/robustness_study.py):
Spearman's ρ and Harrell's concordance with bootstrap intervals, and a
right-censored normal (Tobit) regression of log10 MFPT, written here rather
than taken from a survival library (scripts/requirements.txt has SciPy, not
lifelines), so every step is on this page.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize, stats

BOOTSTRAP = 2000
SEED = 27


def ranks(x: np.ndarray) -> np.ndarray:
    """Ranks from 0 with ties averaged."""
    return stats.rankdata(x, method="average") - 1.0


def spearman(x: np.ndarray, y: np.ndarray) -> float:
    rx, ry = ranks(x), ranks(y)
    if rx.std() == 0 or ry.std() == 0:
        return float("nan")
    return float(np.corrcoef(rx, ry)[0, 1])


def bootstrap(stat, n: int, reps: int = BOOTSTRAP) -> tuple[float, float]:
    """The 2.5–97.5 % percentile interval of `stat(index)` over `reps`
    resamples of `n` items with replacement (seed SEED)."""
    rng = np.random.default_rng(SEED)
    vals = np.array([stat(rng.integers(0, n, n)) for _ in range(reps)])
    lo, hi = np.nanpercentile(vals, [2.5, 97.5])
    return float(lo), float(hi)


def spearman_ci(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """Spearman's ρ and its 95 % percentile bootstrap interval (pairs resampled)."""
    lo, hi = bootstrap(lambda i: spearman(x[i], y[i]), len(x))
    return spearman(x, y), lo, hi


def somers_d(x: np.ndarray, y: np.ndarray, censored: np.ndarray) -> float:
    """Harrell's concordance of a measure `x` with right-censored `y`, as
    Somers' D = 2C − 1 (−1 … +1, positive when a larger `x` goes with a
    longer walk, so it reads as a rank correlation).

    A pair is comparable when the shorter `y` is observed (a censored `y` is
    only known to be at least its value): i with y_i < y_j and i uncensored.
    It is concordant when x_i < x_j, discordant when x_i > x_j, and a tie
    in x counts one half."""
    yi, yj = y[:, None], y[None, :]
    comparable = (yi < yj) & ~censored[:, None]
    xi, xj = x[:, None], x[None, :]
    conc = ((xi < xj) & comparable).sum() + 0.5 * ((xi == xj) & comparable).sum()
    n = comparable.sum()
    if n == 0:
        return float("nan")
    return float(2.0 * conc / n - 1.0)


def somers_d_ci(x, y, censored, reps: int = 300) -> tuple[float, float, float]:
    lo, hi = bootstrap(lambda i: somers_d(x[i], y[i], censored[i]), len(x), reps)
    return somers_d(x, y, censored), lo, hi


def normal_scores(x: np.ndarray) -> np.ndarray:
    """Van der Waerden scores Φ⁻¹(rank / (n + 1)), ties averaged: a measure
    on a common scale whatever its units and tails (the step down stops at
    16 L, the GSN spans decades), standardised to unit SD."""
    z = stats.norm.ppf((ranks(x) + 1.0) / (len(x) + 1.0))
    return (z - z.mean()) / z.std()


def tobit_nll(theta: np.ndarray, X: np.ndarray, y: np.ndarray, censored: np.ndarray) -> tuple[float, np.ndarray]:
    """Negative log-likelihood of y = Xβ + ε, ε ~ N(0, s²), y right-censored
    where `censored` (the true value is at least y), and its gradient;
    theta = (β, log s)."""
    beta, s = theta[:-1], np.exp(theta[-1])
    r = (y - X @ beta) / s
    ll = np.where(censored, stats.norm.logsf(r), stats.norm.logpdf(r) - np.log(s))
    # d ll / d r: −r observed; the inverse Mills ratio φ/(1 − Φ) censored.
    mills = np.exp(stats.norm.logpdf(r) - stats.norm.logsf(r))
    g = np.where(censored, mills, r)  # d ll / d(Xβ) times s
    d_beta = X.T @ g / s
    d_logs = float(np.sum(np.where(censored, mills * r, r * r - 1.0)))
    return -float(ll.sum()), -np.append(d_beta, d_logs)


def tobit_fit(X: np.ndarray, y: np.ndarray, censored: np.ndarray, start=None) -> tuple[np.ndarray, float]:
    """Maximum-likelihood (β, log s) and the log-likelihood."""
    if start is None:
        beta0 = np.linalg.lstsq(X, y, rcond=None)[0]
        start = np.append(beta0, np.log(max(np.std(y - X @ beta0), 1e-3)))
    # Bounded (|β| ≤ 20 decades, s from e⁻⁶ to e⁴): a heavily censored
    # bootstrap resample may have no finite maximum, and the line search must
    # not leave the range where the likelihood is a number.
    bounds = [(-20.0, 20.0)] * X.shape[1] + [(-6.0, 4.0)]
    start = np.clip(start, [b[0] for b in bounds], [b[1] for b in bounds])
    res = optimize.minimize(tobit_nll, start, args=(X, y, censored), jac=True, method="L-BFGS-B", bounds=bounds)
    return res.x, -float(res.fun)


def tobit(columns: list[np.ndarray], y: np.ndarray, censored: np.ndarray, reps: int = 200) -> dict:
    """The censored regression of `y` on the normal scores of `columns`
    (with an intercept): each slope with its 95 % bootstrap interval
    (gaits resampled), the likelihood-ratio test against the intercept-only
    model (χ² with len(columns) degrees of freedom) and the residual SD."""
    n = len(y)
    Z = np.column_stack([np.ones(n)] + [normal_scores(c) for c in columns])
    # The full model starts from the intercept-only fit (slopes 0), so its
    # likelihood cannot end below the null's.
    theta0, ll0 = tobit_fit(Z[:, :1], y, censored)
    start = np.concatenate([theta0[:1], np.zeros(Z.shape[1] - 1), theta0[-1:]])
    theta, ll = tobit_fit(Z, y, censored, start=start)
    lr = 2.0 * (ll - ll0)
    k = len(columns)
    rng = np.random.default_rng(SEED)
    boot = []
    for _ in range(reps):
        i = rng.integers(0, n, n)
        # Rescored on the resample, as the fit itself scores its gaits.
        Zb = np.column_stack([np.ones(n)] + [normal_scores(c[i]) for c in columns])
        boot.append(tobit_fit(Zb, y[i], censored[i], start=start)[0][1 : 1 + k])
    lo, hi = np.percentile(np.array(boot), [2.5, 97.5], axis=0)
    return {
        "beta": theta[1 : 1 + k],
        "lo": lo,
        "hi": hi,
        "sigma": float(np.exp(theta[-1])),
        "lr": float(lr),
        "p": float(stats.chi2.sf(lr, k)),
        "n": n,
        "censored": int(censored.sum()),
    }


def self_check() -> None:
    """Checks the statistics against independent computations: Somers' D of
    uncensored data against SciPy's `somersd`, the Tobit gradient against
    finite differences, and the Tobit fit's recovery of a known slope from a
    simulated right-censored sample where plain least squares is biased."""
    rng = np.random.default_rng(1)
    x = rng.integers(0, 20, 200).astype(float)
    y = 0.3 * x + rng.normal(size=200)
    d = somers_d(x, y, np.zeros(200, dtype=bool))
    ref = stats.somersd(y, x).statistic  # D(x | y): pairs untied in y
    assert abs(d - ref) < 1e-12, (d, ref)
    n = 4000
    z = rng.normal(size=n)
    truth = 1.0 + 0.5 * z + rng.normal(scale=0.7, size=n)
    bound = rng.normal(1.3, 0.5, size=n)
    cens = truth > bound
    obs = np.where(cens, bound, truth)
    X = np.column_stack([np.ones(n), z])
    theta = np.array([0.9, 0.4, -0.3])
    err = optimize.check_grad(lambda t: tobit_nll(t, X, obs, cens)[0], lambda t: tobit_nll(t, X, obs, cens)[1], theta)
    assert err < 1e-3 * np.linalg.norm(tobit_nll(theta, X, obs, cens)[1]), err
    fit, _ = tobit_fit(X, obs, cens)
    ols = np.linalg.lstsq(X, obs, rcond=None)[0]
    # The slope's standard error here is about 0.013.
    assert abs(fit[1] - 0.5) < 0.05 and abs(np.exp(fit[2]) - 0.7) < 0.05, fit
    assert abs(ols[1] - 0.5) > 0.15, ols
    print(f"robustness_stats: self-check passed (Somers' D {d:.6f} = SciPy {ref:.6f}; Tobit slope "
          f"{fit[1]:.3f}, s {np.exp(fit[2]):.3f} against 0.5, 0.7 with {cens.mean():.0%} censored; "
          f"least squares {ols[1]:.3f})")


if __name__ == "__main__":
    self_check()
