#!/usr/bin/env bash
# Times thermonav.allan from Python against the Rust call and allantools (bench/python_allan.py).
# Builds the Rust timing example and installs the Python package and allantools first.
# Usage: bash bench/python_allan.sh [SAMPLES]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p thermonav --example allan_timing
python3 -m pip install --quiet ./python allantools
exec python3 bench/python_allan.py "$@"
