#!/usr/bin/python3
"""Launcher of `rigid plot`: rigidpy.plot, the same as `python3 -m rigidpy.plot` from this folder.
The rigid executable runs this file; a script's folder is on Python's path, so the package beside
it is found without installing it."""
import sys

from rigidpy.plot import main

if __name__ == "__main__":
    sys.exit(main())
