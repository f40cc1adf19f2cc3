"""Times thermonav.allan called from Python against the same Rust call and against allantools.

2.16 M samples (3 h at 200 Hz) of seeded white noise plus a random walk; octave and decade
grids; best of 3 each. The Rust call is `overlapping_adev` in the `allan_timing` example (the
program `bench/compare.sh` uses), on the same data written to a raw f64 file; the Python call
is `thermonav.allan(..., limits=False)`, which makes that same call (with `limits=True`, the
default, it adds the confidence limits and noise identification, timed on its own line).
Prints the times and the ratios, and checks the deviations are the same. Run it with
`bash bench/python_allan.sh` (builds the example and installs the package first).
"""

import json
import os
import subprocess
import sys
import tempfile
import time

import allantools
import numpy as np

import thermonav

SAMPLES = int(sys.argv[1]) if len(sys.argv) > 1 else 2_160_000
RATE_HZ = 200.0
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(REPO, "target", "release", "examples", "allan_timing")


def best_of(runs, call):
    best, result = float("inf"), None
    for _ in range(runs):
        start = time.perf_counter()
        result = call()
        best = min(best, time.perf_counter() - start)
    return best, result


def rust_times(y, tmp):
    path = os.path.join(tmp, "allan.f64")
    y.astype("<f8").tofile(path)
    done = subprocess.run([EXAMPLE, path, str(RATE_HZ), os.path.join(tmp, "allan")],
                          check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


def main():
    rng = np.random.default_rng(2009)
    y = rng.standard_normal(SAMPLES) + np.cumsum(rng.standard_normal(SAMPLES)) * 1e-3
    with tempfile.TemporaryDirectory() as tmp:
        rust = rust_times(y, tmp)
        rows = []
        for grid in ("octave", "decade"):
            ours_s, ours = best_of(3, lambda: thermonav.allan(y, RATE_HZ, taus=grid, limits=False))
            peer_s, peer = best_of(3, lambda: allantools.oadev(y, rate=RATE_HZ, data_type="freq", taus=grid))
            rust_dev = np.fromfile(os.path.join(tmp, f"allan.{grid}.f64"), dtype="<f8")
            assert np.array_equal(ours.adev, rust_dev), "Python and Rust curves differ"
            np.testing.assert_allclose(ours.adev, peer[1], rtol=1e-9)
            rows.append((grid, rust[f"{grid}_s"], ours_s, peer_s))
        limits_s, _ = best_of(3, lambda: thermonav.allan(y, RATE_HZ))
    print(f"overlapping Allan deviation, {SAMPLES} samples, {rust['threads']} threads, best of 3")
    print(f"{'grid':<8} {'Rust s':>9} {'Python s':>9} {'allantools s':>13} {'Python/Rust':>12} {'allantools/Python':>18}")
    for grid, rust_s, ours_s, peer_s in rows:
        print(f"{grid:<8} {rust_s:>9.4f} {ours_s:>9.4f} {peer_s:>13.4f} {ours_s / rust_s:>12.3f} {peer_s / ours_s:>18.1f}")
    print(f"thermonav.allan with its confidence limits (octave): {limits_s:.4f} s")


if __name__ == "__main__":
    main()
