#!/usr/bin/env python3
"""thermonav's EKF and KF-GINS side by side on one simulated vessel survey, in one run.

Both filters get the same inputs and the same noise model:
- a one-temperature chamber record (17 degC, 1 h, 200 Hz) characterised by thermonav into a
  bank; `bank export --format kf-gins` writes KF-GINS's `imunoise` block from it, and
  thermonav's `integrate --bank` reads the same bank;
- a 30 min harbour survey at 17 degC (200 Hz IMU, 1 Hz position fixes, antenna 0.3 m ahead
  and 2.5 m above the IMU), position aiding only (KF-GINS has no velocity or heading update),
  of two units: the built-in profile's, whose gyro turn-on bias has the data sheet's 1 deg/s
  sd, and the same unit with its turn-on bias removed at power-on (0.01 deg/s left). With the
  first, neither filter holds heading on the survey's straight legs (position fixes do not
  show a heading error without acceleration), so the outage errors compare two lost filters;
  the second is where the filters' accuracy can be compared. Timings are on the second;
  8 outages of 60 s (300 s, then every 180 s): thermonav with `--outages`, KF-GINS on a GNSS
  file without those fixes (it has no outage option);
- both start at the reference state at the first fix, with thermonav's default initial
  standard deviations (2 m, 0.5 m/s, 2/2/5 deg, the bias sds `integrate --json` reports,
  1000 ppm scale factors).

Equal work is KF-GINS's own mode: covariance propagated and the solution written at every IMU
sample (`--covariance-rate-hz 200 --output-rate-hz 200`; thermonav also writes the 21 states
and their sds, as KF-GINS writes its IMU errors and sds). thermonav's default (covariance at
10 Hz, output at the IMU rate) is timed too. Times are the best of --repeats runs of each,
interleaved; peak memory is the max resident set size (`/usr/bin/time -v`). Both solutions
are scored by `thermonav evaluate --solution` against the simulated reference with the same
outage metrics.

Differences that remain, stated: KF-GINS has one correlation time for all bias and scale-
factor states (the export writes the geometric mean of the six bias Tc; thermonav uses each
channel's, and 1 h for the scale factors); KF-GINS has no innovation gate (thermonav's scaled
gate rejects nothing on these simulated fixes).

Second, the real car drive of ../shared/data/rtklibexplorer-gnss-imu/drive_0708 (100 Hz MEMS
IMU, 5 Hz RTK fixes, the settings of bench/drive_gating.sh): KF-GINS starts at thermonav's
first solution epoch (its alignment from the fixes) with the drive profile's noise (white noise
x10 as `--process-noise-scale 10`; the profile's one-hour correlation times are KF-GINS's
`corrtime` exactly), and both are scored by the horizontal RMS distance of their antenna
point from the RTK fixes (aided RMS; fixes from 5 s after the start): thermonav with position
fixes only, as KF-GINS, and with the fixes' velocities too (its default on the drive).

KF-GINS (GPL-3.0) is built from ../shared/peers/kf-gins-f39bc2e.tar.gz in a temporary folder
(about 3 minutes with -j2), or taken from --kf-gins. Nothing of it enters the repository.

Usage: python3 bench/kf_gins_side_by_side.py [--thermonav T] [--kf-gins BIN] [--repeats 3]
"""

import argparse
import bisect
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARBALL = ROOT.parent / "shared" / "peers" / "kf-gins-f39bc2e.tar.gz"
LEVER_ARM_M = (0.3, 0.0, -2.5)  # the simulated vessel's antenna (vessel.json)
OUTAGES = "every:300,60,180,8"
OUTAGE_WINDOWS = [(300.0 + 180.0 * k, 360.0 + 180.0 * k) for k in range(8)]
IMU_RATE_HZ = 200
MG_TO_MGAL = 9.80665e-3 / 1e-5  # 1 mg in mGal
RAD_S_TO_DEG_H = math.degrees(1.0) * 3600.0


# The z-gyro bias prior split into 41 filters (`integrate --bias-hypotheses`): the position-only
# runs here are where one filter loses its heading.
GAUSSIAN_SUM = ("--bias-hypotheses", "41")


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


def build_kf_gins(work: Path) -> Path:
    src = work / "kf-gins-src"
    src.mkdir()
    run(["tar", "xzf", str(TARBALL), "-C", str(src)])
    run(["cmake", "-S", str(src), "-B", str(src / "build"), "-DCMAKE_BUILD_TYPE=Release"])
    run(["make", "-C", str(src / "build"), "-j2", "KF-GINS"])
    return src / "bin" / "KF-GINS"


def timed(cmd, cwd=None):
    """Wall time, CPU time and peak RSS of one run of `cmd`, from /usr/bin/time -v."""
    out = subprocess.run(["/usr/bin/time", "-v", *cmd], cwd=cwd, text=True,
                         capture_output=True)
    if out.returncode != 0:
        sys.exit(f"{cmd[0]} failed:\n{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
    field = lambda name: re.search(rf"{name}: (.*)", out.stderr).group(1).strip()
    h_m_s = [float(x) for x in field(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\)").split(":")]
    wall = sum(v * 60 ** (len(h_m_s) - 1 - i) for i, v in enumerate(h_m_s))
    cpu = float(field("User time \\(seconds\\)")) + float(field("System time \\(seconds\\)"))
    return {"wall_s": wall, "cpu_s": cpu, "max_rss_mb": int(field("Maximum resident set size \\(kbytes\\)")) / 1024}


def reference_at(reference_csv: Path, t_s: float):
    rows = list(csv.DictReader(open(reference_csv)))
    times = [float(r["t_s"]) for r in rows]
    k = min(max(bisect.bisect_left(times, t_s), 1), len(rows) - 1)
    a, b = rows[k - 1], rows[k]
    w = (t_s - times[k - 1]) / (times[k] - times[k - 1])
    lerp = lambda key: float(a[key]) + w * (float(b[key]) - float(a[key]))
    yaw_a, yaw_b = float(a["yaw_deg"]), float(b["yaw_deg"])
    yaw = yaw_a + w * ((yaw_b - yaw_a + 180.0) % 360.0 - 180.0)
    return {k: lerp(k) for k in ("lat_deg", "lon_deg", "h_m", "vn_m_s", "ve_m_s", "vd_m_s",
                                 "roll_deg", "pitch_deg")} | {"yaw_deg": yaw}


def withhold_fixes(gnss_txt: Path, out: Path) -> int:
    kept = 0
    with open(gnss_txt) as src, open(out, "w") as dst:
        for line in src:
            t = float(line.split()[0])
            if not any(start <= t < end for start, end in OUTAGE_WINDOWS):
                dst.write(line)
                kept += 1
    return kept


def vec(v):
    return "[ " + ", ".join(repr(float(x)) for x in v) + " ]"


def kf_gins_config(w: Path, start, t0: float, bias_sd, imunoise_block: str,
                   rate_hz: int = IMU_RATE_HZ, lever_arm_m=LEVER_ARM_M) -> Path:
    gyro_deg_h = bias_sd["gyro_deg_h"]
    accel_mgal = [v * MG_TO_MGAL for v in bias_sd["accel_mg"]]
    text = f"""imupath: "{w}/kf/imu.txt"
gnsspath: "{w}/kf/gnss.txt"
outputpath: "{w}/kf/out"
imudatalen: 7
imudatarate: {rate_hz}
starttime: {t0!r}
endtime: -1
initpos: {vec([start['lat_deg'], start['lon_deg'], start['h_m']])}
initvel: {vec([start['vn_m_s'], start['ve_m_s'], start['vd_m_s']])}
initatt: {vec([start['roll_deg'], start['pitch_deg'], start['yaw_deg'] % 360.0])}
initgyrbias: [ 0, 0, 0 ]
initaccbias: [ 0, 0, 0 ]
initgyrscale: [ 0, 0, 0 ]
initaccscale: [ 0, 0, 0 ]
initposstd: [ 2.0, 2.0, 3.0 ]
initvelstd: [ 0.5, 0.5, 0.5 ]
initattstd: [ 2.0, 2.0, 5.0 ]
initbgstd: {vec(gyro_deg_h)}
initbastd: {vec(accel_mgal)}
initsgstd: [ 1000, 1000, 1000 ]
initsastd: [ 1000, 1000, 1000 ]
{imunoise_block}
antlever: {vec(lever_arm_m)}
"""
    path = w / "kf" / "kf-gins.yaml"
    path.write_text(text)
    return path


def imunoise_block(yaml_text: str) -> str:
    lines = yaml_text.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("imunoise:"))
    block = [lines[start]]
    for line in lines[start + 1:]:
        if not line.startswith("  "):
            break
        block.append(line)
    return "\n".join(block)


def unit_profiles(t: str, w: Path):
    """The built-in profile, and the same with the gyro turn-on bias sd cut to 0.01 deg/s."""
    run([t, "simulate", "profile", "--out", str(w / "profile.toml")])
    text = (w / "profile.toml").read_text()
    removed, n = re.subn(r"(?m)^turn_on_bias_sd_deg_s = .*$", "turn_on_bias_sd_deg_s = 0.01", text)
    assert n == 3, "the profile's three gyro turn-on bias keys"
    (w / "turn_on_removed.toml").write_text(removed)
    return {"data-sheet turn-on bias": w / "profile.toml",
            "turn-on bias removed": w / "turn_on_removed.toml"}


def prepare_survey(t: str, w: Path, profile: Path):
    """The survey of one unit in `w`, and KF-GINS's input files in `w/kf`."""
    run([t, "simulate", "vessel", "--out", str(w / "vessel"), "--duration-s", "1800",
         "--profile", str(profile), "--quiet"])
    (w / "kf" / "out").mkdir(parents=True)
    run([t, "convert", str(w / "vessel/imu.csv"), "--to", "kf-gins", "--out", str(w / "kf/imu.txt")])
    run([t, "convert", str(w / "vessel/gnss.csv"), "--to", "kf-gins", "--out", str(w / "kf/all_gnss.txt")])
    return withhold_fixes(w / "kf/all_gnss.txt", w / "kf/gnss.txt")


def prepare_bank(t: str, w: Path):
    quiet = ["--quiet"]
    run([t, "simulate", "chamber", "--out", str(w / "chamber"), "--temperatures-c", "17",
         "--duration-s", "3600", "--rate-hz", str(IMU_RATE_HZ), *quiet])
    chamber = sorted(str(p) for p in (w / "chamber").glob("imu_*.csv"))
    run([t, "characterize", *chamber, "--out", str(w / "bank.json"), *quiet])
    run([t, "bank", "export", str(w / "bank.json"), "--format", "kf-gins",
         "--scale-factor-std-ppm", "1000", "--out", str(w / "imunoise.yaml")])


def thermonav_cmd(t: str, w: Path, label: str, equal_work: bool, extra=()):
    cmd = [t, "integrate", "--imu", str(w / "vessel/imu.csv"), "--gnss", str(w / "vessel/gnss.csv"),
           "--bank", str(w.parent / "bank.json"), "--no-heading", "--no-velocity",
           "--initial-from", str(w / "vessel/reference.csv"),
           "--lever-arm-m", ",".join(str(v) for v in LEVER_ARM_M), "--outages", OUTAGES,
           "--output-rate-hz", str(IMU_RATE_HZ), "--out", str(w / f"{label}.csv"), "--quiet", "--json"]
    if equal_work:
        cmd += ["--covariance-rate-hz", str(IMU_RATE_HZ)]
    return cmd + list(extra)


def score(t: str, w: Path, solutions):
    cmd = [t, "evaluate", "--reference", str(w / "vessel/reference.csv"), "--outages", OUTAGES,
           "--out", str(w / "evaluation"), "--json"]
    for label, path in solutions:
        cmd += ["--solution", str(path), "--solution-label", label]
    run(cmd)
    return json.load(open(w / "evaluation" / "evaluation.json"))


def outside_rows(evaluation):
    """label -> the outside row of the first table that holds it."""
    rows = {}

    def walk(node):
        if isinstance(node, dict):
            if node.get("kind") == "outside" and "label" in node:
                rows.setdefault(node["label"], node)
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk(evaluation)
    return rows


def survey_runs(t: str, kf: Path, w: Path):
    """The three commands on one unit's survey (KF-GINS's configuration written first)."""
    first = json.loads(run(thermonav_cmd(t, w, "probe", False)).stdout)
    t0 = float(open(w / "kf/gnss.txt").readline().split()[0])
    start = reference_at(w / "vessel/reference.csv", t0)
    config = kf_gins_config(w, start, t0, first["initial_bias_sd"],
                            imunoise_block((w.parent / "imunoise.yaml").read_text()))
    return {
        "KF-GINS": ([str(kf), str(config)], w / "kf"),
        "thermonav EKF, equal work": (thermonav_cmd(t, w, "equal", True), None),
        "thermonav EKF, default": (thermonav_cmd(t, w, "default", False), None),
        "thermonav EKF, Gaussian sum": (thermonav_cmd(t, w, "sum", False, GAUSSIAN_SUM), None),
    }


def best_times(runs, repeats: int):
    best = {}
    for _ in range(repeats):
        for label, (cmd, cwd) in runs.items():
            m = timed(cmd, cwd)
            if label not in best or m["wall_s"] < best[label]["wall_s"]:
                best[label] = m
    return best


def scores(t: str, w: Path):
    nav = next((w / "kf/out").glob("*.nav"))
    evaluation = score(t, w, [("KF-GINS", nav), ("thermonav-equal-work", w / "equal.csv"),
                              ("thermonav-default", w / "default.csv"),
                              ("thermonav-gaussian-sum", w / "sum.csv")])
    keys = ("rms_horizontal_m", "max_drift_horizontal_m", "rms_of_max_north_m",
            "rms_of_max_east_m", "rms_heading_deg")
    return {label: {k: row[k] for k in keys} for label, row in outside_rows(evaluation).items()}


def print_scores(name: str, table):
    print(f"\n{name}: outage errors (evaluate --solution, 8 x 60 s)")
    print(f"{'solution':22}" + "".join(f"{k:>24}" for k in next(iter(table.values()))))
    base = table["KF-GINS"]
    for label, row in table.items():
        cells = "".join(f"{v:14.2f} ({v / base[k] - 1:+6.1%})" for k, v in row.items())
        print(f"{label:22}{cells}")


DRIVE = ROOT.parent / "shared" / "data" / "rtklibexplorer-gnss-imu" / "drive_0708"
DRIVE_PROFILE = ROOT / "examples" / "profiles" / "drive_0708_imu.toml"
DRIVE_LEVER_ARM_M = (0.0, -0.05, 0.0)
DRIVE_NOISE_SCALE = 10.0


def drive_inputs(t: str, w: Path):
    w.mkdir()
    run([t, "convert", str(DRIVE / "imu_1934.csv"), "--imu-frame", "drive-frd",
         "--time-offset-s=-0.125", "--out", str(w / "imu.csv")])
    run([t, "convert", str(DRIVE / "gnss_1934_sf.pos"), "--out", str(w / "gnss.csv")])
    (w / "kf" / "out").mkdir(parents=True)
    run([t, "convert", str(w / "imu.csv"), "--to", "kf-gins", "--out", str(w / "kf/imu.txt")])
    run([t, "convert", str(w / "gnss.csv"), "--to", "kf-gins", "--out", str(w / "kf/gnss.txt")])


def drive_thermonav(t: str, w: Path, label: str, velocity: bool):
    cmd = [t, "integrate", "--imu", str(w / "imu.csv"), "--gnss", str(w / "gnss.csv"),
           "--profile", str(DRIVE_PROFILE), "--process-noise-scale", str(DRIVE_NOISE_SCALE),
           "--velocity-sd-m-s", "0.1", "--lever-arm-m", ",".join(map(str, DRIVE_LEVER_ARM_M)),
           "--output-rate-hz", "100", "--out", str(w / f"{label}.csv"), "--quiet", "--json"]
    if not velocity:
        cmd.append("--no-velocity")
    return json.loads(run(cmd).stdout)


def drive_kf_gins_config(w: Path, report) -> Path:
    """KF-GINS at thermonav's first epoch, with the drive profile's noise."""
    import tomllib
    profile = tomllib.loads(DRIVE_PROFILE.read_text())["channels"]
    first = next(csv.DictReader(open(w / "position_only.csv")))
    sow_offset = float(open(w / "kf/gnss.txt").readline().split()[0]) - \
        float(next(csv.DictReader(open(w / "gnss.csv")))["t_s"])
    gyro = [profile[c] for c in ("gx", "gy", "gz")]
    accel = [profile[c] for c in ("ax", "ay", "az")]
    gm = lambda ch, key: ch["bias_gauss_markov"][0][key]
    start = {"lat_deg": float(first["lat_deg"]), "lon_deg": float(first["lon_deg"]),
             "h_m": float(first["h_m"]), "vn_m_s": float(first["vn_m_s"]),
             "ve_m_s": float(first["ve_m_s"]), "vd_m_s": float(first["vd_m_s"]),
             "roll_deg": float(first["roll_deg"]), "pitch_deg": float(first["pitch_deg"]),
             "yaw_deg": float(first["yaw_deg"])}
    noise = "\n".join([
        "imunoise:",
        f"  arw: {vec([c['white_noise_deg_per_sqrt_h'] * DRIVE_NOISE_SCALE for c in gyro])}",
        f"  vrw: {vec([c['white_noise_m_s_per_sqrt_h'] * DRIVE_NOISE_SCALE for c in accel])}",
        f"  gbstd: {vec([gm(c, 'sigma_deg_h') for c in gyro])}",
        f"  abstd: {vec([gm(c, 'sigma_mg') * MG_TO_MGAL for c in accel])}",
        "  gsstd: [ 1000, 1000, 1000 ]",
        "  asstd: [ 1000, 1000, 1000 ]",
        f"  corrtime: {gm(gyro[0], 'correlation_time_s') / 3600.0!r}",
    ])
    config = kf_gins_config(w, start, float(first["t_s"]) + sow_offset, report["initial_bias_sd"],
                            noise, rate_hz=100, lever_arm_m=DRIVE_LEVER_ARM_M)
    return config, sow_offset


def aided_rms_m(track, fixes, lever_right_m: float) -> float:
    """Horizontal RMS distance of the antenna point (the track interpolated at each fix, from
    5 s after its start) from the fixes; `track` rows are (t_s, lat_deg, lon_deg, yaw_deg)."""
    times = [p[0] for p in track]
    errors = []
    for fix in fixes:
        time = float(fix["t_s"])
        k = bisect.bisect_left(times, time)
        if time < times[0] + 5 or k == 0 or k == len(times):
            continue
        a, b = track[k - 1], track[k]
        w = (time - a[0]) / (b[0] - a[0])
        lat, lon = a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2])
        yaw = math.radians(a[3])
        north = math.radians(lat - float(fix["lat_deg"])) * 6378137 - lever_right_m * math.sin(yaw)
        east = (math.radians(lon - float(fix["lon_deg"])) * 6378137 * math.cos(math.radians(lat))
                + lever_right_m * math.cos(yaw))
        errors.append(math.hypot(north, east))
    return math.sqrt(sum(e * e for e in errors) / len(errors))


def drive_side_by_side(t: str, kf: Path, w: Path):
    drive_inputs(t, w)
    report = drive_thermonav(t, w, "position_only", False)
    with_velocity = drive_thermonav(t, w, "with_velocity", True)
    config, sow_offset = drive_kf_gins_config(w, report)
    run([str(kf), str(config)], cwd=w / "kf")
    fixes = list(csv.DictReader(open(w / "gnss.csv")))
    ours = lambda label: [(float(r["t_s"]), float(r["lat_deg"]), float(r["lon_deg"]),
                           float(r["yaw_deg"])) for r in csv.DictReader(open(w / f"{label}.csv"))]
    nav = next((w / "kf/out").glob("*.nav"))
    theirs = [(float(c[1]) - sow_offset, float(c[2]), float(c[3]), float(c[10]))
              for c in (line.split() for line in open(nav))]
    rejected = lambda r: next(i for i in r["innovations"] if i["kind"] == "position")["rejected"]
    lever = DRIVE_LEVER_ARM_M[1]
    rows = {"KF-GINS (positions)": (aided_rms_m(theirs, fixes, lever), 0),
            "thermonav EKF (positions)": (aided_rms_m(ours("position_only"), fixes, lever), rejected(report)),
            "thermonav EKF (positions, velocities)": (aided_rms_m(ours("with_velocity"), fixes, lever),
                                                      rejected(with_velocity))}
    print(f"\ncar drive (drive_0708): aided RMS of the antenna point against {len(fixes)} RTK fixes")
    base = rows["KF-GINS (positions)"][0]
    for label, (rms, n) in rows.items():
        print(f"{label:40} {rms:8.4f} m ({rms / base - 1:+6.1%})  fixes rejected {n}")
    return {label: {"aided_rms_m": rms, "fixes_rejected": n} for label, (rms, n) in rows.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--thermonav", default=str(ROOT / "target/release/thermonav"))
    ap.add_argument("--kf-gins", help="a KF-GINS binary already built from the peers tarball")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--keep", help="keep the working folder here")
    args = ap.parse_args()
    t = args.thermonav
    w = Path(args.keep or tempfile.mkdtemp(prefix="kfgins-side-"))
    w.mkdir(parents=True, exist_ok=True)
    kf = Path(args.kf_gins) if args.kf_gins else build_kf_gins(w)
    prepare_bank(t, w)
    results = {}
    for k, (name, profile) in enumerate(unit_profiles(t, w).items()):
        unit = w / f"unit{k}"
        unit.mkdir()
        kept = prepare_survey(t, unit, profile)
        runs = survey_runs(t, kf, unit)
        timing = best_times(runs, args.repeats if k == 1 else 1)
        results[name] = {"timing": timing, "scores": scores(t, unit), "fixes_to_kf_gins": kept}
    timing = results["turn-on bias removed"]["timing"]
    print(f"simulated vessel, 1800 s, {IMU_RATE_HZ} Hz IMU, 1 Hz position-only GNSS, "
          f"8 x 60 s outages; turn-on bias removed; best of {args.repeats} runs")
    print(f"{'run':28} {'wall s':>8} {'cpu s':>8} {'peak MB':>8} {'KF-GINS/run':>12}")
    kf_wall = timing["KF-GINS"]["wall_s"]
    for label, m in timing.items():
        print(f"{label:28} {m['wall_s']:8.2f} {m['cpu_s']:8.2f} {m['max_rss_mb']:8.1f} "
              f"{kf_wall / m['wall_s']:12.2f}")
    for name, r in results.items():
        print_scores(name, r["scores"])
    results["car drive"] = drive_side_by_side(t, kf, w / "drive")
    (w / "side_by_side.json").write_text(json.dumps(results, indent=1))
    print(f"\nworking folder: {w}")


if __name__ == "__main__":
    main()
