"""A minimal ArduPilot DataFlash (.bin) writer: every message is 0xA3 0x95, a type byte and a
packed little-endian payload; FMT messages (type 128) describe the others. Written: FMT for
FMT, PARM and IMU; a few PARM messages; one IMU message (instance 0) per sample."""
import struct

import numpy as np

HEAD = b"\xa3\x95"
FMT_TYPE, PARM_TYPE, IMU_TYPE = 128, 64, 65
# format characters: Q uint64, B uint8, f float32, n char[4], N char[16], Z char[64]
FORMATS = {
    FMT_TYPE: ("FMT", "BBnNZ", "Type,Length,Name,Format,Columns"),
    PARM_TYPE: ("PARM", "QNf", "TimeUS,Name,Value"),
    IMU_TYPE: ("IMU", "QBfffffff", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,T"),
}
SIZES = {"Q": 8, "B": 1, "f": 4, "n": 4, "N": 16, "Z": 64}
# AHRS_ORIENTATION 0: no rotation; INS_TCAL1_ENABLE 0: the log carries no correction to undo.
# No INS_ACC1_CALTEMP, so the fitter takes each accel axis's mean as its reference value.
PARAMS = [("AHRS_ORIENTATION", 0.0), ("INS_TCAL1_ENABLE", 0.0)]


def _length(fmt):
    return 3 + sum(SIZES[c] for c in fmt)


def _pad(text, n):
    b = text.encode("ascii")
    if len(b) > n:
        raise ValueError("%r longer than %d" % (text, n))
    return b + bytes(n - len(b))


def write(path, t_s, gyro, accel, temp_c):
    """t_s: (n,) seconds; gyro (n,3) rad/s; accel (n,3) m/s^2; temp_c (n,) degC."""
    time_us = np.round(np.asarray(t_s) * 1e6).astype(np.uint64)
    out = bytearray()
    for typ, (name, fmt, cols) in FORMATS.items():
        out += HEAD + bytes([FMT_TYPE]) + struct.pack(
            "<BB", typ, _length(fmt)) + _pad(name, 4) + _pad(fmt, 16) + _pad(cols, 64)
    for name, value in PARAMS:
        out += HEAD + bytes([PARM_TYPE]) + struct.pack("<Q", int(time_us[0])) + _pad(name, 16) \
            + struct.pack("<f", value)
    dt = np.dtype([("h0", "u1"), ("h1", "u1"), ("type", "u1"), ("TimeUS", "<u8"), ("I", "u1"),
                   ("GyrX", "<f4"), ("GyrY", "<f4"), ("GyrZ", "<f4"), ("AccX", "<f4"),
                   ("AccY", "<f4"), ("AccZ", "<f4"), ("T", "<f4")], align=False)
    assert dt.itemsize == _length(FORMATS[IMU_TYPE][1])
    arr = np.zeros(len(time_us), dtype=dt)
    arr["h0"], arr["h1"], arr["type"] = 0xA3, 0x95, IMU_TYPE
    arr["TimeUS"] = time_us
    arr["I"] = 0
    for i, axis in enumerate("XYZ"):
        arr["Gyr" + axis] = gyro[:, i]
        arr["Acc" + axis] = accel[:, i]
    arr["T"] = temp_c
    with open(path, "wb") as f:
        f.write(bytes(out))
        f.write(arr.tobytes())


def verify(path, t_s, gyro, accel, temp_c):
    """Read the log back with pymavlink's DFReader and compare (float32 rounding)."""
    from pymavlink import DFReader
    log = DFReader.DFReader_binary(path, zero_time_base=True)
    params = {}
    rows = []
    while True:
        m = log.recv_match(type=["PARM", "IMU"])
        if m is None:
            break
        if m.get_type() == "PARM":
            params[m.Name] = m.Value
        else:
            rows.append((m.TimeUS, m.I, m.GyrX, m.GyrY, m.GyrZ, m.AccX, m.AccY, m.AccZ, m.T))
    if params != dict(PARAMS):
        raise RuntimeError("DFReader read back PARM %r" % params)
    got = np.array(rows, dtype=float)
    if got.shape[0] != len(t_s):
        raise RuntimeError("DFReader read %d IMU messages, %d written" % (got.shape[0], len(t_s)))
    want = np.column_stack([np.round(np.asarray(t_s) * 1e6), np.zeros(len(t_s)),
                            gyro.astype(np.float32), accel.astype(np.float32),
                            np.asarray(temp_c, dtype=np.float32)])
    if not np.array_equal(got, want.astype(float)):
        raise RuntimeError("DFReader read back different IMU values")
    return got.shape[0]
