#!/usr/bin/python3
"""Launcher of `rigid fragility` and `rigid hazard` (rigidpy.fragility, the same as `python3 -m rigidpy.fragility` from this folder): the
rigid executable runs this file, and the folder a script is in is on Python's path, so the package
beside it is found without installing it."""
import sys

from rigidpy.fragility import main

if __name__ == "__main__":
    sys.exit(main())
