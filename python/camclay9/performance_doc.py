"""docs/performance.md is made of sections, one per benchmark, each starting with a '## ' title: a benchmark replaces
its own section and leaves the others (the benches of bench/, tools/reproduce.py)."""
from camclay9 import results_store
from camclay9.launch import repo_root

HEADER = "# Performance\n\nBenchmarks print numbers and write them here; none is a timed test.\n"


def replace_section(title, section, path=None):
    """Replace the section that starts with 'title' (up to the next '## ') by 'section', or append it. path: the
    document (default: docs/performance.md of the repository, camclay9.repo_root)."""
    path = path or repo_root() / "docs" / "performance.md"
    text = path.read_text() if path.exists() else HEADER
    if title in text:
        head, _, rest = text.partition(title)
        tail = rest[rest.find("\n## "):] if "\n## " in rest else ""
        text = head + section.rstrip("\n") + "\n" + tail
    else:
        text = text.rstrip() + "\n\n" + section
    path.write_text(text)


def publish(title, section, store_name, store, write=True):
    """A bench's section written from its results store (the text its study module makes from `store`, as
    tools/doc_numbers.py checks it): printed; with `write`, it replaces its section of docs/performance.md and the
    store is saved as docs/results/<store_name>.json."""
    print(section)
    if write:
        replace_section(title, section)
        path = results_store.save(store_name, store)
        print(f"written: docs/performance.md ({title}), {path.relative_to(repo_root())}")


def republish(study, write=True):
    """A bench's --from-store: its section written again from the store it keeps (study: the module with STORE, TITLE
    and section(store)), nothing run; a clear error when the store does not exist yet."""
    store = results_store.load(study.STORE)
    if not store:
        raise SystemExit(f"{results_store.path(study.STORE)}: no such store; run the bench first")
    publish(study.TITLE, study.section(store), study.STORE, store, write=write)
