#!/usr/bin/env bash
# The Kaiser low-pass against wavelet de-noising before the AR fit, on the quick demo's chamber
# campaign (6 set points, -40..60 °C, 1800 s at 100 Hz, seed 2009: the records `thermonav demo
# --quick` writes, made here by `simulate chamber` alone). Both banks are built by
# `characterize --denoise kaiser|wavelet`; per temperature and channel it prints the simulated
# Gauss-Markov truth, the AR-based model (the paper's: AR(1) of the de-noised, decimated series)
# and the exact Gauss-Markov + white-noise likelihood (irregular_ml, on block means of the raw
# record, so the de-noiser cannot change it), then the ranges of estimate / truth.
# Tc in s; sigma in deg/h (gyros) and mg (accelerometers). Needs python3 (standard library only)
# for the table. Usage: bash bench/denoise_side_by_side.sh [DIR]   (default: a temporary folder)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p thermonav-cli
bin=target/release/thermonav
dir=${1:-$(mktemp -d)}
temperatures=-40,-20,0,20,40,60
"$bin" --quiet simulate chamber --duration-s 1800 --rate-hz 100 --out "$dir/chamber" >/dev/null
files=()
for t in ${temperatures//,/ }; do files+=("$dir/chamber/imu_${t}C.csv"); done
for denoise in kaiser wavelet; do
  "$bin" --quiet characterize "${files[@]}" --temperature-c="$temperatures" \
    --denoise "$denoise" --out "$dir/bank_$denoise.json" --json >/dev/null
done
python3 - "$dir" <<'PY'
import json, math, sys
d = sys.argv[1]
truth = json.load(open(f"{d}/chamber/truth.json"))
banks = {m: json.load(open(f"{d}/bank_{m}.json")) for m in ("kaiser", "wavelet")}
G = 9.80665
def edge(channel, sigma):  # SI -> deg/h or mg
    return sigma * 180 / math.pi * 3600 if channel.startswith("g") else sigma / G * 1000
def model(entry, channel, family):
    gm = entry["channels"][channel]["gauss_markov"][family]
    return (gm["correlation_time_s"], gm["sigma"]) if gm.get("status") == "model" else None
def cell(est, channel):
    return "%9s %8s" % ("-", "-") if est is None else "%9.1f %8.2f" % (est[0], edge(channel, est[1]))
wav = banks["wavelet"]["entries"][0]["preprocessing"]["wavelet"]
print(f"wavelet: {wav['wavelet']}, level {wav['level']}, {wav['mode']}, {wav['threshold']} threshold, {wav['thresholding']}")
print("Tc s, sigma deg/h (g*) or mg (a*); AR = AR-based, ML = irregular_ml")
head = "%6s %3s | %9s %8s | %18s | %18s | %18s | %18s" % ("T degC", "ch", "true Tc", "sigma",
       "Kaiser AR", "wavelet AR", "Kaiser ML", "wavelet ML")
print(head); print("-" * len(head))
ratios = {}
for t in truth["temperatures"]:
    entries = {m: next(e for e in b["entries"] if e["temperature_c"] == t["temperature_c"]) for m, b in banks.items()}
    for ch, c in t["channels"].items():
        true = (c["gauss_markov"]["correlation_time_s"], c["gauss_markov"]["sigma"])
        row = []
        for fam, m in (("ar_based", "kaiser"), ("ar_based", "wavelet"), ("irregular_ml", "kaiser"), ("irregular_ml", "wavelet")):
            est = model(entries[m], ch, fam)
            row.append(cell(est, ch))
            if est:
                r = ratios.setdefault((fam, m), [[], []])
                r[0].append(est[0] / true[0]); r[1].append(est[1] / true[1])
        print("%6.0f %3s | %9.1f %8.2f | %s" % (t["temperature_c"], ch, true[0], edge(ch, true[1]), " | ".join(row)))
print("\nestimate / truth over the 36 channel-temperatures (min .. max, median):")
for (fam, m), (tc, sg) in sorted(ratios.items()):
    med = lambda v: sorted(v)[len(v) // 2]
    print(f"  {m:7s} {fam:12s} ({len(tc):2d} models)  Tc {min(tc):8.3f} .. {max(tc):8.3f} (median {med(tc):7.3f})"
          f"   sigma {min(sg):6.3f} .. {max(sg):6.3f} (median {med(sg):5.3f})")
PY
