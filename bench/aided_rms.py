"""Horizontal RMS distance of a solution's antenna point from the GNSS (RTK) fixes, all fixes
from 5 s after the solution's start; the solution interpolated to each fix (the computation of
bench/kf_gins_side_by_side.py's car-drive rows, on a solution CSV of `integrate`).
Usage: python3 bench/aided_rms.py SOL.csv GNSS.csv [LEVER_RIGHT_M]"""
import csv
import sys

from kf_gins_side_by_side import aided_rms_m


def track_of(solution_path):
    """(t_s, lat_deg, lon_deg, yaw_deg) rows of a solution CSV."""
    with open(solution_path) as f:
        return [tuple(float(r[k]) for k in ("t_s", "lat_deg", "lon_deg", "yaw_deg"))
                for r in csv.DictReader(f)]


if __name__ == "__main__":
    lever = float(sys.argv[3]) if len(sys.argv) > 3 else -0.05
    with open(sys.argv[2]) as f:
        fixes = list(csv.DictReader(f))
    print(f"{aided_rms_m(track_of(sys.argv[1]), fixes, lever):.4f} m")
