"""One navigation run of thermonav against the fastest GNSS/INS filter found on PyPI, on the same
simulated survey (driven by `bash bench/compare.sh ins`; issue 21, item 1, second sentence).

The peer is INSLIB (PyPI `inslib`, AGPL-3.0, called here, never copied): a C11 15-state
error-state Kalman filter (position, velocity, attitude, accelerometer and gyro biases as random
walks, single precision) behind a ctypes binding, fed one IMU sample per call. thermonav runs
`integrate --filter ekf` with the built-in profile's noise model: a 21-state error-state EKF
(double precision; Gauss-Markov bias states; covariance at 10 Hz) with its gating. Both start
from the reference state at the first GNSS epoch, take the 1 Hz position fixes and the
dual-antenna heading, and coast through the same outages; the horizontal error at the end of
each outage is computed for both solutions by the same code below. The filters differ (states,
noise model, tuning, precision), so the errors are a sanity check that the peer navigates, not an
agreement check; the times are the point. The other PyPI candidates are listed in the user
guide (docs/user-guide.md, Speed) with why they were not timed.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
THERMONAV = os.path.join(ROOT, "target", "release", "thermonav")
A, E2 = 6378137.0, 6.69437999014e-3


def horizontal_error_m(lat_deg, lon_deg, ref_lat_deg, ref_lon_deg, h_m):
    """North/east distance between two nearby geodetic points, WGS84 radii of curvature."""
    lat = np.radians(ref_lat_deg)
    s2 = np.sin(lat) ** 2
    meridian = A * (1 - E2) / (1 - E2 * s2) ** 1.5 + h_m
    normal = A / np.sqrt(1 - E2 * s2) + h_m
    dn = np.radians(lat_deg - ref_lat_deg) * meridian
    de = np.radians(lon_deg - ref_lon_deg) * normal * np.cos(lat)
    return float(np.hypot(dn, de))


def errors_at(times_s, solution, reference):
    """Horizontal error of `solution` (t_s, lat_deg, lon_deg) at each time, both interpolated."""
    out = []
    for t in times_s:
        at = lambda frame, col: float(np.interp(t, frame["t_s"], frame[col]))
        out.append(horizontal_error_m(at(solution, "lat_deg"), at(solution, "lon_deg"), at(reference, "lat_deg"),
                                      at(reference, "lon_deg"), at(reference, "h_m")))
    return out


def run_thermonav(folder, outages, out):
    profile = os.path.join(folder, "profile.toml")
    subprocess.run([THERMONAV, "simulate", "profile", "--out", profile, "--quiet"], check=True, capture_output=True)
    t0 = time.perf_counter()
    result = subprocess.run([THERMONAV, "integrate", "--imu", os.path.join(folder, "imu.csv"), "--gnss",
                             os.path.join(folder, "gnss.csv"), "--profile", profile, "--filter", "ekf",
                             "--outages", outages, "--initial-from", os.path.join(folder, "reference.csv"),
                             "--out", out, "--json", "--quiet"], check=True, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    return wall, json.loads(result.stdout)


def noise_model(report):
    """Per triad (gyro, accel): white-noise density N, the bias random walk standing in for the
    Gauss-Markov bias (sigma sqrt(2/Tc), the stand-in `bank export` writes) and the turn-on bias
    sd, from the model thermonav's run used, so that the peers are tuned from the same numbers."""
    channels = {c["channel"]: c for c in report["model"]["channels"]}
    triad = lambda names: (np.array([channels[n]["white_noise_density"] for n in names]),
                           np.array([channels[n]["bias_sigma"] * np.sqrt(2 / channels[n]["bias_correlation_time_s"])
                                     for n in names]))
    gyro_n, gyro_walk = triad(["gx", "gy", "gz"])
    accel_n, accel_walk = triad(["ax", "ay", "az"])
    turn_on = report["initial_bias_sd"]
    gyro_bias = np.radians(np.array(turn_on["gyro_deg_h"]) / 3600)
    accel_bias = np.array(turn_on["accel_mg"]) * 9.80665e-3
    return {"gyro": (gyro_n, gyro_walk, gyro_bias), "accel": (accel_n, accel_walk, accel_bias)}


def read_survey(folder):
    imu = pd.read_csv(os.path.join(folder, "imu.csv"))
    gnss = pd.read_csv(os.path.join(folder, "gnss.csv"))
    reference = pd.read_csv(os.path.join(folder, "reference.csv"))
    return imu, gnss, reference


def start_state(reference, imu, first_fix):
    """The reference state at the first IMU sample at or after the first fix, and its index."""
    k0 = int(np.searchsorted(imu["t_s"], first_fix))
    t = float(imu["t_s"].iloc[k0])
    row = {c: float(np.interp(t, reference["t_s"], reference[c])) for c in reference.columns if c != "t_s"}
    return k0, t, row


def run_inslib(folder, outages, model):
    """INSLIB's Ins (the lean 15-state ESKF), fed the same files sample by sample; returns the
    wall time (CSV reading included, as for thermonav) and the 10 Hz solution."""
    from INSLIB import Config, Ins
    t0 = time.perf_counter()
    imu, gnss, reference = read_survey(folder)
    first_fix = float(gnss["t_s"].iloc[0])
    k0, t_start, start = start_state(reference, imu, first_fix)
    dt_nominal = float(np.median(np.diff(imu["t_s"])))
    (gyro_n, gyro_walk, gyro_bias), (accel_n, accel_walk, accel_bias) = model["gyro"], model["accel"]
    config = Config()
    # Variance of one sample of white noise of density N is N^2/dt.
    gyr_var, acc_var = tuple(gyro_n ** 2 / dt_nominal), tuple(accel_n ** 2 / dt_nominal)
    config.gyr_bias_pred_stddev_rps_sqrts = float(gyro_walk.max())
    config.acc_bias_pred_stddev_mps2_sqrts = float(accel_walk.max())
    config.gyr_bias_init_stddev_rps = float(gyro_bias.max())
    config.acc_bias_init_stddev_mps2 = float(accel_bias.max())
    config.auto_init = False
    config.time_us = int(round(t_start * 1e6))
    config.lat_rad, config.lon_rad, config.h_m = np.radians(start["lat_deg"]), np.radians(start["lon_deg"]), start["h_m"]
    config.rpy_init_rad = tuple(np.radians([start["roll_deg"], start["pitch_deg"], start["yaw_deg"]]))
    config.init_vel_ned = (start["vn_m_s"], start["ve_m_s"], start["vd_m_s"])
    config.allow_unlimited_deadreckoning = True
    ins = Ins(config)
    in_outage = lambda t: any(a <= t < b for a, b in outages)
    t = imu["t_s"].to_numpy()
    acc = imu[["ax_m_s2", "ay_m_s2", "az_m_s2"]].to_numpy().tolist()
    gyr = imu[["gx_rad_s", "gy_rad_s", "gz_rad_s"]].to_numpy().tolist()
    fixes = gnss.to_dict("records")
    next_fix, next_output, rows = 0, first_fix, []
    for k in range(k0 + 1, len(t)):
        ins.imu(int(round(t[k] * 1e6)), t[k] - t[k - 1], acc[k], gyr[k], acc_var, gyr_var)
        while next_fix < len(fixes) and fixes[next_fix]["t_s"] <= t[k]:
            fix = fixes[next_fix]
            if not in_outage(fix["t_s"]):
                age_us = int(round((t[k] - fix["t_s"]) * 1e6))
                ins.gnss_pos_llh((np.radians(fix["lat_deg"]), np.radians(fix["lon_deg"]), fix["h_m"]),
                                 (fix["sd_n_m"] ** 2, fix["sd_e_m"] ** 2, fix["sd_u_m"] ** 2), delay_us=age_us)
                ins.yaw(np.radians(fix["heading_deg"]), np.radians(fix["sd_heading_deg"]))
            next_fix += 1
        ins.update()
        if t[k] >= next_output:
            lat, lon, h = ins.position_llh()
            rows.append((t[k], np.degrees(lat), np.degrees(lon), h))
            next_output += 0.1
    wall = time.perf_counter() - t0
    return wall, pd.DataFrame(rows, columns=["t_s", "lat_deg", "lon_deg", "h_m"]), reference


def run_pyins(folder, outages, model):
    """pyins (PyPI `python-ins`, MIT) `run_feedback_filter`: its EKF with feedback corrections,
    strapdown in numba, covariance every 0.1 s; position fixes only (pyins has no heading
    measurement). Returns the wall time (CSV reading included) and the solution."""
    import pyins
    from pyins import filters, inertial_sensor, measurements, strapdown
    t0 = time.perf_counter()
    imu, gnss, reference = read_survey(folder)
    first_fix = float(gnss["t_s"].iloc[0])
    k0, t_start, start = start_state(reference, imu, first_fix)
    readings = imu.iloc[k0:].set_index("t_s")
    readings = readings.rename(columns={"gx_rad_s": "gyro_x", "gy_rad_s": "gyro_y", "gz_rad_s": "gyro_z",
                                        "ax_m_s2": "accel_x", "ay_m_s2": "accel_y", "az_m_s2": "accel_z"})
    increments = strapdown.compute_increments_from_imu(readings[pyins.util.GYRO_COLS + pyins.util.ACCEL_COLS], "rate")
    pva = pd.Series({"lat": start["lat_deg"], "lon": start["lon_deg"], "alt": start["h_m"], "VN": start["vn_m_s"],
                     "VE": start["ve_m_s"], "VD": start["vd_m_s"], "roll": start["roll_deg"],
                     "pitch": start["pitch_deg"], "heading": start["yaw_deg"]}, name=t_start)
    aided = gnss[[not any(a <= t < b for a, b in outages) for t in gnss["t_s"]]]
    fixes = aided.set_index("t_s").rename(columns={"lat_deg": "lat", "lon_deg": "lon", "h_m": "alt"})
    (gyro_n, gyro_walk, gyro_bias), (accel_n, accel_walk, accel_bias) = model["gyro"], model["accel"]
    gyro_model = inertial_sensor.EstimationModel(bias_sd=gyro_bias, noise=gyro_n, bias_walk=gyro_walk)
    accel_model = inertial_sensor.EstimationModel(bias_sd=accel_bias, noise=accel_n, bias_walk=accel_walk)
    result = filters.run_feedback_filter(pva, 1.0, 0.1, 0.5, 1.0, increments, gyro_model, accel_model,
                                         [measurements.Position(fixes[["lat", "lon", "alt"]],
                                                                float(gnss["sd_n_m"].iloc[0]))])
    wall = time.perf_counter() - t0
    trajectory = result.trajectory.reset_index()
    trajectory = trajectory.rename(columns={trajectory.columns[0]: "t_s", "lat": "lat_deg", "lon": "lon_deg"})
    return wall, trajectory


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration-s", type=float, default=1800, help="survey length (the demo's: 1800)")
    parser.add_argument("--outages", default="spread:8,100", help="thermonav's --outages (the demo's: 8 x 100 s)")
    parser.add_argument("--pyins", action="store_true",
                        help="also time pyins (about 0.25 s per survey second here: 7 minutes for the demo's survey)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = os.path.join(tmp, "vessel")
        subprocess.run([THERMONAV, "simulate", "vessel", "--out", folder, "--duration-s", str(args.duration_s),
                        "--quiet"], check=True, capture_output=True)
        ours_s, report = run_thermonav(folder, args.outages, os.path.join(tmp, "solution.csv"))
        outages = [(o["start_s"], o["end_s"]) for o in report["outages"]]
        model = noise_model(report)
        peer_s, peer_solution, reference = run_inslib(folder, outages, model)
        if args.pyins:
            # numba compiles pyins' strapdown on first use: do that on a 60 s survey (the shortest), untimed.
            warm_up = os.path.join(tmp, "warm-up")
            subprocess.run([THERMONAV, "simulate", "vessel", "--out", warm_up, "--duration-s", "60", "--quiet"],
                           check=True, capture_output=True)
            run_pyins(warm_up, [], model)
            pyins_s, pyins_solution = run_pyins(folder, outages, model)
        ours_solution = pd.read_csv(os.path.join(tmp, "solution.csv"))
        ends = [b for _, b in outages]
        ours_err, peer_err = errors_at(ends, ours_solution, reference), errors_at(ends, peer_solution, reference)
        pyins_err = errors_at(ends, pyins_solution, reference) if args.pyins else []
    samples = report["imu_samples"]
    print(f"survey: {args.duration_s:.0f} s, {samples} IMU samples at 200 Hz, 1 Hz GNSS position + heading, "
          f"outages {args.outages}; load average (1 min) {os.getloadavg()[0]:.1f}")
    print(f"{'run':<64} {'wall s':>8} {'samples/s':>10} {'ratio':>6}")
    print(f"{'INSLIB 1.4.1 Ins (C 15-state ESKF, ctypes, one call per sample)':<64} {peer_s:8.2f} "
          f"{samples / peer_s:10.0f} {peer_s / ours_s:6.1f}")
    if args.pyins:
        print(f"{'pyins 1.0.1 run_feedback_filter (EKF, numba strapdown, P at 10 Hz)':<64} {pyins_s:8.2f} "
              f"{samples / pyins_s:10.0f} {pyins_s / ours_s:6.1f}")
    print(f"{'thermonav integrate --filter ekf (21 states, whole command)':<64} {ours_s:8.2f} "
          f"{samples / ours_s:10.0f} {1.0:6.1f}")
    print("horizontal error at each outage's end, m (different filters and tuning: a sanity check):")
    print("  thermonav " + " ".join(f"{e:7.1f}" for e in ours_err))
    print("  INSLIB    " + " ".join(f"{e:7.1f}" for e in peer_err))
    if args.pyins:
        print("  pyins     " + " ".join(f"{e:7.1f}" for e in pyins_err) + "  (position fixes only)")
    sys.exit(0 if all(np.isfinite(peer_err + pyins_err)) else 1)


if __name__ == "__main__":
    main()
