#!/usr/bin/env python3
"""Speed and agreement of thermonav's octave overlapping Allan deviation vs allantools.

Generates 2 160 000 samples (seeded white noise plus a random walk and an offset, like a
gyro rate at 100 Hz), writes them as raw little-endian f64, times allantools
`oadev(y, rate=100, data_type='freq', taus='octave')` (best of 3), runs
`cargo run --release -p thermonav --example allan_timing -- FILE 100` (best of 5 inside),
checks m, term counts and values (1e-9 relative) and prints the speed ratio.
Run from the repository root. Needs numpy and allantools.
"""
import subprocess
import sys
import tempfile
import time

import allantools
import numpy as np

N_SAMPLES = 2_160_000
RATE_HZ = 100.0


def make_series():
    rng = np.random.default_rng(2024)
    white = rng.standard_normal(N_SAMPLES) * 0.05
    walk = np.cumsum(rng.standard_normal(N_SAMPLES)) * 1e-5
    return 0.4 + white + walk


def time_allantools(y):
    best, result = float("inf"), None
    for _ in range(3):
        start = time.perf_counter()
        result = allantools.oadev(y, rate=RATE_HZ, data_type="freq", taus="octave")
        best = min(best, time.perf_counter() - start)
    return best, result


def run_thermonav(path):
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--release", "-p", "thermonav", "--example",
         "allan_timing", "--", path, str(RATE_HZ)],
        check=True, capture_output=True, text=True).stdout.split("\n")
    elapsed = float(out[0].split()[1])
    rows = [line.split() for line in out[1:] if line.strip()]
    return elapsed, [(int(r[0]), int(r[1]), float(r[2])) for r in rows]


def main():
    y = make_series()
    with tempfile.NamedTemporaryFile(suffix=".f64") as f:
        y.astype("<f8").tofile(f.name)
        ours_s, rows = run_thermonav(f.name)
    theirs_s, (taus, devs, _, ns) = time_allantools(y)
    ms = [int(round(t * RATE_HZ)) for t in taus]
    if [r[0] for r in rows] != ms or [r[1] for r in rows] != [int(n) for n in ns]:
        sys.exit(f"averaging factors or term counts differ: {rows} vs {ms} {ns}")
    worst = max(abs(r[2] - d) / d for r, d in zip(rows, devs))
    if worst > 1e-9:
        sys.exit(f"values differ: worst relative difference {worst:.3e}")
    print(f"{N_SAMPLES} samples, {len(ms)} octave taus; values agree (worst {worst:.1e} relative)")
    print(f"allantools {theirs_s * 1e3:.1f} ms, thermonav {ours_s * 1e3:.2f} ms, "
          f"ratio {theirs_s / ours_s:.1f}x")


if __name__ == "__main__":
    main()
