#!/usr/bin/python3
"""Launcher of `rigid fragility` and `rigid hazard`: rigidpy.fragility, the same as
`python3 -m rigidpy.fragility` from this folder. The rigid executable runs this file; a script's folder is on Python's path, so the package beside
it is found without installing it."""
import sys

from rigidpy.fragility import main

if __name__ == "__main__":
    sys.exit(main())
