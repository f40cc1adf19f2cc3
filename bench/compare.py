"""Side-by-side timing of thermonav and the Python peers on the same data (see compare.sh).

Each section writes the data once to a raw little-endian float64 file, times the peer (best of
3), runs the thermonav example that times the same operation (best of 3), checks the results
agree, and prints the ratio peer_time / thermonav_time.
"""
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
from scipy import signal

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "target", "release", "examples")


def best_of(n, f):
    best = float("inf")
    out = None
    for _ in range(n):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def run_example(name, *args):
    out = subprocess.run([os.path.join(EXAMPLES, name), *map(str, args)], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_signal(n, seed=2009):
    rng = np.random.default_rng(seed)
    k = np.arange(n)
    return np.sin(0.01 * k) + 0.3 * rng.standard_normal(n)


def section_filter(n, tmp, rows):
    fs, cutoff, width, ripple = 200.0, 5.0, 1.0, 60.0
    numtaps, beta = signal.kaiserord(ripple, width / (fs / 2))
    taps = signal.firwin(numtaps, cutoff, window=("kaiser", beta), fs=fs)
    x = test_signal(n)
    path = os.path.join(tmp, "filter.f64")
    x.astype("<f8").tofile(path)
    peer_s, y_peer = best_of(3, lambda: signal.filtfilt(taps, [1.0], x))
    ours = run_example("filter_timing", path, fs, cutoff, width, ripple, os.path.join(tmp, "filter"))
    y_ours = np.fromfile(os.path.join(tmp, "filter.filtfilt.f64"), dtype="<f8")
    diff = float(np.max(np.abs(y_ours - y_peer)))
    agree = diff < 1e-9
    rows.append((f"Kaiser {numtaps} taps, filtfilt, {n} samples", "scipy.signal.filtfilt", peer_s,
                 ours["filtfilt_s"], agree, f"max |diff| {diff:.1e}"))
    rows.append((f"Kaiser {numtaps} taps, zero-phase one pass, {n} samples", "scipy.signal.filtfilt",
                 peer_s, ours["zero_phase_s"], agree, "same data; one pass vs two"))


def section_allan(n, tmp, rows):
    import allantools
    y = test_signal(n, seed=7) * 1e-3
    path = os.path.join(tmp, "allan.f64")
    y.astype("<f8").tofile(path)
    ours = run_example("allan_timing", path, 200.0, os.path.join(tmp, "allan"))
    for grid in ("octave", "decade"):
        peer_s, res = best_of(3, lambda: allantools.oadev(y, rate=200.0, data_type="freq", taus=grid))
        mine = np.fromfile(os.path.join(tmp, f"allan.{grid}.f64"), dtype="<f8")
        n_common = min(len(mine), len(res[1]))
        rel = float(np.max(np.abs(mine[:n_common] / res[1][:n_common] - 1))) if n_common else float("nan")
        agree = n_common == len(res[1]) and rel < 1e-9
        rows.append((f"overlapping ADEV, {grid}, {n} samples, {ours['threads']} threads", "allantools.oadev", peer_s,
                     ours[f"{grid}_s"], agree, f"{n_common} taus, max rel diff {rel:.1e}"))
        rows.append((f"overlapping ADEV, {grid}, {n} samples, 1 thread", "allantools.oadev", peer_s,
                     ours[f"{grid}_1t_s"], agree, "same curve, one-thread rayon pool"))


def section_ar(n, tmp, rows):
    from statsmodels.regression.linear_model import burg, yule_walker
    rng = np.random.default_rng(11)
    e = rng.standard_normal(n)
    x = signal.lfilter([1.0], [1.0, -0.9, 0.2], e)
    path = os.path.join(tmp, "ar.f64")
    x.astype("<f8").tofile(path)
    ours = run_example("ar_timing", path)
    peer_s, (phi, _) = best_of(3, lambda: burg(x, 4))
    agree = np.allclose(phi, ours["burg_phi"], atol=1e-9)
    rows.append((f"Burg AR(4), {n} samples", "statsmodels burg", peer_s, ours["burg_s"], agree, "coefficients to 1e-9"))
    peer_s, (phi, _) = best_of(3, lambda: yule_walker(x, 4, method="mle"))
    agree = np.allclose(phi, ours["yule_walker_phi"], atol=1e-9)
    rows.append((f"Yule-Walker AR(4), {n} samples", "statsmodels yule_walker", peer_s, ours["yule_walker_s"], agree,
                 "coefficients to 1e-9"))


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2_160_000
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        section_filter(n, tmp, rows)
        section_allan(n, tmp, rows)
        section_ar(n, tmp, rows)
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; "
          f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}")
    print(f"{'operation':<55} {'peer':<24} {'peer s':>9} {'ours s':>9} {'ratio':>7}  agree")
    failed = False
    for op, peer, peer_s, ours_s, agree, note in rows:
        print(f"{op:<55} {peer:<24} {peer_s:9.4f} {ours_s:9.4f} {peer_s / ours_s:7.1f}  {'yes' if agree else 'NO'} ({note})")
        failed |= not agree
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
