#!/usr/bin/env python3
"""Oracle values for the Haar wavelet-variance tests (crates/thermonav/tests/it/wavelet_variance.rs).

Generated ONCE with: Python 3.11, numpy 2.4.6, allantools 2024.6.
Output: crates/thermonav/tests/data/wavelet_variance.json. Run from the repository root, with the
shared data folder beside the repository (../shared/data).

The Haar MODWT wavelet variance at scale tau_j = 2^j samples equals half the overlapping Allan
variance at averaging factor m = 2^(j-1) = tau_j / 2 (the Haar filter of width 2^j differences two
adjacent means of 2^(j-1) samples and divides by 2). allantools has no wavelet variance, so the
oracle is allantools.oadev(y, rate, data_type='freq', taus=m * tau0) squared, halved here in
Python; the Rust test compares its wavelet variance with these numbers.

Contents:
- generated: a series of 4000 samples (numpy default_rng(20130502): white noise + random walk +
  AR(1) + offset 3.7) stored in full, rate 50 Hz, with allantools oadev at every octave m;
- adis_16405_imu2: allantools oadev of each of the six channels of the real ADIS16405 run 2
  (shared/data/smac-imudata/adis_16405_imu2.csv.gz), 100 Hz, octave m.
"""
import gzip
import json
import pathlib

import allantools
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data"
OUT = ROOT / "crates" / "thermonav" / "tests" / "data" / "wavelet_variance.json"


def octave_rows(y, rate):
    m = 1
    rows = []
    while 2 * m <= len(y):
        taus, devs, _, ns = allantools.oadev(y, rate=rate, data_type="freq", taus=[m / rate])
        rows.append({"m": m, "n_terms": int(ns[0]), "oadev": float(devs[0]),
                     "haar_wv": float(devs[0]) ** 2 / 2.0})
        m *= 2
    return rows


def generated():
    rng = np.random.default_rng(20130502)
    n = 4000
    ar = np.zeros(n)
    e = rng.standard_normal(n)
    for k in range(1, n):
        ar[k] = 0.9 * ar[k - 1] + 0.3 * e[k]
    y = 3.7 + rng.standard_normal(n) + np.cumsum(0.05 * rng.standard_normal(n)) + ar
    return {"rate_hz": 50.0, "y": [float(v) for v in y], "rows": octave_rows(y, 50.0)}


def adis():
    with gzip.open(SHARED / "smac-imudata" / "adis_16405_imu2.csv.gz", "rt") as f:
        header = f.readline().strip().split(",")
        data = np.loadtxt(f, delimiter=",")
    return {name: octave_rows(data[:, i], 100.0) for i, name in enumerate(header)}


def main():
    out = {
        "generator": "tools/oracles/wavelet_variance.py; numpy 2.4.6, allantools 2024.6",
        "generated": generated(),
        "adis_16405_imu2": adis(),
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
