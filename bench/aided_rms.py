"""Horizontal RMS distance of a solution's antenna point from the GNSS (RTK) fixes, all fixes
from 5 s after the solution's start; the solution (output at 100 Hz) interpolated to each
fix. The computation of bench/drive_gating.sh, as a script of its own.
Usage: python3 bench/aided_rms.py SOL.csv GNSS.csv [LEVER_RIGHT_M]"""
import bisect
import csv
import math
import sys


def aided_rms_m(solution_path, fixes_path, lever_right_m):
    sol = list(csv.DictReader(open(solution_path)))
    fixes = list(csv.DictReader(open(fixes_path)))
    t = [float(r["t_s"]) for r in sol]
    errors = []
    for f in fixes:
        time = float(f["t_s"])
        k = bisect.bisect_left(t, time)
        if time < t[0] + 5 or k == 0 or k == len(t):
            continue
        a, b = sol[k - 1], sol[k]
        w = (time - t[k - 1]) / (t[k] - t[k - 1])
        lat, lon = (float(a[key]) + w * (float(b[key]) - float(a[key])) for key in ("lat_deg", "lon_deg"))
        yaw = math.radians(float(a["yaw_deg"]))
        north = math.radians(lat - float(f["lat_deg"])) * 6378137 - lever_right_m * math.sin(yaw)
        east = math.radians(lon - float(f["lon_deg"])) * 6378137 * math.cos(math.radians(lat)) + lever_right_m * math.cos(yaw)
        errors.append(math.hypot(north, east))
    return math.sqrt(sum(e * e for e in errors) / len(errors)), len(errors)


if __name__ == "__main__":
    lever = float(sys.argv[3]) if len(sys.argv) > 3 else -0.05
    rms, n = aided_rms_m(sys.argv[1], sys.argv[2], lever)
    print(f"{rms:.4f} m over {n} fixes")
