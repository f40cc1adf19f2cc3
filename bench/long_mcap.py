#!/usr/bin/env python3
"""A long MCAP bag for the memory figures of the bag readers (issue 37: "a 24 h, 200 Hz MCAP
bag goes through characterize in under 200 MB"), written from the MCAP specification
(mcap.dev/spec) with no MCAP library: a static IMU, seeded, on /imu/data (sensor_msgs/msg/Imu,
CDR little-endian; gyro ~ N(0, 1e-3) rad/s, accelerometer (0, 0, 9.80665) + N(0, 2e-2) m/s^2 in
the ROS body axes) and /imu/temperature (sensor_msgs/msg/Temperature at 1 Hz, 25 C), in
uncompressed chunks of about 4 MiB (rosbag2's default chunk size), with numpy for the noise.

Usage: python3 bench/long_mcap.py OUT.mcap HOURS [RATE_HZ]   (1 h at 200 Hz: about 260 MB;
24 h: about 6.2 GB, a few minutes)
Then: /usr/bin/time -v target/release/thermonav characterize OUT.mcap --out bank.json
"""
import struct
import sys

import numpy as np

MAGIC = b"\x89MCAP0\r\n"
T0_NS = 1_700_000_000_000_000_000
CHUNK_BYTES = 4 << 20


def string(s):
    b = s.encode()
    return struct.pack("<I", len(b)) + b


def record(opcode, body):
    return struct.pack("<BQ", opcode, len(body)) + body


def cdr_header(stamp_ns):
    # encapsulation (CDR little-endian), stamp, frame_id "imu" with its NUL.
    return (b"\x00\x01\x00\x00" + struct.pack("<iI", stamp_ns // 10**9, stamp_ns % 10**9)
            + struct.pack("<I", 4) + b"imu\x00")


def imu_message(stamp_ns, gyro, accel):
    # header is 4 + 16 bytes: the float64 fields start 8-aligned from the encapsulation's end.
    floats = np.zeros(37)
    floats[3] = 1.0
    floats[13:16] = gyro
    floats[25:28] = accel
    return cdr_header(stamp_ns) + floats.astype("<f8").tobytes()


def temperature_message(stamp_ns, celsius):
    return cdr_header(stamp_ns) + struct.pack("<dd", celsius, 0.0)


def message(channel, sequence, log_ns, data):
    return record(0x05, struct.pack("<HIQQ", channel, sequence, log_ns, log_ns) + data)


def chunk(records):
    body = struct.pack("<QQQI", 0, 0, len(records), 0) + string("") + struct.pack("<Q", len(records))
    return record(0x06, body + records)


def main():
    out, hours = sys.argv[1], float(sys.argv[2])
    rate = float(sys.argv[3]) if len(sys.argv) > 3 else 200.0
    count = int(hours * 3600 * rate)
    rng = np.random.default_rng(37)
    with open(out, "wb") as f:
        f.write(MAGIC)
        f.write(record(0x01, string("ros2") + string("thermonav bench/long_mcap.py")))
        for sid, name in [(1, "sensor_msgs/msg/Imu"), (2, "sensor_msgs/msg/Temperature")]:
            f.write(record(0x03, struct.pack("<H", sid) + string(name) + string("ros2msg") + string("")))
        for cid, topic in [(1, "/imu/data"), (2, "/imu/temperature")]:
            f.write(record(0x04, struct.pack("<HH", cid, cid) + string(topic) + string("cdr")
                           + struct.pack("<I", 0)))
        period_ns = int(round(1e9 / rate))
        pending, temp_seq = [], 0
        size = 0
        block = 100_000
        for start in range(0, count, block):
            n = min(block, count - start)
            gyro = rng.normal(0.0, 1e-3, (n, 3))
            accel = rng.normal(0.0, 2e-2, (n, 3)) + [0.0, 0.0, 9.80665]
            for i in range(n):
                k = start + i
                stamp = T0_NS + k * period_ns
                m = message(1, k, stamp + 2_000_000, imu_message(stamp, gyro[i], accel[i]))
                pending.append(m)
                size += len(m)
                if k % int(rate) == 0:
                    t = message(2, temp_seq, stamp + 2_000_000,
                                temperature_message(stamp + 1_000_000, 25.0 + 0.001 * (temp_seq % 100)))
                    temp_seq += 1
                    pending.append(t)
                    size += len(t)
                if size >= CHUNK_BYTES:
                    f.write(chunk(b"".join(pending)))
                    pending, size = [], 0
        if pending:
            f.write(chunk(b"".join(pending)))
        f.write(record(0x0F, struct.pack("<I", 0)))
        f.write(record(0x02, struct.pack("<QQI", 0, 0, 0)))
        f.write(MAGIC)


if __name__ == "__main__":
    main()
