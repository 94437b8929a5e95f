#!/usr/bin/env python3
"""Plots of a triaxial creep run of the FE driver (input/triaxial*.yaml): the axial creep strain with its
Lomnitz fit beside the paper's (Yin, Liu & Borja 2021, Fig. 17) and the per-frame axial viscoplastic strain
(their Fig. 18).

Usage: post/triaxial_plots.py RUN_DIR [--theta 0|90]     (writes creep.png, frames.png, creep_fit.json)

What it plots and prints: camclay9.triaxial_plots (python/camclay9/triaxial_plots.py), which this command
line runs.
"""
import sys

from camclay9.triaxial_plots import main

if __name__ == "__main__":
    sys.exit(main())
