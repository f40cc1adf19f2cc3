"""SciPy oracle values for the Kaiser FIR design and zero-phase filtering.

Run once from the repository root:
    python3 tools/oracles/kaiser_fir.py > crates/thermonav/tests/data/kaiser_fir.json
The test signal is a deterministic formula evaluated identically in the Rust test, so only the
outputs are stored.
"""
import json
import numpy as np
import scipy
from scipy import signal, special


def test_signal(n):
    k = np.arange(n, dtype=float)
    return np.sin(0.01 * k) + 0.5 * np.sin(0.37 * k + 1.0) + 0.25 * np.cos(2.9 * k) + (k % 97) / 97.0


def odd_ext(x, pad):
    left = 2 * x[0] - x[pad:0:-1]
    right = 2 * x[-1] - x[-2:-(pad + 2):-1]
    return np.concatenate([left, x, right])


specs = [(200.0, 5.0, 1.0, 60.0), (200.0, 20.0, 5.0, 40.0), (100.0, 1.0, 0.5, 80.0),
         (1000.0, 100.0, 50.0, 21.0), (200.0, 30.0, 10.0, 30.0), (200.0, 10.0, 4.0, 50.0),
         (200.0, 2.0, 2.0, 60.0)]
designs = []
for fs, cutoff, width, ripple in specs:
    numtaps, beta = signal.kaiserord(ripple, width / (fs / 2))
    taps = signal.firwin(numtaps, cutoff, window=("kaiser", beta), fs=fs)
    designs.append({"fs_hz": fs, "cutoff_hz": cutoff, "transition_hz": width, "ripple_db": ripple,
                    "num_taps": int(numtaps), "beta": float(beta), "taps": taps.tolist()})

i0 = [{"x": x, "i0": float(special.i0(x))} for x in [0.0, 1e-3, 0.5, 1.0, 5.653, 10.0, 30.0, 100.0]]

filtering = []
for spec_index, n in [(0, 2500), (0, 4000), (1, 1200), (2, 3100)]:
    d = designs[spec_index]
    taps = np.array(d["taps"])
    x = test_signal(n)
    entry = {"design": spec_index, "n": n, "filtfilt": signal.filtfilt(taps, [1.0], x).tolist()}
    if len(taps) % 2 == 1:
        pad = 3 * len(taps)
        full = np.convolve(odd_ext(x, pad), taps)
        delay = (len(taps) - 1) // 2
        entry["delay_compensated"] = full[pad + delay: pad + delay + n].tolist()
    filtering.append(entry)

print(json.dumps({"source": f"scipy {scipy.__version__}, numpy {np.__version__}",
                  "signal": "x[k] = sin(0.01k) + 0.5 sin(0.37k + 1) + 0.25 cos(2.9k) + (k mod 97)/97",
                  "designs": designs, "i0": i0, "filtering": filtering}))
