#!/usr/bin/python3
"""Launcher of the fits of `rigid shaketable fragility`: rigidpy.shaketable, the same as `python3 -m rigidpy.shaketable` from this folder.
The rigid executable runs this file; a script's folder is on Python's path, so the package beside
it is found without installing it."""
import sys

from rigidpy.shaketable import main

if __name__ == "__main__":
    sys.exit(main())
