#!/usr/bin/env python3
"""Replace one section of docs/performance.md (camclay9.performance_doc), for the shell scripts:
    python3 bench/performance_doc.py "## Title" < section.md
"""
import sys

from camclay9.performance_doc import replace_section

if __name__ == "__main__":
    replace_section(sys.argv[1], sys.stdin.read())
