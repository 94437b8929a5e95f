#!/usr/bin/env python3
"""Engineering constants <-> (lambda, muT, muL, a, b) of a transversely isotropic elastic frame: the command line of
camclay9.ti_constants (its docstring gives the formulas and conventions; docs/umat.md, the examples).

    tools/ti_constants.py to-lame --Ep .. --En .. --nu-pp .. --nu-pn .. --Gnp ..
    tools/ti_constants.py to-engineering --lam .. --muT .. --muL .. --a .. --b ..
    tools/ti_constants.py isotropic --E .. --nu ..
"""
import sys

from camclay9.ti_constants import main

if __name__ == "__main__":
    sys.exit(main())
