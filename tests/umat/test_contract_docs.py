"""The PROPS contract is written once, in umat/src/ccix_props.f90 (prop_table), and everything else spells it so
(issue 24): docs/umat.md's PROPS table has one row per slot in order, with the table's name, meaning, unit and
bounds (read from the built library through the C API, camclay9_prop_info), the Abaqus/CalculiX decks name the slots
in their comments in that order, and every PROPS name a scene or a calibrate scene uses (material.set keys,
calibrate parameters) is one of them. A misspelt, reordered or out-of-date entry anywhere fails here."""
import ctypes
import os
import re
import unicodedata
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
# camclay9.h: CAMCLAY9_BOUND_*
BOUND_LO, BOUND_LO_CLOSED, BOUND_HI, BOUND_HI_CLOSED, BOUND_COUPLED = 1, 2, 4, 8, 16


class PropInfo(ctypes.Structure):
    """camclay9_prop_info_t of camclay9.h."""
    _fields_ = [("name", ctypes.c_char * 16), ("symbol", ctypes.c_char * 16), ("unit", ctypes.c_char * 16),
                ("meaning", ctypes.c_char * 80), ("lo", ctypes.c_double), ("hi", ctypes.c_double),
                ("bounds", ctypes.c_int)]


def library():
    """The shared library of this build: CAMCLAY9_LIBRARY (set by CTest), else build/umat/libcamclay9.so."""
    path = Path(os.environ.get("CAMCLAY9_LIBRARY", ROOT / "build" / "umat" / "libcamclay9.so"))
    assert path.exists(), f"{path}: build the UMAT library first (or set CAMCLAY9_LIBRARY)"
    lib = ctypes.CDLL(str(path))
    lib.camclay9_prop_info.argtypes = [ctypes.c_int, ctypes.POINTER(PropInfo)]
    lib.camclay9_prop_info.restype = ctypes.c_int
    return lib


def prop_table():
    """The PROPS table as the library exports it: one dict per slot, in slot order."""
    lib, rows, info = library(), [], PropInfo()
    while lib.camclay9_prop_info(len(rows), ctypes.byref(info)):
        rows.append({"name": info.name.decode(), "unit": info.unit.decode(), "meaning": info.meaning.decode(),
                     "lo": info.lo, "hi": info.hi, "bounds": info.bounds})
    return rows


def prop_names():
    return [row["name"] for row in prop_table()]


def bounds_text(row):
    """A slot's own bounds as docs/umat.md writes them: "[0, 1]", "> 0", "≥ 0"; "–" for none."""
    b, num = row["bounds"], lambda x: f"{x:g}"
    if b & BOUND_LO and b & BOUND_HI:
        return ("[" if b & BOUND_LO_CLOSED else "(") + f"{num(row['lo'])}, {num(row['hi'])}" + \
            ("]" if b & BOUND_HI_CLOSED else ")")
    if b & BOUND_LO:
        return ("≥ " if b & BOUND_LO_CLOSED else "> ") + num(row["lo"])
    if b & BOUND_HI:
        return ("≤ " if b & BOUND_HI_CLOSED else "< ") + num(row["hi"])
    return "–"


def plain(text):
    """The docs' typography as the ASCII of the Fortran table: MPa³·s -> MPa^3 s, – -> -, é -> e."""
    text = text.replace("³", "^3").replace("·", " ").replace("–", "-").replace("−", "-")
    return unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()


def test_the_table_has_every_slot():
    names = prop_names()
    assert len(names) == 23 and names[0] == "phi" and names[18] == "eta_soft" and names[19] == "tol"
    assert len(set(names)) == 23


def props_rows():
    """docs/umat.md's PROPS table: (slot, [cells]) per row."""
    text = (ROOT / "docs" / "umat.md").read_text()
    section = text[text.index("## PROPS"):text.index("## STATEV")]
    return [(int(m.group(1)), [c.strip() for c in m.group(2).split("|")])
            for m in re.finditer(r"^\| (\d+) \|(.*)\|$", section, re.M)]


def test_umat_md_props_table_in_slot_order():
    assert [slot for slot, _ in props_rows()] == list(range(1, 24))


def test_umat_md_props_table_is_the_contract():
    """Columns: name, symbol, meaning, unit, bounds, conditions with other slots, Woodford."""
    table = prop_table()
    for (slot, cells), row in zip(props_rows(), table):
        name, _, meaning, unit, bounds, coupled = cells[:6]
        where = f"docs/umat.md PROPS slot {slot}"
        assert name == f"`{row['name']}`", (where, name)
        assert plain(meaning) == row["meaning"], (where, meaning, row["meaning"])
        assert plain(unit) == row["unit"], (where, unit, row["unit"])
        assert bounds == bounds_text(row), (where, bounds, bounds_text(row))
        assert bool(coupled) == bool(row["bounds"] & BOUND_COUPLED), (where, "conditions with other slots", coupled)


def test_bounds_text_can_fail():
    """The comparison above sees open against closed and a changed bound."""
    row = {"lo": 0.0, "hi": 1.0, "bounds": BOUND_LO | BOUND_LO_CLOSED | BOUND_HI | BOUND_HI_CLOSED}
    assert bounds_text(row) == "[0, 1]"
    assert bounds_text({**row, "bounds": BOUND_LO}) == "> 0" != bounds_text({**row, "bounds": BOUND_LO | BOUND_LO_CLOSED})
    assert bounds_text({**row, "lo": 0.5, "bounds": BOUND_LO}) == "> 0.5"


def statev_blocks():
    """(name, first slot 1-based, size) of each STATEV block, as the library exports them (camclay9_statev_block)."""
    lib, blocks = library(), []
    name, first, size = ctypes.create_string_buffer(16), ctypes.c_int(), ctypes.c_int()
    while lib.camclay9_statev_block(len(blocks), name, 16, ctypes.byref(first), ctypes.byref(size)):
        blocks.append((name.value.decode(), first.value + 1, size.value))
    return blocks


def test_umat_md_statev_table_matches_the_blocks():
    text = (ROOT / "docs" / "umat.md").read_text()
    section = text[text.index("## STATEV"):text.index("## Time step control")]
    rows = [(int(a), int(b or a)) for a, b in re.findall(r"^\| (\d+)(?:[–-](\d+))? \|", section, re.M)]
    assert rows == [(f, f + n - 1) for _, f, n in statev_blocks()], rows


def test_deck_comments_spell_the_names():
    names = prop_names()
    decks = sorted((ROOT / "input" / "abaqus").glob("*.inp")) + [ROOT / "tools" / "calculix" / "make_inputs.py",
                                                                  ROOT / "docs" / "umat.md"]
    seen = 0
    for deck in decks:
        text = deck.read_text().splitlines()
        for k, ln in enumerate(text):
            if not ln.startswith("** phi, "):
                continue
            listed = []
            for m in range(k, min(k + 6, len(text))):
                if text[m].startswith("**"):
                    listed += [w.strip() for w in text[m][2:].split("(")[0].split(",") if w.strip()]
            assert listed == names[:len(listed)], (deck.name, listed)
            seen += 1
    assert seen >= 8


def test_scenes_use_the_names():
    names = set(prop_names())
    used = 0
    for path in sorted((ROOT / "input").rglob("*.yaml")):
        doc = yaml.safe_load(path.read_text())
        if not isinstance(doc, dict):
            continue
        mat = doc.get("material") or {}
        for key in (mat.get("set") or {}) if isinstance(mat, dict) else {}:
            assert key in names, f"{path}: material.set.{key}"
            used += 1
        for p in doc.get("parameters") or []:
            if isinstance(p, dict) and "name" in p:
                assert p["name"] in names, f"{path}: parameters.name {p['name']}"
                used += 1
    assert used > 10
