"""The Python snippets of README.md and python/README.md, run as written on simulated files."""

import re
import subprocess
import sys

import pytest

from conftest import REPO


def python_blocks(path, after):
    """The ```python blocks of `path` after the heading `after`."""
    text = path.read_text(encoding="utf-8")
    return re.findall(r"```python\n(.*?)```", text[text.index(after):], flags=re.S)


@pytest.fixture(scope="module")
def chamber(binary, tmp_path_factory):
    """imu_0C.csv and imu_20C.csv, five minutes at 200 Hz each (the snippets' file names)."""
    out = tmp_path_factory.mktemp("readme")
    subprocess.run([str(binary), "simulate", "chamber", "--out", str(out), "--temperatures-c", "0,20",
                    "--duration-s", "300", "--rate-hz", "200", "--quiet"], check=True,
                   capture_output=True)
    return out


@pytest.mark.parametrize("readme, heading", [
    (REPO / "README.md", "## From Python"),
    (REPO / "python" / "README.md", "# thermonav for Python"),
])
def test_the_readme_snippet_runs_and_prints_the_curve_and_the_bank(readme, heading, chamber):
    blocks = python_blocks(readme, heading)
    assert blocks, f"{readme} has no python block after {heading!r}"
    done = subprocess.run([sys.executable, "-c", blocks[0]], cwd=chamber, capture_output=True,
                          text=True, check=True)
    assert "[" in done.stdout and "temperature_c" in done.stdout, done.stdout
