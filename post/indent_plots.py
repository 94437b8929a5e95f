#!/usr/bin/env python3
"""Plots of an indentation run of the FE driver (Yin, Liu & Borja 2021, Figs. 3-15).

Usage: post/indent_plots.py [ph|compare|fields|vectors|profile] RUN... [options] (each subcommand's --help).

The subcommands, their input and conventions: camclay9.indent_plots (python/camclay9/indent_plots.py), which
this command line runs.
"""
import sys

from camclay9.indent_plots import main

if __name__ == "__main__":
    sys.exit(main())
