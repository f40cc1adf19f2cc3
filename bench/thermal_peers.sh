#!/usr/bin/env bash
# Held-out scoring of thermal-bias calibration on the real CATS record (shared data README 1.9):
# PX4's and ArduPilot's own offline fitters (run where they lie in /work/shared/peers/, never
# copied) and, when `thermonav bank check` exists, thermonav. Within each period every leg of
# >= 3 degC is held out in turn (6 channels); across periods two are fitted and the third held
# out (gyros). Writes the legs oracle tools/oracles/cats_legs.json, prints a markdown table and
# writes it to OUT (default: stdout only) and OUT.json (or $TMP/results.json) with the numbers.
# Installs numpy scipy matplotlib pyulog pymavlink into a venv in /tmp (THERMAL_PEERS_VENV);
# logs and peer outputs stay in a mktemp -d folder (kept; its path is printed). Never builds
# thermonav: set THERMONAV to another binary; missing or without `bank check` -> "pending".
# Usage: bash bench/thermal_peers.sh [OUT.md]
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${THERMAL_PEERS_VENV:-/tmp/thermal_peers_venv}"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
if ! "$venv/bin/python" -c 'import numpy, scipy, matplotlib, pyulog, pymavlink' 2>/dev/null; then
  "$venv/bin/pip" install --quiet numpy scipy matplotlib pyulog pymavlink
fi
work="$(mktemp -d -t thermal_peers.XXXXXX)"
echo "work folder: $work" >&2
out="${1:--}"
if [ "$out" = - ]; then json="$work/results.json"; else json="${out%.md}.json"; fi
MPLBACKEND=Agg "$venv/bin/python" bench/thermal_peers/run.py \
  --workdir "$work" --out "$out" --json "$json" \
  --legs-json tools/oracles/cats_legs.json \
  --thermonav "${THERMONAV:-$PWD/target/release/thermonav}" --jobs "${THERMAL_PEERS_JOBS:-2}"
echo "json: $json" >&2
