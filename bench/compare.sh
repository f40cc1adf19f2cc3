#!/usr/bin/env bash
# Times thermonav against the Python peers on the same generated data, in one run.
# Installs the peers (numpy, scipy, statsmodels, allantools, pandas) into bench/.venv from the
# package index; prints a table of times and ratios and checks that the results agree.
# Usage: bash bench/compare.sh [SAMPLES] [SECTIONS] (SECTIONS: a comma-separated subset of
# filter,allan,ar,pipeline,csv; all by default)
#    or: bash bench/compare.sh workflow [workflow.py options] (the whole characterisation of a
# campaign against `thermonav characterize`; by default the demo's 6 x 3 h x 200 Hz campaign,
# e.g. --temperatures-c 0,20 --duration-s 600 for a quick check; see bench/workflow.py)
#    or: bash bench/compare.sh ins [ins_peer.py options] (one navigation run against the fastest
# GNSS/INS filters found on PyPI, INSLIB and, with --pyins, pyins; see bench/ins_peer.py)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x bench/.venv/bin/python ] || python3 -m venv bench/.venv
if ! bench/.venv/bin/python -c 'import numpy, scipy, statsmodels, allantools, pandas' 2>/dev/null; then
  bench/.venv/bin/pip install --quiet numpy scipy statsmodels allantools pandas
fi
if [ "${1:-}" = ins ]; then
  shift
  bench/.venv/bin/python -c 'import pyins, INSLIB' 2>/dev/null || bench/.venv/bin/pip install --quiet python-ins inslib
  cargo build --release --quiet -p thermonav-cli
  exec bench/.venv/bin/python bench/ins_peer.py "$@"
fi
if [ "${1:-}" = workflow ]; then
  shift
  cargo build --release --quiet -p thermonav-cli
  exec bench/.venv/bin/python bench/workflow.py "$@"
fi
cargo build --release --quiet -p thermonav -p thermonav-io --examples
exec bench/.venv/bin/python bench/compare.py "$@"
