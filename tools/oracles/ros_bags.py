#!/usr/bin/env python3
"""Test bags for the ROS readers (crates/thermonav-io/src/ros, tests in
crates/thermonav-io/tests/it/ros.rs) and the values they hold.

Generated ONCE with: Python 3.11.7, rosbags 0.11.9, mcap 1.6.0, zstandard 0.25.0, lz4 4.4.5,
numpy (`pip install rosbags mcap mcap-ros2-support zstandard lz4 numpy`). Run from the repository root:
`python3 tools/oracles/ros_bags.py`. Output: crates/thermonav-io/tests/data/ros/.

A simulated static IMU, seeded: 150 sensor_msgs/Imu at 100 Hz on /imu/data (gyro ~ N(0, 1e-3)
rad/s, accelerometer (0, 0, 9.80665) + N(0, 2e-2) m/s^2 in the ROS body axes, z up), 30
sensor_msgs/Temperature at 20 Hz on /imu/temperature and 8 sensor_msgs/NavSatFix at 5 Hz on
/gnss/fix. Every message is written with a record (log) time later than its header stamp
(2 ms + 1 us per message), so a reader that takes the wrong time is seen.

Files, each holding the same messages:
- static_none.mcap: chunked, chunks uncompressed, CDR little-endian (mcap's Writer, rosbags'
  CDR serializer);
- static_zstd.mcap: chunked, zstd chunks, plus a second IMU topic /imu/raw (5 messages) so that
  a reader must be told --topic;
- static_none.mcap, static_unchunked_be.mcap and static.bag also hold 8
  geometry_msgs/TwistStamped on /gnss/vel;
- static_lz4.mcap: chunked, lz4 chunks;
- static_unchunked_be.mcap: no chunks, every message CDR big-endian;
- static.db3: rosbag2's SQLite storage (rosbags' rosbag2 Writer, version 8), plus a topic
  /blob (std_msgs/String of 10000 characters 'A'..'Z' repeated, one message) whose row spills
  onto overflow pages;
- static.bag, static_lz4.bag, static_bz2.bag: ROS 1 bag v2.0 (rosbags' rosbag1 Writer),
  uncompressed, lz4 and bz2 chunks; ROS 1 serialization;
- static_10hz.mcap: the README's example, long enough for `characterize` with its default
  conditioning (1500 sensor_msgs/Imu at 10 Hz, values rounded to binary32 as a driver publishing
  floats gives them, so that zstd keeps the file small; 150 Temperature at 1 Hz, 25 C);
  expected_10hz.json holds its count and its first and last messages.

expected.json: the values written, as written (ROS axes), with each message's header stamp
and record time in integer nanoseconds.
"""
import json
import pathlib
import random
import shutil
import tempfile

from mcap.writer import CompressionType, Writer as McapWriter
from rosbags.rosbag1 import Writer as Bag1Writer
from rosbags.rosbag2 import Writer as Bag2Writer
from rosbags.typesys import Stores, get_typestore

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "crates" / "thermonav-io" / "tests" / "data" / "ros"
T0_NS = 1_700_000_000_123_456_789
G = 9.80665
IMU, TEMP, FIX = "sensor_msgs/msg/Imu", "sensor_msgs/msg/Temperature", "sensor_msgs/msg/NavSatFix"
TWIST = "geometry_msgs/msg/TwistStamped"
BLOB_TEXT = "".join(chr(65 + i % 26) for i in range(10000))


def simulate():
    rng = random.Random(20261203)
    imu = []
    for k in range(150):
        stamp = T0_NS + k * 10_000_000
        imu.append({
            "stamp_ns": stamp,
            "log_time_ns": stamp + 2_000_000 + 1000 * k,
            "gyro": [rng.gauss(0, 1e-3) for _ in range(3)],
            "accel": [rng.gauss(0, 2e-2), rng.gauss(0, 2e-2), G + rng.gauss(0, 2e-2)],
        })
    temperature = []
    for k in range(30):
        stamp = T0_NS + k * 50_000_000 + 3_000_000
        temperature.append({
            "stamp_ns": stamp,
            "log_time_ns": stamp + 2_000_000 + 1000 * k,
            "temperature_c": 25.0 + 0.01 * k + rng.gauss(0, 0.02),
            "variance": 0.0004,
        })
    fixes = []
    for k in range(8):
        stamp = T0_NS + k * 200_000_000 + 7_000_000
        fixes.append({
            "stamp_ns": stamp,
            "log_time_ns": stamp + 2_000_000 + 1000 * k,
            "latitude_deg": 30.5 + rng.gauss(0, 1e-6),
            "longitude_deg": 114.3 + rng.gauss(0, 1e-6),
            "altitude_m": 20.0 + rng.gauss(0, 0.5),
            "status": 0,
            "service": 1,
            "position_covariance": [1.5, 0, 0, 0, 1.5, 0, 0, 0, 4.0],
            "position_covariance_type": 2,
        })
    raw = [{"stamp_ns": T0_NS + k * 5_000_000, "log_time_ns": T0_NS + k * 5_000_000 + 1000,
            "gyro": [0.1, 0.2, 0.3], "accel": [1.0, 2.0, 3.0]} for k in range(5)]
    twist_rng = random.Random(7)
    twists = [{"stamp_ns": T0_NS + k * 200_000_000 + 9_000_000,
               "log_time_ns": T0_NS + k * 200_000_000 + 11_000_000,
               "linear": [twist_rng.gauss(0, 0.05) for _ in range(3)],
               "angular": [twist_rng.gauss(0, 0.01) for _ in range(3)]} for k in range(8)]
    return {"imu": imu, "temperature": temperature, "fixes": fixes, "imu_raw": raw, "twists": twists}


def twist_msg(ts, m, k, ros1):
    Twist = ts.types["geometry_msgs/msg/Twist"]
    return ts.types[TWIST](header=header(ts, m["stamp_ns"], "gnss", k if ros1 else None),
                           twist=Twist(linear=vec3(ts, m["linear"]), angular=vec3(ts, m["angular"])))


def header(ts, stamp_ns, frame_id, seq=None):
    Time = ts.types["builtin_interfaces/msg/Time"]
    Header = ts.types["std_msgs/msg/Header"]
    time = Time(sec=stamp_ns // 1_000_000_000, nanosec=stamp_ns % 1_000_000_000)
    if seq is None:
        return Header(stamp=time, frame_id=frame_id)
    return Header(seq=seq, stamp=time, frame_id=frame_id)


def vec3(ts, v):
    return ts.types["geometry_msgs/msg/Vector3"](x=v[0], y=v[1], z=v[2])


def imu_msg(ts, m, k, ros1):
    import numpy as np
    Imu = ts.types[IMU]
    Quaternion = ts.types["geometry_msgs/msg/Quaternion"]
    orientation_cov = np.zeros(9)
    orientation_cov[0] = -1.0
    return Imu(
        header=header(ts, m["stamp_ns"], "imu_link", k if ros1 else None),
        orientation=Quaternion(x=0.0, y=0.0, z=0.0, w=1.0),
        orientation_covariance=orientation_cov,
        angular_velocity=vec3(ts, m["gyro"]),
        angular_velocity_covariance=np.diag([1e-6] * 3).ravel(),
        linear_acceleration=vec3(ts, m["accel"]),
        linear_acceleration_covariance=np.diag([4e-4] * 3).ravel(),
    )


def temp_msg(ts, m, k, ros1):
    return ts.types[TEMP](header=header(ts, m["stamp_ns"], "imu_link", k if ros1 else None),
                          temperature=m["temperature_c"], variance=m["variance"])


def fix_msg(ts, m, k, ros1):
    import numpy as np
    Status = ts.types["sensor_msgs/msg/NavSatStatus"]
    return ts.types[FIX](
        header=header(ts, m["stamp_ns"], "gnss", k if ros1 else None),
        status=Status(status=m["status"], service=m["service"]),
        latitude=m["latitude_deg"], longitude=m["longitude_deg"], altitude=m["altitude_m"],
        position_covariance=np.array(m["position_covariance"], dtype=float),
        position_covariance_type=m["position_covariance_type"],
    )


def streams(data, with_raw, with_twist=False):
    """(topic, type, builder, records) in the order the bags hold them."""
    out = [("/imu/data", IMU, imu_msg, data["imu"]),
           ("/imu/temperature", TEMP, temp_msg, data["temperature"]),
           ("/gnss/fix", FIX, fix_msg, data["fixes"])]
    if with_raw:
        out.append(("/imu/raw", IMU, imu_msg, data["imu_raw"]))
    if with_twist:
        out.append(("/gnss/vel", TWIST, twist_msg, data["twists"]))
    return out


def time_ordered(ts, data, with_raw, ros1, serialize, with_twist=False):
    rows = []
    for topic, typename, build, records in streams(data, with_raw, with_twist):
        for k, m in enumerate(records):
            rows.append((m["log_time_ns"], topic, typename, bytes(serialize(build(ts, m, k, ros1), typename))))
    rows.sort(key=lambda r: r[0])
    return rows


def write_mcap(path, data, compression, chunked, little_endian, with_raw, with_twist=False):
    ts = get_typestore(Stores.ROS2_HUMBLE)
    ser = lambda msg, t: ts.serialize_cdr(msg, t, little_endian=little_endian)
    with open(path, "wb") as f:
        w = McapWriter(f, chunk_size=16 * 1024, compression=compression, use_chunking=chunked)
        w.start(profile="ros2", library="thermonav oracle (mcap python)")
        channels = {}
        for topic, typename, _, _ in streams(data, with_raw, with_twist):
            if typename not in channels:
                msgdef, _ = ts.generate_msgdef(typename, ros_version=2)
                channels[typename] = w.register_schema(typename, "ros2msg", msgdef.encode())
            channels[topic] = w.register_channel(topic, "cdr", channels[typename])
        for seq, (log_time, topic, _, raw) in enumerate(time_ordered(ts, data, with_raw, False, ser, with_twist)):
            w.add_message(channels[topic], log_time=log_time, data=raw, publish_time=log_time, sequence=seq)
        w.finish()


def write_db3(path, data):
    ts = get_typestore(Stores.ROS2_HUMBLE)
    with tempfile.TemporaryDirectory() as tmp:
        bag = pathlib.Path(tmp) / "bag"
        with Bag2Writer(bag, version=8) as w:
            conns = {}
            for topic, typename, _, _ in streams(data, False):
                conns[topic] = w.add_connection(topic, typename, typestore=ts)
            blob = w.add_connection("/blob", "std_msgs/msg/String", typestore=ts)
            rows = time_ordered(ts, data, False, False, ts.serialize_cdr)
            for log_time, topic, _, raw in rows[:50]:
                w.write(conns[topic], log_time, raw)
            String = ts.types["std_msgs/msg/String"]
            w.write(blob, rows[50][0] - 1, bytes(ts.serialize_cdr(String(data=BLOB_TEXT), "std_msgs/msg/String")))
            for log_time, topic, _, raw in rows[50:]:
                w.write(conns[topic], log_time, raw)
        shutil.copy(bag / "bag.db3", path)


def write_bag1(path, data, compression, with_twist=False):
    ts = get_typestore(Stores.ROS1_NOETIC)
    path.unlink(missing_ok=True)
    w = Bag1Writer(path)
    if compression is not None:
        w.set_compression(compression)
    w.chunk_threshold = 16 * 1024
    with w:
        conns = {}
        for topic, typename, _, _ in streams(data, False, with_twist):
            conns[topic] = w.add_connection(topic, typename, typestore=ts)
        for log_time, topic, _, raw in time_ordered(ts, data, False, True, ts.serialize_ros1, with_twist):
            w.write(conns[topic], log_time, raw)


def simulate_10hz():
    import numpy as np
    rng = random.Random(10)
    r32 = lambda x: float(np.float32(x))
    imu = []
    for k in range(1500):
        stamp = T0_NS + k * 100_000_000
        imu.append({
            "stamp_ns": stamp,
            "log_time_ns": stamp + 2_000_000,
            "gyro": [r32(rng.gauss(0, 1e-3)) for _ in range(3)],
            "accel": [r32(rng.gauss(0, 2e-2)), r32(rng.gauss(0, 2e-2)), r32(G + rng.gauss(0, 2e-2))],
        })
    temperature = [{"stamp_ns": T0_NS + k * 1_000_000_000, "log_time_ns": T0_NS + k * 1_000_000_000 + 1000,
                    "temperature_c": 25.0, "variance": 0.0} for k in range(150)]
    return {"imu": imu, "temperature": temperature, "fixes": [], "imu_raw": []}


def write_10hz(path, data):
    ts = get_typestore(Stores.ROS2_HUMBLE)
    with open(path, "wb") as f:
        w = McapWriter(f, chunk_size=64 * 1024, compression=CompressionType.ZSTD)
        w.start(profile="ros2", library="thermonav oracle (mcap python)")
        ids = {}
        for topic, typename, _, _ in streams(data, False)[:2]:
            msgdef, _ = ts.generate_msgdef(typename, ros_version=2)
            ids[topic] = w.register_channel(topic, "cdr", w.register_schema(typename, "ros2msg", msgdef.encode()))
        rows = [r for r in time_ordered(ts, data, False, False, ts.serialize_cdr) if r[1] in ids]
        for seq, (log_time, topic, _, raw) in enumerate(rows):
            w.add_message(ids[topic], log_time=log_time, data=raw, publish_time=log_time, sequence=seq)
        w.finish()


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    data = simulate()
    write_mcap(OUT / "static_none.mcap", data, CompressionType.NONE, True, True, False, True)
    write_mcap(OUT / "static_zstd.mcap", data, CompressionType.ZSTD, True, True, True)
    write_mcap(OUT / "static_lz4.mcap", data, CompressionType.LZ4, True, True, False)
    write_mcap(OUT / "static_unchunked_be.mcap", data, CompressionType.NONE, False, False, False, True)
    write_db3(OUT / "static.db3", data)
    write_bag1(OUT / "static.bag", data, None, True)
    write_bag1(OUT / "static_lz4.bag", data, Bag1Writer.CompressionFormat.LZ4)
    write_bag1(OUT / "static_bz2.bag", data, Bag1Writer.CompressionFormat.BZ2)
    long = simulate_10hz()
    write_10hz(OUT / "static_10hz.mcap", long)
    summary = {"imu_count": len(long["imu"]), "temperature_count": len(long["temperature"]),
               "imu_first": long["imu"][:3], "imu_last": long["imu"][-1]}
    (OUT / "expected_10hz.json").write_text(json.dumps(summary, indent=1) + "\n")
    data["blob_text_len"] = len(BLOB_TEXT)
    (OUT / "expected.json").write_text(json.dumps(data, indent=1) + "\n")
    for p in sorted(OUT.iterdir()):
        print(p.name, p.stat().st_size)


if __name__ == "__main__":
    main()
