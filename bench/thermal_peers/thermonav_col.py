"""The thermonav column: `thermonav characterize --sweep ...` on the training samples, then
`thermonav bank check BANK RECORD --block-s 30 --json` on the held-out samples."""
import json
import os
import subprocess

import numpy as np

HEADER = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c"
TIMEOUT_S = 600


def available(binary):
    """True when the binary exists and `bank check --help` succeeds."""
    if not (binary and os.path.isfile(binary) and os.access(binary, os.X_OK)):
        return False
    try:
        p = subprocess.run([binary, "bank", "check", "--help"], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return p.returncode == 0


def write_csv(path, data, idx):
    cols = [data["t_s"][idx]] + [data[c][idx] for c in ("gx", "gy", "gz", "ax", "ay", "az")] \
        + [data["temp_c"][idx]]
    np.savetxt(path, np.column_stack(cols), delimiter=",", header=HEADER, comments="",
               fmt=["%.0f"] + ["%.10g"] * 7)


class ThermonavFailure(Exception):
    pass


def _run(cmd, cwd, log_name):
    log_path = os.path.join(cwd, log_name)
    with open(log_path, "w") as log:
        try:
            p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=log,
                               timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            raise ThermonavFailure("%s timed out after %d s" % (cmd[1], TIMEOUT_S))
    if p.returncode != 0:
        with open(log_path) as f:
            lines = [l.strip() for l in f if l.strip()]
        raise ThermonavFailure("%s exit %d: %s" % (" ".join(cmd[1:3]), p.returncode,
                                                   lines[-1] if lines else "(no stderr)"))
    return p.stdout


def run(binary, folder, data, sweeps, held_idx):
    """sweeps: list of power-ons, each a list of index arrays (pieces of that power-on).
    Returns the parsed `bank check --json` document."""
    args = [binary, "characterize"]
    for p, pieces in enumerate(sweeps):
        names = []
        for q, idx in enumerate(pieces):
            if len(idx) == 0:
                continue
            name = "train_%d_%d.csv" % (p, q)
            write_csv(os.path.join(folder, name), data, idx)
            names.append(name)
        args += ["--sweep", ",".join(names)]
    args += ["--out", "bank.json"]
    _run(args, folder, "characterize.log")
    write_csv(os.path.join(folder, "heldout.csv"), data, held_idx)
    out = _run([binary, "bank", "check", "bank.json", "heldout.csv", "--block-s", "30", "--json"],
               folder, "bank_check.log")
    with open(os.path.join(folder, "bank_check.json"), "wb") as f:
        f.write(out)
    try:
        return json.loads(out)
    except ValueError as e:
        raise ThermonavFailure("bank check --json is not JSON: %s" % e)


def score(doc, channel, block_start_t_s, block_s, observed, scale):
    """(rms, coverage, note) for one channel, in the table's unit (scale converts from SI).

    thermonav's blocks are matched to ours by t_s: a block of ours holds thermonav's block when
    its t_s falls in [start, start + block_s). With a one-to-one match covering all our blocks,
    r_b = our observed - thermonav's predicted; otherwise thermonav's own blocks are used
    (its observed - predicted) and the note says so. Coverage: fraction of blocks with
    |r_b - mean r| <= band_half_width_offset_removed (the band of the shape: without the
    offset's part, which the shape takes off)."""
    try:
        ch = doc["channels"][channel]
        blocks = ch["blocks"]
        t = np.array([b["t_s"] for b in blocks], dtype=float)
        pred = np.array([b["predicted"] for b in blocks], dtype=float)
        obs_tn = np.array([b["observed"] for b in blocks], dtype=float)
        half = np.array([b.get("band_half_width_offset_removed", b["band_half_width"])
                         for b in blocks], dtype=float)
    except (KeyError, TypeError) as e:
        raise ThermonavFailure("bank check JSON lacks %s for %s" % (e, channel))
    if len(blocks) == 0:
        raise ThermonavFailure("bank check gave no blocks for %s" % channel)
    k = np.floor((t - block_start_t_s[0]) / block_s).astype(int)
    starts = np.asarray(block_start_t_s)
    matched = (len(k) == len(starts) and np.array_equal(np.sort(k), np.arange(len(starts)))
               and np.all((t >= starts[np.clip(k, 0, len(starts) - 1)])
                          & (t < starts[np.clip(k, 0, len(starts) - 1)] + block_s)))
    if matched:
        order = np.argsort(k)
        r = observed - pred[order]
        half = half[order]
        note = ""
    else:
        r = obs_tn - pred
        note = "own blocks (%d vs our %d)" % (len(blocks), len(starts))
    dev = r - r.mean()
    rms = float(np.sqrt(np.mean(dev ** 2))) * scale
    coverage = float(np.mean(np.abs(dev) <= half))
    return rms, coverage, note
