"""The CATS temperature-calibration record (data README section 1.9): loading, the three periods,
and the leg rule whose result is written to tools/oracles/cats_legs.json."""
import gzip

import numpy as np

CSV = "/work/shared/data/cats-tempcal/cats_temperature_calib.csv.gz"
EPOCH_UTC = "2021-09-20T08:52:00Z"  # t_s = 0

# The README's table of periods (UTC), as seconds since EPOCH_UTC; both ends inclusive.
PERIODS = {
    "P0": (8 * 60, 86400 + (10 * 60 + 33 - (8 * 60 + 52)) * 60),          # 09-20 09:00 .. 09-21 10:33
    "P1": (86400 + 108 * 60, 2 * 86400 + (11 * 60 + 55 - 532) * 60),      # 09-21 10:40 .. 09-22 11:55
    "P2": (2 * 86400 + (12 * 60 + 14 - 532) * 60, 3 * 86400 + (11 * 60 + 19 - 532) * 60),  # 09-22 12:14 .. 09-23 11:19
}
PERIOD_UTC = {
    "P0": ("2021-09-20T09:00:00Z", "2021-09-21T10:33:00Z"),
    "P1": ("2021-09-21T10:40:00Z", "2021-09-22T11:55:00Z"),
    "P2": ("2021-09-22T12:14:00Z", "2021-09-23T11:19:00Z"),
}

SMOOTH_HALF_WIDTH_S = 30   # centred moving average over t-30 s .. t+30 s (61 samples at 1 Hz)
REVERSAL_C = 1.0           # a turning point is confirmed by a reversal of at least this much
MIN_SPAN_C = 3.0           # legs with a smaller span are merged into a neighbour

CHANNELS = ["gx", "gy", "gz", "ax", "ay", "az"]


def load():
    """Columns t_s, gx..gz [rad/s], ax..az [m/s^2], temp_c, as float64 arrays in a dict."""
    with gzip.open(CSV, "rt") as f:
        header = f.readline().strip().split(",")
        raw = np.loadtxt(f, delimiter=",")
    col = {name: i for i, name in enumerate(header)}
    out = {"t_s": raw[:, col["t_s_since_2021-09-20T08:52:00Z"]]}
    for axis in "xyz":
        out["g" + axis] = raw[:, col["gyro_%s_mrad_s" % axis]] * 1e-3
        out["a" + axis] = raw[:, col["acc_%s_m_s2" % axis]]
    out["temp_c"] = raw[:, col["temp_c"]]
    if not np.all(np.diff(out["t_s"]) == 1.0):
        raise SystemExit("the CATS record is expected at 1 Hz without gaps")
    return out


def period_mask(data, name):
    a, b = PERIODS[name]
    return (data["t_s"] >= a) & (data["t_s"] <= b)


def smooth(temp):
    """Centred moving average, half-width SMOOTH_HALF_WIDTH_S samples each side; near the ends
    of the period the window is cut to the samples that exist (mean of those)."""
    n = len(temp)
    c = np.concatenate([[0.0], np.cumsum(temp)])
    i = np.arange(n)
    lo = np.maximum(i - SMOOTH_HALF_WIDTH_S, 0)
    hi = np.minimum(i + SMOOTH_HALF_WIDTH_S + 1, n)
    return (c[hi] - c[lo]) / (hi - lo)


def turning_points(ts):
    """Indices of the confirmed extrema of the smoothed temperature ts (hysteresis tracker).

    Before the first turning point both a running maximum and a running minimum are kept. A
    maximum is confirmed at the first sample that lies REVERSAL_C or more below it; the tracker
    then follows the running minimum from that sample on, which is confirmed at the first
    sample REVERSAL_C or more above it, and so on. The running extremum moves only on a strict
    improvement, so on a plateau the earliest sample is the turning point. An extremum
    confirmed at index 0 (the period starts on a slope) is not a turning point: the period
    start is an end already."""
    tps = []
    mode = None          # None: undecided, "down": after a maximum, "up": after a minimum
    imax = imin = 0
    for i in range(1, len(ts)):
        if mode != "down" and ts[i] > ts[imax]:
            imax = i
        if mode != "up" and ts[i] < ts[imin]:
            imin = i
        if mode != "down" and ts[imax] - ts[i] >= REVERSAL_C:
            if imax > 0:
                tps.append(imax)
            mode, imin = "down", i
        elif mode != "up" and ts[i] - ts[imin] >= REVERSAL_C:
            if imin > 0:
                tps.append(imin)
            mode, imax = "up", i
    return tps


def _span(ts, a, b):
    seg = ts[a:b + 1]
    return float(seg.max() - seg.min())


def legs_of(ts):
    """Legs as inclusive index pairs [a, b]: consecutive ends (period start, turning points,
    period end) bound them, so neighbouring legs share their turning-point sample.

    Merging: while a leg spans less than MIN_SPAN_C and there is more than one leg, the leg of
    the smallest span (the earliest on ties) is merged with one neighbour: its only neighbour
    at either end of the period; with two neighbours, the one of the smaller span (the earlier
    on ties). The merged leg's span is recomputed over the union before the next step."""
    ends = [0] + turning_points(ts) + [len(ts) - 1]
    legs = [[ends[k], ends[k + 1]] for k in range(len(ends) - 1)]
    while len(legs) > 1:
        spans = [_span(ts, a, b) for a, b in legs]
        k = int(np.argmin(spans))
        if spans[k] >= MIN_SPAN_C:
            break
        if k == 0:
            j = 1
        elif k == len(legs) - 1:
            j = k - 1
        else:
            j = k - 1 if spans[k - 1] <= spans[k + 1] else k + 1
        lo, hi = min(j, k), max(j, k)
        legs[lo:hi + 1] = [[legs[lo][0], legs[hi][1]]]
    return legs


DEFINITION = (
    "Periods P0, P1, P2 from the data README section 1.9 table, t_s (seconds since "
    "2021-09-20T08:52:00Z) from..to with both ends inclusive. Within a period the 1 Hz temp_c "
    "is smoothed with a centred moving average over t-30 s..t+30 s (61 samples; at the period's "
    "ends the window is cut to the samples inside the period). Turning points of the smoothed "
    "temperature Ts come from a hysteresis tracker: before the first turning point both a running "
    "maximum and a running minimum (from the period start) are kept; a maximum is confirmed at the "
    "first later sample with Ts <= max - 1.0 C, after which the running minimum is tracked from "
    "that sample and confirmed at the first later sample with Ts >= min + 1.0 C, and so on "
    "alternately. Running extrema move only on strict improvement (the earliest sample of a "
    "plateau is the turning point); an extremum confirmed at the period's first sample is not a "
    "turning point. Legs are the stretches between consecutive ends (period start, turning points "
    "in order, period end), inclusive at both ends, so neighbouring legs share the turning-point "
    "sample. span_c = max - min of Ts over the leg. Merging: while some leg has span_c < 3.0 and "
    "the period has more than one leg, take the leg of smallest span (earliest on ties) and merge "
    "it with its only neighbour if it is first or last, else with the neighbour of smaller span "
    "(earlier on ties); recompute the span of the union and repeat. direction = heating if Ts at "
    "the leg's end > Ts at its start, else cooling. t_start_c and t_end_c are Ts at the leg's first "
    "and last sample, t_min_c and t_max_c the extremes of Ts over it; start_t_s and end_t_s are "
    "those samples' t_s (inclusive). turning_points_t_s lists every turning point the tracker "
    "confirmed, before merging (a merged-away one lies inside a leg)."
)


def find_legs(data):
    """{period: [leg dicts]} with the rule above."""
    out = {}
    for name in PERIODS:
        m = period_mask(data, name)
        t = data["t_s"][m]
        ts = smooth(data["temp_c"][m])
        legs = []
        for a, b in legs_of(ts):
            legs.append({
                "start_t_s": int(t[a]),
                "end_t_s": int(t[b]),
                "span_c": round(_span(ts, a, b), 4),
                "direction": "heating" if ts[b] > ts[a] else "cooling",
                "t_start_c": round(float(ts[a]), 4),
                "t_end_c": round(float(ts[b]), 4),
                "t_min_c": round(float(ts[a:b + 1].min()), 4),
                "t_max_c": round(float(ts[a:b + 1].max()), 4),
            })
        out[name] = legs
    return out


def turning_points_t_s(data):
    """{period: [t_s of every turning point the tracker confirmed, before merging]}"""
    out = {}
    for name in PERIODS:
        m = period_mask(data, name)
        out[name] = [int(data["t_s"][m][i]) for i in turning_points(smooth(data["temp_c"][m]))]
    return out


def legs_document(data, legs):
    tps = turning_points_t_s(data)
    return {
        "definition": DEFINITION,
        "source": CSV.replace("/work/shared/", "shared/") + " (data README section 1.9)",
        "generated_by": "bench/thermal_peers/cats.py (run by bench/thermal_peers.sh)",
        "epoch_utc": EPOCH_UTC,
        "smooth_half_width_s": SMOOTH_HALF_WIDTH_S,
        "reversal_c": REVERSAL_C,
        "min_span_c": MIN_SPAN_C,
        "periods": {
            name: {
                "from_utc": PERIOD_UTC[name][0],
                "to_utc": PERIOD_UTC[name][1],
                "from_t_s": PERIODS[name][0],
                "to_t_s": PERIODS[name][1],
                "turning_points_t_s": tps[name],
                "legs": legs[name],
            }
            for name in PERIODS
        },
    }
