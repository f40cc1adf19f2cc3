"""The whole characterisation of a campaign as a careful Python user would write it, timed against
`thermonav characterize` on the same files in the same run (driven by `bash bench/compare.sh
workflow`; see issue 21).

Per file: pandas.read_csv; the nominal rate from the median interval. Per channel, the steps
`thermonav characterize` takes with its defaults (DESIGN.md, crates/thermonav/src/stoch/
characterize.rs), each with the Python package a user would reach for:

1. Allan deviation of the raw rates on the octave grid (allantools.oadev) and the IEEE 952 white
   noise N and bias instability B read off it by the rule thermonav documents
   (noise_terms.rs: N from the shortest-τ run of slope -1/2 starting at 10 samples, B at the
   curve's minimum, an upper bound when that is an end point);
2. the Kaiser low-pass (scipy.signal.kaiserord + firwin, 60 dB, cut-off 0.4 Hz, transition
   0.2 Hz, one tap more when even) applied only at the kept samples of the decimation to 1 Hz
   (scipy.signal.upfirdn), keeping the outputs whose whole window lies inside the record;
3. on that series: Burg AR of order 1..4 chosen by BIC (statsmodels burg), the AR(1)-based
   Gauss-Markov model with its interval from the asymptotic standard error of c1, and the
   classical least-squares fit of sigma^2 exp(-tau/Tc) to the autocovariance up to its first
   zero crossing (statsmodels acovf, scipy.optimize.curve_fit);
4. on 0.5 s block means of the raw record at their mean times: the exact first-order
   Gauss-Markov + white-noise likelihood, evaluated by statsmodels' Kalman filter through a
   custom MLEModel with time-varying transition (phi_k = exp(-dt_k/Tc)) and observation noise
   (N^2/d_k), the scale concentrated out; the maximum from the best point of a 13 x 9 grid
   refined by Nelder-Mead (scipy), the white-noise-only likelihood-ratio test, and the 95 %
   likelihood-ratio interval of Tc (the profile over the white-noise share by bounded scalar
   minimisation, its crossings by Brent's method).

Not done on the Python side (thermonav does them, so its time includes them): the Allan
confidence limits and the terms read with them (rate random walk K, term intervals), the GMWM
composite fit, and the thermal calibration across temperatures. No PyPI package does GMWM
(the R package gmwm is not on PyPI), and the others are thermonav's own rules rather than a
package a user would call.
"""
import argparse
import functools
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np
import pandas as pd
import scipy
from scipy import optimize, signal, stats

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
THERMONAV = os.path.join(ROOT, "target", "release", "thermonav")
CHANNELS = ["gx_rad_s", "gy_rad_s", "gz_rad_s", "ax_m_s2", "ay_m_s2", "az_m_s2"]
SHORT = {name: name.split("_")[0] for name in CHANNELS}

# thermonav characterize's defaults (CharacterizeSettings::default()).
CUTOFF_HZ, TRANSITION_HZ, RIPPLE_DB, MODELLING_HZ = 0.4, 0.2, 60.0, 1.0
MAX_AR_ORDER, ML_BLOCK_S = 4, 0.5
SLOPE_TOLERANCE, BRANCH_TOLERANCE, MIN_WHITE_NOISE_FACTOR, BIAS_INSTABILITY_FACTOR = 0.15, 0.35, 10, 0.664
SIGNIFICANCE_LR = stats.chi2.ppf(0.99, 2)
LR_DROP_95 = stats.chi2.ppf(0.95, 1) / 2


# ---------------------------------------------------------------- Allan deviation and its terms

def allan_terms(values, rate_hz):
    """Octave overlapping ADEV (allantools) and the white noise N and bias instability B."""
    import allantools
    taus, adev, _, _ = allantools.oadev(values, rate=rate_hz, data_type="freq", taus="octave")
    m = np.rint(taus * rate_hz).astype(int)
    return {"tau_s": taus, "adev": adev, "white_noise_density": white_noise(taus, adev, m),
            **bias_instability(adev)}


def local_slopes(taus, adev):
    """Central differences of ln adev over ln tau, one-sided at the ends."""
    lt, la = np.log(taus), np.log(np.maximum(adev, np.finfo(float).tiny))
    n = len(adev)
    lo, hi = np.maximum(np.arange(n) - 1, 0), np.minimum(np.arange(n) + 1, n - 1)
    return (la[hi] - la[lo]) / (lt[hi] - lt[lo])


def white_noise(taus, adev, m):
    """N = geometric mean of adev * sqrt(tau) over the first run of slope -1/2 (thermonav's rule)."""
    slopes = local_slopes(taus, adev)
    on_branch = lambda j: abs(slopes[j] + 0.5) <= BRANCH_TOLERANCE and adev[j] > 0
    start = np.flatnonzero(m >= MIN_WHITE_NOISE_FACTOR)
    i = int(start[0]) if len(start) else len(slopes)
    while i < len(slopes) and slopes[i] <= 0:
        if not on_branch(i):
            i += 1
            continue
        end = i
        while end + 1 < len(slopes) and on_branch(end + 1):
            end += 1
        last = next((j for j in range(end, i - 1, -1) if abs(slopes[j] + 0.5) <= SLOPE_TOLERANCE), None)
        if last is not None:
            return float(np.exp(np.mean(np.log(adev[i:last + 1] * np.sqrt(taus[i:last + 1])))))
        i = end + 1
    return None


def bias_instability(adev):
    """B = min adev / 0.664; at an end of the curve only a bound."""
    i = int(np.argmin(np.where(adev > 0, adev, np.inf)))
    value = float(adev[i] / BIAS_INSTABILITY_FACTOR)
    at_end = i in (0, len(adev) - 1)
    return {"bias_instability": None if at_end else value, "bias_instability_at_most": value if at_end else None}


# ---------------------------------------------------------------- conditioning and the AR route

def kaiser_lowpass(rate_hz):
    """scipy kaiserord + firwin; one tap more when the count is even (zero phase by a delay)."""
    numtaps, beta = signal.kaiserord(RIPPLE_DB, TRANSITION_HZ / (rate_hz / 2))
    numtaps += 1 - numtaps % 2
    taps = signal.firwin(numtaps, CUTOFF_HZ, window=("kaiser", beta), fs=rate_hz)
    return taps, beta


def filter_and_decimate(x, taps, factor):
    """y_j = sum_i h_i x_{j+D-i} for j = 0, F, 2F, ... with D <= j <= n-1-D (whole window inside
    the record): upfirdn evaluates the full convolution at every F-th index, so the input is
    shifted to put index j + D on that grid."""
    n, delay = len(x), (len(taps) - 1) // 2
    first = -(-delay // factor) * factor
    skip = (first + delay) % factor
    full = signal.upfirdn(taps, x[skip:], up=1, down=factor)
    start = (first + delay - skip) // factor
    count = (n - 1 - delay - first) // factor + 1
    return full[start:start + count]


def ar_route(conditioned, dt_s):
    """Burg AR by BIC up to order 4, the AR(1)-based Gauss-Markov model and the ACF fit."""
    from statsmodels.regression.linear_model import burg
    n = len(conditioned)
    fits = [burg(conditioned, p) for p in range(1, MAX_AR_ORDER + 1)]
    bic = [n * np.log(max(s2, np.finfo(float).tiny)) + (p + 1) * np.log(n) for p, (_, s2) in enumerate(fits)]
    chosen = int(np.argmin(bic))
    rho, s2 = fits[0]
    c1 = float(rho[0])
    gamma0 = float(np.mean((conditioned - conditioned.mean()) ** 2))
    se = np.sqrt(s2 / gamma0 / n)
    ar = {"order": chosen + 1, "coefficients": fits[chosen][0], "noise_variance": float(fits[chosen][1])}
    if not 0 < c1 < 1:
        ar_based = None
    else:
        tc = lambda c: -dt_s / np.log(c)
        z = stats.norm.ppf(0.975)
        lo, hi = c1 - z * se, c1 + z * se
        ar_based = {"correlation_time_s": tc(c1), "sigma": float(np.sqrt(s2 / (1 - c1 * c1))),
                    "ci95_correlation_time_s": [tc(lo) if lo > 0 else None, tc(hi) if hi < 1 else None]}
    return ar, ar_based, acf_fit(conditioned, dt_s)


def acf_fit(x, dt_s):
    """Least squares of a exp(-b tau) to the biased autocovariance at lags 1.. before its first
    non-positive value, started from the log-linear fit; Tc = 1/b, sigma = sqrt(a)."""
    from statsmodels.tsa.stattools import acovf
    max_lag = min(max(len(x) // 4, 2), len(x) - 1)
    gamma = acovf(x, demean=True, adjusted=False, fft=True, nlag=max_lag)
    non_positive = np.flatnonzero(gamma[1:] <= 0)
    last = int(non_positive[0]) if len(non_positive) else len(gamma) - 1
    if last < 2:
        return None
    lags = np.arange(1, last + 1) * dt_s
    slope, intercept = np.polyfit(lags, np.log(gamma[1:last + 1]), 1)
    if not slope < 0:
        return None
    (a, b), _ = optimize.curve_fit(lambda t, a, b: a * np.exp(-b * t), lags, gamma[1:last + 1],
                                   p0=(np.exp(intercept), -slope), xtol=1e-14, ftol=1e-14, maxfev=10000)
    if not (a > 0 and b > 0):
        return None
    return {"correlation_time_s": 1.0 / b, "sigma": float(np.sqrt(a)), "ci95_correlation_time_s": [None, None]}


# ---------------------------------------------------------------- exact GM + white likelihood

@functools.lru_cache(maxsize=None)
def noisy_gm_model_class():
    """A statsmodels state-space model: b_k = phi_k b_{k-1} + w_k, y_k = b_k + n_k, with
    phi_k = exp(-dt_k/Tc), var w_k = 1 - phi_k^2, var n_k = rho/d_k (in units of the scale
    sigma^2, which the Kalman filter concentrates out), b_0 ~ N(0, 1)."""
    from statsmodels.tsa.statespace.mlemodel import MLEModel

    class NoisyGaussMarkov(MLEModel):
        def __init__(self, times_s, values):
            super().__init__(values - values.mean(), k_states=1, k_posdef=1)
            dt = np.diff(times_s)
            self.next_dt = np.append(dt, dt[-1])       # transition t -> t+1
            self.average_s = np.insert(dt, 0, dt[0])   # interval each mean averages over
            self["design"] = np.ones((1, 1))
            self["selection"] = np.ones((1, 1))
            self.ssm.initialize_known(np.zeros(1), np.ones((1, 1)))
            self.ssm.filter_concentrated = True

        @property
        def param_names(self):
            return ["ln_tc", "ln_rho"]

        def update(self, params, **kwargs):
            params = super().update(params, **kwargs)
            phi = np.exp(-self.next_dt / np.exp(params[0]))
            self["transition"] = phi[None, None, :]
            self["state_cov"] = (1.0 - phi * phi)[None, None, :]
            self["obs_cov"] = (np.exp(params[1]) / self.average_s)[None, None, :]

    return NoisyGaussMarkov


def exact_gauss_markov(model_class, block_times_s, block_means):
    """Maximum likelihood of (Tc, rho), the test against white noise and the LR interval of Tc."""
    model = model_class(block_times_s, block_means)
    y, d = model.endog[:, 0], model.average_s
    n, span, min_dt = len(y), block_times_s[-1] - block_times_s[0], model.next_dt.min()
    box = np.array([[np.log(0.5 * min_dt), np.log(2 * span)], [np.log(1e-6 * min_dt), np.log(1e6 * span)]])

    def loglike(p):
        if not (box[0, 0] <= p[0] <= box[0, 1] and box[1, 0] <= p[1] <= box[1, 1]):
            return -np.inf
        return model.loglike(np.asarray(p, dtype=float))

    grid = [(box[0, 0] + (box[0, 1] - box[0, 0]) * (i + 0.5) / 13, box[1, 0] + (box[1, 1] - box[1, 0]) * (j + 0.5) / 9)
            for i in range(13) for j in range(9)]
    start = max(grid, key=loglike)
    best = optimize.minimize(lambda p: -loglike(p), start, method="Nelder-Mead",
                             options={"xatol": 1e-6, "fatol": 1e-6, "initial_simplex": [start, start + np.array([0.5, 0]),
                                                                                         start + np.array([0, 0.5])]}).x
    if abs(best[0] - box[0, 1]) < 0.05 or abs(best[0] - box[0, 0]) < 0.05 or abs(best[1] - box[1, 1]) < 0.05:
        return None
    top = loglike(best)
    density_sq = np.sum(y * y * d) / n
    white = -0.5 * n * (np.log(2 * np.pi) + 1 + np.log(density_sq)) + 0.5 * np.sum(np.log(d))
    if 2 * (top - white) < SIGNIFICANCE_LR:
        return None
    scale = model.filter(best).scale
    return {"correlation_time_s": float(np.exp(best[0])), "sigma": float(np.sqrt(scale)),
            "ci95_correlation_time_s": lr_interval(loglike, box, best, top)}


def lr_interval(loglike, box, best, top):
    """Where the profile log-likelihood of ln Tc falls chi2(1, 0.95)/2 below its maximum."""
    target = top - LR_DROP_95

    def profile(ln_tc, hint):
        lo, hi = max(hint - 3, box[1, 0]), min(hint + 3, box[1, 1])
        r = optimize.minimize_scalar(lambda r: -loglike((ln_tc, r)), bounds=(lo, hi), method="bounded",
                                     options={"xatol": 1e-4})
        return -r.fun, r.x

    def side(direction):
        inside, rho, step = best[0], best[1], 0.3
        while True:
            candidate = inside + direction * step
            if not box[0, 0] <= candidate <= box[0, 1]:
                return None
            value, r = profile(candidate, rho)
            if value < target:
                root = optimize.brentq(lambda t: profile(t, r)[0] - target, min(inside, candidate),
                                       max(inside, candidate), xtol=2e-3)
                return float(np.exp(root))
            inside, rho, step = candidate, r, step * 1.5

    low = side(-1.0)
    return [low if low is not None else float(np.exp(box[0, 0])), side(1.0)]


# ---------------------------------------------------------------- the workflow

def characterize_file(path):
    """One file's bank entry, as a dict of the quantities the bank holds."""
    model_class = noisy_gm_model_class()
    stages = dict.fromkeys(STAGES, 0.0)
    clock = time.perf_counter()

    def lap(stage):
        nonlocal clock
        now = time.perf_counter()
        stages[stage] += now - clock
        clock = now

    frame = pd.read_csv(path)
    lap("pandas.read_csv")
    t = frame["t_s"].to_numpy()
    dt = np.diff(t)
    # thermonav's nominal interval is the lower median of the positive intervals, an actual
    # interval of the data (DESIGN.md); np.median would average the two middle ones of an even
    # count, which with timing jitter moves the rate by ~3e-7 and every tau, AR dt and N with it.
    positive = np.sort(dt[dt > 0])
    rate_hz = 1.0 / positive[(len(positive) - 1) // 2]
    taps, beta = kaiser_lowpass(rate_hz)
    factor = int(round(rate_hz / MODELLING_HZ))
    dt_model = factor / rate_hz
    per_block = max(int(round(ML_BLOCK_S * rate_hz)), 1)
    blocks = len(t) // per_block
    block_times = (t[:blocks * per_block] - t[0]).reshape(blocks, per_block).mean(axis=1)
    entry = {"temperature_c": float(frame["temp_c"].mean()), "input_rate_hz": rate_hz, "num_taps": len(taps),
             "beta": beta, "decimation_factor": factor, "channels": {}, "stages_s": stages}
    lap("rate, Kaiser design, block times")
    for name in CHANNELS:
        x = frame[name].to_numpy()
        allan = allan_terms(x, rate_hz)
        lap("allantools.oadev + N, B")
        conditioned = filter_and_decimate(x, taps, factor)
        lap("scipy upfirdn (filter + decimate)")
        ar, ar_based, acf = ar_route(conditioned, dt_model)
        lap("statsmodels burg (BIC), AR-based, ACF fit")
        means = x[:blocks * per_block].reshape(blocks, per_block).mean(axis=1)
        ml = exact_gauss_markov(model_class, block_times, means)
        lap("statsmodels state-space ML + LR interval")
        entry["channels"][SHORT[name]] = {"allan": allan, "ar": ar, "ar_based": ar_based, "acf_fit": acf,
                                          "irregular_ml": ml}
    return entry


STAGES = ["pandas.read_csv", "rate, Kaiser design, block times", "allantools.oadev + N, B",
          "scipy upfirdn (filter + decimate)", "statsmodels burg (BIC), AR-based, ACF fit",
          "statsmodels state-space ML + LR interval"]


def quiet_characterize_file(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # statsmodels' convergence warnings: the agreement check judges
        return characterize_file(path)


def python_workflow(paths, processes):
    """Every file in turn, or `processes` files at a time in worker processes (what a user with
    several cores would do: the steps themselves are single-threaded)."""
    if processes <= 1:
        return [quiet_characterize_file(p) for p in paths]
    from concurrent.futures import ProcessPoolExecutor
    with ProcessPoolExecutor(max_workers=processes) as pool:
        return list(pool.map(quiet_characterize_file, paths))


def children_cpu_s():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed_python_workflow(paths, processes):
    """Wall and CPU time (this process and its workers) of the Python workflow, and its entries."""
    cpu0, children0, t0 = time.process_time(), children_cpu_s(), time.perf_counter()
    entries = python_workflow(paths, processes)
    wall = time.perf_counter() - t0
    return wall, time.process_time() - cpu0 + children_cpu_s() - children0, entries


def run_thermonav(paths, bank_path, *extra):
    """`thermonav characterize` with its defaults (or `extra` options); wall and CPU (user +
    system) time."""
    before = children_cpu_s()
    t0 = time.perf_counter()
    subprocess.run([THERMONAV, "characterize", *paths, "--out", bank_path, *extra], check=True, capture_output=True)
    wall = time.perf_counter() - t0
    cpu = children_cpu_s() - before
    with open(bank_path) as f:
        return wall, cpu, json.load(f)


# ---------------------------------------------------------------- agreement

def rel(a, b):
    return abs(a / b - 1.0)


class Agreement:
    """Collects the largest relative difference of each quantity and whether it is in tolerance."""

    def __init__(self):
        self.worst = {}
        self.failures = []
        self.counts = {}
        self.both_absent = {}

    def check(self, what, ours, theirs, tol, where):
        if ours is None or theirs is None:
            if (ours is None) != (theirs is None):
                self.failures.append(f"{where} {what}: thermonav {ours}, Python {theirs}")
            else:
                self.both_absent[what] = self.both_absent.get(what, 0) + 1
            return
        self.counts[what] = self.counts.get(what, 0) + 1
        ours, theirs = np.atleast_1d(np.asarray(ours, float)), np.atleast_1d(np.asarray(theirs, float))
        if ours.shape != theirs.shape:
            self.failures.append(f"{where} {what}: shapes {ours.shape} and {theirs.shape}")
            return
        d = float(np.max(np.abs(ours / theirs - 1.0))) if ours.size else 0.0
        self.worst[what] = max(self.worst.get(what, (0.0, tol))[0], d), tol
        if not d <= tol:
            self.failures.append(f"{where} {what}: max rel diff {d:.2e} > {tol:g}")


def gm_values(estimate):
    """A bank Gauss-Markov estimate as (Tc, sigma, [lo, hi]), or None for no_equivalent."""
    if estimate is None or estimate.get("status") != "model":
        return None
    return estimate


# Tolerances (relative), and why:
TOLERANCES = {
    # Our rate comes from integer-nanosecond intervals, the Python user's from differences of the
    # t_s column as doubles: at t ~ 1e4 s each difference carries ~1e4 x 2.2e-16 s of rounding
    # against a 5 ms interval, 5e-10 relative; tau = m / rate inherits it.
    "rate, tau": 1e-9,
    # The Kaiser design depends on the rate only through the transition's share of Nyquist, which
    # sets an integer tap count; beta depends on the attenuation alone: the same numbers.
    "taps, beta, factor": 1e-12,
    "temperature": 1e-12,
    # Same data, same definition, different summation order (our blocked sweep against
    # allantools' cumulative sum): 1e-9 as in compare.py's Allan section.
    "adev": 1e-9,
    # N and B are products/geometric means of adev points on the same region: as adev, if the
    # same region is chosen (a different region would be a ~10 % difference).
    "N, B": 1e-9,
    # The same taps (kaiserord/firwin; our design is checked against SciPy to 1e-12) and the same
    # kept samples, convolved by direct sums against upfirdn: 1e-12 per sample; but the taps are
    # designed for the rate, which differs by up to ~5e-10 (above), and Burg on a slowly
    # decorrelating series (c1 near 1) amplifies both; Tc = -dt/ln c1 amplifies by 1/|ln c1|.
    # 1e-8 (compare.py has 1e-9 with the rate the same on both sides). Measured on the demo-sized
    # campaign of 2026-12-03: 3.6e-9 (coefficients), 4.7e-10 (Tc, sigma).
    "AR coefficients, noise variance": 1e-8,
    "AR-based Tc, sigma, interval": 1e-8,
    # Gauss-Newton to 1e-14 against curve_fit's Levenberg-Marquardt to 1e-14 on the same points:
    # both at the least-squares minimum; 1e-6 allows for its flatness in b.
    "ACF-fit Tc, sigma": 1e-6,
    # Two optimisers (our Nelder-Mead stopping at 1e-10 relative in the log-likelihood, SciPy's
    # at 1e-6 absolute in (ln Tc, ln rho) and the likelihood) on the same exact likelihood: the
    # maximum is flat (a change of 1 % in Tc costs ~ (0.01/sd(ln Tc))^2/2 of log-likelihood,
    # sd(ln Tc) 0.1-0.5 here), so 1 % on Tc and sigma; the interval's ends are bisected to 2e-3 in
    # ln Tc on both sides, from profiles maximised to 1e-4 in ln rho: 1 % as well.
    "exact-ML Tc, sigma": 1e-2,
    "exact-ML 95 % interval": 1e-2,
}


def compare(entries, bank):
    agreement = Agreement()
    by_source = {os.path.basename(e["source"].split(":")[0]): e for e in bank["entries"]}
    for path, py in entries:
        ours = by_source[os.path.basename(path)]
        where = os.path.basename(path)
        pre = ours["preprocessing"]
        agreement.check("rate, tau", pre["input_rate_hz"], py["input_rate_hz"], TOLERANCES["rate, tau"], where)
        agreement.check("taps, beta, factor", [pre["filter"]["num_taps"], pre["filter"]["beta"], pre["decimation_factor"]],
                        [py["num_taps"], py["beta"], py["decimation_factor"]], TOLERANCES["taps, beta, factor"], where)
        agreement.check("temperature", ours["temperature_c"], py["temperature_c"], TOLERANCES["temperature"], where)
        for channel, p in py["channels"].items():
            o = ours["channels"][channel]
            at = f"{where} {channel}"
            n_common = min(len(o["allan"]["adev"]), len(p["allan"]["adev"]))
            agreement.check("rate, tau", o["allan"]["tau_s"][:n_common], p["allan"]["tau_s"][:n_common],
                            TOLERANCES["rate, tau"], at)
            agreement.check("adev", o["allan"]["adev"][:n_common], p["allan"]["adev"][:n_common], TOLERANCES["adev"], at)
            for term in ("white_noise_density", "bias_instability", "bias_instability_at_most"):
                agreement.check("N, B", o["allan"].get(term), p["allan"][term], TOLERANCES["N, B"], f"{at} {term}")
            ar = o["ar"]
            if len(ar["coefficients"]) != p["ar"]["order"]:
                agreement.failures.append(f"{at}: AR order {len(ar['coefficients'])} against {p['ar']['order']}")
            else:
                agreement.check("AR coefficients, noise variance", ar["coefficients"] + [ar["noise_variance"]],
                                list(p["ar"]["coefficients"]) + [p["ar"]["noise_variance"]],
                                TOLERANCES["AR coefficients, noise variance"], at)
            for key, label in (("ar_based", "AR-based Tc, sigma, interval"), ("acf_fit", "ACF-fit Tc, sigma"),
                               ("irregular_ml", "exact-ML Tc, sigma")):
                mine, theirs = gm_values(o["gauss_markov"][key]), p[key]
                if mine is None or theirs is None:
                    agreement.check(label, mine, theirs, 0, f"{at} {key}")
                    continue
                values = lambda e: [e["correlation_time_s"], e["sigma"]]
                agreement.check(label, values(mine), values(theirs), TOLERANCES[label], f"{at} {key}")
                if key == "acf_fit":
                    continue  # no interval: the ACF values are correlated
                ci_label = "exact-ML 95 % interval" if key == "irregular_ml" else label
                for lo_hi in (0, 1):
                    agreement.check(ci_label, mine["ci95_correlation_time_s"][lo_hi],
                                    theirs["ci95_correlation_time_s"][lo_hi], TOLERANCES[ci_label], f"{at} {key} ci")
    return agreement


# ---------------------------------------------------------------- the campaign and the table

def simulate_campaign(folder, temperatures, duration_s, rate_hz):
    subprocess.run([THERMONAV, "simulate", "chamber", "--out", folder, "--temperatures-c",
                    ",".join(map(str, temperatures)), "--duration-s", str(duration_s), "--rate-hz", str(rate_hz)],
                   check=True, capture_output=True)
    return sorted(os.path.join(folder, f) for f in os.listdir(folder) if f.startswith("imu_") and f.endswith(".csv"))


def cpu_model():
    with open("/proc/cpuinfo") as cpuinfo:
        names = [line.split(":", 1)[1].strip() for line in cpuinfo if line.startswith("model name")]
    return names[0] if names else platform.machine()


def campaign_paths(args, tmp):
    """The files given, or a campaign simulated into `tmp` as the options say."""
    if args.files:
        return args.files
    temperatures = [float(t) for t in args.temperatures_c.split(",")]
    return simulate_campaign(os.path.join(tmp, "campaign"), temperatures, args.duration_s, args.rate_hz)


def pandas_read(paths):
    """Wall and CPU time of pandas.read_csv of every file, one after the other; the row count."""
    cpu0, t0 = time.process_time(), time.perf_counter()
    rows = sum(len(pd.read_csv(p)) for p in paths)
    return time.perf_counter() - t0, time.process_time() - cpu0, rows


def read_ratio(args):
    """`thermonav characterize` against pandas reading the same files, the two alternating so
    that both see the same machine; every run printed, then the ratio of the bests."""
    with tempfile.TemporaryDirectory(dir=os.environ.get("WORKFLOW_TMP")) as tmp:
        paths = campaign_paths(args, tmp)
        megabytes = sum(os.path.getsize(p) for p in paths) / 1e6
        load_before = os.getloadavg()
        reads, ours = [], []
        for _ in range(args.repeats):
            reads.append(pandas_read(paths))
            ours.append(run_thermonav(paths, os.path.join(tmp, "bank.json"))[:2])
        load_after = os.getloadavg()
    print(f"machine: {cpu_model()}, {os.cpu_count()} cores; load average (1 min) {load_before[0]:.1f} at start, "
          f"{load_after[0]:.1f} at end; pandas {pd.__version__}")
    print(f"campaign: {len(paths)} files, {reads[0][2]} rows, {megabytes:.0f} MB of CSV")
    for k, ((read_s, read_cpu_s, _), (ours_s, ours_cpu_s)) in enumerate(zip(reads, ours)):
        print(f"run {k + 1}: pandas.read_csv {read_s:.2f} s wall ({read_cpu_s:.2f} s CPU); "
              f"thermonav characterize {ours_s:.2f} s wall ({ours_cpu_s:.2f} s CPU); ratio {ours_s / read_s:.2f}")
    best_read, best_ours = min(r[0] for r in reads), min(o[0] for o in ours)
    print(f"best of {args.repeats}: thermonav characterize / pandas read alone: {best_ours / best_read:.2f} "
          f"(issue 21 target <= 1.5)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--temperatures-c", default="-40,-20,0,20,40,60",
                        help="set points of the simulated campaign (one file each)")
    parser.add_argument("--duration-s", type=float, default=10800, help="record length per file")
    parser.add_argument("--rate-hz", type=float, default=200)
    parser.add_argument("--processes", type=int, default=0,
                        help="also time the Python workflow with this many worker processes (files in parallel)")
    parser.add_argument("--read-only", action="store_true",
                        help="time only pandas.read_csv of the files against thermonav characterize, alternating, "
                             "best of --repeats each (issue 21's read ratio; no Python workflow, no agreement check)")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each side with --read-only")
    parser.add_argument("files", nargs="*", help="IMU CSV files instead of a simulated campaign")
    args = parser.parse_args()
    if args.read_only:
        read_ratio(args)
        return
    with tempfile.TemporaryDirectory(dir=os.environ.get("WORKFLOW_TMP")) as tmp:
        paths = campaign_paths(args, tmp)
        megabytes = sum(os.path.getsize(p) for p in paths) / 1e6
        load_before = os.getloadavg()
        read_s, read_cpu_s, rows = pandas_read(paths)
        python_s, python_cpu_s, entries = timed_python_workflow(paths, 1)
        parallel = timed_python_workflow(paths, args.processes) if args.processes > 1 else None
        ours_s, ours_cpu_s, bank = run_thermonav(paths, os.path.join(tmp, "bank.json"))
        no_gmwm_s, no_gmwm_cpu_s, _ = run_thermonav(paths, os.path.join(tmp, "bank-no-gmwm.json"), "--gmwm", "off")
        load_after = os.getloadavg()
    agreement = compare(list(zip(paths, entries)), bank)
    if parallel is not None:
        parallel_agreement = compare(list(zip(paths, parallel[2])), bank)
        agreement.failures += [f"{args.processes} processes: {f}" for f in parallel_agreement.failures]
    print(f"machine: {cpu_model()}, {os.cpu_count()} cores; load average (1 min) {load_before[0]:.1f} at start, "
          f"{load_after[0]:.1f} at end; python {platform.python_version()}, pandas {pd.__version__}, "
          f"numpy {np.__version__}, scipy {scipy.__version__}")
    print(f"campaign: {len(paths)} files, {rows} rows, {megabytes:.0f} MB of CSV")
    print(f"{'step':<58} {'wall s':>8} {'CPU s':>8} {'ratio to thermonav':>19}")
    steps = [("pandas.read_csv of every file, alone", read_s, read_cpu_s),
             ("Python workflow (read, SciPy, allantools, statsmodels)", python_s, python_cpu_s)]
    if parallel is not None:
        steps.append((f"Python workflow, {args.processes} processes (files in parallel)", parallel[0], parallel[1]))
    steps += [("thermonav characterize (defaults, whole command)", ours_s, ours_cpu_s),
              ("thermonav characterize --gmwm off", no_gmwm_s, no_gmwm_cpu_s)]
    for step, wall, cpu in steps:
        print(f"{step:<58} {wall:8.2f} {'' if cpu is None else f'{cpu:8.2f}':>8} {wall / ours_s:19.2f}")
    print(f"thermonav characterize / pandas read alone: {ours_s / read_s:.2f} (issue 21 target <= 1.5); "
          f"Python workflow / thermonav: {python_s / ours_s:.1f} (target >= 20)"
          + (f", {args.processes}-process Python workflow / thermonav: {parallel[0] / ours_s:.1f}" if parallel else ""))
    print("Python workflow (one process) by stage, wall s: " + "; ".join(
        f"{stage} {sum(e['stages_s'][stage] for e in entries):.2f}" for stage in STAGES))
    print("agreement (largest relative difference over files and channels, tolerance):")
    for what, (worst, tol) in agreement.worst.items():
        absent = agreement.both_absent.get(what, 0)
        print(f"  {what:<36} {worst:9.1e}  (tol {tol:g}; {agreement.counts[what]} compared"
              + (f", {absent} absent on both sides)" if absent else ")"))
    for failure in agreement.failures:
        print(f"  DISAGREES: {failure}")
    print("agree: " + ("yes" if not agreement.failures else f"NO ({len(agreement.failures)} differences)"))
    sys.exit(1 if agreement.failures else 0)


if __name__ == "__main__":
    main()
