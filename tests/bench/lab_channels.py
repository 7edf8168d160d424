#!/usr/bin/env python3
"""Which channel of a shake-table recording should drive the pedestal: the accelerometer
(band-passed), the displacement transducer (band-passed, differentiated twice), or both combined
(the displacement below 2 Hz, the accelerometer above)?

Over every test of a lab's sheet (default ../shared/shaketable/tests.csv), runs
`rigid motion info --lab FILE --json` once per channel with the default format (band-pass
0.1-25 Hz, order 4, zero-phase) and prints the median and 5-95 % range of the two single
channels' ratio, and each channel's PGA, PGV/PGA and PGD against the sheet (the table's stroke
bounds a physical PGD).

With --spectra, also reads every 5th recording with numpy and prints, per frequency band, the
ratio of the accelerometer's Fourier amplitude to the twice-differentiated displacement's (w^2 |X|):
where the two transducers agree, and where each one is noise.

usage: lab_channels.py RIGID [TESTS.csv] [--csv OUT.csv] [--spectra]
"""
import csv
import json
import os
import subprocess
import sys

import numpy as np


def info(rigid, path, channel):
    out = subprocess.run([rigid, "motion", "info", "--json", "--lab", path, "--lab-channel", channel],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def spread(v):
    v = np.asarray(v, float)
    return "median %.3f, 5-95 %% %.3f-%.3f, min %.3f, max %.3f" % (
        np.median(v), np.percentile(v, 5), np.percentile(v, 95), v.min(), v.max())


def spectra(rows, root):
    bands = [(0.1, 0.3), (0.3, 0.6), (0.6, 1), (1, 2), (2, 5), (5, 10), (10, 18), (18, 25)]
    dt, g, inch_per_volt = 1 / 800.0, 9.80665, 5.9797e-4
    ratios = []
    for row in rows[::5]:
        d = np.loadtxt(os.path.join(root, row["file"]), skiprows=1)
        a = (d[:, 1] - d[:, 1].mean()) * g
        x = (d[:, 2] - d[:, 2].mean()) * inch_per_volt * 0.0254
        f = np.fft.rfftfreq(len(a), dt)
        fa, fx = np.abs(np.fft.rfft(a)), np.abs(np.fft.rfft(x)) * (2 * np.pi * f) ** 2
        ratios.append([np.sqrt((fa[(f >= lo) & (f < hi)] ** 2).sum() / (fx[(f >= lo) & (f < hi)] ** 2).sum())
                       for lo, hi in bands])
    for (lo, hi), r in zip(bands, np.array(ratios).T):
        print("%5.1f-%4.1f Hz accelerometer / differentiated displacement amplitude: %s" % (lo, hi, spread(r)))


def main():
    args = sys.argv[1:]
    want_spectra = "--spectra" in args
    if want_spectra:
        args.remove("--spectra")
    out_csv = None
    if "--csv" in args:
        i = args.index("--csv")
        out_csv = args[i + 1]
        del args[i:i + 2]
    rigid = os.path.abspath(args[0])
    sheet = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared",
                                                       "shaketable", "tests.csv")
    root = os.path.dirname(os.path.abspath(sheet))
    with open(sheet) as f:
        rows = list(csv.DictReader(f))
    table = []
    for row in rows:
        path = row["file"] if os.path.isabs(row["file"]) else os.path.join(root, row["file"])
        entry = {"test_no": row["test_no"], "overturned": row.get("overturned", ""), "sheet_pga_g": float(row["pga_g"]),
                 "sheet_pgv_pga_s": float(row["pgv_over_pga_s"])}
        for ch, name in (("acc", "acceleration"), ("disp", "displacement"), ("comb", "combined")):
            j = info(rigid, path, name)
            entry.update({ch + "_pga_g": j["pga_g"], ch + "_pgv_m_s": j["pgv_m_s"], ch + "_pgv_pga_s": j["pgv_pga_s"],
                          ch + "_pgd_m": j["pgd_m"]})
        table.append(entry)
    col = lambda k: np.array([r[k] for r in table])
    print("%d tests of %s" % (len(table), sheet))
    print("PGA displacement/acceleration channel:      " + spread(col("disp_pga_g") / col("acc_pga_g")))
    print("PGV displacement/acceleration channel:      " + spread(col("disp_pgv_m_s") / col("acc_pgv_m_s")))
    print("PGV/PGA displacement/acceleration channel:  " + spread(col("disp_pgv_pga_s") / col("acc_pgv_pga_s")))
    for ch in ("acc", "disp", "comb"):
        r = col(ch + "_pga_g") / col("sheet_pga_g")
        q = col(ch + "_pgv_pga_s") / col("sheet_pgv_pga_s")
        print("%-4s PGA / sheet pga_g:          %s; |diff| median %.3f" % (ch, spread(r), np.median(np.abs(r - 1))))
        print("%-4s PGV/PGA / sheet's:          %s; |diff| median %.3f" % (ch, spread(q), np.median(np.abs(q - 1))))
        print("%-4s PGD (m):                    %s" % (ch, spread(col(ch + "_pgd_m"))))
    if want_spectra:
        spectra(rows, root)
    big = np.abs(col("disp_pga_g") / col("acc_pga_g") - 1) > 0.2
    print("tests whose channels differ by more than 20 %% in PGA: %d" % big.sum())
    if out_csv:
        with open(out_csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            w.writeheader()
            w.writerows(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
