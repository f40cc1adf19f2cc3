"""Held-out scoring of thermal-bias calibration on the CATS record (data README section 1.9):
PX4's and ArduPilot's own offline fitters and, when its `bank check` exists, thermonav.

Folds: (1) within each period, each leg held out and the fit made on the period's other samples
(all six channels); (2) gyros only, two periods fitted and the third held out whole.
Score of a method on a held-out stretch and channel: 30 s block means (consecutive from the
stretch's first sample, an incomplete last block dropped), r_b = observed_b - predicted_b with
the prediction evaluated at the block's mean temperature, and the RMS of r_b - mean(r)
("shape": constant offsets do not count). Uncompensated: RMS of observed_b - mean(observed).
Gyros in deg/h, accels in mg (9.80665e-3 m/s^2).

Usage: run.py --workdir DIR [--out TABLE.md|-] [--json OUT.json] [--legs-json PATH]
              [--thermonav BINARY] [--jobs N] [--only FOLD_ID,...]"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cats  # noqa: E402
import peers  # noqa: E402
import thermonav_col  # noqa: E402

BLOCK_S = 30
DEG_H_PER_RAD_S = 180.0 / math.pi * 3600.0
MG_PER_M_S2 = 1.0 / 9.80665e-3
UNIT = {"g": ("deg/h", DEG_H_PER_RAD_S), "a": ("mg", MG_PER_M_S2)}
GYROS = ["gx", "gy", "gz"]


def blocks(data, idx):
    """30 s block means over the held-out samples idx (1 Hz, consecutive): start t_s, mean
    temperature and mean of each channel."""
    n = len(idx) // BLOCK_S
    sel = idx[:n * BLOCK_S]
    out = {"t_start_s": data["t_s"][sel][::BLOCK_S]}
    for c in ["temp_c"] + cats.CHANNELS:
        out[c] = data[c][sel].reshape(n, BLOCK_S).mean(axis=1)
    return out


def shape_rms(residual):
    d = residual - residual.mean()
    return float(np.sqrt(np.mean(d ** 2)))


def make_folds(data, legs):
    folds = []
    t = data["t_s"]
    for p in cats.PERIODS:
        pm = cats.period_mask(data, p)
        for k, leg in enumerate(legs[p]):
            if leg["span_c"] < cats.MIN_SPAN_C:
                continue  # only when a period is a single short leg
            held = pm & (t >= leg["start_t_s"]) & (t <= leg["end_t_s"])
            before = np.flatnonzero(pm & (t < leg["start_t_s"]))
            after = np.flatnonzero(pm & (t > leg["end_t_s"]))
            folds.append({
                "name": "%s leg %d (%s %.1f→%.1f °C)" % (
                    p, k + 1, leg["direction"], leg["t_start_c"], leg["t_end_c"]),
                "id": "%s_leg%d" % (p, k + 1),
                "kind": "within-period",
                "held": np.flatnonzero(held),
                "train": np.concatenate([before, after]),
                "sweeps": [[before, after]],  # one power-on, two pieces
                "channels": list(cats.CHANNELS),
                "held_t_s": [leg["start_t_s"], leg["end_t_s"]],
            })
    names = list(cats.PERIODS)
    for held_p in reversed(names):
        train_p = [q for q in names if q != held_p]
        masks = [np.flatnonzero(cats.period_mask(data, q)) for q in train_p]
        held = np.flatnonzero(cats.period_mask(data, held_p))
        folds.append({
            "name": "gyros: %s → %s" % ("+".join(train_p), held_p),
            "id": "%s_to_%s" % ("".join(train_p), held_p),
            "kind": "across-periods",
            "held": held,
            "train": np.concatenate(masks),
            "sweeps": [[m] for m in masks],  # separate power-ons
            "channels": list(GYROS),
            "held_t_s": [int(data["t_s"][held[0]]), int(data["t_s"][held[-1]])],
        })
    return folds


def peer_job(which, folder, data, train):
    g = np.column_stack([data[c][train] for c in GYROS])
    a = np.column_stack([data[c][train] for c in ("ax", "ay", "az")])
    start = time.time()
    try:
        run = peers.run_px4 if which == "px4" else peers.run_ardupilot
        fit = run(folder, data["t_s"][train], g, a, data["temp_c"][train])
        return {"fit": fit, "seconds": time.time() - start}
    except Exception as e:  # a failing peer is reported in the table, not dropped
        return {"error": "%s: %s" % (type(e).__name__, e) if not isinstance(
            e, peers.PeerFailure) else str(e), "seconds": time.time() - start}


def thermonav_job(binary, folder, data, fold):
    start = time.time()
    try:
        doc = thermonav_col.run(binary, folder, data, fold["sweeps"], fold["held"])
        return {"doc": doc, "seconds": time.time() - start}
    except Exception as e:
        return {"error": str(e), "seconds": time.time() - start}


def fmt(v):
    if isinstance(v, str):
        return v
    return "%.2f" % v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--out", default="-")
    ap.add_argument("--json", default=None)
    ap.add_argument("--legs-json", default=None)
    ap.add_argument("--thermonav", default=None)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default=None,
                    help="comma-separated fold ids to run (e.g. P0_leg2,P0P1_to_P2); default all")
    args = ap.parse_args()
    t0 = time.time()

    data = cats.load()
    legs = cats.find_legs(data)
    if args.legs_json:
        doc = cats.legs_document(data, legs)
        text = json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
        old = open(args.legs_json).read() if os.path.exists(args.legs_json) else None
        if old != text:
            with open(args.legs_json, "w") as f:
                f.write(text)
            print("wrote %s" % args.legs_json, file=sys.stderr)
    for p in cats.PERIODS:
        for k, l in enumerate(legs[p]):
            print("%s leg %d: t_s %d..%d, %s %.2f→%.2f °C, span %.2f °C" % (
                p, k + 1, l["start_t_s"], l["end_t_s"], l["direction"], l["t_start_c"],
                l["t_end_c"], l["span_c"]), file=sys.stderr)

    folds = make_folds(data, legs)
    if args.only:
        keep = args.only.split(",")
        unknown = set(keep) - {f["id"] for f in folds}
        if unknown:
            raise SystemExit("unknown fold ids %s; known: %s" % (
                ",".join(sorted(unknown)), ",".join(f["id"] for f in folds)))
        folds = [f for f in folds if f["id"] in keep]
    tn_ok = thermonav_col.available(args.thermonav)
    print("thermonav bank check: %s" % ("available" if tn_ok else "not available (pending)"),
          file=sys.stderr)

    # longest jobs first: ArduPilot's loader is quadratic in the sample count
    jobs = []
    for f in folds:
        folder = os.path.join(args.workdir, f["id"])
        for which in ("ardupilot", "px4") + (("thermonav",) if tn_ok else ()):
            sub = os.path.join(folder, which)
            os.makedirs(sub, exist_ok=True)
            jobs.append((len(f["train"]) * (3 if which == "ardupilot" else 1), f["id"], which, sub))
    jobs.sort(key=lambda j: -j[0])
    by_id = {f["id"]: f for f in folds}
    results = {}
    with cf.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futs = {}
        for _, fid, which, sub in jobs:
            f = by_id[fid]
            if which == "thermonav":
                fut = pool.submit(thermonav_job, args.thermonav, sub, data, f)
            else:
                fut = pool.submit(peer_job, which, sub, data, f["train"])
            futs[fut] = (fid, which)
        for fut in cf.as_completed(futs):
            fid, which = futs[fut]
            results[(fid, which)] = fut.result()
            r = results[(fid, which)]
            print("  %-12s %-10s %6.1f s %s" % (fid, which, r["seconds"],
                                                 ("FAILED: " + r["error"]) if "error" in r else "ok"),
                  file=sys.stderr)

    rows = []
    for f in folds:
        b = blocks(data, f["held"])
        for c in f["channels"]:
            unit, scale = UNIT[c[0]]
            obs = b[c]
            row = {"fold": f["name"], "fold_id": f["id"], "kind": f["kind"], "channel": c,
                   "unit": unit, "blocks": int(len(obs)),
                   "held_t_s": f["held_t_s"], "train_samples": int(len(f["train"])),
                   "uncompensated": shape_rms(obs - obs.mean()) * scale}
            for which, pred in (("px4", peers.predict_px4), ("ardupilot", peers.predict_ardupilot)):
                r = results[(f["id"], which)]
                if "error" in r:
                    row[which] = "failed: " + r["error"]
                else:
                    row[which] = shape_rms(obs - pred(r["fit"][c], b["temp_c"])) * scale
            if not tn_ok:
                row["thermonav"] = row["thermonav_coverage"] = "pending"
            else:
                r = results[(f["id"], "thermonav")]
                if "error" in r:
                    row["thermonav"] = "failed: " + r["error"]
                    row["thermonav_coverage"] = "—"
                else:
                    try:
                        rms, cov, note = thermonav_col.score(
                            r["doc"], c, b["t_start_s"], BLOCK_S, obs, scale)
                        row["thermonav"] = rms
                        row["thermonav_coverage"] = cov
                        if note:
                            row["thermonav_note"] = note
                    except thermonav_col.ThermonavFailure as e:
                        row["thermonav"] = "failed: " + str(e)
                        row["thermonav_coverage"] = "—"
            rows.append(row)

    lines = ["| fold | channel | unit | uncompensated | PX4 | ArduPilot | thermonav | thermonav coverage |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        tn = fmt(r["thermonav"]) + (" (%s)" % r["thermonav_note"] if "thermonav_note" in r else "")
        cov = r["thermonav_coverage"]
        cov = "%.0f %%" % (100 * cov) if isinstance(cov, float) else cov
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["fold"], r["channel"], r["unit"], fmt(r["uncompensated"]), fmt(r["px4"]),
            fmt(r["ardupilot"]), tn, cov))
    summary = summarise(rows, tn_ok)
    lines += ["", summary]
    table = "\n".join(lines) + "\n"
    if args.out == "-":
        sys.stdout.write(table)
    else:
        with open(args.out, "w") as fo:
            fo.write(table)
        sys.stdout.write(table)
    doc = {
        "definition": {
            "block_s": BLOCK_S,
            "score": "RMS over the held-out blocks of (r_b - mean r), r_b = observed_b - "
                     "predicted_b, prediction at the block's mean temperature; uncompensated: "
                     "RMS of observed_b - mean observed",
            "units": {"gyro": "deg/h", "accel": "mg (9.80665e-3 m/s^2)"},
        },
        "legs": legs,
        "thermonav_available": tn_ok,
        "rows": rows,
        "summary": summary,
        "peer_fits": {"%s/%s" % k: (v.get("error") or {c: list(map(_jsonable, fit))
                                                       for c, fit in v["fit"].items()})
                      for k, v in results.items() if k[1] != "thermonav"},
        "seconds": time.time() - t0,
    }
    if args.json:
        with open(args.json, "w") as fo:
            json.dump(doc, fo, indent=1, ensure_ascii=False)
    print("total %.0f s" % (time.time() - t0), file=sys.stderr)


def _jsonable(v):
    if isinstance(v, (list, tuple)):
        return [float(x) for x in v]
    return float(v)


def summarise(rows, tn_ok):
    parts = []
    methods = [("px4", "PX4"), ("ardupilot", "ArduPilot")] + ([("thermonav", "thermonav")] if tn_ok else [])
    for kind in ("within-period", "across-periods"):
        sub = [r for r in rows if r["kind"] == kind]
        if not sub:
            continue
        bits = []
        for key, label in methods:
            ratios = [r[key] / r["uncompensated"] for r in sub if isinstance(r[key], float)]
            fails = sum(1 for r in sub if not isinstance(r[key], float))
            bits.append("%s median %.2f× uncompensated%s" % (
                label, float(np.median(ratios)) if ratios else float("nan"),
                " (%d rows failed)" % fails if fails else ""))
        best = {label: 0 for _, label in methods}
        for r in sub:
            vals = [(r[k], label) for k, label in methods if isinstance(r[k], float)]
            if vals:
                best[min(vals)[1]] += 1
        parts.append("%s (%d rows): %s; lowest RMS: %s" % (
            kind, len(sub), ", ".join(bits), ", ".join("%s %d" % kv for kv in best.items())))
    if not tn_ok:
        parts.append("thermonav pending (no `bank check`)")
    return "**Summary:** " + " | ".join(parts) + "."


if __name__ == "__main__":
    main()
