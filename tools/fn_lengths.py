#!/usr/bin/env python3
"""Function lengths of Rust source files: median, 90th percentile, the longest.

A function's length is the number of lines from the line of its `fn` keyword to the line of its
closing brace, both included (a one-line function is 1). Functions inside `#[cfg(test)]` modules
are left out; trait method declarations without a body are not functions.

    python3 tools/fn_lengths.py crates/thermonav-cli/src            # summary and the 10 longest
    python3 tools/fn_lengths.py crates/thermonav-cli/src --max 60 --median 10   # exit 1 if over

The scan is lexical: strings, characters, lifetimes and comments are skipped so that braces in
them do not count.
"""

import argparse
import re
import statistics
import sys
from pathlib import Path

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def code_only(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        two = text[i : i + 2]
        if two == "//":
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif two == "/*":
            depth, j = 1, i + 2
            while j < n and depth:
                if text[j : j + 2] == "/*":
                    depth, j = depth + 1, j + 2
                elif text[j : j + 2] == "*/":
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:]) and (i == 0 or not text[i - 1].isalnum()):
            hashes = re.match(r"r(#*)\"", text[i:]).group(1)
            end = text.find('"' + hashes, i + 2 + len(hashes))
            j = n if end < 0 else end + 1 + len(hashes)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(re.sub(r"[^\n]", " ", text[i : j + 1]))
            i = j + 1
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:  # a lifetime
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def test_module_spans(code):
    """Character spans of `#[cfg(test)] mod NAME { ... }` blocks."""
    spans = []
    for m in re.finditer(r"#\[cfg\(test\)\]\s*(pub\s+)?mod\s+\w+\s*\{", code):
        end = matching_brace(code, m.end() - 1)
        spans.append((m.start(), end))
    return spans


def matching_brace(code, open_at):
    depth = 0
    for j in range(open_at, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def functions(path):
    """(name, first line, length in lines) of every function with a body in one file."""
    code = code_only(path.read_text(encoding="utf-8"))
    skip = test_module_spans(code)
    found = []
    for m in FN.finditer(code):
        if any(a <= m.start() <= b for a, b in skip):
            continue
        j, depth = m.end(), 0
        # The body starts at the first `{` outside parentheses, brackets and generics' depth;
        # a `;` first means a declaration without a body.
        while j < len(code):
            ch = code[j]
            if ch in "([":
                depth += 1
            elif ch in ")]":
                depth -= 1
            elif depth == 0 and ch == ";":
                j = -1
                break
            elif depth == 0 and ch == "{":
                break
            j += 1
        if j < 0 or j >= len(code):
            continue
        end = matching_brace(code, j)
        first = code.count("\n", 0, m.start()) + 1
        last = code.count("\n", 0, end) + 1
        found.append((m.group(1), first, last - first + 1))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("roots", nargs="+", type=Path)
    parser.add_argument("--max", type=int, help="fail if any function is longer")
    parser.add_argument("--median", type=float, help="fail if the median is longer")
    parser.add_argument("--top", type=int, default=10, help="how many of the longest to list")
    args = parser.parse_args()
    rows = []
    for root in args.roots:
        files = [root] if root.is_file() else sorted(root.rglob("*.rs"))
        for f in files:
            rows += [(length, f"{f}:{line}", name) for name, line, length in functions(f)]
    if not rows:
        print("no functions found", file=sys.stderr)
        return 1
    lengths = sorted(r[0] for r in rows)
    median = statistics.median(lengths)
    p90 = lengths[int(0.9 * (len(lengths) - 1))]
    print(f"functions: {len(rows)}  median: {median:g} lines  p90: {p90} lines  longest: {lengths[-1]} lines")
    for length, place, name in sorted(rows, reverse=True)[: args.top]:
        print(f"{length:5d}  {name}  {place}")
    failed = False
    if args.max is not None and lengths[-1] > args.max:
        print(f"over the limit: a function of {lengths[-1]} lines (limit {args.max})")
        failed = True
    if args.median is not None and median > args.median:
        print(f"over the limit: median {median:g} lines (limit {args.median:g})")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
