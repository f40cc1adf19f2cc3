#!/usr/bin/env python3
"""ARCHITECTURE.md names every Rust module of 150 lines or more.

    python3 tools/architecture_check.py [--min-lines 150] [--map ARCHITECTURE.md]

The rule:
- The crates are every `crates/NAME/src` and `python/src`. A crate's section of the map is the
  Markdown heading (any level) whose text holds the crate's folder in backticks
  (`crates/thermonav-io` or `python/`), down to the next heading of the same or a higher level.
- Every `.rs` file under a crate's `src` with at least --min-lines lines must be named in its
  crate's section by its path relative to that `src`: `stoch/gmwm/fit.rs`, or the same without
  `.rs` (`stoch/gmwm/fit`), or by a folder that holds it written with its trailing slash
  (`stoch/gmwm/`), meaning every file under that folder is described there.
- A path counts only as a whole word: not preceded by a letter, digit, `_`, `-`, `/` or `.`, and
  not followed by a letter, digit, `_`, `-`, `/` or `.` (so `nav/run.rs` is not found inside
  `evaluation/nav/run.rs`, nor `stoch/bank` inside `stoch/bank_values.rs`).

Each file missing is printed with its line count; the exit code is 1 if any is missing.
"""

import argparse
import re
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
HEADING = re.compile(r"^(#+)\s+(.*)$")


def crates():
    """(folder as the map names it, src path) of every crate."""
    out = [(f"crates/{src.parent.name}", src) for src in sorted((REPO / "crates").glob("*/src"))]
    if (REPO / "python" / "src").is_dir():
        out.append(("python/", REPO / "python" / "src"))
    return out


def sections(text):
    """(level, heading, body) of every heading of the map, fenced blocks left as they are."""
    out, fence = [], False
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("```"):
            fence = not fence
        m = None if fence else HEADING.match(line)
        if m:
            out.append((len(m.group(1)), m.group(2), i))
    result = []
    for k, (level, heading, start) in enumerate(out):
        end = next((s for lv, _, s in out[k + 1:] if lv <= level), len(lines))
        result.append((level, heading, "\n".join(lines[start + 1:end])))
    return result


def section_of(folder, all_sections):
    """The text of the section whose heading names `folder` in backticks, or None."""
    name = re.escape(folder.rstrip("/"))
    pattern = re.compile(r"`" + name + r"/?`")
    bodies = [body for _, heading, body in all_sections if pattern.search(heading)]
    return "\n".join(bodies) if bodies else None


def named(path, text):
    """Whether `path` appears in `text` as a whole word (see the rule above)."""
    return re.search(r"(?<![\w/.\-])" + re.escape(path) + r"(?![\w/.\-])", text) is not None


def is_described(relative, text):
    if named(relative, text) or named(relative[: -len(".rs")], text):
        return True
    parts = relative.split("/")[:-1]
    return any(named("/".join(parts[: i + 1]) + "/", text) for i in range(len(parts)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--min-lines", type=int, default=150)
    parser.add_argument("--map", default=str(REPO / "ARCHITECTURE.md"))
    args = parser.parse_args()
    all_sections = sections(Path(args.map).read_text(encoding="utf-8"))
    missing, checked = [], 0
    for folder, src in crates():
        text = section_of(folder, all_sections)
        for path in sorted(src.rglob("*.rs")):
            with open(path, encoding="utf-8") as f:
                count = sum(1 for _ in f)
            if count < args.min_lines:
                continue
            checked += 1
            relative = path.relative_to(src).as_posix()
            if text is None:
                missing.append((folder, relative, count, f"no section whose heading names `{folder}`"))
            elif not is_described(relative, text):
                missing.append((folder, relative, count, "not named"))
    for folder, relative, count, why in missing:
        print(f"{folder.rstrip('/')}/src/{relative} ({count} lines): {why} in {Path(args.map).name}")
    print(f"{checked} modules of {args.min_lines} lines or more, {len(missing)} not in the map")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
