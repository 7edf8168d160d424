#!/usr/bin/python3
"""Launcher of `rigid shaketable calibrate`'s diagnostic figure: rigidpy.shaketable.calibration_main.
The rigid executable runs this file; a script's folder is on Python's path, so the package beside
it is found without installing it."""
import sys

from rigidpy.shaketable import calibration_main

if __name__ == "__main__":
    sys.exit(calibration_main())
