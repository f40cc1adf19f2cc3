#!/usr/bin/env python3
"""Check the thermonav commands written in the docs against the binary's argument parser.

    python3 tools/doc_commands.py target/release/thermonav README.md docs/*.md

What is checked. In every fenced code block (``` ... ```) of the given Markdown files, except
blocks tagged as another language (python, toml, json, yaml), every line that starts with
`thermonav `, `$ thermonav ` or `cargo run --release -- ` (after leading blanks, and after a
`/usr/bin/time -v ` or `time ` in front) is a command; a line ending in `\\` continues on the
next. A line may hold several commands separated by `;`, `&&` or a pipe ` | ` (a pipe inside
[...] or (...) is a synopsis's "or" and does not end the command); only the thermonav ones are
checked. For each:

- the words after `thermonav` that are not options name the subcommand path: the first must be
  one of `thermonav --help`'s commands, and each next word is taken as a sub-subcommand while
  the current command's `--help` lists it (`bank export`, `evaluate merge`, `simulate vessel`);
  a command whose usage requires a subcommand (`thermonav bank <COMMAND>`) without one fails;
- every long option `--name` or `--name=value` of the line (also inside a synopsis's
  `[--name X]`) must be listed by `thermonav <subcommand path> --help`.

Values and file arguments are not checked (`$(...)` and `...` are left out). Each failure is
printed as `FILE:LINE: ...`; the exit code is 1 on any failure, 0 otherwise.
"""

import functools
import re
import subprocess
import sys

OTHER_LANGUAGES = {"python", "py", "toml", "json", "yaml", "yml", "text-output"}
PREFIXES = ("$ thermonav ", "thermonav ", "cargo run --release -- ")
WRAPPERS = ("/usr/bin/time -v ", "time ")
OPTION = re.compile(r"(?<![\w-])--([a-z0-9][a-z0-9-]*)")
HELP_OPTION = re.compile(r"^\s+(?:-[A-Za-z0-9], )?--([a-z0-9][a-z0-9-]*)")


def commands_of(path):
    """(line number, text) of every thermonav command in the fenced blocks of `path`."""
    out, fence, language, pending, start = [], None, "", None, 0
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            stripped = line.strip()
            if stripped.startswith("```"):
                if fence is None:
                    fence, language = stripped[:3], stripped[3:].strip().lower()
                else:
                    fence, pending = None, None
                continue
            if fence is None or language in OTHER_LANGUAGES:
                continue
            if pending is not None:
                pending += " " + stripped.rstrip("\\")
                if not stripped.endswith("\\"):
                    out.append((start, pending))
                    pending = None
                continue
            text = stripped
            for wrapper in WRAPPERS:
                if text.startswith(wrapper):
                    text = text[len(wrapper):]
            if not text.startswith(PREFIXES):
                continue
            if text.endswith("\\"):
                pending, start = text.rstrip("\\"), number
            else:
                out.append((number, text))
    return out


def without_comment(text):
    """`text` without a trailing shell comment (` # ...` outside quotes)."""
    quote = None
    for i, c in enumerate(text):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or text[i - 1].isspace()):
            return text[:i]
    return text


def without_substitutions(text):
    """`text` with every `$(...)` (nested too) replaced by a placeholder word."""
    out, i = [], 0
    while i < len(text):
        if text.startswith("$(", i):
            depth, j = 1, i + 2
            while j < len(text) and depth:
                depth += {"(": 1, ")": -1}.get(text[j], 0)
                j += 1
            out.append("VALUE")
            i = j
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def pieces(text):
    """The shell commands of one line: split at `;`, `&&` and ` | ` outside [...] and (...)."""
    parts, depth, current, i = [], 0, [], 0
    while i < len(text):
        c = text[i]
        if c in "[(":
            depth += 1
        elif c in "])":
            depth = max(0, depth - 1)
        if depth == 0 and (c == ";" or text.startswith("&&", i) or text.startswith(" | ", i)):
            parts.append("".join(current))
            current = []
            i += 1 if c == ";" else 2
            continue
        current.append(c)
        i += 1
    parts.append("".join(current))
    return [p.strip() for p in parts if p.strip()]


class Parser:
    """The binary's `--help` pages, read once each."""

    def __init__(self, binary):
        self.binary = binary

    @functools.lru_cache(maxsize=None)
    def help(self, path):
        done = subprocess.run([self.binary, *path, "--help"], capture_output=True, text=True)
        return done.stdout if done.returncode == 0 else None

    def subcommands(self, path):
        page, names, inside = self.help(path) or "", set(), False
        for line in page.splitlines():
            if line.startswith("Commands:"):
                inside = True
                continue
            if inside:
                if not line.startswith("  "):
                    break
                word = line.split()[0]
                if word != "help":
                    names.add(word)
        return names

    def needs_subcommand(self, path):
        usage = [l for l in (self.help(path) or "").splitlines()
                 if l.startswith(("Usage:", "       thermonav"))]
        return bool(usage) and all("<COMMAND>" in l for l in usage)

    def options(self, path):
        return {m.group(1) for l in (self.help(path) or "").splitlines()
                if (m := HELP_OPTION.match(l))}


def check(parser, text):
    """The failures of one thermonav command line (without its prefix)."""
    words = [w.strip("[]()") for w in text.split()]
    path, rest = [], words
    for i, word in enumerate(words):
        known = parser.subcommands(tuple(path))
        if word.startswith("-") or word not in known:
            if not path and not word.startswith("-"):
                return [f"'{word}' is not a thermonav subcommand"]
            rest = words[i:]
            break
        path.append(word)
    else:
        rest = []
    name = " ".join(["thermonav", *path])
    if parser.help(tuple(path)) is None:
        return [f"'{name} --help' fails"]
    if parser.needs_subcommand(tuple(path)):
        return [f"'{name}' needs a subcommand ({', '.join(sorted(parser.subcommands(tuple(path))))})"]
    accepted = parser.options(tuple(path))
    failures = []
    for option in OPTION.findall(" ".join(rest)):
        if option not in accepted:
            failures.append(f"option --{option} not accepted by '{name}'")
    return failures


def main(argv):
    if len(argv) < 3:
        print(__doc__.split("\n\n")[0], file=sys.stderr)
        return 2
    parser, failures, checked = Parser(argv[1]), 0, 0
    if parser.help(()) is None:
        print(f"{argv[1]} --help fails", file=sys.stderr)
        return 2
    for path in argv[2:]:
        for number, line in commands_of(path):
            line = without_substitutions(without_comment(line))
            for piece in pieces(line):
                for prefix in PREFIXES:
                    if piece.startswith(prefix):
                        checked += 1
                        for failure in check(parser, piece[len(prefix):]):
                            print(f"{path}:{number}: {failure}")
                            failures += 1
                        break
    print(f"{checked} commands checked in {len(argv) - 2} files, {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
