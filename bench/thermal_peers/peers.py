"""Runs the two autopilots' offline thermal fitters where they lie in shared/peers/ on a fold's
training samples, and turns what they write into bias predictions.

PX4 (Tools/process_sensor_caldata.py): reads a ULog, writes LOG.ulg.params (QGC format, tab
separated `1 1 NAME VALUE TYPE`). Prediction: sum_k X_k (T - TREF)^k, k = 0..3, T clamped to
[TMIN, TMAX]; gyro in rad/s, accel in m/s^2 (its median removed before the fit).

ArduPilot (Tools/scripts/tempcal_IMU.py): reads a DataFlash log, writes `NAME VALUE` lines.
Prediction: sum_k c_k 1e-6 (T - 35)^k, k = 1..3 (no constant), T clamped to [TMIN, TMAX]. The
fitter fits the samples as logged (no rotation with AHRS_ORIENTATION 0, no log correction to
undo with INS_TCAL1_ENABLE 0), and the firmware subtracts this polynomial from the sample, so
it is the bias itself with ArduPilot's sign; the accel fit is of the sample minus its mean."""
import os
import subprocess
import sys

import numpy as np

import dataflash_writer
import ulog_writer

PEERS_DIR = "/work/shared/peers"
PX4_SCRIPT = os.path.join(PEERS_DIR, "px4-process_sensor_caldata.py")
AP_SCRIPT = os.path.join(PEERS_DIR, "ardupilot-tempcal_IMU.py")
TIMEOUT_S = 600
AXIS_INDEX = {"x": 0, "y": 1, "z": 2}


class PeerFailure(Exception):
    pass


def _run(cmd, cwd, log_name):
    with open(os.path.join(cwd, log_name), "w") as log:
        try:
            p = subprocess.run(cmd, cwd=cwd, stdout=log, stderr=subprocess.STDOUT,
                               timeout=TIMEOUT_S, env=dict(os.environ, MPLBACKEND="Agg"))
        except subprocess.TimeoutExpired:
            raise PeerFailure("timed out after %d s" % TIMEOUT_S)
    if p.returncode != 0:
        with open(os.path.join(cwd, log_name)) as f:
            lines = [l.strip() for l in f if l.strip()]
        raise PeerFailure("exit %d: %s" % (p.returncode, lines[-1] if lines else "(no output)"))


def run_px4(folder, t_s, gyro, accel, temp_c):
    """Returns {channel: (coeffs k=0..3, tref, tmin, tmax)} for gx..az."""
    path = os.path.join(folder, "train.ulg")
    ulog_writer.write(path, t_s, gyro, accel, temp_c)
    ulog_writer.verify(path, t_s, gyro, accel, temp_c)
    _run([sys.executable, PX4_SCRIPT, "train.ulg"], folder, "px4.log")
    params = {}
    try:
        with open(path + ".params") as f:
            for line in f:
                if line.startswith("#") or not line.strip():
                    continue
                parts = line.rstrip("\n").split("\t")
                params[parts[2]] = float(parts[3])
    except (OSError, IndexError, ValueError) as e:
        raise PeerFailure("unreadable train.ulg.params: %s" % e)
    out = {}
    for sensor, prefix in (("g", "TC_G0_"), ("a", "TC_A0_")):
        for axis, a in AXIS_INDEX.items():
            try:
                coeffs = [params["%sX%d_%d" % (prefix, k, a)] for k in range(4)]
                lim = [params[prefix + n] for n in ("TREF", "TMIN", "TMAX")]
            except KeyError as e:
                raise PeerFailure("missing %s in train.ulg.params" % e)
            if not np.all(np.isfinite(coeffs + lim)):
                raise PeerFailure("non-finite %s coefficients" % (prefix + str(a)))
            out[sensor + axis] = (coeffs, lim[0], lim[1], lim[2])
    return out


def predict_px4(fit, temp_c):
    coeffs, tref, tmin, tmax = fit
    x = np.clip(temp_c, tmin, tmax) - tref
    return sum(c * x ** k for k, c in enumerate(coeffs))


def run_ardupilot(folder, t_s, gyro, accel, temp_c):
    """Returns {channel: (coeffs k=1..3 in SI, tmin, tmax)} for gx..az."""
    path = os.path.join(folder, "train.bin")
    dataflash_writer.write(path, t_s, gyro, accel, temp_c)
    dataflash_writer.verify(path, t_s, gyro, accel, temp_c)
    _run([sys.executable, AP_SCRIPT, "--no-graph", "--outfile", "tcal.parm", "train.bin"],
         folder, "ardupilot.log")
    params = {}
    try:
        with open(os.path.join(folder, "tcal.parm")) as f:
            for line in f:
                if line.strip():
                    name, value = line.split()
                    params[name] = float(value)
    except (OSError, ValueError) as e:
        raise PeerFailure("unreadable tcal.parm: %s" % e)
    out = {}
    for sensor, kind in (("g", "GYR"), ("a", "ACC")):
        for axis in AXIS_INDEX:
            try:
                coeffs = [params["INS_TCAL1_%s%d_%s" % (kind, k, axis.upper())] * 1e-6
                          for k in (1, 2, 3)]
                tmin, tmax = params["INS_TCAL1_TMIN"], params["INS_TCAL1_TMAX"]
            except KeyError as e:
                raise PeerFailure("missing %s in tcal.parm" % e)
            if not np.all(np.isfinite(coeffs + [tmin, tmax])):
                raise PeerFailure("non-finite INS_TCAL1_%s coefficients" % kind)
            out[sensor + axis] = (coeffs, tmin, tmax)
    return out


AP_TEMP_REF_C = 35.0


def predict_ardupilot(fit, temp_c):
    coeffs, tmin, tmax = fit
    x = np.clip(temp_c, tmin, tmax) - AP_TEMP_REF_C
    return sum(c * x ** k for k, c in zip((1, 2, 3), coeffs))
