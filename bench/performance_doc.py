"""docs/performance.md is made of sections, one per benchmark, each starting with a '## ' title: a
benchmark replaces its own section and leaves the others. Also a command line for the shell scripts:
    python3 bench/performance_doc.py "## Title" < section.md
"""
import sys
from pathlib import Path

PERFORMANCE = Path(__file__).resolve().parents[1] / "docs" / "performance.md"
HEADER = "# Performance\n\nBenchmarks print numbers and write them here; none is a timed test.\n"


def replace_section(title, section, path=PERFORMANCE):
    """Replace the section that starts with 'title' (up to the next '## ') by 'section', or append it."""
    text = path.read_text() if path.exists() else HEADER
    if title in text:
        head, _, rest = text.partition(title)
        tail = rest[rest.find("\n## "):] if "\n## " in rest else ""
        text = head + section.rstrip("\n") + "\n" + tail
    else:
        text = text.rstrip() + "\n\n" + section
    path.write_text(text)


if __name__ == "__main__":
    replace_section(sys.argv[1], sys.stdin.read())
