"""Oracle values for the least-squares AR estimators and the Ljung-Box test.

Run once from the repository root:
    python3 tools/oracles/ar_least_squares.py > crates/thermonav/tests/data/ar_least_squares.json
Covariance and modified-covariance estimates are computed with numpy.linalg.lstsq on explicitly
built regression matrices (an independent implementation of the same definition); the
Ljung-Box values come from statsmodels.stats.diagnostic.acorr_ljungbox.
"""
import json
import os
import numpy as np
import statsmodels
from statsmodels.stats.diagnostic import acorr_ljungbox

here = os.path.dirname(os.path.abspath(__file__))
xar2 = np.loadtxt(os.path.join(here, "../../../shared/data/statsmodels/xar2.txt"))
x1000 = xar2 / 1000.0
c = x1000 - x1000.mean()
n = len(c)

cases = []
for p in (1, 2, 5):
    forward = np.array([[c[k - i] for i in range(1, p + 1)] for k in range(p, n)])
    y_f = c[p:]
    phi_cov, *_ = np.linalg.lstsq(forward, y_f, rcond=None)
    rss_cov = float(np.sum((y_f - forward @ phi_cov) ** 2))
    backward = np.array([[c[k - p + i] for i in range(1, p + 1)] for k in range(p, n)])
    y_b = c[:n - p]
    stacked = np.vstack([forward, backward])
    phi_mcov, *_ = np.linalg.lstsq(stacked, np.concatenate([y_f, y_b]), rcond=None)
    rss_mcov = float(np.sum((np.concatenate([y_f, y_b]) - stacked @ phi_mcov) ** 2))
    cases.append({"order": p,
                  "covariance_phi": phi_cov.tolist(), "covariance_noise_variance": rss_cov / (n - p),
                  "modified_covariance_phi": phi_mcov.tolist(),
                  "modified_covariance_noise_variance": rss_mcov / (2 * (n - p))})

lb = acorr_ljungbox(c, lags=[10], model_df=2, return_df=True)
white = np.random.default_rng(7).standard_normal(500)
lb_white = acorr_ljungbox(white, lags=[15], model_df=0, return_df=True)
print(json.dumps({
    "source": f"numpy {np.__version__} lstsq, statsmodels {statsmodels.__version__} acorr_ljungbox",
    "series": "x1000 = xar2/1000 (shared/data/statsmodels/xar2.txt), mean removed",
    "least_squares": cases,
    "ljung_box_x1000_lag10_df2": {"statistic": float(lb["lb_stat"].iloc[0]), "p_value": float(lb["lb_pvalue"].iloc[0])},
    "ljung_box_white": {"series": white.tolist(), "lags": 15, "statistic": float(lb_white["lb_stat"].iloc[0]),
                        "p_value": float(lb_white["lb_pvalue"].iloc[0])},
}))
