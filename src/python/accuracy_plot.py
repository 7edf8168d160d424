#!/usr/bin/python3
"""Launcher of the figure and table of `rigid study accuracy`: rigidpy.accuracy, the same as `python3 -m rigidpy.accuracy` from this folder.
The rigid executable runs this file; a script's folder is on Python's path, so the package beside
it is found without installing it."""
import sys

from rigidpy.accuracy import main

if __name__ == "__main__":
    sys.exit(main())
