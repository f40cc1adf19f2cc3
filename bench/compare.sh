#!/usr/bin/env bash
# Times thermonav against the Python peers on the same generated data, in one run.
# Installs the peers (numpy, scipy, statsmodels, allantools, pandas) into bench/.venv from the
# package index; prints a table of times and ratios and checks that the results agree.
# Usage: bash bench/compare.sh [SAMPLES] [SECTIONS] (SECTIONS: a comma-separated subset of
# filter,allan,ar,pipeline,csv; all by default)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x bench/.venv/bin/python ] || python3 -m venv bench/.venv
if ! bench/.venv/bin/python -c 'import numpy, scipy, statsmodels, allantools, pandas' 2>/dev/null; then
  bench/.venv/bin/pip install --quiet numpy scipy statsmodels allantools pandas
fi
cargo build --release --quiet -p thermonav -p thermonav-io --examples
exec bench/.venv/bin/python bench/compare.py "$@"
