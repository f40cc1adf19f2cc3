"""Does a CATS channel follow the temperature or the clock? Per period and channel, the slope of
the channel against temperature on each leg (least squares on 300 s block means, with its 95 %
interval from the blocks' scatter) and the channel's change over the leg against its time.

A channel whose slope in temperature flips sign between a cooling and a heating leg while its
change over time keeps its sign drifts with the clock, not the temperature: no curve in T (or in
T and dT/dt) fitted on one of those legs predicts the other, and within one leg, where the
temperature is a monotone function of time, nothing can tell the two apart.

Usage: python3 bench/thermal_peers/time_or_temperature.py (reads tools/oracles/cats_legs.json,
which bench/thermal_peers.sh writes)."""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cats  # noqa: E402

BLOCK_S = 300
SCALE = {"g": 180 / np.pi * 3600, "a": 1000 / 9.80665}
UNIT = {"g": "deg/h", "a": "mg"}
LEGS_JSON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                         "oracles", "cats_legs.json")


def block_means(data, start, end, channel):
    """(t, T, y) 300 s block means of one leg, a last shorter block dropped."""
    m = (data["t_s"] >= start) & (data["t_s"] <= end)
    n = m.sum() // BLOCK_S
    idx = np.flatnonzero(m)[: n * BLOCK_S]
    shape = (n, BLOCK_S)
    return (data["t_s"][idx].reshape(shape).mean(1), data["temp_c"][idx].reshape(shape).mean(1),
            data[channel][idx].reshape(shape).mean(1) * SCALE[channel[0]])


def slope_with_interval(x, y):
    """Least-squares slope of y on x and its 95 % half-width (normal, from the residuals)."""
    X = np.column_stack([np.ones_like(x), x - x.mean()])
    beta, *_ = np.linalg.lstsq(X, y, rcond=None)
    r = y - X @ beta
    s2 = r @ r / max(len(y) - 2, 1)
    se = np.sqrt(s2 / np.sum((x - x.mean()) ** 2))
    return beta[1], 1.96 * se


def main():
    data = cats.load()
    legs = json.load(open(LEGS_JSON))["periods"]
    print("| period | channel | unit | leg | direction | slope in T (per °C) | change over the leg |"
          " follows |")
    print("|---|---|---|---|---|---|---|---|")
    for period, info in legs.items():
        legs_of = [l for l in info["legs"] if l["span_c"] >= cats.MIN_SPAN_C]
        for channel in cats.CHANNELS:
            rows = []
            for k, leg in enumerate(legs_of, 1):
                t, temp, y = block_means(data, leg["start_t_s"], leg["end_t_s"], channel)
                slope, half = slope_with_interval(temp, y)
                rows.append((k, leg["direction"], slope, half, y[-1] - y[0]))
            signs_t = {np.sign(r[2]) for r in rows if abs(r[2]) > r[3]}
            signs_clock = {np.sign(r[4]) for r in rows}
            directions = {r[1] for r in rows}
            follows = ("the clock" if len(directions) == 2 and len(signs_t) == 2
                       and len(signs_clock) == 1 else "—")
            for k, direction, slope, half, change in rows:
                print("| %s | %s | %s | %d | %s | %+.2f ± %.2f | %+.1f | %s |" % (
                    period, channel, UNIT[channel[0]], k, direction, slope, half, change,
                    follows))


if __name__ == "__main__":
    main()
