#!/usr/bin/env bash
# Measures `thermonav characterize` on a 24-hour, 1 kHz, 6-channel static log (86.4 M rows,
# about 14 GB of full-precision CSV) read in streaming mode: peak resident memory, wall time
# and rows per second. A manual measurement (not run in CI): it needs ~15 GB of free disk and
# about 25 minutes to write the file.
#
# Usage: bash bench/day_at_1khz.sh [WORK_DIR] [HOURS]   (defaults: a temporary dir, 24)
# The generated CSV is deleted at the end unless KEEP=1.
set -euo pipefail
cd "$(dirname "$0")/.."
work="${1:-$(mktemp -d)}"
hours="${2:-24}"
mkdir -p "$work"
csv="$work/day_at_1khz.csv"
cargo build --release --quiet -p thermonav-cli -p thermonav-io --example static_log
if [ ! -s "$csv" ]; then
    echo "writing $hours h at 1 kHz to $csv"
    /usr/bin/time -f "generated in %e s" target/release/examples/static_log "$csv" "$hours" 1000
fi
rows=$(($(wc -l < "$csv") - 1))
echo "$rows rows, $(du -h "$csv" | cut -f1) on disk"
/usr/bin/time -v target/release/thermonav characterize "$csv" --reading streaming \
    --out "$work/day_bank.json" --json > "$work/day_summary.json" 2> "$work/day_time.txt"
wall=$(grep "Elapsed (wall clock)" "$work/day_time.txt" | awk '{print $NF}')
rss_kb=$(grep "Maximum resident set size" "$work/day_time.txt" | awk '{print $NF}')
seconds=$(echo "$wall" | awk -F: '{ if (NF == 3) print $1*3600 + $2*60 + $3; else print $1*60 + $2 }')
echo "wall ${wall} (${seconds} s), peak RSS $((rss_kb / 1024)) MB, $(awk -v r="$rows" -v s="$seconds" 'BEGIN { printf "%.2f", r / s / 1e6 }') M rows/s"
grep -E "User time|System time|Percent of CPU" "$work/day_time.txt"
echo "bank: $work/day_bank.json"
if [ "${KEEP:-0}" != 1 ]; then rm -f "$csv"; fi
