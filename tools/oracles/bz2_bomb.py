#!/usr/bin/env python3
"""A bz2 stream of 1 GiB of zero bytes (785 bytes compressed), for the ROS 1 bag reader's
bounded-decompression test (crates/thermonav-io/tests/it/ros_bounds.rs): a bz2 chunk that
expands to 1 GiB must be refused after at most the bytes its record declares.

Generated ONCE with Python 3.11.7's bz2 module (level 9; about 8 s). Run from the repository
root: `python3 tools/oracles/bz2_bomb.py`. Output: crates/thermonav-io/tests/data/ros/zeros_1gib.bz2.
"""
import bz2
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "crates" / "thermonav-io" / "tests" / "data" / "ros" / "zeros_1gib.bz2"

compressor = bz2.BZ2Compressor(9)
parts = [compressor.compress(bytes(1 << 24)) for _ in range(64)]
parts.append(compressor.flush())
OUT.write_bytes(b"".join(parts))
print(OUT, OUT.stat().st_size, "bytes")
