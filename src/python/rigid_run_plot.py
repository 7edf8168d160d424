#!/usr/bin/python3
"""Launcher of `rigid run --plot/--animate`: rigidpy.history_figure, the same as
`python3 -m rigidpy.history_figure` from this folder. The rigid executable runs this file after the
run, on the history table it wrote; a script's folder is on Python's path, so the package beside it
is found without installing it."""
import sys

from rigidpy.history_figure import main

if __name__ == "__main__":
    sys.exit(main())
