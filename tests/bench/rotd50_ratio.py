"""RotD50 / GMRotI50 PGA over the PEER records of ../shared/waveforms/peer (docs/hazard.md, "GMRotI50
against RotD50"): each record's two horizontals through `rigid motion info --json`, the ratio's
median, mean, 5-95 % and the standard deviation of its logarithm printed.

    /usr/bin/python3 tests/bench/rotd50_ratio.py build/bin/rigid [../shared/waveforms/peer]

A record is the horizontals of one PEER sequence number (RSN...), or of one name stem; verticals
(names ending -V, UD, DWN, UP, BHZ.00) are left out; records whose horizontals cannot be read as a
pair are named and skipped."""
import collections
import glob
import json
import math
import os
import re
import statistics
import subprocess
import sys

VERTICAL = re.compile(r"(-V|UD|DWN|UP|BHZ\.00)$")


def records(folder):
    sets = collections.defaultdict(list)
    for path in sorted(glob.glob(os.path.join(folder, "*", "*.AT2"))):
        name = os.path.basename(path)[:-4]
        if VERTICAL.search(name):
            continue
        sets[name.split("_")[0] if name.startswith("RSN") else re.sub(r"\d+$", "", name)].append(path)
    return sets


def main(rigid, folder):
    ratios = []
    for key, files in records(folder).items():
        if len(files) != 2:
            print(f"skipped {key}: {len(files)} horizontals")
            continue
        r = subprocess.run([rigid, "motion", "info", ",".join(files), "--json"], capture_output=True, text=True)
        if r.returncode:
            print(f"skipped {key}: {r.stderr.strip()[:120]}")
            continue
        info = json.loads(r.stdout.splitlines()[0])
        ratios.append(info["rotd50_pga_g"] / info["gmroti50_pga_g"])
    if len(ratios) < 2:
        print("fewer than 2 records read")
        return 1
    q = statistics.quantiles(ratios, n=20)
    print(f"{len(ratios)} records: RotD50/GMRotI50 PGA median {statistics.median(ratios):.3f}, mean "
          f"{statistics.mean(ratios):.3f}, 5-95 % {q[0]:.3f}-{q[-1]:.3f}, sd of ln {statistics.stdev(map(math.log, ratios)):.3f}")
    return 0


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.normpath(os.path.join(here, "..", "..", "..", "shared", "waveforms", "peer"))
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else default))
