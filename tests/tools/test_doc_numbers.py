"""tools/doc_numbers.py: the documents' numbers against the results store (docs/results/). The committed documents
agree with the store; a number edited by hand in README.md, docs/paper.md or a generated section of
docs/performance.md, or a store value changed, makes the check fail and name the place; --write puts the store's
numbers back."""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from camclay9 import (calculix_study, calibrate_study, doc_quotes, fe_scaling_study, fe_solver_study, indent_ranks_study,
                      indent_speed_study, point_creep_study, results_store, step_control_study, time_error_study,
                      umat_time_study)

ROOT = Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "doc_numbers.py"

DOCS = ("README.md", "docs/paper.md", "docs/performance.md", "docs/contact.md", "docs/calibrate.md", "docs/adapt.md",
        "docs/parallel.md",
        "bench/indent2d_convergence_conclusions.md",
        "bench/indent_convergence_conclusions.md", "bench/adapt_conclusions.md")


def run(*args):
    return subprocess.run([sys.executable, str(TOOL), *args], capture_output=True, text=True, timeout=300)


@pytest.fixture
def tree(tmp_path):
    """A copy of the documents and the store, to edit."""
    for d in DOCS:
        (tmp_path / d).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(ROOT / d, tmp_path / d)
    shutil.copytree(ROOT / "docs" / "results", tmp_path / "docs" / "results")
    return tmp_path


def edit(path, old, new):
    text = path.read_text(encoding="utf-8")
    assert text.count(old) >= 1, old
    path.write_text(text.replace(old, new, 1), encoding="utf-8")


def test_the_committed_documents_agree_with_the_store():
    r = run()
    assert r.returncode == 0, r.stdout
    assert "(all)" in r.stdout


def test_every_quote_is_found_once_with_its_numbers():
    """...and once with any numbers, so that --write puts the store's numbers into the quote's own place."""
    ns = doc_quotes.namespace()
    for doc, text in doc_quotes.QUOTES:
        have = (ROOT / doc).read_text(encoding="utf-8")
        assert have.count(doc_quotes.render(text, ns)) == 1, text[:60]
        assert len(re.findall(doc_quotes.pattern(text), have)) == 1, text[:60]


@pytest.mark.parametrize("doc, old, new", [
    ("README.md", "its creep is 0.88×", "its creep is 0.90×"),                     # a quote of the main job
    ("README.md", "creep depth −1.6 %, residual depth −1.4 %", "creep depth −1.6 %, residual depth −1.5 %"),
    ("docs/paper.md", "(0.88× θ0, 0.92× θ90", "(0.88× θ0, 0.93× θ90"),             # generated from paper.json
    ("docs/performance.md", "creep 35.46 ± 0.4%", "creep 35.41 ± 0.4%"),           # the 2D study's reference
    ("docs/performance.md", "| triaxial_theta0 | ", "| triaxial_theta0 | 9"),    # a run time (a digit put before it, whatever it is)
    ("docs/contact.md", "24 against 45 in 0.47×", "24 against 45 in 0.74×"),   # the p-multigrid's CPU
    ("docs/performance.md", "| 883 | 47.69 | 1.36 |", "| 883 | 47.69 | 1.63 |"),     # contact solve: a CPU ratio
    ("docs/parallel.md", "at 190 k (5.9 GB)", "at 190 k (5.8 GB)"),                 # the direct path's memory
    ("docs/performance.md", "| 417 | 56.7 | 36.76 |", "| 417 | 56.7 | 36.67 |"),         # FE triaxial: assembly per Newton it.
    ("docs/performance.md", "it took 13.1 s (median", "it took 12.1 s (median"),  # the 3D section's reading
    ("bench/indent_convergence_conclusions.md", "**P = 537.6 µN ± 0.4 %**", "**P = 537.5 µN ± 0.4 %**"),  # its reference
    ("docs/performance.md", "| 0.12 | 5882 | 547.18 (+2.2%) |", "| 0.12 | 5882 | 547.81 (+2.2%) |"),  # a rung of its tables
    ("docs/calibrate.md", "standard errors in 56 (93 %)", "standard errors in 57 (95 %)"),  # the 300 s drift hold's coverage
    ("docs/calibrate.md", "the two noisy cases give −2.36 %", "the two noisy cases give −2.63 %"),  # the 60 s drift hold's
    ("docs/performance.md", "| drift | 20 (0 failed) | 19 of 20 (95 %) |", "| drift | 20 (0 failed) | 18 of 20 (90 %) |"),
    ("bench/indent2d_convergence_conclusions.md", "Fig. 13's quantity Δσ̄ +1.8 %", "Fig. 13's quantity Δσ̄ +1.9 %"),
    ("docs/performance.md", "| -0.785 % | 0.702 % | 0.89 |", "| -0.785 % | 0.702 % | 0.98 |"),  # stated time-step error: an effectivity
    ("docs/adapt.md", "1.03–1.05 on the 3D kerogen sector", "1.02–1.05 on the 3D kerogen sector"),   # its reading
    ("docs/adapt.md", "splits into 0.54 % from the load", "splits into 0.45 % from the load"),
    ("docs/adapt.md", "against 18 of 30 before.", "against 16 of 30 before."),   # the contact term's effect
    ("bench/adapt_conclusions.md", "least 0.2 %) it lies in [0.5, 2] in ", "least 0.2 %) it lies in [0.5, 2] in 9"),   # the adapted meshes' reading
    ("docs/performance.md", "| elastic | 2054 | 2447 |", "| elastic | 2054 | 2403 |"),    # UMAT: instructions per call
    ("docs/performance.md", "the library +3 % and +33 %", "the library +3 % and +22 %"),  # UMAT: the reading's figures
    ("docs/performance.md", "| 1e-07 | 396 | 0 | 7.50 |", "| 1e-07 | 396 | 0 | 5.90 |"),  # material point: a median wall time
    ("docs/performance.md", "eta_hard 1.306658e+13 (+0.51 % ± 0.5 %)", "eta_hard 1.306658e+13 (+0.51 % ± 0.34 %)"),  # calibr.
    ("docs/performance.md", "| microindent_BP | 2 | 56.1 | 111.0 |", "| microindent_BP | 2 | 51.6 | 111.0 |"),  # 1 and 2 ranks
    ("docs/performance.md", "1.4–1.5× in wall time", "1.4–1.6× in wall time"),                      # their reading's range
    ("docs/performance.md", "| 631 | 764 | 1,850,260 | 2.5 | 2.2 |", "| 631 | 764 | 1,850,260 | 2.5 | 2.3 |"),  # step control
    ("docs/performance.md", "| -0.50% | -3.20% | -0.29% |", "| -0.50% | -3.02% | -0.29% |"),          # its table of measures
    ("docs/performance.md", "| 8,032,472 | 58.7 | 17.2 |", "| 8,032,472 | 58.7 | 17.3 |"),          # a row taken over
    ("docs/performance.md", "bedding_theta45 9.56 s", "bedding_theta45 9.65 s"),                    # its quiet machine's
    ("docs/performance.md", "| 7,072,230 | 119.6 | 35.2 |", "| 7,072,230 | 119.6 | 32.5 |"),      # the 3D half models'
    ("docs/performance.md", "3 553, 3 021 and 3 041 steps", "3 553, 3 012 and 3 041 steps"),     # issue 10's, quoted
    ("docs/performance.md", "| 2 | GAMG | 1208 of 85114 (ptscotch) | 4 | 93 |", "| 2 | GAMG | 1208 of 85114 (ptscotch) | 4 | 39 |"),
    ("docs/parallel.md", "took 43.5 s on 2 ranks", "took 34.5 s on 2 ranks"),                    # FE scaling, quoted
    ("docs/performance.md", "| 713 | 76 | 5.3e-09 | 2.7e-10 |", "| 713 | 76 | 5.3e-09 | 2.9e-10 |"),  # CalculiX: agreement
    ("docs/performance.md", "| 284 | 2 | 12.75 | 7.00 | 94.7 |", "| 284 | 2 | 12.75 | 7.00 | 97.4 |"),  # FE solver: a cell
    ("docs/performance.md", "| 631 | 1248 | 28 |", "| 631 | 1284 | 28 |"),     # indentation speed: Krylov iterations
])
def test_a_number_edited_by_hand_fails_the_check(tree, doc, old, new):
    assert run("--root", str(tree)).returncode == 0
    edit(tree / doc, old, new)
    r = run("--root", str(tree))
    assert r.returncode == 1 and doc in r.stdout, r.stdout
    run("--root", str(tree), "--write")                       # the store's numbers put back
    assert run("--root", str(tree)).returncode == 0


def test_a_store_value_changed_fails_the_check(tree):
    """The finest kerogen rung's load moved: the 3D reference moves with it (camclay9.indent3d_study), and README's
    quote of it, the section's tables and its reading all differ from the store."""
    edit(tree / "docs" / "results" / "indent_convergence.json", '"load at end of loading": 539.56', '"load at end of loading": 549.56')
    r = run("--root", str(tree))
    assert r.returncode == 1 and "README.md" in r.stdout and "P 549.6 µN" in r.stdout
    assert "3D indentation: mesh convergence" in r.stdout and "bench/indent_convergence_conclusions.md" in r.stdout


def _drop(store, path):
    """The store with the key at path (a tuple of keys and indices) removed; the key's name."""
    *at, key = path
    d = store
    for k in at:
        d = d[k]
    del d[key]
    return key


@pytest.mark.parametrize("study, path", [
    (time_error_study, ("cases", "sphere", "rows", 1, "stated")),
    (umat_time_study, ("rows", 2, "after_nocache")),
    (point_creep_study, ("rows", 3, "err_10h")),
    (calibrate_study, ("examples", 2, "cpu_s")),
    (calibrate_study, ("examples", 0, "quote", "eta_soft", "relative_std_error")),
    (indent_ranks_study, ("rows", 5, "h_res_vs_1")),
    (indent_ranks_study, ("rows", 2, "wall_s")),
    (step_control_study, ("parts", "axi", "scenes", 1, "rows", 0, "calls")),
    (step_control_study, ("parts", "axi", "quiet", "rate_wall_s")),    # a figure the hand-written text quotes
    (step_control_study, ("parts", "axi", "table", "rows", 4, "errors", "creep depth")),
    (fe_scaling_study, ("rows", 3, "rss_all")),
    (calculix_study, ("meshes", 2, "runs", 2, "cpu")),                 # CalculiX's CPU on the largest mesh
    (fe_solver_study, ("rows", 3, "cpu")),                             # a table's number
    (fe_solver_study, ("probe", "asymmetry")),                         # a number only the reading quotes
    (indent_speed_study, ("rows", 2, "umat_ns")),                      # the UMAT benchmark's time of a scene
])
def test_a_store_lacking_a_number_names_its_file_and_key(study, path):
    store = results_store.load(study.STORE)
    key = _drop(store, path)
    with pytest.raises(ValueError, match=rf"docs/results/{study.STORE}\.json: .*{key}"):
        study.section(store)


@pytest.mark.parametrize("path", [("parts", "3d", "scenes", 2, "rows", 0, "cpu_s"), ("parts", "3d", "issue10_before", "steps")])
def test_the_3d_step_control_section_names_a_missing_number(path):
    store = results_store.load(step_control_study.STORE)
    key = _drop(store, path)
    with pytest.raises(ValueError, match=rf"docs/results/step_control\.json: parts\.3d.* lacks {key}"):
        step_control_study.sections(store)
