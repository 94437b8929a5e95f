"""The PROPS contract is written once, in umat/src/ccix_props.f90 (prop_names), and everything else spells it so
(issue 24): docs/umat.md's PROPS table has one row per slot in order, the Abaqus/CalculiX decks name the slots in
their comments in that order, and every PROPS name a scene or a calibrate scene uses (material.set keys,
calibrate parameters) is one of them. A misspelt or reordered name anywhere fails here."""
import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]


def prop_names():
    src = (ROOT / "umat" / "src" / "ccix_props.f90").read_text()
    block = re.search(r"prop_names\(nprops_normal\) = \[character\(len=\d+\) :: &(.*?)\]", src, re.S).group(1)
    return re.findall(r"'(\w+)'", block)


def test_the_table_has_every_slot():
    names = prop_names()
    assert len(names) == 23 and names[0] == "phi" and names[18] == "eta_soft" and names[19] == "tol"
    assert len(set(names)) == 23


def test_umat_md_props_table_in_slot_order():
    text = (ROOT / "docs" / "umat.md").read_text()
    section = text[text.index("## PROPS"):text.index("## STATEV")]
    slots = [int(m) for m in re.findall(r"^\| (\d+)(?:[–-]\d+)? \|", section, re.M)]
    assert slots[:20] == list(range(1, 21)), slots
    assert 21 in slots and slots == sorted(slots)


def statev_blocks():
    src = (ROOT / "umat" / "src" / "ccix_props.f90").read_text()
    consts = {k: int(v) for k, v in re.findall(r"(is_\w+) = (\d+)", src)}
    names = re.findall(r"'(\w+)'", re.search(r"statev_block_names\(n_statev_blocks\) = \[(.*?)\]", src, re.S).group(1))
    first = [consts[c] for c in re.findall(r"(is_\w+)", re.search(r"statev_block_first\(n_statev_blocks\) = \[(.*?)\]",
                                                                      src, re.S).group(1))]
    size = [int(x) for x in re.findall(r"\d+", re.search(r"statev_block_size\(n_statev_blocks\) = \[(.*?)\]", src).group(1))]
    return list(zip(names, first, size))


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
