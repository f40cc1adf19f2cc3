#!/usr/bin/env python3
"""Issue 38, rows 13 and 14, on the simulated slow rover: a 0.4 m/s ground rover with 20 Hz,
0.7 m position-only fixes (no heading), a -100 deg/h z-gyro bias added to the unit's own, and a
known IMU-GNSS time offset, one run per seed (each seed its own unit serial and offset).

Row 13: does `integrate --estimate-time-offset`'s 95 % likelihood-ratio interval cover the
simulated offset? (the issue asks for at least 17 of 20 seeds; an open end counts as reaching
the bracket's end, which is where the data leave the offset unbounded).
Row 14 (with --time-offset-s 0 and no estimation, so that the solution's times are the
truth's): the heading error against the filter's own heading sd (the share of epochs inside
3 sd, and the heading sd once the rover has moved 20 m), and the final z-gyro bias estimate
against the truth (the unit's repeatable curve at the survey temperature + the survey's
power-on offset + the added bias) in units of its sd.

Usage: python3 bench/slow_rover.py [--seeds 20] [--first-seed 1] [--duration-s 300] [--out DIR]
Needs the release binary (cargo build --release -p thermonav-cli). Standard library only.
"""

import argparse
import bisect
import csv
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

BIN = Path(__file__).resolve().parent.parent / "target" / "release" / "thermonav"
SPEED_M_S, GNSS_RATE_HZ, GNSS_SD_M, GYRO_Z_BIAS_DEG_H = 0.4, 20, 0.7, -100.0


def offset_of_seed_s(seed):
    """A known offset per seed, spread over -0.3..+0.3 s (a golden-ratio sequence)."""
    return round(0.6 * ((seed * 0.618033988749895) % 1.0) - 0.3, 3)


def run(*args):
    done = subprocess.run([str(BIN), *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"thermonav {' '.join(map(str, args))} failed:\n{done.stderr}")
    return done


def simulate(out, seed, offset_s, duration_s):
    run("simulate", "vessel", "--out", out, "--speed-m-s", SPEED_M_S, "--duration-s", duration_s,
        "--gnss-rate-hz", GNSS_RATE_HZ, "--gnss-sd-m", GNSS_SD_M, "--gnss-heading", "none",
        f"--gyro-bias-deg-h=0,0,{GYRO_Z_BIAS_DEG_H}", f"--time-offset-s={offset_s}",
        "--seed", seed, "--unit-serial", seed)


def integrate(folder, profile, *extra):
    done = run("integrate", "--imu", folder / "imu.csv", "--gnss", folder / "gnss.csv",
               "--profile", profile, "--out", folder / "sol.csv", "--quiet", "--json", *extra)
    return json.loads(done.stdout), done.stderr


def rows(path):
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def true_z_gyro_bias_deg_h(truth, temperature_c):
    curve = truth["unit"]["repeatable_bias"]["gz"]
    b, c1, c2 = curve["coefficients"]
    d = temperature_c - curve["reference_temperature_c"]
    rad_s = b + (c1 + c2 * d) * d + truth["power_on_offset"]["gz"] + truth["imu_offsets"]["gyro_bias_rad_s"][2]
    return math.degrees(rad_s) * 3600.0


def heading_figures(folder):
    """(share of epochs with |error| <= 3 sd, heading sd at 20 m travelled, deg, max |error| deg)."""
    ref = rows(folder / "reference.csv")
    ref_t = [r["t_s"] for r in ref]
    sol = rows(folder / "sol.csv")
    states = {r["t_s"]: r for r in rows(folder / "sol.states.csv")}
    inside, total, sd_at_20m, worst = 0, 0, None, 0.0
    travelled, last = 0.0, None
    for s in sol:
        k = bisect.bisect_left(ref_t, s["t_s"])
        if k >= len(ref) or s["t_s"] not in states:
            continue
        r = ref[k]
        if last is not None:
            travelled += math.hypot(r["vn_m_s"], r["ve_m_s"]) * (s["t_s"] - last)
        last = s["t_s"]
        error = (s["yaw_deg"] - r["yaw_deg"] + 180.0) % 360.0 - 180.0
        sd = states[s["t_s"]]["sd_att_d_deg"]
        total += 1
        inside += abs(error) <= 3.0 * sd
        worst = max(worst, abs(error))
        if sd_at_20m is None and travelled >= 20.0:
            sd_at_20m = sd
    return inside / max(total, 1), sd_at_20m, worst


def seed_result(work, profile, seed, duration_s):
    offset_s = offset_of_seed_s(seed)
    shifted = work / f"seed{seed}_offset"
    simulate(shifted, seed, offset_s, duration_s)
    summary, stderr = integrate(shifted, profile, "--estimate-time-offset")
    t = summary["time_offset"]
    lower, upper = t["lower"]["offset_s"], t["upper"]["offset_s"]
    aligned = work / f"seed{seed}"
    simulate(aligned, seed, 0.0, duration_s)
    integrate(aligned, profile)
    truth = json.loads((aligned / "truth.json").read_text())
    last = rows(aligned / "sol.states.csv")[-1]
    bias_truth = true_z_gyro_bias_deg_h(truth, truth["temperature"]["temperature_c"])
    share, sd20, worst = heading_figures(aligned)
    return {
        "seed": seed, "offset_s": offset_s, "estimate_s": t["time_offset_s"],
        "lower": t["lower"], "upper": t["upper"], "observability": t["observability"],
        "dispersion": t["dispersion"], "runs": t["runs"], "warned": "warning:" in stderr,
        "covered": lower <= offset_s <= upper,
        "heading_within_3sd": share, "heading_sd_at_20m_deg": sd20, "heading_max_error_deg": worst,
        "bgz_estimate_deg_h": last["bgz_deg_h"], "bgz_sd_deg_h": last["sd_bgz_deg_h"],
        "bgz_truth_deg_h": bias_truth,
    }


def end_text(end):
    mark = "" if end["kind"] == "within" else "|"
    return f"{1e3 * end['offset_s']:+5.0f}{mark}"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seeds", type=int, default=20)
    p.add_argument("--first-seed", type=int, default=1, help="seeds first..first+seeds-1")
    p.add_argument("--duration-s", type=float, default=300.0)
    p.add_argument("--out", type=Path, default=None, help="keep the runs here (default: a temporary folder)")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = a.out or Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        profile = work / "profile.toml"
        run("simulate", "profile", "--out", profile)
        results = []
        print("seed offset_ms estimate_ms interval_ms (| = open at the bracket's end) covered observability"
              " | heading in 3sd, sd@20m deg, max err deg | bgz est +- sd vs truth deg/h")
        for seed in range(a.first_seed, a.first_seed + a.seeds):
            r = seed_result(work, profile, seed, a.duration_s)
            results.append(r)
            z = (r["bgz_estimate_deg_h"] - r["bgz_truth_deg_h"]) / r["bgz_sd_deg_h"]
            sd20 = "-" if r["heading_sd_at_20m_deg"] is None else f"{r['heading_sd_at_20m_deg']:.2f}"
            print(f"{r['seed']:4d} {1e3 * r['offset_s']:+6.0f} {1e3 * r['estimate_s']:+6.0f} "
                  f"[{end_text(r['lower'])}, {end_text(r['upper'])}] {str(r['covered']):5s} {r['observability']:22s}"
                  f" | {100 * r['heading_within_3sd']:5.1f} % {sd20:>6s} {r['heading_max_error_deg']:6.2f}"
                  f" | {r['bgz_estimate_deg_h']:8.1f} +- {r['bgz_sd_deg_h']:5.1f} vs {r['bgz_truth_deg_h']:8.1f} ({z:+.1f} sd)",
                  flush=True)
        covered = sum(r["covered"] for r in results)
        bias_inside = sum(abs(r["bgz_estimate_deg_h"] - r["bgz_truth_deg_h"]) <= 3 * r["bgz_sd_deg_h"] for r in results)
        print(f"time offset: the 95 % interval covers the simulated offset in {covered} of {len(results)} seeds "
              f"({sum(r['warned'] for r in results)} runs warned; mean {sum(r['runs'] for r in results) / len(results):.0f} filter runs each)")
        kept = sum(r["heading_within_3sd"] >= 0.95 for r in results)
        sd_small = sum(r["heading_sd_at_20m_deg"] is not None and r["heading_sd_at_20m_deg"] < 10.0 for r in results)
        print(f"heading: epochs inside 3 sd, median over seeds {100 * sorted(r['heading_within_3sd'] for r in results)[len(results) // 2]:.1f} %; "
              f"95 % or more of the epochs inside 3 sd in {kept} of {len(results)} seeds; "
              f"heading sd below 10 deg at 20 m travelled in {sd_small} of {len(results)}; "
              f"z-gyro bias within 3 sd of the truth at the end in {bias_inside} of {len(results)} seeds")
        if a.out:
            (work / "slow_rover.json").write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
