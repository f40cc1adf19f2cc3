#!/usr/bin/env python3
"""Oracle values for the Allan-family tests (crates/thermonav/tests/it/allan_family.rs and the
CLI test of `allan --kind`).

Generated ONCE with: Python 3.11.7, numpy 2.4.6, allantools 2024.6.
Output: crates/thermonav/tests/data/allan_family.json. Run from the repository root, with the
shared data folder beside the repository (../shared/data).

Every deviation is allantools' own, called on rate (frequency) data:
    allantools.<kind>(y, rate=rate_hz, data_type='freq', taus=...)
for kind in mdev, hdev, ohdev, tdev, totdev. allantools integrates y to phase
x = tau0 * cumsum(y - mean(y)) (N + 1 points, x_0 = 0) and works on x; tdev is
tau * mdev / sqrt(3), in the data's unit times seconds. Each entry stores the averaging factors
m = tau * rate, allantools' term counts ("ns") and the deviations.

Series:
- adis_16405_imu1_gyro_x: ../shared/data/smac-imudata/adis_16405_imu1.csv.gz column Gyro_X
  (deg/s, 10^6 samples at 100 Hz; real data, CC BY-NC-SA 4.0: tests only), octave grid. Not
  stored here: the test reads the shared file.
- nbs14_1000: ../shared/data/allantools/nbs14/nbs14_1000_frequency.txt at 1 Hz, octave grid and
  explicit taus 1, 3, 10, 33, 100, 250 s. Not stored here.
- pink_frequency: ../shared/data/allantools/pink_frequency/pink_frequency.txt at rate 1/42 Hz
  (tau0 = 42 s), octave grid. Not stored here.
- white_fm, random_walk_fm, flicker_fm: generated here with numpy.random.default_rng(seed) and
  stored in full (repr of each float64, so they read back bit for bit):
    white_fm: 5000 standard normal samples + 3.0 (a bias), 10 Hz;
    random_walk_fm: cumulative sum of 4096 standard normal samples, 1 Hz;
    flicker_fm: 4096 samples with a 1/f power spectrum (white noise shaped by 1/sqrt(f) in the
      frequency domain, numpy.fft.irfft), 2 Hz.
  Each on the octave grid and on explicit factors (m = 1, 3, 7, 10, 33, 100, 333).
"""
import gzip
import json
import pathlib

import allantools
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data"
OUT = ROOT / "crates" / "thermonav" / "tests" / "data" / "allan_family.json"

KINDS = ("mdev", "hdev", "ohdev", "tdev", "totdev")
EXPLICIT_FACTORS = [1, 3, 7, 10, 33, 100, 333]


def deviations(y, rate_hz, taus):
    """Each kind of allantools on y (frequency data) at taus ('octave' or seconds)."""
    out = {}
    for kind in KINDS:
        fn = getattr(allantools, kind)
        t, dev, _, ns = fn(np.asarray(y), rate=rate_hz, data_type="freq", taus=taus)
        out[kind] = {"m": [int(round(v * rate_hz)) for v in t],
                     "n_terms": [int(n) for n in ns],
                     "deviation": [float(d) for d in dev]}
    return out


def grids(y, rate_hz, factors):
    explicit = [m / rate_hz for m in factors]
    return {"octave": deviations(y, rate_hz, "octave"),
            "explicit": deviations(y, rate_hz, explicit)}


def adis_gyro_x():
    with gzip.open(SHARED / "smac-imudata" / "adis_16405_imu1.csv.gz", "rt") as f:
        y = np.loadtxt(f, delimiter=",", skiprows=1, usecols=0)
    return {"source": "smac-imudata/adis_16405_imu1.csv.gz", "column": "Gyro_X",
            "unit": "deg/s", "rate_hz": 100.0,
            "octave": deviations(y, 100.0, "octave")}


def nbs14():
    y = np.loadtxt(SHARED / "allantools" / "nbs14" / "nbs14_1000_frequency.txt")
    return {"source": "allantools/nbs14/nbs14_1000_frequency.txt", "unit": "1",
            "rate_hz": 1.0,
            "octave": deviations(y, 1.0, "octave"),
            "explicit": deviations(y, 1.0, [1.0, 3.0, 10.0, 33.0, 100.0, 250.0])}


def pink():
    y = np.loadtxt(SHARED / "allantools" / "pink_frequency" / "pink_frequency.txt")
    return {"source": "allantools/pink_frequency/pink_frequency.txt", "unit": "1",
            "rate_hz": 1.0 / 42.0, "octave": deviations(y, 1.0 / 42.0, "octave")}


def flicker(rng, n):
    white = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n)
    shaping = np.zeros_like(f)
    shaping[1:] = 1.0 / np.sqrt(f[1:])
    return np.fft.irfft(white * shaping, n)


def generated():
    series = {
        "white_fm": (np.random.default_rng(20261101).standard_normal(5000) + 3.0, 10.0),
        "random_walk_fm": (np.cumsum(np.random.default_rng(20261102).standard_normal(4096)), 1.0),
        "flicker_fm": (flicker(np.random.default_rng(20261103), 4096), 2.0),
    }
    out = {}
    for name, (y, rate_hz) in series.items():
        entry = {"rate_hz": rate_hz, "unit": "1", "y": [float(v) for v in y]}
        entry.update(grids(y, rate_hz, EXPLICIT_FACTORS))
        out[name] = entry
    return out


def main():
    out = {
        "generator": "tools/oracles/allan_family.py; Python 3.11.7, numpy 2.4.6, allantools 2024.6",
        "call": "allantools.<kind>(y, rate=rate_hz, data_type='freq', taus='octave' or m/rate_hz)",
        "adis_16405_imu1_gyro_x": adis_gyro_x(),
        "nbs14_1000": nbs14(),
        "pink_frequency": pink(),
        "generated": generated(),
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
