#!/usr/bin/env python3
"""The documents' numbers against the results store (docs/results/*.json, camclay9.results_store).

Usage: tools/doc_numbers.py [--write] [--root DIR]

  (default)  check; exit 1, each difference listed, when a document's number differs from the store:
             * docs/paper.md against the text its generator writes from docs/results/paper.json
               (camclay9.paper_doc, render_store);
             * the sections of docs/performance.md written from a store against what their generators write:
               "## Reproducing the paper" (paper.json), "## 2D indentation: mesh and element study"
               (camclay9.indent2d_study, indent2d_convergence.json), "## Adapted meshes: ..."
               (camclay9.adapt_study, adapt_bench.json), "## Contact solve: direct against field split"
               (camclay9.contact_solver_study, contact_solver.json), "## FE: triaxial cylinder"
               (camclay9.fe_triaxial_study, fe_triaxial.json), "## Stated time-step error"
               (camclay9.time_error_study, time_error.json), "## UMAT: time per call"
               (camclay9.umat_time_study, umat_time.json), "## Material point: triaxial creep, ..."
               (camclay9.point_creep_study, point_creep.json), "## Calibration" (camclay9.calibrate_study,
               calibrate_bench.json), "## 3D indentation on 1 and 2 ranks" (camclay9.indent_ranks_study,
               indent_ranks.json), the two "## Time-step error control" sections (camclay9.step_control_study,
               step_control.json), "## FE solver: the triaxial main job" (camclay9.fe_main_job_study,
               fe_main_job.json), "## FE solver: defaults by measurement" (camclay9.fe_solver_study,
               fe_solver.json), "## Indentation: 3D half model, sector and axisymmetric twin"
               (camclay9.indent_models_study, indent_models.json), "## FE scaling: 1 and 2 ranks, direct and GAMG"
               (camclay9.fe_scaling_study, fe_scaling.json), "## CalculiX on the same mesh (issue 13)"
               (camclay9.calculix_study, calculix.json), "## Indentation speed: the contact solve and the physics"
               (camclay9.indent_speed_study, indent_speed.json) and "## 3D indentation: mesh convergence and the
               cheapest model" (camclay9.indent3d_study, indent_convergence.json); a section's reading written by
               hand (bench/*_conclusions.md of this repository) is part of what its generator writes;
             * every quote of camclay9.doc_quotes (README.md, the hand-written readings): its text, with its
               numbers computed from the stores, must stand in its document.
  --write    put the stores' numbers into the quotes' places in the documents (where a quote's text is found with
             other numbers in it), then write those sections and docs/paper.md from the stores.
  --root     the tree whose README.md, docs/ and docs/results/ are read (default: this repository); the
             generators' own text (bench/*_conclusions.md) is always this repository's.

CTest docs.numbers runs the check; tests/tools/test_doc_numbers.py shows it failing on a hand edit.
"""
import argparse
import difflib
import sys
from pathlib import Path

from camclay9 import (adapt_study, calculix_study, calibrate_study, contact_solver_study, coverage_study, doc_quotes,
                      fe_main_job_study, fe_scaling_study, fe_solver_study, fe_triaxial_study, half_model_study, indent3d_study, indent_models_study,
                      loading_steps_study, error_floor_study, kink_steps_study, paper_measures_study, blas_kernels_study,
                      indent_ranks_study, indent_speed_study, paper_doc, point_creep_study, results_store, step_control_study,
                      time_error_study, umat_time_study)
from camclay9 import indent2d_study as i2d

ROOT = Path(__file__).resolve().parents[1]

# the sections written by a generator module from its own store alone: its STORE, and TITLE with section(store, root),
# or sections(store) for a store behind several sections ({title: text})
STUDIES = (adapt_study, contact_solver_study, fe_triaxial_study, coverage_study, time_error_study, umat_time_study,
           point_creep_study, calibrate_study, indent_ranks_study, step_control_study, fe_main_job_study, indent_models_study,
           fe_scaling_study, calculix_study, fe_solver_study, indent_speed_study, indent3d_study, half_model_study,
           loading_steps_study, error_floor_study, kink_steps_study, paper_measures_study, blas_kernels_study)

def section_of(text, title):
    """The section of a '## ' Markdown file that starts with title, up to the next '## ' (as camclay9.performance_doc
    replaces it); None if absent."""
    if title not in text:
        return None
    rest = text[text.index(title):]
    end = rest.find("\n## ", 1)
    return rest if end < 0 else rest[:end + 1]


def generated(store_dir):
    """{(document, section title or None): the text its generator writes from the store}."""
    paper = results_store.load("paper", store_dir)
    out = {}
    if paper:
        out[("docs/paper.md", None)] = paper_doc.render_store(paper)
        out[("docs/performance.md", paper_doc.PERFORMANCE_TITLE)] = paper_doc.performance_section(paper["meta"])
    s2 = results_store.load(i2d.STORE, store_dir)
    if s2:
        out[("docs/performance.md", i2d.TITLE)] = i2d.section(s2, paper, ROOT)
    for study in STUDIES:
        s = results_store.load(study.STORE, store_dir)
        texts = (study.sections(s) if hasattr(study, "sections") else {study.TITLE: study.section(s, ROOT)}) if s else {}
        for title, text in texts.items():
            out[("docs/performance.md", title)] = text
    return out


def diff_lines(want, have, name):
    d = list(difflib.unified_diff(have.splitlines(), want.splitlines(), f"{name} (the document)",
                                  f"{name} (from the store)", n=0, lineterm=""))
    return d[:12] + ([f"... {len(d) - 12} more lines"] if len(d) > 12 else [])


def check(root):
    store_dir = Path(root) / "docs" / "results"
    problems = []
    for (doc, title), want in generated(store_dir).items():
        text = (Path(root) / doc).read_text(encoding="utf-8")
        have = text if title is None else section_of(text, title)
        if have is None:
            problems.append(f"{doc}: no section '{title}'")
        elif have.rstrip("\n") != want.rstrip("\n"):
            problems.append(f"{doc}{', ' + title if title else ''}: differs from its store\n"
                            + "\n".join(diff_lines(want, have, doc)))
    ns = doc_quotes.namespace(store_dir)
    for q in doc_quotes.QUOTES:
        try:
            doc, want = q[0], doc_quotes.render(q[1], ns)
        except doc_quotes.QuoteError as e:
            problems.append(f"{q[0]}: {e}: the text that quotes it must be rewritten for the store's numbers")
            continue
        if want not in (Path(root) / doc).read_text(encoding="utf-8"):
            near = doc_quotes.find(q[1], (Path(root) / doc).read_text(encoding="utf-8"))
            problems.append(f"{doc}: the quote '{want}' (numbers from the store) is not in the document"
                            + (f"; it has '{near}'" if near else " (nor its text with other numbers)"))
    return problems


def write(root):
    """The quotes' numbers first (some stand in a reading, bench/*_conclusions.md, that a section carries), then the
    generated sections and docs/paper.md."""
    store_dir = Path(root) / "docs" / "results"
    ns = doc_quotes.namespace(store_dir)
    for q in doc_quotes.QUOTES:
        p = Path(root) / q[0]
        text = p.read_text(encoding="utf-8")
        try:
            near, want = doc_quotes.find(q[1], text), doc_quotes.render(q[1], ns)
        except doc_quotes.QuoteError as e:
            print(f"{q[0]}: {e}")
            continue
        if near and near != want:
            p.write_text(text.replace(near, want, 1), encoding="utf-8")
            print(f"{q[0]}: '{near}' -> '{want}'")
        elif not near:
            print(f"{q[0]}: the quote's text is not in the document: {want}")
    for (doc, title), want in generated(store_dir).items():
        p = Path(root) / doc
        text = p.read_text(encoding="utf-8")
        if title is None:
            text = want
        else:
            have = section_of(text, title)
            text = text.replace(have, want.rstrip("\n") + have[len(have.rstrip("\n")):]) if have else text
        p.write_text(text, encoding="utf-8")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="write the documents' numbers from the store")
    ap.add_argument("--root", default=str(ROOT), help="the tree to read (default: this repository)")
    a = ap.parse_args(argv)
    if a.write:
        write(a.root)
        return 0
    problems = check(a.root)
    for p in problems:
        print(p)
    n = len(doc_quotes.QUOTES) + len(generated(Path(a.root) / "docs" / "results"))
    print(f"doc_numbers: {n - len(problems)} of {n} checks agree with the store" + ("" if problems else " (all)"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
