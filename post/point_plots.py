#!/usr/bin/env python3
"""Plots of one material-point run of the Cam-Clay IX driver.

    python3 post/point_plots.py RUN_DIR [--out DIR]

What it reads and writes: camclay9.point_plots (python/camclay9/point_plots.py), which this command line runs.
"""
import sys

from camclay9.point_plots import main

if __name__ == "__main__":
    sys.exit(main())
