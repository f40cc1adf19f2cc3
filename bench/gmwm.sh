#!/usr/bin/env bash
# Times the Haar wavelet variance plus the GMWM fit (no bootstrap) of one channel of 2.16 M
# samples on one core (the issue's target: under 0.3 s; the R package gmwm reports 1.5 s for
# 2 M). Usage: bash bench/gmwm.sh [SAMPLES]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p thermonav --example gmwm_timing
exec target/release/examples/gmwm_timing "$@"
