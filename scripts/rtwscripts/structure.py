"""Three structural rules for the library crates (docs/architecture.md):

1. No source file has more than 600 lines outside its `#[cfg(test)]` module
   (files that are wholly tests, declared under a `#[cfg(test)] mod`, are
   exempt).
2. No file imports a file that imports it back, test modules included.
3. Imports go down the layers: outside its tests, a file of a top-level
   module imports only from its own module or from one in a layer above
   (`LAYERS`: rank 0 is the top). Items defined in the crate root (`lib.rs`,
   such as the fault-injection hook) may be used everywhere.

An import is any path `crate::…` or `super::…` in code (a `use` or an
inline path; comments and doc links are not imports). A path is resolved to
the file that defines the item: through `pub use` re-exports of a `lib.rs`
or `mod.rs` (a façade naming its children's items is not a dependency), to
the longest module prefix that is a file. `mod child;` declarations are not
imports. Cycles are strongly connected components of the file graph.

`scripts/check_structure.py` runs these checks; `scripts/code_counts.py`
counts with them.
"""

import os
import re
import sys

MAX_LINES = 600

# Each crate's top-level modules by layer (docs/architecture.md, "The
# layers"): a module may import from its own layer or a lower rank. A
# module missing here is reported, so a new one must be placed.
LAYERS = {
    "hybrid-ode": [
        {"tableau", "dense"},
        {"system"},
        {"events", "integrate", "kernels"},
        {"engine"},
        {"variational", "nonsmooth", "limit"},
        {"continuation"},
        {"metastable", "logistic"},
        {"splitting", "chain"},
        {"rimless", "counting"},
    ],
    "rtw-model": [
        {"cancel", "params"},
        {"options"},
        {"outcome"},
        {"plant"},
        {"cycles", "modal"},
        {"run"},
    ],
    "rtw-engine": [
        {"hash", "files", "sizes"},
        {"sampling"},
        {"config"},
        {"io"},
        {"scan"},
        {"analysis"},
        {"entry", "fake"},
    ],
    "rtw-studies": [
        {"bifurcation", "continuation", "refine", "sensitivity"},
        {"basin", "profile"},
        {"search"},
        {"dictionary"},
    ],
    # The command line: the parsers of flag values and the terminal first,
    # then the subcommands (a subcommand borrows another's flags: `basin`
    # and `continuation` take `bifurcation`'s, `design` and `profile`
    # `simulate`'s).
    "rtw-scan": [
        {"values", "signal", "progress"},
        {"validate"},
        {"simulate", "bifurcation"},
        {"analysis", "basin", "continuation", "design", "profile", "refine", "run", "sensitivity"},
    ],
}
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def module_files(src):
    """Module path (tuple) -> file, for every file under src/."""
    out = {}
    for dirpath, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(dirpath, f), src)
            parts = rel[:-3].split(os.sep)
            if parts == ["lib"] or parts == ["main"]:
                mod = ()
            elif parts[-1] == "mod":
                mod = tuple(parts[:-1])
            else:
                mod = tuple(parts)
            out[mod] = os.path.join(dirpath, f)
    return out


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return "\n".join(re.sub(r"//.*$", "", line) for line in text.split("\n"))


def test_block_spans(text):
    """Line spans (start, end) of `#[cfg(test)] mod name { … }` blocks."""
    spans = []
    for m in re.finditer(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{", text):
        depth, i = 0, m.end() - 1
        while i < len(text):
            if text[i] == "{":
                depth += 1
            elif text[i] == "}":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        spans.append((text.count("\n", 0, m.start()), text.count("\n", 0, i)))
    return spans


def test_modules(files):
    """Module paths declared as `#[cfg(test)] mod x;` (whole files of tests)."""
    out = set()
    for mod, path in files.items():
        text = open(path, encoding="utf-8").read()
        for m in re.finditer(r"#\[cfg\(test\)\]\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;", text):
            out.add(mod + (m.group(1),))
    return out


def expand(prefix, body):
    """`a::{b::C, d}` -> [a::b::C, a::d] (nested groups too)."""
    body = body.strip()
    if body.startswith("{") and body.endswith("}"):
        inner, depth, cur, out = body[1:-1], 0, "", []
        for ch in inner:
            if ch == "," and depth == 0:
                out.append(cur)
                cur = ""
                continue
            depth += ch == "{"
            depth -= ch == "}"
            cur += ch
        out.append(cur)
        res = []
        for part in out:
            if part.strip():
                res += expand(prefix, part)
        return res
    m = re.match(r"^(" + IDENT + r")\s*::\s*(.*)$", body, re.S)
    if m:
        return expand(prefix + [m.group(1)], m.group(2))
    name = re.split(r"\s+as\s+", body)[0].strip()
    return [prefix + [name]] if name else [prefix]


def reexports(text):
    """Names a façade re-exports from its children: name -> path list."""
    out = {}
    for m in re.finditer(r"\bpub(?:\([^)]*\))?\s+use\s+([^;]+);", text):
        for path in expand([], m.group(1)):
            if path and path[0] not in ("crate", "super", "self") and path[0][0].islower():
                out[path[-1]] = path
            elif path and path[0] == "crate":
                out[path[-1]] = path
    return out


def resolve(path, here, files, facades):
    """File that defines what `path` (absolute module path list) names."""
    for _ in range(8):
        # Longest prefix that is a module with a file.
        k = len(path)
        while k > 0 and tuple(path[:k]) not in files:
            k -= 1
        mod = tuple(path[:k])
        rest = path[k:]
        if rest and rest[0] in facades.get(mod, {}):
            target = facades[mod][rest[0]]
            if target[0] == "crate":
                path = target[1:] + rest[1:]
            else:
                path = list(mod) + target + rest[1:]
            continue
        return files[mod]
    return files[mod]


def import_paths(code):
    """Every `crate::…` or `super::…` path of some code, as a list of parts."""
    paths = []
    for m in re.finditer(r"\buse\s+((?:crate|super)\b[^;]*);", code):
        paths += expand([], m.group(1))
    for m in re.finditer(r"(?<![\w:])((?:crate|super)(?:\s*::\s*" + IDENT + r")+)", code):
        paths.append([p.strip() for p in m.group(1).split("::")])
    return paths


def check(crate):
    src = os.path.join(crate, "src")
    files = module_files(src)
    tests = test_modules(files)
    facades = {}
    for mod, path in files.items():
        facades[mod] = reexports(strip_comments(open(path, encoding="utf-8").read()))
    bad = []
    edges = {f: set() for f in files.values()}
    layers = LAYERS.get(os.path.basename(os.path.normpath(crate)))
    rank = {m: i for i, group in enumerate(layers or []) for m in group}
    where = {f: m for m, f in files.items()}
    against = []
    for mod, path in files.items():
        raw = open(path, encoding="utf-8").read()
        is_test = any(mod[: len(t)] == t for t in tests)
        lines = raw.count("\n")
        if not is_test:
            outside = lines - sum(b - a + 1 for a, b in test_block_spans(raw))
            if outside > MAX_LINES:
                bad.append(f"{path}: {outside} lines outside its tests (max {MAX_LINES})")
        code = strip_comments(raw)
        # The same file without its inline test modules: tests may import
        # across layers, the library may not.
        lines_of = raw.split("\n")
        for a, b in test_block_spans(raw):
            for i in range(a, b + 1):
                lines_of[i] = ""
        library_code = "" if is_test else strip_comments("\n".join(lines_of))
        # The module a `super::` in this file means: its parent (a file
        # `x.rs` or `x/mod.rs` is module x; its parent is one up).
        for p, in_library in [(p, False) for p in import_paths(code)] + [(p, True) for p in import_paths(library_code)]:
            if p[0] == "crate":
                absolute = p[1:]
            else:
                base = list(mod)
                while p and p[0] == "super":
                    base = base[:-1]
                    p = p[1:]
                absolute = base + p
            if any(not re.fullmatch(IDENT, s) for s in absolute):
                continue
            target = resolve(absolute, mod, files, facades)
            if not in_library:
                if target != path:
                    edges[path].add(target)
                continue
            there = where[target]
            if layers is None or not mod or not there or mod[0] == there[0]:
                continue
            for m in (mod[0], there[0]):
                if m not in rank:
                    bad.append(f"{crate}: module {m} has no layer in LAYERS (scripts/check_structure.py)")
                    rank[m] = -1
            if rank[there[0]] > rank[mod[0]]:
                against.append(f"{path} imports from {target} ({there[0]} is below {mod[0]})")
    # Strongly connected components (Tarjan).
    index, low, stack, on, sccs = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                sccs.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in edges:
        if v not in index:
            visit(v)
    for comp in sccs:
        bad.append("import cycle: " + " <-> ".join(comp))
    against = sorted(set(against))
    bad += ["import against the layers: " + a for a in against]
    n_edges = sum(len(e) for e in edges.values())
    print(f"{crate}: {len(files)} files, {n_edges} import edges, "
          f"{len(sccs)} cycles, {len(against)} imports against the layers, "
          f"{sum(1 for b in bad if 'lines outside' in b)} files over {MAX_LINES} lines")
    return bad


def default_crates() -> list[str]:
    """Every crate of the workspace (a directory under crates/ with a src/),
    relative to the current directory."""
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "crates")
    return sorted(os.path.relpath(os.path.join(root, d)) for d in os.listdir(root)
                  if os.path.isdir(os.path.join(root, d, "src")))


def main():
    crates = sys.argv[1:] or default_crates()
    bad = []
    for c in crates:
        bad += check(c)
    for b in bad:
        print("  " + b)
    sys.exit(1 if bad else 0)
