#!/usr/bin/env python3
"""Oracle for the classical Gauss-Markov fit to an autocovariance (stoch::gauss_markov).

Generates ONCE a noisy sample autocovariance (a Gauss-Markov process plus white noise,
simulated with NumPy) and fits sigma^2 * exp(-tau / Tc) to it with SciPy's curve_fit
(Levenberg-Marquardt, MINPACK) over several lag windows, with tolerances tightened to 1e-15.
Writes crates/thermonav/tests/data/gm_acf_fit.json. The 1/e crossing is computed here by the
definition documented in thermonav (ln rho interpolated between the bracketing lags).

Made with: Python 3, numpy 2.4.6, scipy 1.17.1. Run from the repository root:
    python3 tools/oracles/gm_acf_fit.py
"""
import json
import math

import numpy as np
import scipy
from scipy.optimize import curve_fit, least_squares

SEED = 20090811
DT_S = 0.01
TC_S = 0.2
SIGMA = 1.5
WHITE_SIGMA = 0.5
N = 4000
MAX_LAG = 150


def simulate():
    rng = np.random.default_rng(SEED)
    phi = math.exp(-DT_S / TC_S)
    drive = SIGMA * math.sqrt(1.0 - phi * phi)
    x = np.empty(N)
    x[0] = SIGMA * rng.standard_normal()
    for k in range(1, N):
        x[k] = phi * x[k - 1] + drive * rng.standard_normal()
    return x + WHITE_SIGMA * rng.standard_normal(N)


def biased_autocovariance(y, max_lag):
    d = y - y.mean()
    return np.array([np.dot(d[: len(d) - k], d[k:]) / len(d) for k in range(max_lag + 1)])


def last_lag(window, gamma):
    kind = window["kind"]
    last = len(gamma) - 1
    if kind == "first_zero_crossing":
        outside = lambda k: gamma[k] <= 0.0
    elif kind == "until_rho_below":
        outside = lambda k: gamma[k] / gamma[0] < window["threshold"]
    else:
        return min(window["max_lag"], last)
    for k in range(1, last + 1):
        if outside(k):
            return k - 1
    return last


def model(tau, s2, tc):
    return s2 * np.exp(-tau / tc)


def fit(gamma, first, last):
    lags = np.arange(first, last + 1)
    tau = lags * DT_S
    g = gamma[first : last + 1]
    positive = g > 0
    slope, intercept = np.polyfit(tau[positive], np.log(g[positive]), 1)
    p0 = [math.exp(intercept), -1.0 / slope]
    popt, _ = curve_fit(model, tau, g, p0=p0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                        maxfev=100000)
    # Independent cross-check in another parametrisation (s2, ln tc) and another solver.
    check = least_squares(lambda p: model(tau, p[0], math.exp(p[1])) - g,
                          [p0[0], math.log(p0[1])], xtol=1e-15, ftol=1e-15, gtol=1e-15)
    assert abs(check.x[0] / popt[0] - 1) < 1e-8, (check.x, popt)
    assert abs(math.exp(check.x[1]) / popt[1] - 1) < 1e-8, (check.x, popt)
    rss = float(np.sum((model(tau, *popt) - g) ** 2))
    return float(popt[0]), float(popt[1]), rss


def e_folding(gamma):
    rho = gamma / gamma[0]
    target = math.exp(-1.0)
    for k in range(1, len(rho)):
        if rho[k] <= target:
            before, after = rho[k - 1], rho[k]
            if after > 0:
                fraction = (math.log(before) + 1.0) / (math.log(before) - math.log(after))
            else:
                fraction = (before - target) / (before - after)
            return (k - 1 + fraction) * DT_S
    return None


def main():
    gamma = biased_autocovariance(simulate(), MAX_LAG)
    cases = []
    for window, zero_lag in [
        ({"kind": "first_zero_crossing"}, "exclude"),
        ({"kind": "until_rho_below", "threshold": math.exp(-2.0)}, "exclude"),
        ({"kind": "max_lag", "max_lag": 40}, "include"),
        ({"kind": "max_lag", "max_lag": 150}, "exclude"),
    ]:
        first = 0 if zero_lag == "include" else 1
        last = last_lag(window, gamma)
        s2, tc, rss = fit(gamma, first, last)
        cases.append({"window": window, "zero_lag": zero_lag, "first_lag": first,
                      "last_lag": last, "sigma2": s2, "tc_s": tc, "rss": rss})
    out = {
        "description": "Gauss-Markov + white noise, biased sample autocovariance, fitted by "
                       "scipy.optimize.curve_fit(s2*exp(-tau/tc)) per lag window",
        "generator": f"numpy {np.__version__}, scipy {scipy.__version__}, seed {SEED}",
        "true_values": {"dt_s": DT_S, "tc_s": TC_S, "sigma": SIGMA, "white_sigma": WHITE_SIGMA,
                        "n": N},
        "lag_dt_s": DT_S,
        "autocovariance": [float(v) for v in gamma],
        "cases": cases,
        "e_folding_tc_s": e_folding(gamma),
    }
    with open("crates/thermonav/tests/data/gm_acf_fit.json", "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
