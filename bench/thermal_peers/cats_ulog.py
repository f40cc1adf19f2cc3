#!/usr/bin/env python3
"""One period of the CATS record (shared data README section 1.9) as a PX4 ULog of raw
sensor_gyro and sensor_accel, as PX4 logs a thermal calibration: the README's ULog workflow
starts from it. Standard library only (no numpy), so that workflow runs on a bare Python.

    python3 bench/thermal_peers/cats_ulog.py CATS.csv.gz P2 OUT.ulg

The record as written by ulog_writer.py (same topics, fields, device ids, µs timestamps and
binary32 values, gyro mrad/s to rad/s), without sensor_baro; periods as in cats.py."""
import gzip
import struct
import sys

MAGIC = b"ULog\x01\x12\x35"
# period -> (first, last) second since 2021-09-20T08:52:00Z, both inclusive (cats.PERIODS)
PERIODS = {"P0": (480, 92_460), "P1": (92_880, 183_780), "P2": (184_920, 268_020)}
TOPICS = {"sensor_gyro": 2293768, "sensor_accel": 2293784}  # topic -> device_id
FIELDS = "uint64_t timestamp;uint32_t device_id;float x;float y;float z;float temperature;"


def message(kind, payload):
    return struct.pack("<HB", len(payload), ord(kind)) + payload


def header(first_us):
    out = MAGIC + struct.pack("<BQ", 1, first_us)
    out += message("B", bytes(16) + struct.pack("<3Q", 0, 0, 0))
    for topic in TOPICS:
        out += message("F", ("%s:%s" % (topic, FIELDS)).encode("ascii"))
    for msg_id, topic in enumerate(TOPICS):
        out += message("A", struct.pack("<BH", 0, msg_id) + topic.encode("ascii"))
    return out


def rows(path, period):
    """(t_s, gyro rad/s, accel m/s^2, temp_c) of the period's rows."""
    first, last = PERIODS[period]
    with gzip.open(path, "rt") as f:
        f.readline()
        for line in f:
            t_s = float(line[: line.index(",")])
            if t_s > last:
                return
            if t_s >= first:
                v = [float(x) for x in line.split(",")]
                yield t_s, [g * 1e-3 for g in v[4:7]], v[1:4], v[11]


def main(path, period, out):
    body = bytearray()
    first_us = None
    for t_s, gyro, accel, temp_c in rows(path, period):
        us = round(t_s * 1e6)
        first_us = us if first_us is None else first_us
        for msg_id, (topic, xyz) in enumerate(zip(TOPICS, (gyro, accel))):
            record = struct.pack("<HQI4f", msg_id, us, TOPICS[topic], *xyz, temp_c)
            body += message("D", record)
    with open(out, "wb") as f:
        f.write(header(first_us) + body)


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[2] not in PERIODS:
        sys.exit("usage: cats_ulog.py CATS.csv.gz P0|P1|P2 OUT.ulg")
    main(*sys.argv[1:])
