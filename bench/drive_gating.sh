#!/usr/bin/env bash
# The car drive (../shared/data/rtklibexplorer-gnss-imu/drive_0708) through the plain chi-square
# gate and the scaled gate: fixes rejected, and the horizontal RMS distance of the solution's
# antenna point (output at 100 Hz, interpolated to each fix) from the RTK fixes, all fixes from
# 5 s after the alignment. Usage: bash bench/drive_gating.sh [THERMONAV]
set -euo pipefail
cd "$(dirname "$0")/.."
T=${1:-target/release/thermonav}
D=../shared/data/rtklibexplorer-gnss-imu/drive_0708
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
"$T" convert "$D/imu_1934.csv" --imu-frame drive-frd --time-offset-s=-0.125 --out "$W/imu.csv" >/dev/null
"$T" convert "$D/gnss_1934_sf.pos" --out "$W/gnss.csv" >/dev/null
for window in 0 5; do
  "$T" integrate --imu "$W/imu.csv" --gnss "$W/gnss.csv" --profile examples/profiles/drive_0708_imu.toml \
    --process-noise-scale 10 --velocity-sd-m-s 0.1 --lever-arm-m 0,-0.05,0 --output-rate-hz 100 \
    --gate-window "$window" --out "$W/sol$window.csv" --json 2>/dev/null >"$W/run$window.json"
  python3 - "$W/sol$window.csv" "$W/gnss.csv" "$W/run$window.json" "$window" <<'PY'
import csv, json, math, sys
sol = list(csv.DictReader(open(sys.argv[1])))
fixes = list(csv.DictReader(open(sys.argv[2])))
run = json.load(open(sys.argv[3]))
t = [float(r["t_s"]) for r in sol]
lever_right_m = -0.05  # --lever-arm-m 0,-0.05,0 (forward, right, down)
def at(time):
    import bisect
    k = bisect.bisect_left(t, time)
    if k == 0 or k == len(t):
        return None
    a, b = sol[k - 1], sol[k]
    w = (time - t[k - 1]) / (t[k] - t[k - 1])
    lerp = lambda key: float(a[key]) + w * (float(b[key]) - float(a[key]))
    yaw = math.radians(float(a["yaw_deg"]))
    return lerp("lat_deg"), lerp("lon_deg"), yaw
errors = []
for f in fixes:
    time = float(f["t_s"])
    if time < t[0] + 5:
        continue
    p = at(time)
    if p is None:
        continue
    lat, lon, yaw = p
    north = math.radians(lat - float(f["lat_deg"])) * 6378137 - lever_right_m * math.sin(yaw)
    east = math.radians(lon - float(f["lon_deg"])) * 6378137 * math.cos(math.radians(lat)) + lever_right_m * math.cos(yaw)
    errors.append(math.hypot(north, east))
position = next(i for i in run["innovations"] if i["kind"] == "position")
rms = math.sqrt(sum(e * e for e in errors) / len(errors))
name = "plain gate" if sys.argv[4] == "0" else f"scaled gate (window {sys.argv[4]})"
print(f"{name}: {position['rejected']} of {position['offered']} fixes rejected ({position['forced']} forced), aided RMS {rms:.4f} m over {len(errors)} fixes")
PY
done
