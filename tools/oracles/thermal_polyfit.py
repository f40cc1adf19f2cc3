"""Oracle for the thermal bias curves (thermonav::stoch::thermal): polynomial least squares in
(T - T_ref), the order chosen by leave-one-out cross-validation, the coefficient covariance and
Scheffe's simultaneous 95 % band; and the fixed-effects fit with one offset per power-on.

Independent of the Rust code on purpose: coefficients from numpy.polynomial.polynomial.polyfit
and numpy.linalg.lstsq in the unscaled basis, PRESS by actually refitting without each
observation (not the hat-matrix shortcut the Rust code uses), covariance from statsmodels OLS,
the Scheffe factor from scipy.stats.f.ppf.
Run once: python3 tools/oracles/thermal_polyfit.py > crates/thermonav/tests/data/thermal_polyfit.json"""
import json
import numpy as np
import scipy
import statsmodels
import statsmodels.api as sm
from numpy.polynomial import polynomial as P
from scipy.stats import f as fisher

MAX_ORDER = 3
CONFIDENCE = 0.95


def loo_press(x, y, include):
    """Sum of squared deletion residuals, each from a refit without that observation; None
    when the refit is rank deficient."""
    total = 0.0
    for i in np.flatnonzero(include):
        keep = np.arange(len(y)) != i
        xk = x[keep]
        if np.linalg.matrix_rank(xk) < x.shape[1]:
            return None
        beta, *_ = np.linalg.lstsq(xk, y[keep], rcond=None)
        total += float((y[i] - x[i] @ beta) ** 2)
    return total


def band(cov, t_ref, factor, temperatures):
    out = []
    for t in temperatures:
        x = (t - t_ref) ** np.arange(cov.shape[0])
        out.append({"temperature_c": float(t), "half_width": float(factor * np.sqrt(x @ cov @ x))})
    return out


def plain_case(name, channel, temps, values, t_ref, eval_temps):
    temps, values = np.asarray(temps, float), np.asarray(values, float)
    ref = float(t_ref) if t_ref is not None else float((temps.min() + temps.max()) / 2)
    d = temps - ref
    distinct = len(np.unique(temps))
    press = []
    for k in range(MAX_ORDER + 1):
        if k > distinct - 1 or len(temps) <= k + 1:
            press.append(None)
            continue
        press.append(loo_press(np.vander(d, k + 1, increasing=True), values, np.ones(len(d), bool)))
    order = int(np.nanargmin([np.inf if p is None else p for p in press]))
    coefficients = P.polyfit(d, values, order)
    ols = sm.OLS(values, np.vander(d, order + 1, increasing=True)).fit()
    p, dof = order + 1, len(values) - order - 1
    factor = float(np.sqrt(p * fisher.ppf(CONFIDENCE, p, dof)))
    cov = np.asarray(ols.cov_params())
    return {
        "name": name, "channel": channel, "reference_temperature_c": None if t_ref is None else ref,
        "expected_reference_temperature_c": ref,
        "temperatures_c": temps.tolist(), "values": values.tolist(),
        "press": press, "order": order, "coefficients": coefficients.tolist(),
        "statsmodels_params": ols.params.tolist(), "coefficient_covariance": cov.tolist(),
        "residual_sd": float(np.sqrt(ols.scale)), "residual_degrees_of_freedom": dof,
        "scheffe_factor": factor, "band": band(cov, ref, factor, eval_temps),
    }


def power_on_case(name, channel, records, t_ref, eval_temps):
    ids = sorted({r[0] for r in records})
    pid = np.array([r[0] for r in records])
    temps = np.array([r[1] for r in records], float)
    values = np.array([r[2] for r in records], float)
    d = temps - t_ref
    J = len(ids)
    dummies = np.column_stack([(pid == i).astype(float) for i in ids])
    counts = {i: int((pid == i).sum()) for i in ids}
    include = np.array([counts[i] >= 2 for i in pid])

    def design(k):
        return np.column_stack([dummies] + [d ** m for m in range(1, k + 1)])

    press = []
    for k in range(MAX_ORDER + 1):
        x = design(k)
        if len(values) <= x.shape[1] or np.linalg.matrix_rank(x) < x.shape[1]:
            press.append(None)
            continue
        press.append(loo_press(x, values, include))
    order = int(np.nanargmin([np.inf if p is None else p for p in press]))
    ols = sm.OLS(values, design(order)).fit()
    theta, cov = ols.params, np.asarray(ols.cov_params())
    L = np.zeros((order + 1, J + order))
    L[0, :J] = 1.0 / J
    for m in range(1, order + 1):
        L[m, J + m - 1] = 1.0
    curve, curve_cov = L @ theta, L @ cov @ L.T
    offsets = []
    for j, i in enumerate(ids):
        c = np.zeros(J + order)
        c[:J] = -1.0 / J
        c[j] += 1.0
        offsets.append({"power_on": int(i), "offset": float(c @ theta), "offset_sd": float(np.sqrt(c @ cov @ c))})
    o = np.array([x["offset"] for x in offsets])
    v = np.array([x["offset_sd"] for x in offsets]) ** 2
    p, dof = order + 1, len(values) - J - order
    factor = float(np.sqrt(p * fisher.ppf(CONFIDENCE, p, dof)))
    return {
        "name": name, "channel": channel, "reference_temperature_c": t_ref,
        "records": [{"power_on": int(a), "temperature_c": float(b), "value": float(c)} for a, b, c in records],
        "press": press, "order": order, "coefficients": curve.tolist(),
        "coefficient_covariance": curve_cov.tolist(), "residual_sd": float(np.sqrt(ols.scale)),
        "residual_degrees_of_freedom": dof, "scheffe_factor": factor, "offsets": offsets,
        "offset_spread_sd": float(np.sqrt((o ** 2).sum() / (J - 1))),
        "between_power_on_sd": float(np.sqrt(max(0.0, ((o ** 2).sum() - v.sum()) / (J - 1)))),
        "band": band(curve_cov, t_ref, factor, eval_temps),
    }


rng = np.random.default_rng(1953)

# A gyro in a chamber: one record mean per set point, a clear cubic (rad/s).
chamber_t = np.arange(-40.0, 81.0, 15.0)
dc = chamber_t - 25.0
chamber_y = 2e-3 + 3e-5 * dc - 4e-7 * dc ** 2 + 6e-9 * dc ** 3 + 2e-5 * rng.standard_normal(len(dc))

# An accelerometer in a continuous sweep from 5 to 45 degC: many samples, a quadratic (m/s^2),
# reference temperature left to the fit (the middle of the range).
sweep_t = np.linspace(5.0, 45.0, 240) + 0.05 * rng.standard_normal(240)
ds = sweep_t - 25.0
sweep_y = 0.05 + 1e-3 * ds + 2e-5 * ds ** 2 + 3e-3 * rng.standard_normal(240)

# Few chamber points: the order rule keeps the fit below the number of temperatures.
few_t = np.array([-10.0, 20.0, 50.0, 20.0])
few_y = 1e-3 + 2e-5 * (few_t - 20.0) + 1e-5 * rng.standard_normal(4)

# Three power-ons of a gyro, overlapping in temperature, each with its own offset.
truth = lambda t: 1e-3 + 2e-5 * (t - 20.0) + 3e-7 * (t - 20.0) ** 2
power_ons = {1: (-20.0, 0.0, 20.0, 40.0), 2: (0.0, 20.0, 40.0, 60.0), 4: (20.0, 40.0)}
offset = {1: 4e-4, 2: -1e-4, 4: -3e-4}
records = [(i, t, truth(t) + offset[i] + 1e-5 * rng.standard_normal())
           for i, ts in power_ons.items() for t in ts]

eval_t = [-40.0, -12.5, 5.0, 25.0, 44.0, 80.0]
print(json.dumps({
    "source": f"numpy {np.__version__}, scipy {scipy.__version__}, statsmodels {statsmodels.__version__}",
    "confidence": CONFIDENCE,
    "plain": [
        plain_case("chamber cubic", "gx", chamber_t, chamber_y, 25.0, eval_t),
        plain_case("sweep quadratic", "az", sweep_t, sweep_y, None, [5.0, 15.0, 25.0, 45.0]),
        plain_case("few temperatures", "gy", few_t, few_y, 20.0, [-10.0, 20.0, 50.0]),
    ],
    "power_on": [power_on_case("three overlapping power-ons", "gz", records, 20.0, [-20.0, 0.0, 30.0, 60.0])],
}, indent=1))
