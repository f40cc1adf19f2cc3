"""Burg and Yule-Walker AR(4): thermonav vs statsmodels on the same 2.16 M samples.

    python3 bench/ar_vs_statsmodels.py [N]

Generates N (default 2 160 000 = 6 h at 100 Hz) samples of an AR(4) process plus an offset
(numpy default_rng(2009), scipy.signal.lfilter), writes them as raw little-endian f64 to a
temporary file, times statsmodels `burg(x, 4)` and `yule_walker(x, 4, method='mle')` (best of 3,
mean removal included), runs `cargo run --release -p thermonav --example ar_timing -- FILE 4`
(best of 3 per method, mean removal and validation included), checks that the coefficients and
innovation variances agree, and prints the speed ratios. Target: Burg >= 20x faster.
"""

import json
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np
import scipy.signal
import statsmodels
from statsmodels.regression.linear_model import burg, yule_walker

warnings.simplefilter("ignore", FutureWarning)

ORDER = 4
COEFFICIENTS = [0.7, -0.2, 0.1, 0.05]
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def simulate(n):
    rng = np.random.default_rng(2009)
    w = rng.standard_normal(n + 1000)
    y = scipy.signal.lfilter([1.0], [1.0] + [-c for c in COEFFICIENTS], w)
    return 0.35 + y[1000:]


def best_of_three(f):
    best, result = float("inf"), None
    for _ in range(3):
        start = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - start)
    return best, result


def run_thermonav(path):
    subprocess.run(
        ["cargo", "build", "--release", "-q", "-p", "thermonav", "--example", "ar_timing"],
        cwd=REPO, check=True,
    )
    out = subprocess.run(
        ["cargo", "run", "--release", "-q", "-p", "thermonav", "--example", "ar_timing", "--", path, str(ORDER)],
        cwd=REPO, check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)


def compare(name, ours, their_seconds, their_phi, their_sigma2):
    phi_diff = np.max(np.abs(np.array(ours["coefficients"]) - their_phi))
    var_rel = abs(ours["noise_variance"] / their_sigma2 - 1.0)
    ratio = their_seconds / ours["seconds"]
    ok = phi_diff < 1e-9 and var_rel < 1e-9
    print(f"{name:12s} statsmodels {their_seconds * 1e3:8.2f} ms   thermonav {ours['seconds'] * 1e3:7.2f} ms"
          f"   ratio {ratio:6.1f}x   max|dphi| {phi_diff:.1e}   rel dsigma2 {var_rel:.1e}   {'agree' if ok else 'DISAGREE'}")
    return ok, ratio


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2_160_000
    x = simulate(n)
    print(f"N = {n}, AR({ORDER}) c = {COEFFICIENTS} + 0.35, statsmodels {statsmodels.__version__}, numpy {np.__version__}")
    with tempfile.NamedTemporaryFile(suffix=".f64", delete=False) as f:
        x.astype("<f8").tofile(f)
        path = f.name
    try:
        ours = run_thermonav(path)["fits"]
    finally:
        os.unlink(path)
    t_burg, (phi_burg, sigma2_burg) = best_of_three(lambda: burg(x, ORDER))
    t_yw, (phi_yw, sigma_yw) = best_of_three(lambda: yule_walker(x, ORDER, method="mle"))
    ok_burg, ratio_burg = compare("burg", ours["burg"], t_burg, phi_burg, sigma2_burg)
    ok_yw, _ = compare("yule-walker", ours["yule-walker"], t_yw, phi_yw, sigma_yw**2)
    for name in ("covariance", "modified-covariance"):
        print(f"{name:20s} thermonav {ours[name]['seconds'] * 1e3:7.2f} ms (no statsmodels counterpart timed)")
    target = ratio_burg >= 20.0
    print(f"Burg speed target (>= 20x): {'met' if target else 'NOT met'}")
    sys.exit(0 if ok_burg and ok_yw and target else 1)


if __name__ == "__main__":
    main()
