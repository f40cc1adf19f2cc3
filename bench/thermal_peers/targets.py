"""Issue 35's three CATS targets counted from the results JSON that bench/thermal_peers.sh
prints: pairs whose thermonav RMS is at most 1.05x the better peer's, pairs worse than 1.1x the
uncompensated RMS (thermonav's and each peer's), and pairs whose thermonav band covers at least
80 % of the held-out blocks; for every (fold, channel) pair, and apart for the folds whose
choice saw one training leg (P0's and P1's, whose periods hold two legs) and those that saw two
or more (P2's and the across-period folds).

Usage: python3 bench/thermal_peers/targets.py RESULTS.json"""
import json
import sys

ONE_TRAINING_LEG = {"P0_leg1", "P0_leg2", "P1_leg1", "P1_leg2"}


def counts(rows):
    better_peer = [min(r["px4"], r["ardupilot"]) for r in rows]
    near_peer = sum(r["thermonav"] <= 1.05 * b for r, b in zip(rows, better_peer))
    worse = {who: sum(r[who] > 1.1 * r["uncompensated"] for r in rows)
             for who in ("thermonav", "px4", "ardupilot")}
    covered = sum(r["thermonav_coverage"] >= 0.8 for r in rows)
    return near_peer, worse, covered


def main():
    rows = json.load(open(sys.argv[1]))["rows"]
    groups = [
        ("all folds", rows),
        ("folds with one training leg", [r for r in rows if r["fold_id"] in ONE_TRAINING_LEG]),
        ("folds with two or more", [r for r in rows if r["fold_id"] not in ONE_TRAINING_LEG]),
    ]
    print("| folds | pairs | within 1.05x the better peer | worse than 1.1x uncompensated "
          "(thermonav / PX4 / ArduPilot) | band covers 80 % |")
    print("|---|---|---|---|---|")
    for name, group in groups:
        n = len(group)
        near, worse, covered = counts(group)
        print("| %s | %d | %d (%.0f %%) | %d / %d / %d | %d (%.0f %%) |" % (
            name, n, near, 100 * near / n, worse["thermonav"], worse["px4"],
            worse["ardupilot"], covered, 100 * covered / n))


if __name__ == "__main__":
    main()
