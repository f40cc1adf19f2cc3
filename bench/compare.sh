#!/usr/bin/env bash
# Times thermonav against the Python peers on the same generated data, in one run.
# Installs the peers into bench/.venv from the package index; prints a table of times and
# ratios and checks that the results agree. Usage: bash bench/compare.sh [SAMPLES]
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x bench/.venv/bin/python ]; then
  python3 -m venv bench/.venv
  bench/.venv/bin/pip install --quiet numpy scipy statsmodels allantools
fi
cargo build --release --quiet -p thermonav --examples
exec bench/.venv/bin/python bench/compare.py "$@"
