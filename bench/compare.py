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


def best_of(n, f, clock=time.perf_counter):
    best = float("inf")
    out = None
    for _ in range(n):
        t0 = clock()
        out = f()
        best = min(best, clock() - t0)
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


def gauss_markov_channels(n, rate_hz, seed=1934):
    """Six static channels: a first-order Gauss-Markov bias (Tc 60-600 s) plus white noise."""
    rng = np.random.default_rng(seed)
    channels = []
    for k, (tc_s, sigma, white) in enumerate([(60, 2e-3, 1e-2), (150, 1e-3, 1e-2), (600, 5e-4, 5e-3),
                                              (90, 5e-3, 3e-2), (300, 3e-3, 2e-2), (450, 2e-3, 2e-2)]):
        a = np.exp(-1.0 / (tc_s * rate_hz))
        bias = signal.lfilter([sigma * np.sqrt(1 - a * a)], [1.0, -a], rng.standard_normal(n))
        channels.append(bias + white * rng.standard_normal(n) + (-9.80665 if k == 5 else 0.0))
    return np.array(channels)


def kaiser_taps_odd(fs, cutoff, width, ripple):
    """SciPy's kaiserord + firwin, with one tap more when the count is even (as characterize)."""
    numtaps, beta = signal.kaiserord(ripple, width / (fs / 2))
    numtaps += 1 - numtaps % 2
    return signal.firwin(numtaps, cutoff, window=("kaiser", beta), fs=fs)


def ar_based_numpy(x, taps, factor, dt_s, kept_only=True):
    """The paper's pipeline in NumPy/SciPy: odd extension by 3 N at each end (SciPy's filtfilt
    padding), one FIR pass read (N-1)/2 samples later (zero phase), every factor-th sample,
    statsmodels Burg AR(1), Tc = -dt/ln c1, sigma^2 = var(w)/(1 - c1^2). Like thermonav, only
    the kept samples are filtered: scipy.signal.upfirdn(taps, x, down=factor) evaluates the full
    convolution at multiples of factor, so the input is first trimmed by (pad + delay) mod factor
    samples to put the wanted samples on that grid. With kept_only=False the whole record is
    convolved (scipy.signal.oaconvolve) and then decimated: the pipeline as usually written."""
    from statsmodels.regression.linear_model import burg
    n, pad, delay = len(x), 3 * len(taps), (len(taps) - 1) // 2
    extended = np.concatenate((2 * x[0] - x[pad:0:-1], x, 2 * x[-1] - x[-2:-pad - 2:-1]))
    if kept_only:
        skip = (pad + delay) % factor
        first, kept = (pad + delay - skip) // factor, -(-n // factor)
        conditioned = signal.upfirdn(taps, extended[skip:], up=1, down=factor)[first:first + kept]
    else:
        full = signal.oaconvolve(extended, taps, mode="full")[pad + delay:pad + delay + n]
        conditioned = full[::factor]
    rho, sigma2 = burg(conditioned, 1)
    c1 = float(rho[0])
    return c1, -dt_s / np.log(c1), float(np.sqrt(sigma2 / (1 - c1 * c1)))


def section_pipeline(n, tmp, rows):
    fs, cutoff, width, ripple, modelling_hz = 200.0, 0.4, 0.2, 60.0, 1.0
    data = gauss_markov_channels(n, fs)
    path = os.path.join(tmp, "pipeline.f64")
    data.astype("<f8").tofile(path)
    taps = kaiser_taps_odd(fs, cutoff, width, ripple)
    factor = int(round(fs / modelling_hz))
    peer_s, fits = best_of(3, lambda: [ar_based_numpy(x, taps, factor, factor / fs) for x in data])
    full_s, full_fits = best_of(3, lambda: [ar_based_numpy(x, taps, factor, factor / fs, kept_only=False)
                                            for x in data])
    ours = run_example("gm_pipeline_timing", path, fs, cutoff, width, ripple, modelling_hz)
    peer = np.array(fits).T
    mine = np.array([ours["c1"], ours["correlation_time_s"], ours["sigma"]])
    rel = np.abs(mine / peer - 1)
    # Same arithmetic in another order (FFT sizes, summation): the filtered samples differ by
    # ~1e-15 relative, the Burg sums over ~1e4 of them by ~1e-13, and Tc = -dt/ln c1 amplifies a
    # relative change of c1 by 1/|ln c1| (about 11 for the largest c1 here, 0.91): 1e-9 leaves
    # four orders of margin and still catches a different filter, rate or estimator.
    agree = len(taps) == ours["num_taps"] and float(rel.max()) < 1e-9
    note = (f"{len(taps)} taps, /{factor}; max rel diff c1 {rel[0].max():.1e}, Tc {rel[1].max():.1e}, "
            f"sigma {rel[2].max():.1e}; Tc {peer[1].min():.0f}-{peer[1].max():.0f} s")
    op = f"AR-based GM, 6 channels x {n} samples"
    rows.append((f"{op}, {ours['threads']} threads", "NumPy/SciPy/statsmodels", peer_s, ours["pipeline_s"], agree, note))
    rows.append((f"{op}, 1 thread", "NumPy/SciPy/statsmodels", peer_s, ours["pipeline_1t_s"], agree,
                 "same, one-thread rayon pool"))
    full_rel = float(np.abs(np.array(full_fits).T / peer - 1).max())
    rows.append((f"{op}, 2 threads", "same, full oaconvolve then [::F]", full_s, ours["pipeline_s"],
                 agree and full_rel < 1e-9, f"peer filters every sample; max rel diff to upfirdn {full_rel:.1e}"))
    return data


def write_imu_csv(path, data, rate_hz):
    """The canonical IMU CSV of the six channels, 9 significant digits, time to the nanosecond."""
    import pandas as pd
    n = data.shape[1]
    frame = pd.DataFrame({"t_s": np.arange(n) / rate_hz})
    for k, name in enumerate(["gx_rad_s", "gy_rad_s", "gz_rad_s", "ax_m_s2", "ay_m_s2", "az_m_s2"]):
        frame[name] = data[k]
    frame["temp_c"] = 20.0 + 0.5 * np.sin(np.arange(n) / (3600 * rate_hz))
    frame["t_s"] = frame["t_s"].map("{:.9f}".format)
    frame.to_csv(path, index=False, float_format="%.9g")


def section_csv(data, tmp, rows):
    import pandas as pd
    path = os.path.join(tmp, "imu.csv")
    write_imu_csv(path, data, 200.0)
    megabytes = os.path.getsize(path) / 1e6
    peer_s, frame = best_of(3, lambda: pd.read_csv(path, engine="c"))
    peer_cpu_s, _ = best_of(3, lambda: pd.read_csv(path, engine="c"), clock=time.process_time)
    ours = run_example("imu_csv_timing", path, os.path.join(tmp, "imu"))
    mine = np.fromfile(os.path.join(tmp, "imu.f64"), dtype="<f8").reshape(8, -1)
    theirs = frame.to_numpy().T
    # pandas' default C parser (float_precision=None) may be 1 ulp off the correctly rounded
    # value, ours is correctly rounded (times through integer nanoseconds): allow 2 ulp.
    rel = float(np.max(np.abs(mine - theirs) / np.maximum(np.abs(theirs), 1e-300)))
    agree = mine.shape == theirs.shape and rel < 4.5e-16
    note = f"{megabytes:.0f} MB, {len(frame)} rows; pandas {megabytes / peer_s:.0f} MB/s"
    rows.append((f"IMU CSV read, 2 halves on 2 threads: {megabytes / ours['read_s']:.0f} MB/s", "pandas.read_csv (C)",
                 peer_s, ours["read_s"], agree, f"{note}; max rel diff {rel:.1e}"))
    rows.append((f"IMU CSV read, 1 thread: {megabytes / ours['read_1t_s']:.0f} MB/s", "pandas.read_csv (C)",
                 peer_s, ours["read_1t_s"], agree, note))
    if "read_1t_cpu_s" in ours:
        # CPU time of the reading thread (pandas' C parser is single-threaded): MB per core-second,
        # which other builds on the machine disturb far less than wall time.
        rows.append((f"IMU CSV read, 1 thread, CPU time: {megabytes / ours['read_1t_cpu_s']:.0f} MB/s per core",
                     "pandas.read_csv (C)", peer_cpu_s, ours["read_1t_cpu_s"], agree,
                     f"pandas {megabytes / peer_cpu_s:.0f} MB/s per core"))


def cpu_model():
    """The processor's model name, as lscpu shows it."""
    with open("/proc/cpuinfo") as cpuinfo:
        names = [line.split(":", 1)[1].strip() for line in cpuinfo if line.startswith("model name")]
    return names[0] if names else platform.machine()


def main():
    """Usage: compare.py [SAMPLES] [SECTIONS]; SECTIONS is a comma-separated subset of
    filter,allan,ar,pipeline,csv (default all)."""
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2_160_000
    chosen = sys.argv[2].split(",") if len(sys.argv) > 2 else ["filter", "allan", "ar", "pipeline", "csv"]
    rows = []
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        for name, section in [("filter", section_filter), ("allan", section_allan), ("ar", section_ar)]:
            if name in chosen:
                section(n, tmp, rows)
        if "pipeline" in chosen or "csv" in chosen:
            data = section_pipeline(n, tmp, rows) if "pipeline" in chosen else gauss_markov_channels(n, 200.0)
            if "csv" in chosen:
                section_csv(data, tmp, rows)
    load_after = os.getloadavg()
    print(f"machine: {cpu_model()}, {os.cpu_count()} cores; load average (1 min) {load_before[0]:.1f} at start, "
          f"{load_after[0]:.1f} at end; python {platform.python_version()}, numpy {np.__version__}, "
          f"scipy {scipy.__version__}")
    print(f"{'operation':<62} {'peer':<24} {'peer s':>9} {'ours s':>9} {'ratio':>7}  agree")
    failed = False
    for op, peer, peer_s, ours_s, agree, note in rows:
        print(f"{op:<62} {peer:<24} {peer_s:9.4f} {ours_s:9.4f} {peer_s / ours_s:7.1f}  {'yes' if agree else 'NO'} ({note})")
        failed |= not agree
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
