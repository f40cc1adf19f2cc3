#!/usr/bin/env bash
# A lagging unit from the command line: `simulate chamber --temperature-file` replays a chamber
# program (25 → −5 → 55 → 25 °C at 2 °C/min, 10 min dwells, 2 Hz) with every channel's
# structure lagging by 120 s, for seeds 1..N of the built-in profile; `characterize --sweep`
# then fits it. Prints per seed and channel the chosen model's lag and its 95 % interval, and
# counts how often the lag is chosen and its interval holds −120 s.
# Usage: bench/thermal_lag_cli.sh [SEEDS] (default 10)
set -euo pipefail
seeds=${1:-10}
root=$(cd "$(dirname "$0")/.." && pwd)
cargo build --release --quiet --manifest-path "$root/Cargo.toml"
bin="$root/target/release/thermonav"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 't_s,temp_c\n0,25\n900,-5\n1500,-5\n3300,55\n3900,55\n4800,25\n5400,25\n' > "$work/program.csv"
for seed in $(seq 1 "$seeds"); do
  "$bin" simulate chamber --out "$work/s$seed" --temperature-file "$work/program.csv" \
    --rate-hz 2 --thermal-lag-s 120 --seed "$seed" > /dev/null
  "$bin" characterize --sweep "$work/s$seed/imu_program.csv" --out "$work/s$seed/bank.json" > /dev/null
done
python3 - "$work" "$seeds" <<'PY'
import json, sys
work, seeds = sys.argv[1], int(sys.argv[2])
chosen = {c: 0 for c in ["gx", "gy", "gz", "ax", "ay", "az"]}
held = dict(chosen)
for seed in range(1, seeds + 1):
    bank = json.load(open(f"{work}/s{seed}/bank.json"))
    row = []
    for c in chosen:
        ch = bank["thermal"]["channels"][c]
        if not ch["selection"]["chosen"]["lag"]:
            row.append(f"{c} T only")
            continue
        lag = ch["lagged"]["lag"]
        lo, hi = lag["tau_interval_s"]
        chosen[c] += 1
        held[c] += lo <= -120 <= hi
        row.append(f"{c} {lag['tau_s']:.0f} [{lo:.0f}, {hi:.0f}]")
    print(f"seed {seed}: " + "; ".join(row))
print("lag chosen (of %d): " % seeds + ", ".join(f"{c} {n}" for c, n in chosen.items()))
print("interval holds -120 s (of those chosen): " + ", ".join(f"{c} {held[c]}/{chosen[c]}" for c in chosen))
PY
