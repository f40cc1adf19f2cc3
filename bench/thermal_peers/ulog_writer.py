"""A minimal ULog (version 1) writer, from the format's published description: a 16-byte file
header (magic, version, start timestamp), a flag-bits message, format definitions, add-logged
messages, then data messages, each message framed by uint16 payload size and uint8 type.

Only what PX4's thermal-calibration fitter reads is written: sensor_gyro, sensor_accel and
sensor_baro, instance 0, one data message of each per sample, in time order."""
import struct

import numpy as np

MAGIC = b"ULog\x01\x12\x35"
VERSION = 1

# topic -> fields (ULog type, name), the timestamp first; numpy dtypes to match
TOPICS = {
    "sensor_gyro": [("uint64_t", "timestamp"), ("uint32_t", "device_id"), ("float", "x"),
                    ("float", "y"), ("float", "z"), ("float", "temperature")],
    "sensor_accel": [("uint64_t", "timestamp"), ("uint32_t", "device_id"), ("float", "x"),
                     ("float", "y"), ("float", "z"), ("float", "temperature")],
    "sensor_baro": [("uint64_t", "timestamp"), ("uint32_t", "device_id"), ("float", "pressure"),
                    ("float", "temperature")],
}
NUMPY = {"uint64_t": "<u8", "uint32_t": "<u4", "float": "<f4"}
DEVICE_ID = {"sensor_gyro": 2293768, "sensor_accel": 2293784, "sensor_baro": 6620706}
PRESSURE_HPA = 1013.25


def _message(msg_type, payload):
    return struct.pack("<HB", len(payload), ord(msg_type)) + payload


def write(path, t_s, gyro, accel, temp_c):
    """t_s: (n,) seconds; gyro (n,3) rad/s; accel (n,3) m/s^2; temp_c (n,) degC."""
    n = len(t_s)
    timestamp = np.round(np.asarray(t_s) * 1e6).astype(np.uint64)
    out = bytearray()
    out += MAGIC + struct.pack("<BQ", VERSION, int(timestamp[0]))
    # flag bits: 8 compat, 8 incompat (none set: no appended data), 3 appended offsets
    out += _message("B", bytes(16) + struct.pack("<3Q", 0, 0, 0))
    for topic, fields in TOPICS.items():
        text = topic + ":" + "".join("%s %s;" % f for f in fields)
        out += _message("F", text.encode("ascii"))
    for msg_id, topic in enumerate(TOPICS):
        out += _message("A", struct.pack("<BH", 0, msg_id) + topic.encode("ascii"))

    # one record per sample holding the three data messages back to back
    rec = []
    cols = {}
    for msg_id, (topic, fields) in enumerate(TOPICS.items()):
        size = 2 + sum(np.dtype(NUMPY[t]).itemsize for t, _ in fields)
        rec += [(topic + ".size", "<u2"), (topic + ".type", "u1"), (topic + ".msg_id", "<u2")]
        cols[topic + ".size"] = size
        cols[topic + ".type"] = ord("D")
        cols[topic + ".msg_id"] = msg_id
        rec += [(topic + "." + name, NUMPY[t]) for t, name in fields]
    arr = np.zeros(n, dtype=np.dtype(rec, align=False))
    for k, v in cols.items():
        arr[k] = v
    for topic, values in (("sensor_gyro", gyro), ("sensor_accel", accel)):
        arr[topic + ".timestamp"] = timestamp
        arr[topic + ".device_id"] = DEVICE_ID[topic]
        for i, axis in enumerate("xyz"):
            arr[topic + "." + axis] = values[:, i]
        arr[topic + ".temperature"] = temp_c
    arr["sensor_baro.timestamp"] = timestamp
    arr["sensor_baro.device_id"] = DEVICE_ID["sensor_baro"]
    arr["sensor_baro.pressure"] = PRESSURE_HPA
    arr["sensor_baro.temperature"] = temp_c
    with open(path, "wb") as f:
        f.write(bytes(out))
        f.write(arr.tobytes())


def verify(path, t_s, gyro, accel, temp_c):
    """Read the file back with pyulog and compare with what was written (float32 rounding)."""
    from pyulog import ULog
    ulog = ULog(path)
    got = {d.name: d for d in ulog.data_list if d.multi_id == 0}
    for topic in TOPICS:
        if topic not in got:
            raise RuntimeError("pyulog did not read %s back" % topic)
        if len(got[topic].data["timestamp"]) != len(t_s):
            raise RuntimeError("pyulog read %d %s samples, %d written"
                               % (len(got[topic].data["timestamp"]), topic, len(t_s)))
    for topic, values in (("sensor_gyro", gyro), ("sensor_accel", accel)):
        d = got[topic].data
        for i, axis in enumerate("xyz"):
            if not np.array_equal(d[axis], values[:, i].astype(np.float32)):
                raise RuntimeError("pyulog read back a different %s.%s" % (topic, axis))
        if not np.array_equal(d["temperature"], np.asarray(temp_c, dtype=np.float32)):
            raise RuntimeError("pyulog read back a different %s.temperature" % topic)
    if ulog.file_corruption:
        raise RuntimeError("pyulog reports file corruption")
    return len(t_s)
