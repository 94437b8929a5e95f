#!/usr/bin/env python3
"""The driver's folders are its architecture, and dependencies run one way (driver/README.md, "The layers"):

    app -> calibrate -> stepping -> contact -> {fe, point} -> scene -> material -> io

A file may include its own folder's headers and those of folders below it, never one above it or beside it (fe and
point are siblings: neither includes the other); only material/ includes the UMAT's C header camclay9.h (the
material contract is the material's).

Files depend on one another without a cycle, within a folder as across folders: a file depends on each header it
includes, and a source file on each source file that defines a function it names (a function declared in some
third header, one that declares several files' functions, still makes its caller depend on its definer). A cycle
is reported with its files, the include or the function behind each edge, and the files of the whole tangle.

Prints every include against the layers and every cycle, and exits 1 if there is one, else says how many includes
and files it checked.

Usage: tools/check_includes.py [driver/src]
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LAYER = {"io": 0, "material": 1, "scene": 2, "fe": 3, "point": 3, "contact": 4, "stepping": 5, "calibrate": 6,
         "app": 7}
CHAIN = "app -> calibrate -> stepping -> contact -> {fe, point} -> scene -> material -> io"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# A function definition: at the start of a line, a type, the name, the parameters, a brace (group 1: static).
DEFINITION = re.compile(r"^(static\s+)?(?!typedef\b|extern\b|struct\b|enum\b|union\b)[A-Za-z_][\w \t*]*?\b([A-Za-z_]\w*)"
                        r"\s*\([^;{}]*\)\s*\{", re.M)
IDENTIFIER = re.compile(r"(?<!\.)(?<!->)\b[A-Za-z_]\w*\b")  # not a member
COMMENT_OR_STRING = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)


def code_of(text):
    """The text without comments and string literals (lines kept), so that only code names a function."""
    return COMMENT_OR_STRING.sub(lambda m: "\n" * m.group(0).count("\n") + " ", text)


def layer_check(src, rel):
    bad, n = [], 0
    for path in sorted(src.rglob("*.[ch]")):
        folder = path.parent.name
        if folder not in LAYER:
            bad.append(f"{rel(path)}: folder '{folder}' has no place in the layers")
            continue
        for target in INCLUDE.findall(path.read_text()):
            n += 1
            if target == "camclay9.h":
                if folder != "material":
                    bad.append(f"{rel(path)}: includes camclay9.h (only material/ may)")
                continue
            dest = (path.parent / target).resolve()
            if not dest.is_relative_to(src.resolve()):
                continue  # a system or library header
            to = dest.parent.name
            if to == folder:
                continue
            if to not in LAYER or LAYER[to] >= LAYER[folder]:
                bad.append(f"{rel(path)}: includes {target} ({folder} -> {to} runs against {CHAIN})")
    return bad, n


def file_graph(src):
    """{file: {file it depends on: why}}, files named folder/name.c or folder/name.h: a file depends on each header it
    includes, and a source on each source that defines a function it names."""
    root = src.resolve()
    files = sorted(p.resolve() for p in src.rglob("*.[ch]"))
    name = {p: p.relative_to(root).as_posix() for p in files}
    graph = {n: {} for n in name.values()}
    definer, code, own = {}, {}, {}
    for p in files:
        code[p] = code_of(p.read_text(errors="replace"))
        if p.suffix == ".c":
            own[p] = {f for _, f in DEFINITION.findall(code[p])}  # its own, static or not: a call to its own
            for static, f in DEFINITION.findall(code[p]):
                if not static:
                    definer.setdefault(f, p)
    for p in files:
        for target in INCLUDE.findall(p.read_text(errors="replace")):
            dest = (p.parent / target).resolve()
            if dest in name and dest != p:
                graph[name[p]].setdefault(name[dest], f"includes {target}")
        if p.suffix != ".c":
            continue  # a header's prototypes declare, they do not use
        for f in sorted(set(IDENTIFIER.findall(code[p])) & definer.keys() - own[p]):
            if definer[f] != p:
                graph[name[p]].setdefault(name[definer[f]], f"calls {f}")
    return graph


def cycles(graph):
    """Every strongly connected set of two or more files (Tarjan), each as its shortest cycle through the set's first
    file: a list of (file, next file, why)."""
    index, low, stack, on, sets = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v), on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            s = set()
            while True:
                w = stack.pop()
                on.discard(w), s.add(w)
                if w == v:
                    break
            if len(s) > 1:
                sets.append(s)

    sys.setrecursionlimit(max(1000, 4 * len(graph)))
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return [(s, shortest_cycle(graph, s)) for s in sorted(sets, key=min)]


def shortest_cycle(graph, members):
    """The shortest cycle through the set's first file, within the set (breadth first)."""
    start = min(members)
    came, frontier = {start: None}, [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(graph[v]):
                if w == start:
                    path = [v]
                    while came[path[-1]] is not None:
                        path.append(came[path[-1]])
                    path.reverse()
                    return [(a, b, graph[a][b]) for a, b in zip(path, path[1:] + [start])]
                if w in members and w not in came:
                    came[w] = v
                    nxt.append(w)
        frontier = nxt
    return []


def check(src):
    """(lines against the layers, includes checked, cycles, files checked)."""
    def rel(path):  # as the user would write it: from the repository, or from src for another tree
        return path.relative_to(ROOT) if path.resolve().is_relative_to(ROOT) else path.relative_to(src)

    bad, n = layer_check(src, rel)
    graph = file_graph(src)
    return bad, n, cycles(graph), len(graph)


def main():
    src = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "driver" / "src"
    bad, n, cyc, nfiles = check(src)
    for b in bad:
        print(b)
    for members, c in cyc:
        print("cycle: " + " -> ".join(a for a, _, _ in c) + f" -> {c[0][0]}")
        for a, b, why in c:
            print(f"  {a} {why} ({b})")
        if len(members) > len(c):
            print(f"  tangled with it ({len(members)} files): " + ", ".join(sorted(members)))
    print(f"{n} includes checked, {len(bad)} against the layers")
    print(f"{nfiles} files checked, {len(cyc)} dependency cycles")
    sys.exit(1 if bad or cyc else 0)


if __name__ == "__main__":
    main()
