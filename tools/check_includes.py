#!/usr/bin/env python3
"""The driver's folders are its architecture, and dependencies run one way (driver/README.md, "The layers"):

    app -> calibrate -> stepping -> contact -> {fe, point} -> scene -> material -> io

A file may include its own folder's headers and those of folders below it, never one above it or beside it (fe and
point are siblings: neither includes the other); only material/ includes the UMAT's C header camclay9.h (the
material contract is the material's). Prints every include that breaks this and exits 1, else says how many
includes it checked.

Usage: tools/check_includes.py [driver/src]
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LAYER = {"io": 0, "material": 1, "scene": 2, "fe": 3, "point": 3, "contact": 4, "stepping": 5, "calibrate": 6,
         "app": 7}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def check(src):
    def rel(path):  # as the user would write it: from the repository, or from src for another tree
        return path.relative_to(ROOT) if path.resolve().is_relative_to(ROOT) else path.relative_to(src)

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
                bad.append(f"{rel(path)}: includes {target} ({folder} -> {to} runs against "
                           "app -> calibrate -> stepping -> contact -> {fe, point} -> scene -> material -> io)")
    return bad, n


def main():
    src = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "driver" / "src"
    bad, n = check(src)
    for b in bad:
        print(b)
    print(f"{n} includes checked, {len(bad)} against the layers")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
