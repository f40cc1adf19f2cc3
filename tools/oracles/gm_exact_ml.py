#!/usr/bin/env python3
"""Oracle for the exact Gauss-Markov maximum likelihood on irregular times (stoch::gauss_markov).

Generates ONCE an irregularly sampled Gauss-Markov series (NumPy) and computes, with the DENSE
multivariate normal likelihood (covariance sigma^2 exp(-|t_i - t_j|/Tc), Cholesky by SciPy),
independently of thermonav's Markov factorisation:
- the log-likelihood at fixed parameters (scipy.stats.multivariate_normal.logpdf);
- for a zero mean and for an estimated mean: the maximum-likelihood Tc, sigma, mean (mean and
  sigma^2 profiled out in their closed GLS forms, ln Tc maximised by scipy minimize_scalar,
  cross-checked by a 3-parameter Nelder-Mead on the full logpdf), the maximised
  log-likelihood, and the 95 % likelihood-ratio interval of Tc (brentq on the profile drop of
  chi2.ppf(0.95, 1) / 2);
- the same for the restricted likelihood (REML: the mean integrated out), written with dense
  matrices as -(n-1)/2 ln(2 pi s2) - ln|R|/2 - ln(1'R^-1 1)/2 - Q/(2 s2), s2 = Q/(n-1), and
  cross-checked by integrating the full likelihood over the mean with scipy.integrate.quad.
Writes crates/thermonav/tests/data/gm_exact_ml.json.

Made with: Python 3, numpy 2.4.6, scipy 1.17.1. Run from the repository root:
    python3 tools/oracles/gm_exact_ml.py
"""
import json
import math

import numpy as np
import scipy
from scipy.linalg import cho_factor, cho_solve
from scipy.integrate import quad
from scipy.optimize import brentq, minimize, minimize_scalar
from scipy.stats import chi2, multivariate_normal

SEED = 52009
N = 400
TC_S = 0.03
SIGMA = 0.8
MEAN = 0.25
LEVEL = 0.95


def sample_times(rng):
    dt = 0.002 + rng.exponential(0.003, N - 1)
    dt[::97] += 0.05  # a few gaps of 50 ms
    return np.concatenate([[0.0], np.cumsum(dt)])


def simulate(rng, t):
    x = np.empty(N)
    x[0] = SIGMA * rng.standard_normal()
    for k in range(1, N):
        phi = math.exp(-(t[k] - t[k - 1]) / TC_S)
        x[k] = phi * x[k - 1] + SIGMA * math.sqrt(1 - phi * phi) * rng.standard_normal()
    return x + MEAN


def correlation(t, tc):
    return np.exp(-np.abs(t[:, None] - t[None, :]) / tc)


def profile(t, x, ln_tc, mean_model):
    """Profile log-likelihood at ln Tc; mean_model in 'zero', 'estimated', 'restricted'."""
    r = correlation(t, math.exp(ln_tc))
    factor = cho_factor(r, lower=True)
    ones = np.ones(len(x))
    mean = 0.0
    information = ones @ cho_solve(factor, ones)
    if mean_model != "zero":
        mean = ones @ cho_solve(factor, x) / information
    d = x - mean
    q = d @ cho_solve(factor, d)
    log_det = 2.0 * np.sum(np.log(np.diag(factor[0])))
    n = len(x)
    if mean_model == "restricted":
        s2 = q / (n - 1)
        ll = -0.5 * (n - 1) * (math.log(2 * math.pi * s2) + 1.0) - 0.5 * log_det \
            - 0.5 * math.log(information)
    else:
        s2 = q / n
        ll = -0.5 * n * (math.log(2 * math.pi * s2) + 1.0) - 0.5 * log_det
    return ll, mean, s2


def check_restricted_by_integration(t, x, ln_tc):
    """REML = log of the full likelihood integrated over the mean (flat), at fixed sigma."""
    ll, mean, s2 = profile(t, x, ln_tc, "restricted")
    cov = s2 * correlation(t, math.exp(ln_tc))
    full = lambda m: multivariate_normal.logpdf(x, mean=np.full(len(x), m), cov=cov)
    peak = full(mean)
    width = 10.0 * math.sqrt(s2)
    integral, _ = quad(lambda m: math.exp(full(m) - peak), mean - width, mean + width,
                       epsabs=0, epsrel=1e-12, limit=200)
    assert abs(peak + math.log(integral) - ll) < 1e-8, (peak + math.log(integral), ll)


def cross_check_full_likelihood(t, x, mean_model, ln_tc, ll, mean, s2):
    """The profiled maximum against a 3-parameter Nelder-Mead on the full dense logpdf."""
    def negative(p):
        cov = math.exp(2 * p[1]) * correlation(t, math.exp(p[0]))
        m = p[2] if mean_model == "estimated" else 0.0
        return -multivariate_normal.logpdf(x, mean=np.full(len(x), m), cov=cov)
    full = minimize(negative, [ln_tc + 0.1, 0.5 * math.log(s2) - 0.1, mean + 0.01],
                    method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-12,
                                                   "maxiter": 20000, "maxfev": 40000})
    assert abs(full.x[0] - ln_tc) < 1e-4, (full.x, ln_tc)
    assert abs(-full.fun - ll) < 1e-7, (full.fun, ll)


def fit(t, x, mean_model):
    lo, hi = math.log(1e-4), math.log(10.0)
    res = minimize_scalar(lambda u: -profile(t, x, u, mean_model)[0], bounds=(lo, hi),
                          method="bounded", options={"xatol": 1e-12})
    ln_tc = res.x
    ll, mean, s2 = profile(t, x, ln_tc, mean_model)
    if mean_model == "restricted":
        check_restricted_by_integration(t, x, ln_tc)
        check_restricted_by_integration(t, x, ln_tc + 1.0)
    else:
        cross_check_full_likelihood(t, x, mean_model, ln_tc, ll, mean, s2)
    threshold = ll - 0.5 * chi2.ppf(LEVEL, 1)
    g = lambda u: profile(t, x, u, mean_model)[0] - threshold
    lower = brentq(g, lo, ln_tc, xtol=1e-14, rtol=1e-15)
    upper = brentq(g, ln_tc, hi, xtol=1e-14, rtol=1e-15)
    return {"tc_s": math.exp(ln_tc), "sigma": math.sqrt(s2), "mean": mean,
            "log_likelihood": ll, "lr_lower_s": math.exp(lower), "lr_upper_s": math.exp(upper)}


def main():
    rng = np.random.default_rng(SEED)
    t = sample_times(rng)
    x = simulate(rng, t)
    fixed = {"tc_s": 0.05, "sigma": 1.1, "mean": 0.1}
    fixed_cov = fixed["sigma"] ** 2 * correlation(t, fixed["tc_s"])
    fixed["log_likelihood"] = float(
        multivariate_normal.logpdf(x, mean=np.full(N, fixed["mean"]), cov=fixed_cov))
    out = {
        "description": "irregularly sampled Gauss-Markov series; dense-covariance likelihood "
                       "and its maximum (SciPy), 95 % likelihood-ratio interval of Tc; ML with zero or "
                       "estimated mean, and REML",
        "generator": f"numpy {np.__version__}, scipy {scipy.__version__}, seed {SEED}",
        "true_values": {"tc_s": TC_S, "sigma": SIGMA, "mean": MEAN, "n": N},
        "level": LEVEL,
        "times_s": [float(v) for v in t],
        "values": [float(v) for v in x],
        "fixed_parameters": fixed,
        "zero_mean": fit(t, x, "zero"),
        "estimated_mean": fit(t, x, "estimated"),
        "restricted_mean": fit(t, x, "restricted"),
    }
    with open("crates/thermonav/tests/data/gm_exact_ml.json", "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
