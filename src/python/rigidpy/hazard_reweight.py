"""`rigid hazard reweight`: rocks that survived their exposure ages reweight the branches of an
OpenQuake logic tree (logic_tree_weights.py: Baker et al. 2013; --prune: Stirling et al. 2021).

    rigid hazard reweight OQ_DIR --rock CUBE[:OBJECT] --age YEARS [--age-sd YEARS] [--age-dist normal|lognormal]
                          [--rock ... --age ...]... [--site LON,LAT] [--prune P] [--json] [--csv FILE]
                          [--plot FILE] [--write-curves DIR] [--fragility-uncertainty bootstrap|none]

--age, --age-sd and --age-dist belong to the --rock before them. Exit status 0 done, 2 bad input.
"""
import argparse
import csv
import json
import math
import os
import sys
import types

import numpy as np

from . import files as cube_files
from . import logic_tree_weights as lt
from . import openquake_export as oq
from .command_line import OneLineParser, exit_status
from .errors import InputError
from .exposure_age import KINDS, ExposureAge
from .fragility_report import fmt_probability, json_clean
from .hazard_command import RockFragility, check_figure_path, is_pooled, object_fragility, pooled_fragility, select_rock

BAKER = "survival weights w' = w S / sum w S (Baker et al. 2013)"


# --------------------------------------------------------------------------------------------
# the command line: --age, --age-sd and --age-dist attach to the --rock before them


class RockOption(argparse.Action):
    def __call__(self, parser, namespace, values, option_string=None):
        rocks = getattr(namespace, "rocks", None) or []
        if option_string == "--rock":
            rocks.append({"rock": values})
        elif not rocks:
            parser.error(f"{option_string} before any --rock: give each rock's age after its --rock")
        else:
            key = {"--age": "age", "--age-sd": "age_sd", "--age-dist": "age_dist"}[option_string]
            if key in rocks[-1]:
                parser.error(f"{option_string} given twice for --rock {rocks[-1]['rock']}")
            rocks[-1][key] = values
        namespace.rocks = rocks


def build_parser():
    p = OneLineParser(prog="rigid hazard reweight",
                      description="Reweight the branches of an OpenQuake logic tree by the survival of rocks over "
                                  "their exposure ages (Baker et al. 2013).",
                      epilog="Exit status: 0 done, 2 bad input, 1 internal error.")
    p.add_argument("oq_dir", help="folder of an OpenQuake classical calculation's CSV export (realizations_*.csv and "
                                  "hazard_curve-rlz-NNN-PGA_*.csv)")
    p.add_argument("--rock", action=RockOption, required=True, metavar="CUBE[:OBJECT]",
                   help="a rock: a campaign cube and its object (repeatable: the rocks' survivals multiply)")
    p.add_argument("--age", action=RockOption, type=float, metavar="YEARS", help="the rock's exposure age (years)")
    p.add_argument("--age-sd", action=RockOption, type=float, metavar="YEARS",
                   help="its one-sigma uncertainty (years); default: the age is known")
    p.add_argument("--age-dist", action=RockOption, choices=KINDS,
                   help="the age's distribution with --age-sd: normal (truncated at 0, the default) or lognormal")
    p.add_argument("--site", help="the site of a multi-site export: lon,lat (or a row's 0-based index)")
    p.add_argument("--prune", type=float, metavar="P",
                   help="Stirling et al.'s rule instead of survival weights: drop branches whose survival is below P "
                        "and renormalise the others' prior weights")
    p.add_argument("--fragility-uncertainty", choices=("bootstrap", "none"), default="bootstrap",
                   help="integrate the survival over the fragility's bootstrap replicates (default) or use the fitted "
                        "fragility alone")
    p.add_argument("--json", action="store_true", help="JSON on standard output instead of the table")
    p.add_argument("--csv", help="write the branches (rlz_id, branch_path, weights, rate, survival) to this CSV")
    p.add_argument("--plot", help="figure: prior and posterior mean and fractile curves, and each branch's survival")
    p.add_argument("--write-curves", metavar="DIR",
                   help="write the reweighted calculation in OpenQuake's CSV layout (realizations with the posterior "
                        "weights, the realizations' curves, posterior mean and quantile curves)")
    p.add_argument("--pgv-pga", type=float, help="PGV/PGA (s) at which each rock's vector fit gives a lognormal "
                                                 "(default: the median of its records)")
    p.add_argument("--bootstrap", type=int, default=200, help="bootstrap resamples of records (default 200)")
    p.add_argument("--seed", type=int, default=1, help="seed of the bootstrap (default 1)")
    p.add_argument("--require-complete", action="store_true",
                   help="refuse a cube whose campaign has not run every cell")
    return p


def main(argv):
    args = build_parser().parse_args(joined_site(argv))
    return exit_status("rigid hazard reweight", lambda: run(args), args)


def joined_site(argv):
    """`--site -122.5,38.1` as `--site=-122.5,38.1`: argparse takes a value that starts with '-' and
    holds a comma for an option, and western longitudes are negative."""
    out, i = [], 0
    while i < len(argv):
        if argv[i] == "--site" and i + 1 < len(argv):
            out.append(f"--site={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


# --------------------------------------------------------------------------------------------


def check_options(args):
    if args.prune is not None and not 0 < args.prune < 1:
        raise InputError(f"--prune {args.prune:g}: must be a survival probability between 0 and 1")
    if args.bootstrap < 20 or args.bootstrap > 100000:
        raise InputError(f"--bootstrap {args.bootstrap}: must be 20-100000")
    if not 0 <= args.seed < 2 ** 63:
        raise InputError(f"--seed {args.seed}: must be a whole number from 0 to 2^63 - 1")
    if args.pgv_pga is not None and not (args.pgv_pga > 0 and math.isfinite(args.pgv_pga)):
        raise InputError(f"--pgv-pga {args.pgv_pga}: must be a positive number of seconds")
    for r in args.rocks:
        if "age" not in r:
            raise InputError(f"--rock {r['rock']}: no --age after it (each rock's exposure age, years)")
        r["exposure"] = ExposureAge(r["age"], r.get("age_sd"), r.get("age_dist") or "normal")
        if r.get("age_dist") and not r.get("age_sd"):
            raise InputError(f"--rock {r['rock']}: --age-dist without --age-sd")
        cube, _, name = r["rock"].rpartition(":")
        if not cube or not os.path.isfile(cube):  # no object named, or a ':' inside the path
            cube, name = r["rock"], None
        if not os.path.isfile(cube):
            raise InputError(f"--rock {r['rock']}: {cube}: no such cube")
        r["cube"], r["object"] = cube, name or None
    inputs = [r["cube"] for r in args.rocks]
    if args.csv:
        cube_files.refuse_output_over_inputs(args.csv, "--csv", inputs)
    if args.plot:
        check_figure_path(args.plot, inputs)
    if args.write_curves and os.path.abspath(args.write_curves) == os.path.abspath(args.oq_dir):
        raise InputError(f"--write-curves {args.write_curves}: the export being read; choose another folder")


def rock_fragility(args, r):
    """The rock r's fragility from its cube, fitted as `rigid hazard` fits it."""
    fit_args = types.SimpleNamespace(cube=r["cube"], object=r["object"], variant=None, pgv_pga=args.pgv_pga,
                                     pgv_pga_dist=None, bootstrap=args.bootstrap, seed=args.seed, level=0.9,
                                     require_complete=args.require_complete, command="hazard")
    cube, objs = select_rock(fit_args)
    if is_pooled(cube, fit_args):
        rock = pooled_fragility(fit_args, cube, objs)[0]
    else:
        rock = object_fragility(fit_args, cube, objs[0])[0]
    if args.fragility_uncertainty == "none":
        rock = RockFragility(rock.label, rock.mixture, [], "the fitted fragility alone (--fragility-uncertainty none)")
    return rock


def run(args):
    check_options(args)
    tree = oq.read_export(args.oq_dir, args.site)
    rocks = []
    for r in args.rocks:
        fragility = rock_fragility(args, r)
        rocks.append(lt.RockEvidence(f"{fragility.label} of {r['cube']}", fragility, r["exposure"]))
    evidence = lt.branch_evidence(tree.branches, rocks)
    survival = np.array([np.prod([s for _, s in per_rock]) for per_rock in evidence])
    prior = tree.weights()
    posterior = lt.posterior_weights(prior, survival, args.prune)
    if posterior is None:
        why = (f"every branch has survival below --prune {args.prune:g}" if args.prune is not None
               else "every branch gives the rocks survival 0")
        raise InputError(f"{tree.realizations_path}: {why}: the rocks rule out the whole logic tree; no posterior")
    poes = tree.poes()
    before, after = lt.curve_statistics(poes, prior), lt.curve_statistics(poes, posterior)
    result = document(args, tree, rocks, evidence, survival, prior, posterior, before, after)
    if args.json:
        json.dump(json_clean(result), sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print_report(result)
    if args.csv:
        write_branches_csv(args.csv, result, [r["cube"] for r in args.rocks])
    if args.write_curves:
        written = oq.write_export(args.write_curves, tree, posterior, after,
                                  f"rigid hazard reweight: {result['method']}")
        if not args.json:
            print(f"wrote {len(written)} files to {args.write_curves}")
    if args.plot:
        from .reweight_figure import draw
        draw(args.plot, result, [r["cube"] for r in args.rocks])
        if not args.json:
            print(f"wrote {args.plot}")
    return 0


def document(args, tree, rocks, evidence, survival, prior, posterior, before, after):
    t = tree.investigation_time
    method = (f"Stirling et al. (2021) pruning: branches with survival below {args.prune:g} dropped, the rest "
              f"renormalised" if args.prune is not None else BAKER)
    branches = []
    for b, per_rock, s, w0, w1 in zip(tree.branches, evidence, survival, prior, posterior):
        row = {"rlz_id": b.rlz_id, "branch_path": b.branch_path, "prior_weight": float(w0),
               "toppling_rate_per_year": float(sum(rate for rate, _ in per_rock)), "survival": float(s),
               "posterior_weight": float(w1)}
        if len(rocks) > 1:
            row["rocks"] = [{"rock": r.name, "toppling_rate_per_year": rate, "survival": sr}
                            for r, (rate, sr) in zip(rocks, per_rock)]
        branches.append(row)
    pga_before = lt.pga_at_rates(tree.imls, before["mean"], t)
    pga_after = lt.pga_at_rates(tree.imls, after["mean"], t)
    pga = []
    for rate in lt.RATES_OF_INTEREST:
        entry = {"annual_rate": rate, "prior_mean_pga_g": pga_before[rate], "posterior_mean_pga_g": pga_after[rate],
                 "change_percent": 100 * (pga_after[rate] / pga_before[rate] - 1)}
        for q in lt.FRACTILES:
            name = lt.fractile_name(q)
            entry[f"prior_{name}_pga_g"] = lt.pga_at_rates(tree.imls, before[name], t)[rate]
            entry[f"posterior_{name}_pga_g"] = lt.pga_at_rates(tree.imls, after[name], t)[rate]
        pga.append(entry)
    comparison = {}
    for name, (path, poe) in tree.statistics.items():
        ours = before[name] if name in before else None
        if ours is not None:
            comparison[name] = {"file": path, "max_abs_poe_difference": float(np.max(np.abs(ours - poe)))}
    return {
        "openquake_export": tree.folder, "realizations_file": tree.realizations_path, "site": tree.site,
        "investigation_time_years": t, "method": method, "prune": args.prune,
        "independence": "the rocks' survivals multiply: given a branch, they topple independently",
        "rocks": [{"rock": r.name, "exposure_age": r.age.describe(), "age_years": r.age.years,
                   "age_sd_years": r.age.sd_years, "age_distribution": r.age.kind,
                   "fragility": [{"weight": w, "theta_g": th, "beta": be} for w, th, be in r.fragility.mixture],
                   "fragility_uncertainty": r.fragility.source,
                   "fragility_members": [{"weight": w, "lognormals": [{"weight": a, "theta_g": th, "beta": be}
                                                                      for a, th, be in m]}
                                         for w, m in r.fragility.members]} for r in rocks],
        "branches": branches,
        "branches_kept": int(np.count_nonzero(posterior)),
        "curves": {"pga_g": [float(a) for a in tree.imls],
                   "prior": {k: annual(v, t) for k, v in before.items()},
                   "posterior": {k: annual(v, t) for k, v in after.items()},
                   "units": "annual rate of exceedance"},
        "pga_at_annual_rate": pga,
        "openquake_statistics": comparison,
    }


def annual(poe, t):
    return [float(v) for v in lt.annual_rates(poe, t)]


# --------------------------------------------------------------------------------------------
# outputs


CSV_COLUMNS = ("rlz_id", "branch_path", "prior_weight", "toppling_rate_per_year", "survival", "posterior_weight")


def write_branches_csv(path, result, inputs):
    rocks = result["rocks"]

    def write(tmp):
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            extra = [f"{c}_rock{i + 1}" for i in range(len(rocks)) for c in ("toppling_rate_per_year", "survival")] \
                if len(rocks) > 1 else []
            w.writerow(list(CSV_COLUMNS) + extra)
            for b in result["branches"]:
                row = [b["rlz_id"], b["branch_path"]] + [repr(b[c]) for c in CSV_COLUMNS[2:]]
                for r in b.get("rocks", []):
                    row += [repr(r["toppling_rate_per_year"]), repr(r["survival"])]
                w.writerow(row)
    cube_files.write_output(path, "--csv", inputs, write)


# Rows of the branch table printed in full; a larger tree prints the branches that changed most.
PRINTED_BRANCHES = 30


def print_report(r):
    print(f"rigid hazard reweight: OpenQuake export {r['openquake_export']} ({os.path.basename(r['realizations_file'])}: "
          f"{len(r['branches'])} branches), site {r['site']}, investigation time {r['investigation_time_years']:g} years")
    for rock in r["rocks"]:
        f = rock["fragility"]
        frag = (f"theta {f[0]['theta_g']:.3f} g, beta {f[0]['beta']:.3f}" if len(f) == 1
                else f"a mixture of {len(f)} lognormals")
        print(f"  rock {rock['rock']}: exposure age {rock['exposure_age']}; fragility {frag}; its uncertainty: "
              f"{rock['fragility_uncertainty']} ({len(rock['fragility_members'])} member(s))")
    print(f"  method: {r['method']}")
    rows = r["branches"]
    if len(rows) > PRINTED_BRANCHES:
        rows = sorted(rows, key=lambda b: -abs(b["posterior_weight"] - b["prior_weight"]))[:PRINTED_BRANCHES]
        print(f"  the {PRINTED_BRANCHES} of {len(r['branches'])} branches whose weight changed most (all: --json, --csv)")
    width = max(11, max(len(b["branch_path"]) for b in rows))
    print(f"  {'rlz':>5}  {'branch_path':<{width}}  {'prior':>8}  {'rate/yr':>10}  {'survival':>8}  {'posterior':>9}")
    for b in rows:
        print(f"  {b['rlz_id']:>5}  {b['branch_path']:<{width}}  {b['prior_weight']:8.4f}  "
              f"{b['toppling_rate_per_year']:10.3e}  {fmt_probability(b['survival']):>8}  {b['posterior_weight']:9.4f}")
    print(f"  branches kept: {r['branches_kept']} of {len(r['branches'])}")
    print("  PGA (g) at annual rate   prior mean  posterior mean  change   prior 5-95 %     posterior 5-95 %")
    for p in r["pga_at_annual_rate"]:
        change = f"{p['change_percent']:+.0f} %" if math.isfinite(p["change_percent"]) else "-"
        print(f"  {p['annual_rate']:<22g}   {fmt_pga(p['prior_mean_pga_g']):>10}  {fmt_pga(p['posterior_mean_pga_g']):>14}"
              f"  {change:>6}   {fmt_pga(p['prior_0.05_pga_g'])}-{fmt_pga(p['prior_0.95_pga_g']):<10}"
              f"  {fmt_pga(p['posterior_0.05_pga_g'])}-{fmt_pga(p['posterior_0.95_pga_g'])}")
    if any(not math.isfinite(p["prior_mean_pga_g"]) for p in r["pga_at_annual_rate"]):
        print("  (-: the curve's levels do not reach that rate)")
    for name, c in r["openquake_statistics"].items():
        print(f"  OpenQuake's own {name} curve ({os.path.basename(c['file'])}): the prior {name} differs by at most "
              f"{c['max_abs_poe_difference']:.1e} in PoE")


def fmt_pga(v):
    return f"{v:.3f}" if math.isfinite(v) else "-"
