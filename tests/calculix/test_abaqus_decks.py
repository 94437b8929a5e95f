"""The Abaqus/Standard decks of input/abaqus (issue 21), which no Abaqus runs here: each describes the test
of its CalculiX deck, which CalculiX runs (test_calculix.py), in the keywords checked in
input/abaqus/KEYWORDS.md and nothing of CalculiX's own.

- Only the keywords and parameters of KEYWORDS.md, and every keyword there appears in its table.
- The same model as the CalculiX deck: nodes, elements, sets, surfaces, orientation, material constants,
  amplitude, boundary conditions, steps, increments and loads, card for card (everything but the
  differences KEYWORDS.md lists).
- Abaqus' forms where the two codes differ: the initial stress by element set, one line for all points;
  *SOLID SECTION with its data line; no GLOBAL, *NODE FILE, *EL FILE, *INCLUDE or *CONTROLS.
- The *USER MATERIAL data: CONSTANTS numbers, at most 8 a line; *DEPVAR >= 32; lines within Abaqus' 256
  characters.
"""
import os
import re

import pytest
from camclay9 import calculix_inputs

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
INPUTS = os.path.join(REPO, "input", "abaqus")

# Keyword -> parameters allowed (the table of KEYWORDS.md).
ALLOWED = {
    "HEADING": set(), "NODE": {"NSET"}, "ELEMENT": {"TYPE", "ELSET"}, "NSET": {"NSET"}, "ELSET": {"ELSET"},
    "SURFACE": {"NAME", "TYPE"}, "ORIENTATION": {"NAME", "SYSTEM"},
    "SOLID SECTION": {"ELSET", "MATERIAL", "ORIENTATION"}, "MATERIAL": {"NAME"},
    "USER MATERIAL": {"CONSTANTS", "UNSYMM"}, "DEPVAR": set(), "AMPLITUDE": {"NAME"}, "BOUNDARY": set(),
    "INITIAL CONDITIONS": {"TYPE"}, "STEP": {"INC"}, "STATIC": {"DIRECT"}, "DSLOAD": {"AMPLITUDE"},
    "EL PRINT": {"ELSET"}, "NODE PRINT": {"NSET"}, "OUTPUT": {"FIELD"}, "ELEMENT OUTPUT": {"ELSET"},
    "NODE OUTPUT": set(), "END STEP": set(),
}
# Cards whose text differs between the dialects (KEYWORDS.md, "How the Abaqus decks differ").
DIFFERENT = {"INITIAL CONDITIONS", "SOLID SECTION", "EL PRINT", "NODE FILE", "EL FILE", "OUTPUT", "ELEMENT OUTPUT",
             "NODE OUTPUT", "CONTROLS", "INCLUDE"}


def cards(path):
    """[(keyword, {parameter: value}, [data lines])] of a deck, comments dropped."""
    out = []
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            assert len(line) <= 256, f"{path}: a line longer than 256 characters"
            if line.startswith("**"):
                continue
            if line.startswith("*"):
                parts = [p.strip() for p in line[1:].split(",")]
                params = {}
                for p in parts[1:]:
                    key, _, value = p.partition("=")
                    params[key.strip().upper()] = value.strip()
                out.append((parts[0].upper(), params, []))
            else:
                out[-1][2].append(line)
    return out


def model(deck):
    """The cards that both dialects share, as comparable tuples."""
    return [(k, tuple(sorted(p.items())), tuple(d)) for k, p, d in deck if k not in DIFFERENT]


@pytest.mark.parametrize("name", sorted(calculix_inputs.ABAQUS_DECKS))
def test_abaqus_deck(name):
    deck = cards(os.path.join(INPUTS, name))
    with open(os.path.join(INPUTS, "KEYWORDS.md")) as f:
        note = f.read()
    for key, params, data in deck:
        assert key in ALLOWED, f"{name}: *{key} is not among the keywords checked in KEYWORDS.md"
        assert set(params) <= ALLOWED[key], f"{name}: *{key} parameters {set(params) - ALLOWED[key]} not checked"
        assert f"`*{key}" in note, f"{name}: *{key} has no row in KEYWORDS.md"

    # The CalculiX deck of the same test (which CalculiX runs) is the same model, card for card.
    ccx = cards(os.path.join(INPUTS, name.replace("_abaqus", "")))
    assert model(deck) == model(ccx), f"{name}: the model differs from its CalculiX deck"

    # Abaqus' forms.
    ic = [d for k, p, d in deck if k == "INITIAL CONDITIONS"]
    assert ic == [[" EALL, -35., -35., -35., 0., 0., 0."]]
    section = [d for k, p, d in deck if k == "SOLID SECTION"]
    assert section == [[","]]
    assert all("GLOBAL" not in p for k, p, _ in deck if k == "EL PRINT")
    mat = [(p, d) for k, p, d in deck if k == "USER MATERIAL"][0]
    values = [v for line in mat[1] for v in line.split(",") if v.strip()]
    assert len(values) == int(mat[0]["CONSTANTS"]) and all(len(line.split(",")) <= 8 for line in mat[1])
    depvar = [d for k, p, d in deck if k == "DEPVAR"][0]
    assert int(depvar[0]) >= 32
    # Every *STEP holds one procedure, its loads and its output, and ends.
    steps = [k for k, _, _ in deck if k in ("STEP", "END STEP")]
    assert steps == ["STEP", "END STEP"] * (len(steps) // 2) and steps


def test_every_listed_keyword_is_used():
    """KEYWORDS.md lists no keyword that no Abaqus deck uses."""
    used = {k for name in calculix_inputs.ABAQUS_DECKS for k, _, _ in cards(os.path.join(INPUTS, name))}
    assert used == set(ALLOWED), set(ALLOWED) - used


def test_initial_stress_forms_differ():
    """The dialects really differ where KEYWORDS.md says: the CalculiX deck gives element and point."""
    ccx = cards(os.path.join(INPUTS, "triaxial_c3d8_theta0.inp"))
    ic = [d for k, p, d in ccx if k == "INITIAL CONDITIONS"][0]
    assert len(ic) == 8 and all(re.match(r" 1, [1-8], -35\.", line) for line in ic)
