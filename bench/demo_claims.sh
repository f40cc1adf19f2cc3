#!/usr/bin/env bash
# The demo's claims (b) and (c) over seeds: runs `thermonav demo` (or `--quick` with QUICK=1)
# for seeds FIRST..FIRST+COUNT-1 and prints, per seed, whether each claim holds, the paired
# p-value of every comparison it rests on, and whether its oracle bound (the true model against
# the claim's hardest rival) holds (from demo.json). Each seed's demo.json and log stay in a
# mktemp -d folder; the rest of its output (about 2.3 GB for `demo`) is removed once read.
# Never builds thermonav: set THERMONAV to another binary.
# Usage: bash bench/demo_claims.sh [COUNT=20] [FIRST=2009]
set -euo pipefail
cd "$(dirname "$0")/.."
count="${1:-20}"
first="${2:-2009}"
bin="${THERMONAV:-$PWD/target/release/thermonav}"
quick=()
[ "${QUICK:-0}" = 1 ] && quick=(--quick)
work="$(mktemp -d -t demo_claims.XXXXXX)"
echo "work folder: $work" >&2
held_b=0
held_c=0
c_oracle=0
c_with_oracle=0
for ((k = 0; k < count; k++)); do
  seed=$((first + k))
  "$bin" demo "${quick[@]}" --seed "$seed" --out "$work/$seed" >"$work/$seed.log" 2>&1
  line="$(python3 - "$work/$seed/demo.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
s = doc["temperature_scenarios"]
out = []
for key, tag in (("temperature_matters", "b"), ("warming_survey", "c")):
    claim = s[key]["claim"]
    ps = ",".join("%.1e" % c["p_value"] if c["p_value"] is not None else "n/a"
                  for c in claim["comparisons"])
    bound = claim.get("oracle_bound") or {}
    oracle = {True: "holds", False: "NOT"}.get(bound.get("holds"), "n/a")
    out.append("%s=%s p=[%s] oracle=%s" % (tag, "holds" if claim["holds"] else "NOT", ps, oracle))
print(" ".join(out))
PY
)"
  find "$work/$seed" -mindepth 1 ! -name demo.json -delete
  echo "seed $seed: $line"
  [[ "$line" == *"b=holds"* ]] && held_b=$((held_b + 1))
  [[ "$line" == *"c=holds"* ]] && held_c=$((held_c + 1))
  [[ "$line" == *"c="*"oracle=holds"* ]] && c_oracle=$((c_oracle + 1))
  [[ "$line" == *"c=holds"*"oracle=holds"* ]] && c_with_oracle=$((c_with_oracle + 1))
done
echo "claim (b) held in $held_b of $count seeds; claim (c) in $held_c of $count, and in $c_with_oracle of the $c_oracle where its oracle bound held"
