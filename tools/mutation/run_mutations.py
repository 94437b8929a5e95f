#!/usr/bin/env python3
"""The mutation run (issue 38): each deliberate break of tools/mutation/breaks.py applied alone to a scratch copy of
the tree, built, and the CTest test named for it run with a timeout; the table (break, file:line, test,
caught/missed, seconds) written into tests/README.md between its markers.

    tools/mutation/run_mutations.py [--scratch DIR] [--only ID,ID] [--timeout S] [--baseline] [--no-readme]

The scratch copy (default /tmp/camclay9-mutation) holds the tracked files of this tree as they are now (committed
or not) and one build directory reused from break to break, so each break rebuilds only what it touches; files
are rewritten only when their content differs, so their timestamps stay and make rebuilds incremental. A break
is "caught" when its test fails (a non-zero exit of ctest, a timeout included), "missed" when it passes, and
"build error" when the break does not compile (a defect of the list, not a catch). --baseline first runs every
named test (and its pytest filter) on the unbroken copy: a test that fails there catches nothing. Results are
kept in DIR/results.json, so --only reruns some breaks and the table keeps the others' last results (without
DIR/results.json, as on a fresh machine, the others' results are read from the README's table).

A benchmark, not part of the CI suite (not registered in CTest); about 40 min on 2 busy cores.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import time
from pathlib import Path

from breaks import BREAKS

ROOT = Path(__file__).resolve().parents[2]

BEGIN, END = "<!-- mutation table: begin (tools/mutation/run_mutations.py writes it) -->", "<!-- mutation table: end -->"
NICE = ["nice", "-n", "15"]


def sync_tree(scratch):
    """Copy the tracked files (their current content) into scratch; unchanged files are left alone."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True, timeout=60).stdout
    for rel in files.decode().split("\0"):
        if not rel:
            continue
        src, dst = ROOT / rel, scratch / rel
        if not src.is_file():
            continue
        data = src.read_bytes()
        if dst.is_file() and dst.read_bytes() == data:
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_bytes(data)
        os.chmod(dst, src.stat().st_mode)


def build(scratch, timeout):
    b = scratch / "build"
    if not (b / "CMakeCache.txt").is_file():
        r = subprocess.run([*NICE, "cmake", "-S", str(scratch), "-B", str(b), "-DCMAKE_BUILD_TYPE=Release"],
                           capture_output=True, text=True, timeout=timeout)
        if r.returncode:
            return r
    return subprocess.run([*NICE, "cmake", "--build", str(b), "-j", "2"], capture_output=True, text=True, timeout=timeout)


def run_test(scratch, test, k, timeout):
    """ctest of one test (its fixtures' set-ups with it); k: a pytest -k filter given through PYTEST_ADDOPTS."""
    env = dict(os.environ)
    if k:
        env["PYTEST_ADDOPTS"] = "-k " + shlex.quote(k)
    t0 = time.time()
    try:
        r = subprocess.run([*NICE, "ctest", "--test-dir", str(scratch / "build"), "-R", f"^{test}$", "--timeout", str(timeout),
                            "--output-on-failure"], capture_output=True, text=True, env=env, timeout=timeout + 120)
        out, rc = r.stdout + r.stderr, r.returncode
    except subprocess.TimeoutExpired as e:
        out, rc = str(e.stdout or ""), -1
    if "No tests were found" in out or "0 tests failed out of 0" in out:
        rc = "no test"
    return rc, time.time() - t0, out


def apply(scratch, b):
    """The break's file with its one edit; returns (original text, 1-based line) or raises if the edit is stale."""
    path = scratch / b["file"]
    text, line = path.read_text(), break_line(b, scratch)
    if line is None:
        raise ValueError(f"{b['id']}: the text to break does not occur exactly once in {b['file']}")
    path.write_text(text.replace(b["old"], b["new"]))
    return text, line


def one(scratch, b, timeout):
    original, line = apply(scratch, b)
    try:
        t0 = time.time()
        r = build(scratch, 1800)
        if r.returncode:
            return {"line": line, "result": "build error", "seconds": round(time.time() - t0, 1), "log": (r.stdout + r.stderr)[-3000:]}
        rc, secs, out = run_test(scratch, b["test"], b.get("k"), timeout)
        result = "no test" if rc == "no test" else ("caught" if rc != 0 else "missed")
        if rc == -1 or "***Timeout" in out:
            result = "caught (timeout)"
        return {"line": line, "result": result, "seconds": round(secs, 1), "log": out[-3000:]}
    finally:
        (scratch / b["file"]).write_text(original)


def break_line(b, root=ROOT):
    """The 1-based line of the break's text in root's file as it is now, or None when the text is not there exactly
    once (the code moved on and the break is stale: its last result says nothing about the code)."""
    text = (root / b["file"]).read_text()
    return text[: text.index(b["old"])].count("\n") + 1 if text.count(b["old"]) == 1 else None


def table(results):
    """The README's rows: each break's file:line from the tree as it is now, its last result (a stale break's
    result replaced by 'stale')."""
    rows = ["| # | break | file:line | test (pytest -k) | result | s |", "|---|---|---|---|---|---|"]
    caught = 0
    for i, b in enumerate(BREAKS, 1):
        r, line = results.get(b["id"], {}), break_line(b)
        result = r.get("result", "not run") if line else "stale: its text is not in the file"
        caught += result.startswith("caught")
        test = f"`{b['test']}`" + (f" ({b['k']})" if b.get("k") else "")
        rows.append(f"| {i} | {b['id']}: {b['why']} | {b['file']}:{line or '?'} | {test} | {result} | {r.get('seconds', '')} |")
    return "\n".join(rows) + f"\n\n{caught} of {len(BREAKS)} breaks caught.\n"


def write_readme(results, when):
    path = ROOT / "tests" / "README.md"
    text = path.read_text()
    if BEGIN not in text or END not in text:
        raise SystemExit(f"{path}: the markers of the mutation table are missing")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    path.write_text(f"{head}{BEGIN}\n{when}\n\n{table(results)}{END}{tail}")


def readme_results():
    """The last results as the README's table shows them ({id: {result, seconds}}), so that --only on a machine
    without DIR/results.json (a fresh one) keeps the other breaks' rows instead of marking them 'not run' (their
    lines are the tree's, table())."""
    text = (ROOT / "tests" / "README.md").read_text()
    if BEGIN not in text or END not in text:
        return {}
    results = {}
    for row in text.split(BEGIN, 1)[1].split(END, 1)[0].splitlines():
        cells = [c.strip() for c in row.strip().strip("|").split("|")]
        if len(cells) != 6 or not cells[0].isdigit() or ":" not in cells[1] or cells[4] == "not run" or cells[4].startswith("stale"):
            continue
        results[cells[1].split(":", 1)[0]] = {"result": cells[4], "seconds": float(cells[5] or 0)}
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scratch", default="/tmp/camclay9-mutation")
    ap.add_argument("--only", default="", help="comma-separated break ids")
    ap.add_argument("--timeout", type=int, default=600, help="seconds per test run")
    ap.add_argument("--baseline", action="store_true", help="run the named tests on the unbroken copy first")
    ap.add_argument("--no-readme", action="store_true")
    a = ap.parse_args()
    scratch = Path(a.scratch)
    scratch.mkdir(parents=True, exist_ok=True)
    store = scratch / "results.json"
    results = json.loads(store.read_text()) if store.is_file() else readme_results()
    todo = [b for b in BREAKS if not a.only or b["id"] in a.only.split(",")]
    sync_tree(scratch)
    r = build(scratch, 3600)
    if r.returncode:
        raise SystemExit("the unbroken copy does not build:\n" + r.stdout[-2000:] + r.stderr[-2000:])
    if a.baseline:
        for test, k in sorted({(b["test"], b.get("k") or "") for b in todo}):
            rc, secs, out = run_test(scratch, test, k, a.timeout)
            print(f"baseline {test} ({k}): {'passes' if rc == 0 else 'FAILS'} in {secs:.0f} s", flush=True)
            if rc != 0:
                raise SystemExit(out[-3000:])
    for b in todo:
        res = one(scratch, b, a.timeout)
        results[b["id"]] = res
        store.write_text(json.dumps(results, indent=1))
        print(f"{b['id']:28s} {b['file']}:{res['line']:<5} {b['test']:28s} {res['result']:16s} {res['seconds']:7.1f} s", flush=True)
        if res["result"] in ("missed", "build error", "no test"):
            print(res["log"][-1500:], flush=True)
    build(scratch, 3600)  # leave the copy built unbroken
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True, timeout=60).stdout.strip()
    when = (f"Last run: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, on {rev} (plus uncommitted changes, if any), "
            f"{len(todo)} of {len(BREAKS)} breaks in this run"
            f"{' (--baseline: each named test and filter passed unbroken first)' if a.baseline else ''}; "
            "seconds: the test run alone (the rebuild not counted).")
    if not a.no_readme:
        write_readme(results, when)
    missed = [b["id"] for b in BREAKS if not results.get(b["id"], {}).get("result", "").startswith("caught")]
    print(table(results))
    sys.exit(1 if missed else 0)


if __name__ == "__main__":
    main()
