"""Writes models/hazard/synthetic_logic_tree/: a SYNTHETIC hazard model in the layout of an
OpenQuake classical calculation's CSV export (realizations_1.csv and one
hazard_curve-rlz-NNN-PGA_1.csv per branch, PoE over a 1-year investigation time), for the worked
example of `rigid hazard reweight` (README, docs/hazard.md). Not a real site.

Nine branches: three activity rates (2.5e-5, 5e-5 and 1e-4 per year at 1 g; weights 0.3, 0.4, 0.3)
times three slopes of the power-law curve H(a) = rate a^-k (k 1.8, 2.2, 2.6: weights 0.25, 0.5,
0.25).

    /usr/bin/python3 models/hazard/synthetic_logic_tree.py
"""
import math
import os

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "synthetic_logic_tree")
LEVELS = [0.05 * (80 ** (i / 29)) for i in range(30)]  # 0.05-4 g
RATES = (("A", 2.5e-5, 0.3), ("B", 5e-5, 0.4), ("C", 1e-4, 0.3))
SLOPES = (("a", 1.8, 0.25), ("b", 2.2, 0.5), ("c", 2.6, 0.25))


def main():
    os.makedirs(HERE, exist_ok=True)
    branches = [(f"{r}~{s}", rate, k, wr * ws) for r, rate, wr in RATES for s, k, ws in SLOPES]
    with open(os.path.join(HERE, "realizations_1.csv"), "w") as f:
        f.write("#,,\"synthetic hazard model for Rigid's worked example (models/hazard/synthetic_logic_tree.py)\"\n")
        f.write("rlz_id,branch_path,weight\n")
        for i, (path, _, _, w) in enumerate(branches):
            f.write(f"{i},{path},{w:.7E}\n")
    for i, (path, rate, k, _) in enumerate(branches):
        with open(os.path.join(HERE, f"hazard_curve-rlz-{i:03d}-PGA_1.csv"), "w") as f:
            f.write("#" + "," * (len(LEVELS) + 2) + f"\"generated_by='models/hazard/synthetic_logic_tree.py', "
                    f"kind='rlz-{i:03d}', investigation_time=1.0, imt='PGA'\"\n")
            f.write("lon,lat,depth," + ",".join(f"poe-{a:.7f}" for a in LEVELS) + "\n")
            f.write("0.00000,0.00000,0.00000," + ",".join(f"{-math.expm1(-rate * a ** -k):.6E}" for a in LEVELS) + "\n")


if __name__ == "__main__":
    main()
