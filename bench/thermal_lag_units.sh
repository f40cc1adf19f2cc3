#!/usr/bin/env bash
# The sweep calibration on 20 simulated lagging units per chamber rate (±2 and ±5 °C/min) and
# 20 without lag: how often the lag is chosen, whether its 95 % interval holds the truth, and
# the held-out shape RMS of the chosen model against the curve in T alone (see the example's
# doc comment). Usage: bash bench/thermal_lag_units.sh [UNITS]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --release -q -p thermonav --example thermal_lag_units -- "${1:-20}"
