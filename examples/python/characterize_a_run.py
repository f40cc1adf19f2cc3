"""Characterise a real static IMU run from Python, notebook style.

The run: ADIS16405 run 1 of `../shared/data/smac-imudata` (10 000 s at 100 Hz, gyros in deg/s,
accelerometers in g, z down; CC BY-NC-SA 4.0: read here, never shipped). It has no temperature
column, so the bank's one entry is put at an assumed 25 °C.

Steps: read the columns into NumPy arrays in SI, draw the overlapping Allan deviation of every
channel (with matplotlib when it is installed, else the figure is skipped), characterise the
run into a model bank, and print the bank: per channel the white-noise density, the bias
instability and the three Gauss-Markov correlation times.

    python3 examples/python/characterize_a_run.py [--out DIR] [--seconds S] [--json]
"""

import argparse
import gzip
from pathlib import Path

import numpy as np

import thermonav

REPO = Path(__file__).resolve().parents[2]
RUN = REPO.parent / "shared" / "data" / "smac-imudata" / "adis_16405_imu1.csv.gz"
RATE_HZ = 100.0
STANDARD_GRAVITY = 9.80665  # m/s^2 per g (CONVENTIONS.md)
ASSUMED_TEMPERATURE_C = 25.0


def read_run(seconds: float) -> dict:
    """The run's first `seconds` as a record in SI, named like the canonical IMU CSV."""
    with gzip.open(RUN, "rt") as f:
        f.readline()
        rows = np.loadtxt(f, delimiter=",", max_rows=int(seconds * RATE_HZ))
    record = {"source": RUN.name, "t_s": np.arange(len(rows)) / RATE_HZ}
    for k, axis in enumerate("xyz"):
        record[f"g{axis}_rad_s"] = np.ascontiguousarray(np.radians(rows[:, k]))
        record[f"a{axis}_m_s2"] = np.ascontiguousarray(rows[:, 3 + k] * STANDARD_GRAVITY)
    return record


def draw_allan(record: dict, out: Path) -> None:
    """Allan deviation of every channel on log-log axes, or a note when matplotlib is absent."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: the Allan figure is skipped")
        return
    fig, (gyro, accel) = plt.subplots(1, 2, figsize=(10, 4))
    for name in ("gx_rad_s", "gy_rad_s", "gz_rad_s", "ax_m_s2", "ay_m_s2", "az_m_s2"):
        curve = thermonav.allan(record[name], RATE_HZ)
        axes = gyro if name.startswith("g") else accel
        axes.loglog(curve.tau_s, curve.adev, label=name[:2])
        axes.fill_between(curve.tau_s, curve.ci_low, curve.ci_high, alpha=0.2)
    for axes, unit in ((gyro, "rad/s"), (accel, "m/s²")):
        axes.set_xlabel("τ (s)")
        axes.set_ylabel(f"Allan deviation ({unit})")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend()
    fig.suptitle(f"{RUN.name}: overlapping Allan deviation, 68.3 % limits")
    fig.tight_layout()
    path = out / "allan.png"
    fig.savefig(path, dpi=100)
    print(f"Allan figure written to {path}")


def print_bank(bank: thermonav.Bank) -> None:
    """One row per channel: N and B from the Allan curve, Tc of each Gauss-Markov family."""
    entry = bank.entries[0]
    print(f"\n{bank!r}\nentry at {entry.temperature_c} °C from {entry.source}, "
          f"conditioned at {entry.preprocessing.modelling_rate_hz} Hz")
    print(f"{'ch':<3} {'unit':<6} {'N (unit·√s)':>12} {'B (unit)':>10} "
          f"{'Tc irregular_ml s':>18} {'Tc ar_based s':>14} {'Tc acf_fit s':>13}")

    def tc(model):
        return f"{model.correlation_time_s:.1f}" if model.status == "model" else "none"

    def value(v):
        return "n/a" if v is None else f"{v:.3e}"

    for name, channel in entry.channels.items():
        gm = channel.gauss_markov
        print(f"{name:<3} {channel.unit:<6} {value(channel.allan.white_noise_density):>12} "
              f"{value(channel.allan.bias_instability):>10} {tc(gm.irregular_ml):>18} "
              f"{tc(gm.ar_based):>14} {tc(gm.acf_fit):>13}")
    for note in bank.notes:
        print(f"note: {note}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO / "target" / "python-example")
    parser.add_argument("--seconds", type=float, default=10_000.0, help="length of the run used")
    parser.add_argument("--json", action="store_true", help="also print the bank's JSON")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    record = read_run(args.seconds)
    print(f"{RUN.name}: {len(record['t_s'])} samples at {RATE_HZ} Hz")
    draw_allan(record, args.out)
    bank = thermonav.characterize([record], temperatures_c=[ASSUMED_TEMPERATURE_C])
    bank.save(args.out / "bank.json")
    print_bank(bank)
    if args.json:
        print(bank.to_json())


if __name__ == "__main__":
    main()
