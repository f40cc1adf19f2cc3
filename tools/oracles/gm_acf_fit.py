"""Oracle for the classical Gauss-Markov fit to an autocovariance: scipy.optimize.curve_fit of
a*exp(-tau/Tc) to a noisy exponential over lags 1..60.
Run once: python3 tools/oracles/gm_acf_fit.py > crates/thermonav/tests/data/gm_acf_fit.json"""
import json
import numpy as np
import scipy
from scipy.optimize import curve_fit

dt = 0.5
rng = np.random.default_rng(31)
lags = np.arange(0, 121)
gamma = 0.09 * np.exp(-lags * dt / 7.0) + 0.004 * rng.standard_normal(len(lags))
gamma[0] += 2.0
tau = lags[1:61] * dt
popt, _ = curve_fit(lambda t, a, tc: a * np.exp(-t / tc), tau, gamma[1:61], p0=[0.1, 5.0],
                    xtol=1e-14, ftol=1e-14, gtol=1e-14, maxfev=100000)
print(json.dumps({"source": f"scipy {scipy.__version__} curve_fit (Levenberg-Marquardt)", "lag_dt_s": dt,
                  "gamma": gamma.tolist(), "fit_lags": [1, 60], "sigma_squared": float(popt[0]),
                  "correlation_time_s": float(popt[1])}))
