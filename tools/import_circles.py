#!/usr/bin/env python3
"""Import circles between the source files (and the top-level modules) of each crate.

    python3 tools/import_circles.py            # every crate; exit 1 on any circle or breach
    python3 tools/import_circles.py --edges    # also list every file -> file edge
    python3 tools/import_circles.py --strict   # also count a parent's bare `child::f()` paths

A crate is each `crates/*/src` and `python/src`; its root is `lib.rs` or `main.rs`, and its module
tree is read from `mod NAME;` declarations (`NAME.rs` or `NAME/mod.rs`, or a `#[path]`) and inline
`mod NAME { ... }` blocks.

The rule, as a file -> file graph:
- An edge `a.rs -> b.rs` is a name that `a.rs` takes from `b.rs` by a crate-internal path: a `use`
  item starting with `crate::`, `super::`, `self::` or a child module's name (groups
  `use crate::a::{b, c::d}` over several lines included), or a `crate::` / `super::` / `self::`
  path written inline in code (`crate::x::y(`, `impl From<super::Name>`).
- A path resolves along the module tree to the deepest module it names (`foo.rs` or
  `foo/mod.rs`); the next segment is the name taken. If that module defines the name, the edge
  goes to its file. If the module only imports it (a `use`, a `pub use` or a glob), the path is
  followed through that import to the file that defines the name: importing through a facade
  `mod.rs` ties the importer to the defining file, not to the facade. A name found nowhere (a
  macro, say) ties to the deepest module's file.
- No edge: a file to itself; `mod` declarations; a facade re-export, i.e. a `pub use` (any `pub`
  visibility) in a module of a name from one of its own descendants that the module's file does
  not use itself. A re-export of anything else (a sibling's or another module's item) is an
  edge: it ties the two files as any import does, so a `pub use` kept for an old path does not
  hide a circle. A parent that `use`s its child's items for its own code has an edge to the
  child: a child importing its parent's items while the parent uses the child's is a circle.
- A parent's bare `child::f()` paths in code (not in a `use`) are the parent driving the child
  modules it declares, like the `mod` line: no edge unless `--strict`. (With `--strict` the
  dispatchers whose children take shared items from the parent show up: the AR methods, the ROS
  bag formats, the noise-export formats, `convert`'s log formats and the Python module's
  registration.)
- Test code does not count: `#[cfg(test)]` modules (inline or in their own file) and items
  under `#[cfg(test)]` are skipped.

The module-level graph has each crate's top-level modules (`src/<module>.rs` or `src/<module>/`)
as nodes; a file edge between files of two different top-level modules is a module edge (the
root file is not a node). A module circle whose modules are all single files is the file circle
already printed, and is not printed again. Some top-level modules are generic (`GENERIC`): the
library's `filter` may take from no module of the crate but `statistics`, and `optimise` from none.

Circles are the strongly connected components (Tarjan) of more than one node, printed with the
names behind each edge inside them. Compared with `farm-studio look` on 2c6e0d4, which reports
5 file circles (html_report/html_temperature, integration/integration_stream,
candidates/tournament, experiment/outside/report/shard, engine/gaussian_sum): this tool finds
those 5 with the same names, and 4 more that it sees because it follows re-exports and inline
paths: stoch/allan's kind.rs <-> mod.rs (`impl From<super::AllanCurve>`) and
family.rs <-> hadamard/modified/total.rs (family imports them through the `allan` facade),
nav/run.rs <-> nav/report.rs (run.rs's `pub use super::report::RunReport`), and
noise_export/mod.rs <-> selection.rs (mod.rs uses the selection types it re-exports). The scan
is lexical: comments, strings and char literals are blanked first.
"""

import argparse
import bisect
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
ITEM = re.compile(
    r"\b(?:fn|struct|enum|trait|type|const|static|union|mod)\s+(" + IDENT + r")|\bmacro_rules!\s*(" + IDENT + r")"
)
MOD = re.compile(r"\bmod\s+(" + IDENT + r")\s*([;{])")
USE = re.compile(r"(?<![\w:])(pub\s*(?:\([^)]*\))?\s*)?use\s+([^;]*);")
INLINE_PATH = re.compile(r"(?<![\w:])((?:crate|super|self)(?:\s*::\s*" + IDENT + r")+)")
RELATIVE_PATH = re.compile(r"(?<![\w:])(" + IDENT + r"(?:\s*::\s*" + IDENT + r")+)")
KEYWORDS = {"crate", "super", "self", "Self"}

# Top-level modules of a crate that may take nothing from the rest of the crate but the
# modules listed: the generic filter knows no domain (no IMU, no bank, no production lot), and
# the general optimisers know nothing of what they optimise.
GENERIC = {"crates/thermonav/src": {"filter": {"statistics"}, "optimise": set()}}


def code_only(text):
    """The text with comments, strings and char literals blanked (newlines and offsets kept)."""
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
        elif c in "rb" and re.match(r'b?r#*"', text[i:]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'b?r(#*)"', text[i:])
            hashes = m.group(1)
            end = text.find('"' + hashes, i + len(m.group(0)))
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


def attributes_before(code, at):
    """The text of the attributes (`#[...]`) directly before position `at`."""
    j = at
    found = []
    while True:
        k = j
        while k > 0 and code[k - 1].isspace():
            k -= 1
        if k > 0 and code[k - 1] == "]":
            depth, m = 0, k - 1
            while m >= 0:
                if code[m] == "]":
                    depth += 1
                elif code[m] == "[":
                    depth -= 1
                    if depth == 0:
                        break
                m -= 1
            if m > 0 and code[m - 1] == "#":
                found.append(code[m - 1 : k])
                j = m - 1
                continue
        return " ".join(found)


def is_test_only(code, at):
    attrs = attributes_before(code, at)
    return re.search(r"#\[\s*cfg\s*\([^\]]*\btest\b", attrs) is not None


def item_start(code, at):
    """The start of the item whose keyword is at `at`, before a visibility such as `pub(crate)`."""
    m = re.search(r"(pub\s*(\([^)]*\))?\s*)$", code[max(0, at - 40) : at])
    return at - len(m.group(1)) if m else at


def parse_use_tree(text):
    """Leaves of a use tree: (segments, alias); a glob leaf ends in '*', `self` in a group is its parent."""
    tokens = re.findall(IDENT + r"|::|[{},*]", text)
    pos = 0

    def tree(prefix):
        nonlocal pos
        segments = list(prefix)
        leaves = []
        while pos < len(tokens):
            tok = tokens[pos]
            if tok == "::":
                pos += 1
            elif tok == "{":
                pos += 1
                while pos < len(tokens) and tokens[pos] != "}":
                    if tokens[pos] == ",":
                        pos += 1
                        continue
                    leaves += tree(segments)
                pos += 1
                return leaves
            elif tok == "*":
                pos += 1
                return [(segments + ["*"], None)]
            elif tok in (",", "}"):
                break
            elif tok == "as":
                pos += 1
                alias = tokens[pos] if pos < len(tokens) else None
                pos += 1
                return [(drop_self(segments), alias)]
            else:
                segments.append(tok)
                pos += 1
        return leaves or [(drop_self(segments), None)]

    return tree([]) if tokens else []


def drop_self(segments):
    if len(segments) > 1 and segments[-1] == "self":
        return segments[:-1]
    return segments


class Module:
    def __init__(self, path, file, parent):
        self.path = path  # tuple of names from the crate root
        self.file = file
        self.parent = parent
        self.children = {}  # name -> Module
        self.defined = set()
        self.imports = {}  # name -> segments of the path it is imported by
        self.globs = []  # segments of `use x::*`
        self.test = False


class Crate:
    def __init__(self, src, strict=False):
        self.src = src
        self.strict = strict
        root_file = src / "lib.rs" if (src / "lib.rs").exists() else src / "main.rs"
        self.root = Module((), root_file, None)
        self.modules = {(): self.root}
        self.uses = []  # (module, segments, alias, is pub, file, position)
        self.inline = []  # (module, segments, file, position)
        self.codes = {}
        self.read(self.root, root_file, is_mod_rs=True)

    # Reading the module tree ------------------------------------------------------------------

    def read(self, module, file, is_mod_rs):
        text = file.read_text(encoding="utf-8")
        code = code_only(text)
        self.codes[file] = code
        blocks = self.inline_modules(module, file, code)
        braces = [(m.start(), 1 if m.group() == "{" else -1) for m in re.finditer(r"[{}]", code)]
        positions = [p for p, _ in braces]
        depth_after = []
        d = 0
        for _, step in braces:
            d += step
            depth_after.append(d)

        def depth_at(pos):
            k = bisect.bisect_left(positions, pos)
            return depth_after[k - 1] if k else 0

        def owner(pos):
            """The innermost module at `pos`, its brace depth, and whether it is test code."""
            best = (module, 0, False)
            for start, end, mod, depth, test in blocks:
                if start < pos < end and depth >= best[1]:
                    best = (mod, depth, test or best[2])
            return best

        for m in ITEM.finditer(code):
            mod, depth, test = owner(m.start())
            if not test and depth_at(m.start()) == depth:
                mod.defined.add(m.group(1) or m.group(2))
        for m in MOD.finditer(code):
            if m.group(2) != ";":
                continue
            mod, depth, test = owner(m.start())
            if test or is_test_only(code, item_start(code, m.start())):
                continue
            self.child_file(mod, m.group(1), file, code, m.start(), is_mod_rs)
        for m in USE.finditer(code):
            mod, _, test = owner(m.start())
            if test or is_test_only(code, m.start()):
                continue
            for segments, alias in parse_use_tree(m.group(2)):
                self.uses.append((mod, segments, alias, m.group(1) is not None, file, m.start()))
                self.note_import(mod, segments, alias)
        without_uses = USE.sub(lambda m: " " * len(m.group(0)), code)
        without_uses = re.sub(r"pub\s*\(\s*in\s+[^)]*\)", lambda m: " " * len(m.group(0)), without_uses)
        for m in INLINE_PATH.finditer(without_uses):
            mod, _, test = owner(m.start())
            if not test:
                self.inline.append((mod, re.split(r"\s*::\s*", m.group(1)), file, m.start()))
        for m in RELATIVE_PATH.finditer(without_uses) if self.strict else ():
            mod, _, test = owner(m.start())
            segments = re.split(r"\s*::\s*", m.group(1))
            if not test and segments[0] not in KEYWORDS:
                self.inline.append((mod, segments, file, m.start()))

    def inline_modules(self, module, file, code):
        """(start, end, Module, depth, is test) of each inline `mod NAME { ... }`, outermost first."""
        blocks = []
        for m in MOD.finditer(code):
            if m.group(2) != "{":
                continue
            open_at = m.end() - 1
            end = matching_brace(code, open_at)
            parent, depth, test = module, 0, False
            for start, stop, mod, d, t in blocks:
                if start < m.start() < stop and d >= depth:
                    parent, depth, test = mod, d, t
            child = Module(parent.path + (m.group(1),), file, parent)
            child.test = test or is_test_only(code, item_start(code, m.start()))
            parent.children[m.group(1)] = child
            self.modules[child.path] = child
            blocks.append((open_at, end, child, depth + 1, child.test))
        return blocks

    def child_file(self, parent, name, file, code, at, is_mod_rs):
        attrs = attributes_before(code, item_start(code, at))
        explicit = re.search(r'#\[\s*path\s*=\s*"([^"]*)"', attrs)
        base = file.parent if is_mod_rs else file.parent / file.stem
        for inline in parent.path[len(self.file_module(file)) :]:
            base = base / inline
        candidates = [file.parent / explicit.group(1)] if explicit else [base / f"{name}.rs", base / name / "mod.rs"]
        for child_file in candidates:
            if child_file.exists():
                child = Module(parent.path + (name,), child_file, parent)
                parent.children[name] = child
                self.modules[child.path] = child
                self.read(child, child_file, is_mod_rs=child_file.name == "mod.rs" or explicit is not None)
                return

    def file_module(self, file):
        for path, mod in self.modules.items():
            if mod.file == file and (mod.parent is None or mod.parent.file != file):
                return path
        return ()

    def note_import(self, module, segments, alias):
        if segments and segments[-1] == "*":
            module.globs.append(segments[:-1])
        elif segments:
            module.imports[alias or segments[-1]] = segments

    # Resolving paths --------------------------------------------------------------------------

    def start(self, module, segments):
        """The module a path starts from and the rest of the path; None for an outside path."""
        if not segments:
            return None
        head, rest = segments[0], segments[1:]
        if head == "crate":
            cur = self.root
        elif head == "self":
            cur = module
        elif head == "super":
            cur = module.parent
            while rest and rest[0] == "super" and cur is not None:
                cur, rest = cur.parent, rest[1:]
        elif head in module.children:
            cur, rest = module.children[head], rest
        else:
            return None
        return (cur, rest) if cur is not None else None

    def resolve(self, module, segments, seen=None):
        """(defining Module, name) of a path, following imports; None if outside the crate."""
        started = self.start(module, segments)
        if started is None:
            return None
        cur, rest = started
        while rest and rest[0] in cur.children:
            cur, rest = cur.children[rest[0]], rest[1:]
        if not rest or rest[0] == "*":
            return cur, None
        return self.find(cur, rest[0], seen or set())

    def find(self, module, name, seen):
        """Where `name`, as seen in `module`, is defined."""
        if (module.path, name) in seen:
            return module, name
        seen.add((module.path, name))
        if name in module.defined:
            return module, name
        if name in module.imports:
            found = self.resolve(module, module.imports[name], seen)
            if found is not None:
                return found
        for glob in module.globs:
            started = self.resolve(module, glob + ["*"])
            if started is not None and started[1] is None:
                inner = self.find(started[0], name, seen)
                if inner[1] is not None and (name in inner[0].defined):
                    return inner
        return module, name

    def is_descendant(self, module, ancestor):
        return len(module.path) > len(ancestor.path) and module.path[: len(ancestor.path)] == ancestor.path

    def edges(self):
        """{(file a, file b): set of names} of the crate."""
        found = defaultdict(set)
        for module, segments, alias, is_pub, file, at in self.uses:
            if segments and segments[-1] == "*":
                target = self.resolve(module, segments)
                if target is not None:
                    self.add(found, file, target[0].file, "*")
                continue
            target = self.resolve(module, segments)
            if target is None:
                continue
            if is_pub and self.is_facade(module, segments, alias, file, at):
                continue
            self.add(found, file, target[0].file, target[1] or segments[-1])
        for module, segments, file, _ in self.inline:
            target = self.resolve(module, segments)
            if target is not None:
                self.add(found, file, target[0].file, target[1] or segments[-1])
        return found

    def is_facade(self, module, segments, alias, file, at):
        """A `pub use` of a descendant's name that the file does not use itself."""
        started = self.start(module, segments)
        if started is None:
            return False
        cur, rest = started
        while rest and rest[0] in cur.children:
            cur, rest = cur.children[rest[0]], rest[1:]
        if not self.is_descendant(cur, module):
            return False
        name = alias or segments[-1]
        code = USE.sub(lambda m: " " * len(m.group(0)), self.codes[file])
        code = MOD.sub(lambda m: " " * len(m.group(0)), code)
        # A child module of the same name (`mod deviation;` beside `pub use family::deviation`)
        # is another thing: its `deviation::` paths are not uses of the name.
        after = r"(?!\s*::)" if name in module.children else ""
        # Nor are fields (`deviation: curve.adev`, `self.deviation`) and methods of that name.
        field = r"(?!\s*:(?!:))"
        return re.search(r"(?<![\w:.])" + re.escape(name) + r"\b" + after + field, code) is None

    def add(self, found, a, b, name):
        if a != b:
            found[(a, b)].add(name)

    def top_module(self, file):
        rel = file.relative_to(self.src)
        if len(rel.parts) == 1:
            return None if file == self.root.file else rel.stem
        return rel.parts[0]


def strongly_connected(nodes, succ):
    """Tarjan's strongly connected components (iterative)."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(sorted(succ.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(succ.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                out.append(sorted(component))
    return out


def names(found):
    return ", ".join(sorted(found, key=lambda s: (s.lower(), s)))


def crates(strict):
    srcs = sorted(p for p in (ROOT / "crates").glob("*/src") if (p / "lib.rs").exists() or (p / "main.rs").exists())
    if (ROOT / "python" / "src" / "lib.rs").exists():
        srcs.append(ROOT / "python" / "src")
    return [Crate(src, strict) for src in srcs]


def rel(path):
    return path.relative_to(ROOT).as_posix()


def circles(edges, label, first, skip=lambda component: False):
    """Prints the circles of one graph {(a, b): names} but those `skip` drops; returns how many."""
    succ = defaultdict(set)
    for a, b in edges:
        succ[a].add(b)
    found = 0
    for component in strongly_connected(sorted(succ), succ):
        if len(component) < 2 or skip(component):
            continue
        found += 1
        kind = "files" if label == "circle" else "modules"
        print(f"{label} {first + found}: {len(component)} {kind}: {', '.join(component)}")
        for a in component:
            for b in component:
                if (a, b) in edges:
                    print(f"  {a} -> {b}: {edges[(a, b)]}")
    return found


def file_graph(crate, edges):
    return {(rel(a), rel(b)): names(found) for (a, b), found in edges.items()}


def module_graph(crate, edges):
    """Edges between top-level modules, each naming the file edges behind it."""
    behind = defaultdict(list)
    for (a, b), found in sorted(edges.items()):
        ma, mb = crate.top_module(a), crate.top_module(b)
        if ma and mb and ma != mb:
            behind[(ma, mb)].append(f"{rel(a)} -> {rel(b)} ({names(found)})")
    return {pair: "; ".join(files) for pair, files in behind.items()}


def generic_breaches(crate, edges):
    """File edges out of a module that may only take from the modules GENERIC lists."""
    rules = GENERIC.get(rel(crate.src), {})
    out = []
    for (a, b), found in sorted(edges.items()):
        ma, mb = crate.top_module(a), crate.top_module(b)
        if ma in rules and mb != ma and mb not in rules[ma]:
            out.append(f"  {rel(a)} -> {rel(b)}: {names(found)} (`{ma}` may take only from "
                       f"{', '.join(f'`{m}`' for m in sorted(rules[ma])) or 'itself'})")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edges", action="store_true", help="also list every file -> file edge")
    parser.add_argument(
        "--strict",
        action="store_true",
        help="also count a module's bare `child::name` paths in code to its own child modules",
    )
    args = parser.parse_args()
    file_circles = module_circles = breaches = files = edge_count = 0
    for crate in crates(args.strict):
        edges = crate.edges()
        edge_count += len(edges)
        files += len({m.file for m in crate.modules.values()})
        graph = file_graph(crate, edges)
        if args.edges:
            for (a, b), found in sorted(graph.items()):
                print(f"edge {a} -> {b}: {found}")
        file_circles += circles(graph, "circle", file_circles)
        modules = module_graph(crate, edges)
        # A circle of top-level modules that are single files is already a file circle.
        single = {m.path[0] for m in crate.modules.values() if len(m.path) == 1 and not m.children}
        prefix = f"module circle ({rel(crate.src)})"
        module_circles += circles(modules, prefix, module_circles, lambda c: set(c) <= single)
        wrong = generic_breaches(crate, edges)
        if wrong:
            print(f"a generic module takes from the domain ({rel(crate.src)}):")
            print("\n".join(wrong))
            breaches += len(wrong)
    print(
        f"import circles: {file_circles} between files, {module_circles} between top-level modules, "
        f"{breaches} generic-module breaches ({files} files, {edge_count} file -> file edges)"
    )
    return 1 if file_circles or module_circles or breaches else 0


if __name__ == "__main__":
    sys.exit(main())
