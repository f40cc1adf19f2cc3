"""Shared fixtures: the repository, its release binary, the shared data and generated series."""

import gzip
import os
import sys
from pathlib import Path

# `python -m pytest` run from inside python/ puts that folder first on sys.path, where the
# package's sources lie without their compiled `_native` module, so `import thermonav` would
# fail there: the tests take the installed package (`pip install ./python`) wherever they are
# run from.
_SOURCES = Path(__file__).resolve().parents[1]
sys.path[:] = [p for p in sys.path if Path(p or os.curdir).resolve() != _SOURCES]

import numpy as np  # noqa: E402
import pytest  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("THERMONAV_SHARED", REPO.parent / "shared" / "data"))
BINARY = Path(os.environ.get("THERMONAV_BIN", REPO / "target" / "release" / "thermonav"))

# Rows of the static ADIS16405 run 1 used (100 Hz): 1000 s, enough for curves to 250 s.
ADIS_ROWS = 100_000


@pytest.fixture(scope="session")
def shared() -> Path:
    if not SHARED.is_dir():
        pytest.skip(f"{SHARED} is missing (the shared data folder beside the repository)")
    return SHARED


@pytest.fixture(scope="session")
def binary() -> Path:
    if not BINARY.is_file():
        pytest.skip(f"{BINARY} is missing: run `cargo build --release` first")
    return BINARY


@pytest.fixture(scope="session")
def adis(shared) -> dict[str, np.ndarray]:
    """The first 1000 s of the static ADIS16405 run 1, in deg/s and g, by column name."""
    path = shared / "smac-imudata" / "adis_16405_imu1.csv.gz"
    with gzip.open(path, "rt") as f:
        names = f.readline().strip().split(",")
        values = np.loadtxt(f, delimiter=",", max_rows=ADIS_ROWS)
    return {name: np.ascontiguousarray(values[:, k]) for k, name in enumerate(names)}


@pytest.fixture(scope="session")
def generated() -> np.ndarray:
    """White noise plus a slow random walk and a first-order Gauss-Markov part (seeded)."""
    rng = np.random.default_rng(2009)
    n = 40_001
    white = rng.standard_normal(n)
    walk = np.cumsum(rng.standard_normal(n)) * 2e-3
    gm = np.zeros(n)
    phi = np.exp(-1.0 / 500.0)
    drive = rng.standard_normal(n) * 0.5 * np.sqrt(1 - phi**2)
    for k in range(1, n):
        gm[k] = phi * gm[k - 1] + drive[k]
    return white + walk + gm
