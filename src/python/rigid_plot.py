#!/usr/bin/python3
"""Launcher of `rigid plot` (rigidpy.plot, the same as `python3 -m rigidpy.plot` from this folder): the
rigid executable runs this file, and the folder a script is in is on Python's path, so the package
beside it is found without installing it."""
import sys

from rigidpy.plot import main

if __name__ == "__main__":
    sys.exit(main())
