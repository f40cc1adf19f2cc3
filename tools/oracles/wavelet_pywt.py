#!/usr/bin/env python3
"""Oracle values for the wavelet de-noising tests (crates/thermonav/tests/it/wavelet_denoise.rs).

Generated ONCE with: Python 3.11, numpy 2.4.6, PyWavelets 1.9.0 (pip; pywt.__version__ says 1.8.0).
Output: crates/thermonav/tests/data/wavelet_pywt.json. Run from anywhere, with the shared data
folder beside the repository (../shared/data).

Every value below is PyWavelets' (or numpy's from the published definitions), never thermonav's:
- filter_banks: pywt.Wavelet('dbN').filter_bank for N = 1..10 (dec_lo, dec_hi, rec_lo, rec_hi);
- max_level: pywt.dwt_max_level(n, filter_len) on a grid of lengths;
- transforms: pywt.wavedec(x, wavelet, mode, level) and pywt.waverec of the result, on generated
  series (stored in full, odd and even lengths) and on a slice of the real ADIS16405 run 2
  (shared/data/smac-imudata/adis_16405_imu2.csv.gz, CC BY-NC-SA: only the slice's position is
  stored here, the test reads the samples from the shared folder);
- waverec_of_random: pywt.waverec of random coefficient lists shaped like a decomposition (the
  inverse on coefficients that no signal produced, as after thresholding);
- threshold: pywt.threshold(x, value, mode) for 'soft' and 'hard';
- visushrink: the universal-threshold de-noising written out in numpy from Donoho & Johnstone
  (1994): sigma = median(|cD1|) / 0.6745, lambda = sigma sqrt(2 ln n), pywt.threshold on every
  detail band, pywt.waverec, the first n samples.
"""
import gzip
import json
import pathlib

import numpy as np
import pywt

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data"
OUT = ROOT / "crates" / "thermonav" / "tests" / "data" / "wavelet_pywt.json"
MODES = ["symmetric", "periodization"]
REAL = {"file": "smac-imudata/adis_16405_imu2.csv.gz", "column": "Gyro_X", "start": 200000,
        "length": 1001}


def floats(a):
    return [float(v) for v in np.asarray(a).ravel()]


def generated_series():
    rng = np.random.default_rng(19940901)
    series = {}
    for n in [5, 16, 33, 128, 257]:
        t = np.arange(n)
        ar = np.zeros(n)
        e = rng.standard_normal(n)
        for k in range(1, n):
            ar[k] = 0.95 * ar[k - 1] + 0.2 * e[k]
        series[f"gen{n}"] = 1.5 + np.sin(t / 9.0) + ar + 0.3 * rng.standard_normal(n)
    return series


def real_slice():
    with gzip.open(SHARED / REAL["file"], "rt") as f:
        header = f.readline().strip().split(",")
        data = np.loadtxt(f, delimiter=",", usecols=[header.index(REAL["column"])])
    return data[REAL["start"]:REAL["start"] + REAL["length"]]


def transform_case(name, x, wavelet, mode, level):
    coeffs = pywt.wavedec(x, wavelet, mode=mode, level=level)
    return {"series": name, "wavelet": wavelet, "mode": mode, "level": level,
            "coefficients": [floats(c) for c in coeffs],
            "waverec": floats(pywt.waverec(coeffs, wavelet, mode=mode))}


def transforms(series):
    """Every wavelet on the short series, three on the longer ones, the real slice at db4 and
    db8; both modes; level 1 and the maximum on the short series, the maximum on the others."""
    cases = []
    for name, x in series.items():
        if len(x) <= 33:
            wavelets = ["db1", "db2", "db3", "db5", "db7", "db10"]
        elif name.startswith("gen"):
            wavelets = ["db1", "db4", "db6", "db9"]
        else:
            wavelets = ["db4", "db8"]
        for wavelet in wavelets:
            top = pywt.dwt_max_level(len(x), pywt.Wavelet(wavelet).dec_len)
            for mode in MODES:
                for level in sorted({1, top} if len(x) <= 33 else {top}):
                    if 1 <= level <= top:
                        cases.append(transform_case(name, x, wavelet, mode, level))
    return cases


def random_reconstructions():
    rng = np.random.default_rng(7)
    cases = []
    for wavelet, n, mode, level in [("db3", 50, "symmetric", 3), ("db5", 77, "periodization", 2),
                                    ("db10", 301, "symmetric", 3), ("db1", 9, "periodization", 3)]:
        shapes = [len(c) for c in pywt.wavedec(np.zeros(n), wavelet, mode=mode, level=level)]
        coeffs = [rng.standard_normal(s) for s in shapes]
        cases.append({"wavelet": wavelet, "mode": mode, "signal_len": n,
                      "coefficients": [floats(c) for c in coeffs],
                      "waverec": floats(pywt.waverec(coeffs, wavelet, mode=mode))})
    return cases


def thresholds():
    rng = np.random.default_rng(11)
    x = np.concatenate([rng.standard_normal(40) * 2.0, [0.0, 0.7, -0.7, 1e-300]])
    return {"x": floats(x), "cases": [
        {"value": v, "mode": m, "out": floats(pywt.threshold(x, v, mode=m))}
        for v, m in [(0.0, "hard"), (0.7, "soft"), (0.7, "hard"), (1.5, "soft"), (1.5, "hard")]]}
    # (value 0 with 'soft' is left out: pywt computes 1 - 0/|x| and gives NaN for a zero sample.)


def visushrink(name, x, wavelet, mode, thresholding):
    coeffs = pywt.wavedec(x, wavelet, mode=mode)
    sigma = np.median(np.abs(coeffs[-1])) / 0.6745
    lam = sigma * np.sqrt(2.0 * np.log(len(x)))
    shrunk = [coeffs[0]] + [pywt.threshold(c, lam, mode=thresholding) for c in coeffs[1:]]
    out = pywt.waverec(shrunk, wavelet, mode=mode)[:len(x)]
    return {"series": name, "wavelet": wavelet, "mode": mode, "thresholding": thresholding,
            "level": len(coeffs) - 1, "sigma": float(sigma), "lambda": float(lam),
            "out": floats(out)}


def main():
    series = generated_series()
    series["adis2_gyro_x"] = real_slice()
    stored = {k: floats(v) for k, v in series.items() if k.startswith("gen")}
    out = {
        "generator": "tools/oracles/wavelet_pywt.py; numpy 2.4.6, PyWavelets 1.9.0",
        "real_slice": REAL,
        "series": stored,
        "filter_banks": {f"db{n}": [floats(f) for f in pywt.Wavelet(f"db{n}").filter_bank]
                         for n in range(1, 11)},
        "max_level": [[n, f, pywt.dwt_max_level(n, f)] for n in [0, 1, 2, 3, 6, 7, 8, 100, 1001,
                                                               2 ** 20 + 3] for f in [2, 8, 20]],
        "transforms": transforms(series),
        "waverec_of_random": random_reconstructions(),
        "threshold": thresholds(),
        "visushrink": [visushrink(n, series[n], w, m, t) for n, w, m, t in [
            ("gen257", "db4", "symmetric", "soft"), ("gen128", "db2", "periodization", "hard"),
            ("adis2_gyro_x", "db4", "symmetric", "soft"),
            ("adis2_gyro_x", "db8", "periodization", "hard")]],
    }
    OUT.write_text(json.dumps(out) + "\n")


if __name__ == "__main__":
    main()
