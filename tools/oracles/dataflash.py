#!/usr/bin/env python3
"""Test logs for the ArduPilot DataFlash reader (crates/thermonav-io/src/dataflash, tests in
crates/thermonav-io/tests/it/dataflash.rs and crates/thermonav-cli/tests/cli/convert_dataflash.rs)
and the values they hold.

Written FROM THE FORMAT'S DOCUMENTATION with Python's `struct` (no ArduPilot or pymavlink code):
ArduPilot's "Adding a new log message" page and the format-character table at the top of
libraries/AP_Logger/LogStructure.h:

- every record is 0xA3 0x95, a message id (u8), then the fields packed little-endian with no
  padding;
- id 128 is FMT: Type (u8), Length (u8, the whole record including its 3 header bytes), Name
  (char[4]), Format (char[16]), Columns (char[64], comma-separated labels); a log starts with
  the FMT that describes FMT itself ("BBnNZ", length 89);
- format characters: a int16_t[32], b int8_t, B uint8_t, h int16_t, H uint16_t, i int32_t,
  I uint32_t, f float, d double, n char[4], N char[16], Z char[64], c int16_t * 100,
  C uint16_t * 100, e int32_t * 100, E uint32_t * 100, L int32_t latitude/longitude (1e-7 deg),
  M uint8_t flight mode, q int64_t, Q uint64_t;
- UNIT (TimeUS Q, Id b (a character), Label Z), MULT (TimeUS Q, Id b, Mult d) and FMTU
  (TimeUS Q, FmtType B, UnitIds N, MultIds N: one unit and one multiplier character per column);
- IMU "QBffffffIIfBBHH" TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz (units
  s#EEEooo--O--zz, multipliers F-000000-----00: rad/s, m/s/s, degC; ArduPilot's body axes are
  forward-right-down, a level unit at rest reads AccZ = -g);
- GPS "QBBIHBcLLeffffB" TimeUS,I,Status,GMS,GWk,NSats,HDop,Lat,Lng,Alt,Spd,GCrs,VZ,Yaw,U
  (Status 3 = 3D fix and above; GMS ms of the GPS week GWk; Alt in cm (e), m above mean sea
  level; Spd m/s, GCrs deg, VZ m/s down);
- GPA "QBCCCCfBIH" TimeUS,I,VDop,HAcc,VAcc,SAcc,YAcc,VV,SMS,Delta (HAcc, VAcc in cm (C)).

Generated ONCE with: Python 3.11.7, pymavlink 2.4.50 (`pip install pymavlink`), used only to
read the files back. Run from the repository root: `python3 tools/oracles/dataflash.py`.
Output: crates/thermonav-io/tests/data/dataflash/.

Files:
- static.bin: a simulated static unit, seeded: IMU instance 0 at 100 Hz (100 records), IMU
  instance 1 at 10 Hz (10 records), GPS instance 0 at 6.7 Hz (7 records, the first two without a
  fix), GPS instance 1 (2 records), GPA for every GPS record, UNIT/MULT/FMTU for IMU, GPS and
  GPA, PARM and MSG records (read past), and TYP1/TYP2 records that use every format character;
- boot.bin: IMU instance 0 only (20 records), no GPS, no units: times stay since boot;
- deg_units.bin: boot.bin with an FMTU that puts GyrX..Z in deg/s, which the reader refuses;
- static_10hz.bin.gz (gzip): long enough for `characterize` with its default conditioning:
  1500 IMU records at 10 Hz, instance 0, T = 25 degC, values multiples of 2^-14 (exact in
  binary32, so that gzip keeps the file small); expected_10hz.json holds its count and its
  first and last records.

expected.json: what was written: each IMU record's TimeUS and values as the binary32 or
scaled-integer value it decodes to (raw / 100 for c, C, e, E; raw / 1e7 for L, each the
correctly rounded quotient); the GPS fixes kept; GPST minus boot time (the median, the upper
one of an even count, of GPST(GWk, GMS) - TimeUS over the fixes with Status >= 3 and
GWk > 0); the TYP1/TYP2 fields. Every file is read back with pymavlink's DFReader and must
decode to the same values (scaled fields within 1 ulp: pymavlink multiplies by 0.01 and 1e-7,
which are not exact in binary, where the documented scale divides by 100 and 1e7).
"""
import gzip
import json
import math
import pathlib
import random
import struct

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "crates" / "thermonav-io" / "tests" / "data" / "dataflash"
HEAD = b"\xa3\x95"
FMT_ID = 128
STRUCT_OF = {
    "a": "32h", "b": "b", "B": "B", "h": "h", "H": "H", "i": "i", "I": "I", "f": "f",
    "d": "d", "n": "4s", "N": "16s", "Z": "64s", "c": "h", "C": "H", "e": "i", "E": "I",
    "L": "i", "M": "B", "q": "q", "Q": "Q",
}
SCALE_DIVISOR = {"c": 100, "C": 100, "e": 100, "E": 100, "L": 10_000_000}
G = 9.80665
GPS_WEEK = 2345
IMU = ("IMU", "QBffffffIIfBBHH", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz")
GPS = ("GPS", "QBBIHBcLLeffffB", "TimeUS,I,Status,GMS,GWk,NSats,HDop,Lat,Lng,Alt,Spd,GCrs,VZ,Yaw,U")
GPA = ("GPA", "QBCCCCfBIH", "TimeUS,I,VDop,HAcc,VAcc,SAcc,YAcc,VV,SMS,Delta")
UNITS = [("s", "s"), ("#", "instance"), ("-", ""), ("E", "rad/s"), ("k", "deg/s"),
         ("o", "m/s/s"), ("O", "degC"), ("D", "deglatitude"), ("U", "deglongitude"),
         ("m", "m"), ("n", "m/s"), ("h", "degheading"), ("S", "satellites"), ("d", "deg"),
         ("z", "Hz")]
MULTS = [("-", 0.0), ("?", 1.0), ("0", 1.0), ("B", 1e-2), ("C", 1e-3), ("F", 1e-6),
         ("G", 1e-7)]
FMTU = {"IMU": ("s#EEEooo--O--zz", "F-000000-----00"),
        "GPS": ("s#-s-S-DUmnhnh-", "F--C-0BGGB000--"),
        "GPA": ("s#mmmnd-ss", "F-BBBB0-CC")}


def f32(x):
    """x rounded to binary32, as a float field holds it."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def layout(fmt):
    return "<" + "".join(STRUCT_OF[c] for c in fmt)


class Log:
    """A DataFlash log being written: FMT records define types, write() adds a record."""

    def __init__(self):
        self.data = bytearray()
        self.types = {}
        self.define(FMT_ID, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns")

    def define(self, type_id, name, fmt, columns):
        length = 3 + struct.calcsize(layout(fmt))
        self.types[name] = (type_id, fmt)
        self.record(FMT_ID, "BBnNZ", type_id, length, name.encode(), fmt.encode(),
                    columns.encode())

    def record(self, type_id, fmt, *values):
        flat = [x for v in values for x in (v if isinstance(v, list) else [v])]
        self.data += HEAD + bytes([type_id]) + struct.pack(layout(fmt), *flat)

    def write(self, name, *values):
        type_id, fmt = self.types[name]
        self.record(type_id, fmt, *values)


def units(log, fmtu):
    """UNIT, MULT and FMTU records (FMTU for each type of `fmtu`)."""
    log.define(177, "UNIT", "QbZ", "TimeUS,Id,Label")
    log.define(178, "MULT", "Qbd", "TimeUS,Id,Mult")
    log.define(179, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds")
    for ident, label in UNITS:
        log.write("UNIT", 0, ord(ident), label.encode())
    for ident, mult in MULTS:
        log.write("MULT", 0, ord(ident), mult)
    for name, (unit_ids, mult_ids) in fmtu.items():
        log.write("FMTU", 0, log.types[name][0], unit_ids.encode(), mult_ids.encode())


def imu_values(rng, k, t0_c):
    """One static sample: gyro ~ N(0, 1e-3) rad/s, accel (0, 0, -g) + N(0, 2e-2) m/s^2 in FRD."""
    gyro = [f32(rng.gauss(0.0, 1e-3)) for _ in range(3)]
    accel = [f32(rng.gauss(0.0, 2e-2)) for _ in range(2)] + [f32(-G + rng.gauss(0.0, 2e-2))]
    return gyro, accel, f32(t0_c + 0.01 * k)


def write_imu(log, time_us, instance, gyro, accel, temp_c):
    log.write("IMU", time_us, instance, *gyro, *accel, 0, 0, temp_c, 1, 1, 100, 100)
    return {"time_us": time_us, "instance": instance, "gyro": gyro, "accel": accel,
            "temp_c": temp_c}


def gps_record(j, time_us, instance):
    """GPS raw fields of fix j: the first two without a fix (Status 1, no week)."""
    fixed = j >= 2
    gms = 123_456_000 + 200 * j + (3 if instance else 0)
    return {
        "time_us": time_us, "instance": instance, "status": 6 if j % 3 == 0 else 3,
        "gms": gms if fixed else 0, "gwk": GPS_WEEK if fixed else 0, "nsats": 14,
        "hdop_raw": 71, "lat_raw": -353632621 + 13 * j + 1000 * instance,
        "lng_raw": 1491652374 - 7 * j, "alt_raw": 58412 + j, "spd": f32(0.03 + 0.001 * j),
        "gcrs": f32(123.4 + j), "vz": f32(-0.01 * j), "yaw": f32(0.0), "u": 1,
    } | ({} if fixed else {"status": 1})


def write_gps(log, r):
    log.write("GPS", r["time_us"], r["instance"], r["status"], r["gms"], r["gwk"], r["nsats"],
              r["hdop_raw"], r["lat_raw"], r["lng_raw"], r["alt_raw"], r["spd"], r["gcrs"],
              r["vz"], r["yaw"], r["u"])
    hacc_raw, vacc_raw = 85 + r["instance"], 132
    log.write("GPA", r["time_us"], r["instance"], 150, hacc_raw, vacc_raw, 21, f32(0.0), 1,
              r["gms"], 200)
    return r | {"hacc_raw": hacc_raw, "vacc_raw": vacc_raw}


def fix_expected(r):
    """A kept fix: its GPST time (the receiver's GWk and GMS) and its scaled values."""
    gpst_ns = ((315_964_800 + r["gwk"] * 604_800) * 1000 + r["gms"]) * 1_000_000
    return {
        "time_us": r["time_us"], "gpst_ns": gpst_ns, "status": r["status"],
        "lat_deg": r["lat_raw"] / 10_000_000, "lng_deg": r["lng_raw"] / 10_000_000,
        "alt_m": r["alt_raw"] / 100, "spd_m_s": r["spd"], "gcrs_deg": r["gcrs"],
        "vz_m_s": r["vz"], "hacc_m": r["hacc_raw"] / 100, "vacc_m": r["vacc_raw"] / 100,
    }


TYP1 = ("TYP1", "abBhHiIfdn", "Arr,SB,UB,SH,UH,SI,UI,F,D,N4")
TYP2 = ("TYP2", "NZcCeELMqQ", "N16,Z64,C,UC,E,UE,L,M,Q,UQ")
TYP1_VALUES = [list(range(-16, 16)), -7, 250, -30000, 65000, -2_000_000_000, 4_000_000_000,
               f32(1.1), 2.2, b"ab"]
TYP2_VALUES = [b"sixteen-chars-ok", b"a longer text of sixty-four bytes at most", -12345, 54321,
               -123456789, 3_000_000_001, -1799999999, 5, -(2**62), 2**63 + 5]


def typ_expected():
    def decoded(fmt, values):
        out = []
        for c, v in zip(fmt, values):
            if c in SCALE_DIVISOR:
                out.append(v / SCALE_DIVISOR[c])
            elif isinstance(v, bytes):
                out.append(v.decode())
            else:
                out.append(v)
        return out
    return {"TYP1": decoded(TYP1[1], TYP1_VALUES), "TYP2": decoded(TYP2[1], TYP2_VALUES)}


def static_log():
    rng = random.Random(20261203)
    log = Log()
    for type_id, (name, fmt, cols) in zip((130, 131, 132, 140, 141), (IMU, GPS, GPA, TYP1, TYP2)):
        log.define(type_id, name, fmt, cols)
    log.define(64, "PARM", "QNff", "TimeUS,Name,Value,Default")
    log.define(91, "MSG", "QZ", "TimeUS,Message")
    units(log, FMTU)
    log.write("MSG", 1_000, b"ArduCopter V4.5.7 (test log)")
    log.write("PARM", 1_100, b"INS_GYRO_FILTER", f32(20.0), f32(20.0))
    log.record(140, TYP1[1], *TYP1_VALUES)
    log.record(141, TYP2[1], *TYP2_VALUES)
    imu0, imu1, gps, others = [], [], [], []
    for k in range(100):
        time_us = 5_000_000 + 10_000 * k + rng.randrange(0, 40)
        gyro, accel, temp = imu_values(rng, k, 40.0)
        imu0.append(write_imu(log, time_us, 0, gyro, accel, temp))
        if k % 10 == 5:
            gyro, accel, temp = imu_values(rng, k, 45.0)
            imu1.append(write_imu(log, time_us + 300, 1, gyro, accel, temp))
        if k % 15 == 7:
            gps.append(write_gps(log, gps_record(len(gps), time_us + 150, 0)))
            if len(gps) in (4, 6):
                others.append(write_gps(log, gps_record(len(gps), time_us + 250, 1)))
    kept = [fix_expected(r) for r in gps if r["status"] >= 3 and r["gwk"] > 0]
    offsets = sorted(f["gpst_ns"] - f["time_us"] * 1000 for f in kept)
    boot_to_gpst_ns = offsets[len(offsets) // 2]
    expected = {
        "boot_to_gpst_ns": boot_to_gpst_ns, "imu0": imu0, "imu1_count": len(imu1),
        "imu1_first": imu1[0], "gps_records": len(gps), "fixes": kept,
        "other_gps_records": len(others), "typ": typ_expected(),
    }
    return bytes(log.data), expected


def boot_log(fmtu=None):
    rng = random.Random(7)
    log = Log()
    log.define(130, "IMU", *IMU[1:])
    log.define(91, "MSG", "QZ", "TimeUS,Message")
    if fmtu is not None:
        units(log, fmtu)
    log.write("MSG", 500, b"boot only")
    imu = []
    for k in range(20):
        gyro, accel, temp = imu_values(rng, k, 30.0)
        imu.append(write_imu(log, 2_000_000 + 2_500 * k, 0, gyro, accel, temp))
    return bytes(log.data), {"imu0": imu}


def q14(rng, sd):
    """A normal draw rounded to a multiple of 2^-14 (exact in binary32)."""
    return round(rng.gauss(0.0, sd) * 2**14) / 2**14


def long_log():
    rng = random.Random(10)
    log = Log()
    log.define(130, "IMU", *IMU[1:])
    imu = []
    for k in range(1500):
        gyro = [q14(rng, 1e-3) for _ in range(3)]
        accel = [q14(rng, 2e-2), q14(rng, 2e-2), -9.8125 + q14(rng, 2e-2)]
        imu.append(write_imu(log, 1_000_000 + 100_000 * k, 0, gyro, accel, 25.0))
    return bytes(log.data), imu


def close(a, b):
    """Equal, or within 1 ulp (pymavlink scales by multiplication, the documentation by
    division)."""
    if isinstance(a, float) or isinstance(b, float):
        return a == b or abs(a - b) <= math.ulp(max(abs(a), abs(b)))
    return a == b


def read_back(path):
    """Every record of the file as pymavlink decodes it: {type: [dict of fields]}."""
    from pymavlink import DFReader
    reader = DFReader.DFReader_binary(str(path), zero_time_base=True)
    records = {}
    while True:
        m = reader.recv_msg()
        if m is None:
            break
        records.setdefault(m.get_type(), []).append(m.to_dict())
    return records


def check_static(path, expected):
    records = read_back(path)
    imu = records["IMU"]
    imu0 = [r for r in imu if r["I"] == 0]
    assert len(imu0) == len(expected["imu0"]) and len(imu) - len(imu0) == expected["imu1_count"]
    for got, want in zip(imu0, expected["imu0"]):
        assert got["TimeUS"] == want["time_us"]
        values = [got[c] for c in ("GyrX", "GyrY", "GyrZ", "AccX", "AccY", "AccZ", "T")]
        assert values == want["gyro"] + want["accel"] + [want["temp_c"]], (values, want)
    gps0 = [r for r in records["GPS"] if r["I"] == 0 and r["Status"] >= 3 and r["GWk"] > 0]
    gpa = {(r["I"], r["TimeUS"]): r for r in records["GPA"]}
    assert len(gps0) == len(expected["fixes"])
    for got, want in zip(gps0, expected["fixes"]):
        a = gpa[(0, got["TimeUS"])]
        pairs = [(got["Lat"], want["lat_deg"]), (got["Lng"], want["lng_deg"]),
                 (got["Alt"], want["alt_m"]), (got["Spd"], want["spd_m_s"]),
                 (got["GCrs"], want["gcrs_deg"]), (got["VZ"], want["vz_m_s"]),
                 (a["HAcc"], want["hacc_m"]), (a["VAcc"], want["vacc_m"])]
        assert all(close(g, w) for g, w in pairs), pairs
        assert got["TimeUS"] == want["time_us"] and got["Status"] == want["status"]
    for name, fmt in (("TYP1", TYP1[1]), ("TYP2", TYP2[1])):
        (got,) = records[name]
        cols = TYP1[2].split(",") if name == "TYP1" else TYP2[2].split(",")
        for c, col, want in zip(fmt, cols, expected["typ"][name]):
            value = got[col]
            if c == "a":
                value = list(value)
            assert close(value, want), (name, col, value, want)
    units = {chr(r["Id"]): r["Label"] for r in records["UNIT"]}
    assert units["E"] == "rad/s" and units["O"] == "degC", units


def check_boot(path, expected):
    imu = read_back(path)["IMU"]
    assert [r["TimeUS"] for r in imu] == [w["time_us"] for w in expected["imu0"]]
    for got, want in zip(imu, expected["imu0"]):
        values = [got[c] for c in ("GyrX", "GyrY", "GyrZ", "AccX", "AccY", "AccZ", "T")]
        assert values == want["gyro"] + want["accel"] + [want["temp_c"]]


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    static, static_expected = static_log()
    (OUT / "static.bin").write_bytes(static)
    check_static(OUT / "static.bin", static_expected)
    boot, boot_expected = boot_log()
    (OUT / "boot.bin").write_bytes(boot)
    check_boot(OUT / "boot.bin", boot_expected)
    degrees = {"IMU": ("s#kkkooo--O--zz", FMTU["IMU"][1])}
    deg, _ = boot_log(degrees)
    (OUT / "deg_units.bin").write_bytes(deg)
    long, long_imu = long_log()
    (OUT / "static_10hz.bin").write_bytes(long)
    check_boot(OUT / "static_10hz.bin", {"imu0": long_imu})
    (OUT / "static_10hz.bin").unlink()
    long_expected = {"imu_count": len(long_imu), "imu_first": long_imu[0], "imu_last": long_imu[-1]}
    (OUT / "static_10hz.bin.gz").write_bytes(gzip.compress(long, 9, mtime=0))
    (OUT / "expected_10hz.json").write_text(json.dumps(long_expected, indent=1) + "\n")
    expected = {"static": static_expected, "boot": boot_expected}
    (OUT / "expected.json").write_text(json.dumps(expected, separators=(",", ":")) + "\n")
    print({p.name: p.stat().st_size for p in sorted(OUT.iterdir())})


if __name__ == "__main__":
    main()
