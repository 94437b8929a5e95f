#!/usr/bin/env python3
"""Write the inputs of input/abaqus/ (issues #6 and 21): the decks of camclay9.calculix_inputs (its docstring says
what they hold). Run from anywhere:

    python3 tools/calculix/make_inputs.py [OUTDIR]      (default: input/abaqus)

The files are committed; tests/calculix checks that they equal what this script writes.
"""
import sys
from pathlib import Path

from camclay9.calculix_inputs import write

if __name__ == "__main__":
    default = Path(__file__).resolve().parents[2] / "input" / "abaqus"
    print("\n".join(write(sys.argv[1] if len(sys.argv) > 1 else str(default))))
