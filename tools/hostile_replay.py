#!/usr/bin/env python3
"""Replays issue 20's and issue 37's hostile cases against the release binary and measures each one.

Every case must end cleanly: exit 0, 1 or 2 (never 101, a signal or a hang), within 10 s of
wall time and under 500 MB of peak memory (the child's maximum resident set, from wait4), and
leave no hidden temporary file. A case that must be refused says so (`refuse`), with a piece
of the message it must print.

    python3 tools/hostile_replay.py [path/to/thermonav]

Prints one line per case (exit code, seconds, MB, the last line of stderr) and exits 1 when
any case breaks a rule. Standard library only.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import time

LIMIT_S = 10.0
LIMIT_MB = 500.0

BINARY = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "target/release/thermonav")


def measured(cwd, shell_words):
    """Runs one case in a child Python whose rusage covers only that case."""
    code = (
        "import resource,subprocess,sys,time,os\n"
        "t=time.monotonic()\n"
        "p=subprocess.run(['bash','-c',sys.argv[1]],stdout=subprocess.DEVNULL,stderr=subprocess.PIPE)\n"
        "s=time.monotonic()-t\n"
        "kb=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss\n"
        "sys.stderr.buffer.write(p.stderr)\n"
        "print(p.returncode, s, kb/1024)\n"
    )
    child = subprocess.run(
        ["timeout", str(LIMIT_S * 3), sys.executable, "-c", code, shell_words],
        cwd=cwd,
        capture_output=True,
        env=dict(os.environ, T=BINARY),
    )
    err = child.stderr.decode(errors="replace")
    try:
        rc, seconds, mb = child.stdout.decode().split()
        return int(rc), float(seconds), float(mb), err
    except ValueError:
        return 124, LIMIT_S * 3, 0.0, err


REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def gzip_of_zeros(path, mib):
    """`mib` MiB of zeros gzipped (about a thousand times smaller)."""
    import gzip
    block = bytes(1 << 20)
    with gzip.open(path, "wb", compresslevel=1) as out:
        for _ in range(mib):
            out.write(block)


def ulog_with_a_huge_field_name(path):
    """A 60 KB ULog whose one format has 60,000 elements under a 60,000-character name."""
    import struct

    def message(kind, payload):
        return struct.pack("<HB", len(payload), ord(kind)) + payload

    head = b"ULog\x01\x12\x35" + bytes([1]) + struct.pack("<Q", 1000) + message("B", bytes(40))
    fmt = message("F", b"huge:uint8_t[60000] " + b"n" * 60000 + b";")
    subscribe = message("A", bytes([0]) + struct.pack("<H", 0) + b"huge")
    with open(path, "wb") as out:
        out.write(head + fmt + subscribe)


def dataflash_in_kelvin(path):
    """The io tests' boot.bin with its first IMU record's temperature (byte 44) at 298.15."""
    import struct
    data = bytearray(open(os.path.join(REPO, "crates/thermonav-io/tests/data/dataflash/boot.bin"), "rb").read())
    # The first IMU record: header A3 95 and the id of the FMT that defines "IMU".
    fmt = data.find(b"IMU\x00")
    imu_id = data[fmt - 2]
    at = next(i for i in range(len(data) - 2) if data[i:i + 3] == bytes([0xA3, 0x95, imu_id]) and i > fmt)
    data[at + 44:at + 48] = struct.pack("<f", 298.15)
    open(path, "wb").write(bytes(data))


def issue_37_fixtures(base):
    """The decompression bombs, hostile logs and a lot of 10^5 units of issue 37's rows."""
    gzip_of_zeros(os.path.join(base, "bomb.bin.gz"), 512)
    shutil.copy(os.path.join(base, "bomb.bin.gz"), os.path.join(base, "bomb.ulg.gz"))
    ulog_with_a_huge_field_name(os.path.join(base, "huge.ulg"))
    dataflash_in_kelvin(os.path.join(base, "kelvin.bin"))
    with open(os.path.join(base, "lot.toml"), "w") as out:
        out.write('name = "big"\n')
        for k in range(100_000):
            out.write(f'[[unit]]\nserial = "SN{k:06d}"\nfiles = ["c/imu_0C.csv", "c/imu_20C.csv"]\n')


def fixtures(base):
    """A 330 s vessel survey and a three-temperature bank, made by the binary itself."""
    subprocess.run([BINARY, "--quiet", "simulate", "vessel", "--out", "v", "--duration-s", "300"],
                   cwd=base, check=True, stdout=subprocess.DEVNULL)
    subprocess.run([BINARY, "--quiet", "simulate", "chamber", "--out", "c", "--temperatures-c",
                    "0,20,40", "--duration-s", "1200"], cwd=base, check=True,
                   stdout=subprocess.DEVNULL)
    records = sorted(os.path.join("c", f) for f in os.listdir(os.path.join(base, "c"))
                     if f.endswith(".csv"))
    subprocess.run([BINARY, "--quiet", "characterize", *records, "--out", "bank.json"],
                   cwd=base, check=True, stdout=subprocess.DEVNULL)
    issue_37_fixtures(base)


NAV = "$T integrate --imu v/imu.csv --gnss {gnss} --bank bank.json --out o.csv"
EVAL = "$T evaluate --imu v/imu.csv --gnss v/gnss.csv --reference v/reference.csv --bank bank.json --out e"
SED_GYRO = "sed '100s/^\\([^,]*\\),[^,]*/\\1,{value}/' v/imu.csv > b.csv; "
NORTH = ("printf 'start = { lat_deg = 88.99, lon_deg = 10.0, h_m = 0.0 }\\n"
         "initial_speed_m_s = 30.0\\n[[segment]]\\nduration_s = 120.0\\n' > n.toml; ")

# (name, shell line, expected exit codes, a piece of stderr that must appear or None)
CASES = [
    ("inspect | true", "$T inspect v/imu.csv | true; exit ${PIPESTATUS[0]}", {0}, None),
    ("allan | true", "$T allan v/imu.csv | true; exit ${PIPESTATUS[0]}", {0}, None),
    ("ar | true", "$T ar v/imu.csv | true; exit ${PIPESTATUS[0]}", {0}, None),
    ("bank show | true", "$T bank show bank.json | true; exit ${PIPESTATUS[0]}", {0}, None),
    ("inspect | head -1", "$T inspect v/imu.csv | head -1; exit ${PIPESTATUS[0]}", {0}, None),
    ("filter X --out X", "$T filter v/imu.csv --cutoff-hz 10 --out v/imu.csv", {2}, "would overwrite the input"),
    ("integrate --out its IMU", NAV.format(gnss="v/gnss.csv").replace("o.csv", "v/imu.csv"), {2}, "would overwrite the input"),
    ("characterize X --out X", "$T characterize c/imu_0C.csv c/imu_20C.csv --out c/imu_0C.csv", {2}, "would overwrite the input"),
    ("sidecar over the GNSS input", "cp v/gnss.csv v/sol.states.csv; " + NAV.format(gnss="v/sol.states.csv").replace("o.csv", "v/sol.csv"), {2}, "would overwrite the input"),
    ("filter --out D/bank", "$T filter v/imu.csv --cutoff-hz 10 --out bank", {2}, "is not a thermonav record"),
    ("outages 1e12", NAV.format(gnss="v/gnss.csv") + " --outages every:10,5,20,1000000000000", {2}, "not inside the data"),
    ("outages 1e8", NAV.format(gnss="v/gnss.csv") + " --outages every:10,5,20,100000000", {2}, "not inside the data"),
    ("monte carlo 1e6", EVAL + " --monte-carlo 1000000", {2}, "at most 1000 replicates"),
    ("bank show /dev/zero", "$T bank show /dev/zero", {1}, "larger than 64 MiB"),
    ("inspect /dev/zero", "$T inspect /dev/zero", {1}, "not a regular file"),
    ("allan on a 2 GB sparse file", "truncate -s 2G sp.csv; $T allan sp.csv", {1}, "line longer than"),
    ("ULog convert of a sparse file", "truncate -s 2G sp.ulg; $T convert sp.ulg --out x.csv", {1, 2}, "sp.ulg"),
    ("bank of a sparse file", "truncate -s 2G sp.json; $T bank show sp.json", {1}, "larger than 64 MiB"),
    ("output rate 1e9", NAV.format(gnss="v/gnss.csv") + " --output-rate-hz 1e9", {2}, "above 5000 Hz"),
    ("plot with 1e6 outages", "$T plot trajectory v/reference.csv --out t.svg --outages every:10,5,20,1000000", {2}, "not inside the data"),
    ("ar --order 500", "$T ar v/imu.csv --order 500", {2}, "from 1 to 100"),
    ("a 1e300 gyro sample, allan", SED_GYRO.format(value="1e300") + "$T allan b.csv", {1}, "b.csv:100: column gx_rad_s"),
    ("a 1.79e308 sample, filter", SED_GYRO.format(value="1.79e308") + "$T filter b.csv --cutoff-hz 10 --out f.csv", {1}, "too large"),
    ("GNSS h_m = 1e300", "sed '10s/^\\([^,]*,[^,]*,[^,]*\\),[^,]*/\\1,1e300/' v/gnss.csv > g.csv; " + NAV.format(gnss="g.csv"), {1}, "g.csv:10: column h_m"),
    ("GNSS at the south pole", "awk -F, 'BEGIN{OFS=\",\"} NR>1{$2=-90} {print}' v/gnss.csv > g.csv; " + NAV.format(gnss="g.csv"), {1}, "within ±89°"),
    ("a motion over the pole", NORTH + "$T simulate vessel --motion n.toml --out nv", {1}, "n.toml: the motion reaches latitude"),
    ("a 60 s IMU hole", "awk -F, 'NR==1 || $1<100 || $1>160' v/imu.csv > h.csv; " + NAV.format(gnss="v/gnss.csv").replace("v/imu.csv", "h.csv"), {1}, "h.csv: the IMU record has a gap of 60"),
    ("a stuck channel", "awk -F, 'BEGIN{OFS=\",\"} NR>1{$3=0.0025} {print}' c/imu_0C.csv > s.csv; $T characterize s.csv c/imu_20C.csv --out b2.json", {1}, "is constant"),
    ("GNSS sd = 0", "awk -F, 'BEGIN{OFS=\",\"} NR>1{$5=0} {print}' v/gnss.csv > g.csv; " + NAV.format(gnss="g.csv"), {1}, "g.csv:2: column sd_n_m"),
    ("temp_c = -300", "awk -F, 'BEGIN{OFS=\",\"} NR>1{$8=-300} {print}' c/imu_0C.csv > t.csv; $T characterize t.csv c/imu_20C.csv --out b2.json", {1}, "-80 to 150"),
    ("temp_c = 1e6", "awk -F, 'BEGIN{OFS=\",\"} NR>1{$8=1e6} {print}' c/imu_0C.csv > t.csv; $T characterize t.csv c/imu_20C.csv --out b2.json", {1}, "-80 to 150"),
    ("--temperatures-c=20,20", "$T simulate chamber --out cc --temperatures-c=20,20 --duration-s 60", {2}, "twice"),
    ("a negative bank sigma", "sed '0,/\"sigma\": 0/s//\"sigma\": -0/' bank.json > nb.json; $T bank show nb.json", {1}, "sigma = -"),
    ("GNSS before the IMU", "awk -F, 'BEGIN{OFS=\",\"} NR==1{print;next} {$1=$1-100; print}' v/gnss.csv > g.csv; " + NAV.format(gnss="g.csv"), {0, 1}, None),
    ("18446744073709551615 taps", "$T fir --fs-hz 100 --cutoff-hz 10 --transition-hz 1e-300", {2}, "more than 2000000"),
    ("a process substitution", "$T inspect <(cat v/imu.csv)", {1, 2}, "process substitution"),
    ("a 254-byte output name", "$T filter v/imu.csv --cutoff-hz 10 --out $(printf 'a%.0s' {1..250}).csv", {2}, "at most 255"),
    # Issue 37 (a second hostile round: binary logs and options that multiply work).
    ("37.3 a DataFlash gzip bomb", "$T convert bomb.bin.gz --format dataflash --out x.csv", {1}, "decompression bomb"),
    ("37.3 a ULog gzip bomb", "$T convert bomb.ulg.gz --format px4-ulog --out x.csv", {1}, "decompression bomb"),
    ("37.5 a 60,000-character field name", "$T convert huge.ulg --out x.csv", {1}, "longer than the 256"),
    ("37.6 a DataFlash log in kelvin", "$T convert kelvin.bin --out x.csv", {1}, "in kelvin?"),
    ("37.9 gmwm --replicates 1e9", "$T gmwm v/imu.csv --replicates 1000000000", {2}, "10 to 1000 bootstrap replicates"),
    ("37.11 an EKF2 export of 1e300", "sed '0,/\"white_noise_density\": [^,]*/s//\"white_noise_density\": 1e300/' bank.json > w.json; $T bank export w.json --format px4-ekf2 --temperature-c 0 --out p.params", {1}, "32-bit float parameter"),
    ("37.12 --shard 1/1000000000", EVAL + " --outages 60+30,150+30 --shard 1/1000000000", {1, 2}, "at most"),
    ("37.14 --bias-hypotheses 9999999", NAV.format(gnss="v/gnss.csv") + " --bias-hypotheses 9999999", {2}, "from 9 to 201"),
    ("37.15 one unit of a 10^5-unit lot", "$T characterize --manifest lot.toml --unit-index 99999 --out lot", {0}, None),
    ("37 a table from a clock time", "printf 't_s,temp_c\\n1700000000,20\\n' > tt.csv; $T simulate vessel --temperature-file tt.csv --duration-s 60 --out vv", {1}, "0 s on the first row"),
]


def main():
    base = tempfile.mkdtemp(prefix="hostile-")
    broken = 0
    try:
        fixtures(base)
        for name, words, codes, needle in CASES:
            work = os.path.join(base, "w")
            shutil.rmtree(work, ignore_errors=True)
            os.mkdir(work)
            for entry in ("v", "c", "bank.json", "bomb.bin.gz", "bomb.ulg.gz", "huge.ulg",
                          "kelvin.bin", "lot.toml"):
                source = os.path.join(base, entry)
                copy = shutil.copytree if os.path.isdir(source) else shutil.copy
                copy(source, os.path.join(work, entry))
            rc, seconds, mb, err = measured(work, words)
            temporaries = [f for root, _, files in os.walk(work) for f in files
                           if f.startswith(".") and f.endswith(".tmp")]
            last = next((l for l in reversed(err.splitlines()) if l.strip()), "")
            faults = []
            if rc not in codes:
                faults.append(f"exit {rc}, expected {sorted(codes)}")
            if seconds > LIMIT_S:
                faults.append(f"{seconds:.1f} s > {LIMIT_S} s")
            if mb > LIMIT_MB:
                faults.append(f"{mb:.0f} MB > {LIMIT_MB} MB")
            if needle and needle not in err:
                faults.append(f"stderr lacks {needle!r}")
            if "panicked" in err:
                faults.append("panicked")
            if temporaries:
                faults.append(f"left {temporaries}")
            broken += bool(faults)
            mark = "BROKEN " + "; ".join(faults) if faults else "ok"
            print(f"{name:32} exit {rc:>3} {seconds:6.2f} s {mb:7.1f} MB  {mark}  | {last[:110]}")
    finally:
        shutil.rmtree(base, ignore_errors=True)
    print(f"{len(CASES)} cases, {broken} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
