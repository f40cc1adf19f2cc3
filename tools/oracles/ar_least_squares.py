"""Oracle values for the least-squares AR estimators, order selection and the Ljung-Box test.

Run once from the repository root:

    python3 tools/oracles/ar_least_squares.py

It writes crates/thermonav/tests/data/ar_least_squares.json. The values were produced with
numpy 2.4.6, scipy 1.17.1 and statsmodels 0.15.0 (Python 3). Nothing here uses thermonav.

Independent implementations used:
- covariance method: numpy.linalg.lstsq (SVD) on explicitly built regression matrices
  (rows t = p..N-1, regressors x[t-1..t-p], optionally a constant column first);
  sigma2 = RSS / (N - p); bse = sqrt(diag(sigma2 * inv(X'X)));
- modified covariance: lstsq on the stacked forward rows and backward rows
  (target x[t-p], regressors x[t-p+1..t]); sigma2 = RSS / (2 (N - p));
- statsmodels AutoReg (conditional OLS) params, bse, sigma2 and residuals, trend 'n' on the
  demeaned series and trend 'c' on the raw series;
- statsmodels pacf_burg (Burg sigma2 per order) and yule_walker(method='mle') sigma per order,
  from which the test recomputes AIC/BIC/FPE;
- statsmodels acorr_ljungbox on stored residual series.
"""

import json
import os
import warnings

import numpy as np
import scipy
import statsmodels
from statsmodels.regression.linear_model import yule_walker
from statsmodels.stats.diagnostic import acorr_ljungbox
from statsmodels.tsa.ar_model import AutoReg
from statsmodels.tsa.stattools import pacf_burg

warnings.simplefilter("ignore", FutureWarning)

OUT = os.path.join("crates", "thermonav", "tests", "data", "ar_least_squares.json")
ORDERS = [1, 2, 3, 5]


def simulate_ar(coefficients, n, offset, seed, burn_in=300):
    """x_t = offset + y_t, y_t = sum c_i y_{t-i} + e_t, e ~ N(0, 1), RandomState(seed)."""
    rng = np.random.RandomState(seed)
    e = rng.standard_normal(n + burn_in)
    y = np.zeros(n + burn_in)
    p = len(coefficients)
    for t in range(n + burn_in):
        y[t] = e[t] + sum(coefficients[i] * y[t - 1 - i] for i in range(p) if t - 1 - i >= 0)
    return offset + y[burn_in:]


def lag_matrix(x, p):
    """Rows t = p..N-1 of [x[t-1], ..., x[t-p]] and the targets x[t]."""
    n = len(x)
    X = np.column_stack([x[p - i : n - i] for i in range(1, p + 1)])
    return X, x[p:]


def ols(X, target, rows):
    params = np.linalg.lstsq(X, target, rcond=None)[0]
    rss = float(np.sum((target - X @ params) ** 2))
    sigma2 = rss / rows
    bse = np.sqrt(np.diag(sigma2 * np.linalg.inv(X.T @ X)))
    return params, sigma2, bse


def covariance_method(x, p, mean):
    y = x - x.mean() if mean == "sample_mean" else x
    X, target = lag_matrix(y, p)
    if mean == "intercept":
        X = np.column_stack([np.ones(len(target)), X])
    params, sigma2, bse = ols(X, target, len(x) - p)
    return {"params": params.tolist(), "sigma2": sigma2, "bse": bse.tolist()}


def modified_covariance(x, p, mean):
    y = x - x.mean() if mean == "sample_mean" else x
    n = len(y)
    Xf, tf = lag_matrix(y, p)
    Xb = np.column_stack([y[i : n - p + i] for i in range(1, p + 1)])
    tb = y[: n - p]
    X = np.vstack([Xf, Xb])
    target = np.concatenate([tf, tb])
    params = np.linalg.lstsq(X, target, rcond=None)[0]
    rss = float(np.sum((target - X @ params) ** 2))
    return {"params": params.tolist(), "sigma2": rss / (2 * (n - p))}


def autoreg(x, p):
    demeaned = AutoReg(x - x.mean(), p, trend="n").fit()
    with_constant = AutoReg(x, p, trend="c").fit()
    return {
        "trend_n_on_demeaned": {
            "params": demeaned.params.tolist(),
            "bse": demeaned.bse.tolist(),
            "sigma2": float(demeaned.sigma2),
            "resid": demeaned.resid.tolist(),
        },
        "trend_c_on_raw": {
            "params": with_constant.params.tolist(),
            "bse": with_constant.bse.tolist(),
            "sigma2": float(with_constant.sigma2),
        },
    }


def per_order_variances(x, max_order):
    burg_sigma2 = pacf_burg(x, max_order, demean=True).sigma2
    yw_sigma = [
        float(yule_walker(x, order=p, method="mle")[1]) for p in range(1, max_order + 1)
    ]
    return {
        "max_order": max_order,
        "burg_sigma2_orders_0_to_max": burg_sigma2.tolist(),
        "yule_walker_sigma_orders_1_to_max": yw_sigma,
    }


def ljung_box(resid, lags, model_df):
    table = acorr_ljungbox(resid, lags=lags, model_df=model_df, return_df=True)
    return {
        "lags": lags,
        "model_df": model_df,
        "lb_stat": table["lb_stat"].tolist(),
        "lb_pvalue": table["lb_pvalue"].tolist(),
    }


def series_entry(name, description, x):
    entry = {"name": name, "description": description, "x": x.tolist(), "orders": {}}
    for p in ORDERS:
        entry["orders"][str(p)] = {
            "covariance": {m: covariance_method(x, p, m) for m in ("zero", "sample_mean", "intercept")},
            "modified_covariance": {m: modified_covariance(x, p, m) for m in ("zero", "sample_mean")},
            "autoreg": autoreg(x, p),
        }
    entry["order_selection"] = per_order_variances(x, 8)
    return entry


def main():
    ar3 = simulate_ar([0.6, -0.3, 0.2], 400, 5.0, 20261122)
    ar1 = simulate_ar([0.95], 300, -2.0, 7)
    white = np.random.RandomState(99).standard_normal(250)
    resid = AutoReg(ar3 - ar3.mean(), 3, trend="n").fit().resid
    out = {
        "generator": "tools/oracles/ar_least_squares.py",
        "versions": {
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "statsmodels": statsmodels.__version__,
        },
        "conventions": "params in the x_t = c0 + sum c_i x_{t-i} + e_t sign; with 'intercept' the constant is first",
        "series": [
            series_entry("ar3", "AR(3) c=(0.6,-0.3,0.2) + 5.0, N=400, RandomState(20261122)", ar3),
            series_entry("ar1_095", "AR(1) c=0.95 - 2.0, N=300, RandomState(7)", ar1),
        ],
        "ljung_box": [
            dict(ljung_box(resid, [5, 10, 20], 3), series="autoreg_resid_ar3_order3", x=resid.tolist()),
            dict(ljung_box(white, [1, 5, 10], 0), series="white_noise_randomstate99", x=white.tolist()),
        ],
    }
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
