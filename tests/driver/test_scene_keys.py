"""One declaration per scene key and per option (issue 35, items 1 and 2), and what is written from them.

- docs/driver.md's "Key reference" is the driver's key table (`driver -key_reference markdown`) line for line;
  `python3 tests/driver/test_scene_keys.py --write` writes it there;
- `driver -help` lists every declared key, each with its type (with its range or choices where it has one) and
  its default where it has one;
- `driver -help` lists every option of the driver's with its default, and every integer or number option with its
  range in brackets, every word option with its choices; a text option without a range is one of the few named
  below: an option added without them fails here;
- docs/driver.md's option table names every option of the driver's, with the range -help gives it;
- every key a scene reader names in its source (yd_get, yd_require, yd_key_line, keys_*) is declared, and every
  declared key is named by a reader (no declaration outlives its key). Keys named at run time (a stage event's word,
  a constraint's stress or strain, the normal's n1-n3) are checked when read: a reader that asks for a key without a
  declaration stops every scene that reaches it.
"""
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DRIVER = os.environ.get("DRIVER", str(ROOT / "build" / "bin" / "driver"))
DOC = ROOT / "docs" / "driver.md"
BEGIN = "<!-- key reference: written by tests/driver/test_scene_keys.py --write from driver/src/scene/scene_keys.c; do not edit -->"
END = "<!-- end of the key reference -->"
READERS = ["fe/fe_scene.c", "contact/indent_scene.c", "point/point_scene.c", "scene/stage.c", "scene/time_function.c",
           "material/material_input.c"]
# text options: a free path or list, no range to give
TEXT_OPTIONS = {"-input", "-output_dir", "-material_set"}


def driver(*args):
    r = subprocess.run([DRIVER, *args], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


def reference():
    return driver("-key_reference", "markdown")


def doc_parts(text):
    assert text.count(BEGIN) == 1 and text.count(END) == 1, f"{DOC}: expected the two marker lines of the key reference"
    head, rest = text.split(BEGIN + "\n", 1)
    body, tail = rest.split(END, 1)
    return head, body, tail


def declared():
    """(path, kinds, type, default) of every declaration, from the table's markdown."""
    rows = []
    for line in reference().splitlines()[2:]:
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        rows.append((cells[0].strip("`"), cells[1], cells[2].replace("\\|", "|"), cells[3]))
    return rows


def test_key_reference_is_the_table():
    _, body, _ = doc_parts(DOC.read_text())
    want = reference()
    assert body == want, ("docs/driver.md's key reference differs from `driver -key_reference markdown`: run "
                          "python3 tests/driver/test_scene_keys.py --write")


def test_help_lists_every_key_with_its_range_and_default():
    help_text = subprocess.run([DRIVER, "-help"], capture_output=True, text=True, timeout=120).stdout
    rows = declared()
    assert len(rows) > 140
    for path, kinds, type_, default in rows:
        line = next((l for l in help_text.splitlines() if l.strip().startswith(f"{path} [{kinds}]")), None)
        assert line, f"-help does not list the key {path}"
        assert type_ in line, (path, type_, line)
        if default:
            assert (default if default == "required" else f"default: {default}") in line, (path, default, line)
    # a number or an integer states its range (or the help line gives it: the ranges that depend on other keys)
    ranged = [r for r in rows if r[2].startswith(("a number", "an integer"))]
    assert sum(1 for r in ranged if re.search(r"[<>]|from|to", r[2])) >= 30


def driver_options(help_text):
    """The driver's own options in -help: name -> their line (PETSc's sections of its own are left out)."""
    sections = ("Scene driver:", "Stages and steps", "Finite-element scenes", "Indentation (", "Material:", "Mesh adaptation")
    options, inside = {}, False
    for line in help_text.splitlines():
        if line.startswith("----"):
            inside = False
        elif line.startswith(sections):
            inside = True
        elif inside and re.match(r"\s+-\w", line):
            options[re.match(r"\s+(-\w+)", line).group(1)] = line
    return options


def test_help_lists_every_option_with_its_range_and_default():
    help_text = subprocess.run([DRIVER, "-help"], capture_output=True, text=True, timeout=120).stdout
    options = driver_options(help_text)
    assert len(options) >= 34, sorted(options)
    for name, line in options.items():
        assert re.search(r"<[^>]*:[^>]*>", line), f"{name}: no default in -help: {line}"
        boolean = re.match(r"\s+-\w+: <(TRUE|FALSE) : (TRUE|FALSE)>", line)
        choices = "(choose one of)" in line
        ranged = re.search(r" \[[^]]+\] \(None\)$", line)
        assert boolean or choices or ranged or name in TEXT_OPTIONS, f"{name}: neither a range nor choices in -help: {line}"
    for name in ["-indent_ksp_rtol", "-step_alpha", "-step_beta", "-indent_rtol", "-adapt_growth"]:
        assert re.search(r" \[[^]]+\] \(None\)$", options[name]), options[name]


def test_docs_give_every_option_its_range():
    options = driver_options(subprocess.run([DRIVER, "-help"], capture_output=True, text=True, timeout=120).stdout)
    rows = [l for l in DOC.read_text().splitlines() if l.startswith("| `-")]
    for name, line in options.items():
        row = next((r for r in rows if re.search(rf"`{name}[` ,]", r)), None)
        assert row, f"docs/driver.md's option table has no row for {name}"
        m = re.search(r" \[([^]]+)\] \(None\)$", line)
        if m:
            assert f"| {m.group(1)} |" in row or f"| {m.group(1)}," in row, (name, m.group(1), row)


def names_in_readers():
    call = re.compile(r'\b(?:yd_get|yd_key_line|keys_(?:number|integer|word|bool|apply|find))\(\s*(?:doc,\s*)?[^,()]+,\s*"([^"]+)"'
                      r'|\byd_require\(\s*doc,\s*[^,()]+,\s*"([^"]+)"')
    found = {}
    for rel in READERS:
        text = (ROOT / "driver" / "src" / rel).read_text()
        for m in call.finditer(text):
            found.setdefault(m.group(1) or m.group(2), rel)
    return found


def test_every_key_a_reader_names_is_declared():
    leaves = {p.rsplit(".", 1)[-1].removesuffix("[]") for p, *_ in declared()}
    named = names_in_readers()
    assert len(named) > 80
    missing = {k: f for k, f in named.items() if k not in leaves}
    assert not missing, f"keys read without a declaration in driver/src/scene/scene_keys.c: {missing}"


def test_every_declared_key_is_read():
    named = set(names_in_readers()) | {"strain", "stress"}  # a constraint's parts, by an array of their names
    named |= {"evp_rate_below", "q_above", "q_below", "p_above"}  # stage events, by their table of names
    stale = sorted({p for p, *_ in declared() if p.rsplit(".", 1)[-1].removesuffix("[]") not in named | {"*"}})
    assert not stale, f"declared keys no reader asks for: {stale}"


def main():
    if sys.argv[1:] not in (["--write"], ["--check"]):
        sys.exit("usage: python3 tests/driver/test_scene_keys.py --write | --check   (DRIVER=build/bin/driver)")
    head, body, tail = doc_parts(DOC.read_text())
    want = reference()
    if sys.argv[1] == "--write":
        DOC.write_text(head + BEGIN + "\n" + want + END + tail)
        print(f"{DOC}: key reference written ({len(want.splitlines()) - 2} keys)")
    else:
        sys.exit(0 if body == want else f"{DOC}: the key reference differs from the driver's table: --write")


if __name__ == "__main__":
    main()
