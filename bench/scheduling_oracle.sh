#!/usr/bin/env bash
# Can scheduling the stochastic model by temperature beat the best fixed model at all, in the
# demo's warming-survey regime? The oracle: the built-in temperature-sensitive profile's true
# Gauss-Markov tables with no deterministic thermal bias (what perfect compensation leaves),
# a survey warming from -20 to 25 °C (tau 600 s, 1800 s, 8 outages of 100 s), and the
# tournament of the TRUE models: fixed at each table temperature, at the mean temperature,
# and scheduled. Prints each model's mean horizontal error and the paired tests of the
# scheduled one (8 replicates with shifted outages).
# Usage: bench/scheduling_oracle.sh [thermonav binary]   (needs python3)
set -euo pipefail
B=${1:-target/release/thermonav}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
python3 - "$W/perfect.toml" <<'PY'
import sys
T=[-40,-20,0,20,40,60]; tc=[1000,600,200,100,300,800]
gs=[10,20,35,50,25,10]; acc=[0.05,0.1,0.2,0.25,0.12,0.05]
out=['name = "temperature-sensitive, perfectly compensated"','reference_temperature_c = 25.0']
for kind,sig,unit,white in (('g',gs,'deg_h','white_noise_deg_per_sqrt_h = 0.3'),('a',acc,'mg','white_noise_m_s_per_sqrt_h = 0.05')):
    for m,ax in zip([1,0.9,1.1],'xyz'):
        out+=[f'[channels.{kind}{ax}]',white,'bias_gauss_markov = [']
        out+=[f'  {{ temperature_c = {t}.0, correlation_time_s = {c*m}, sigma_{unit} = {s*m} }},' for t,s,c in zip(T,sig,tc)]
        out+=[']']
open(sys.argv[1],'w').write('\n'.join(out)+'\n')
PY
"$B" simulate vessel --out "$W/survey" --duration-s 1800 --profile "$W/perfect.toml" \
  --warm-up-from-c=-20 --temperature-c 25 --warm-up-time-constant-s 600 --quiet >/dev/null
"$B" evaluate --imu "$W/survey/imu.csv" --gnss "$W/survey/gnss.csv" \
  --reference "$W/survey/reference.csv" --profile "$W/perfect.toml" --filter ekf \
  --outages spread:8,100 --monte-carlo 8 --out "$W/ev" --quiet >/dev/null
python3 - "$W/ev/evaluation.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for m in r['models']:
    print(f"{m['label']:<24} {m['ci95']['rms_horizontal_m']['mean']:8.2f} m")
for c in r['significance']['horizontal_contrasts']:
    if 'scheduled' in c['better'] + c['worse']:
        p = c['test']['p_value'] if c['test'] else float('nan')
        print(f"{c['better']} beats {c['worse']} by {c['mean_difference_m']:.2f} m, paired p = {p:.2g}")
PY
