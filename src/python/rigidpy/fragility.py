"""`rigid fragility` and `rigid hazard`: from a campaign cube to fitted fragilities, exports hazard
codes read, and the probability that a rock survived a hazard model over its exposure age.

    rigid_fragility.py fragility CUBE [--object NAME]... [--variant K] [--pgv-pga S] [--json] [--csv FILE]
                       [--nrml FILE] [--no-store] [--bootstrap N] [--seed N] [--level 0.9]
    rigid_fragility.py hazard CUBE --curve CURVE.csv --age YEARS [--object NAME] [--variant K]
                       [--pgv-pga S | --pgv-pga-dist lognormal:MEDIAN,BETA] [--site ID]
                       [--confidence 0.95] [--plot PNG] [--json]
    rigid_fragility.py hazard reweight OQ_DIR --rock CUBE:OBJECT --age YEARS ...  (hazard_reweight.py)

Fits (fit.py): per PGV/PGA bin a lognormal (theta, beta) on the records of the bin, and
the vector fit P = Phi((u - mu(x)) / sigma(x)) over all records, evaluated at a chosen PGV/PGA;
90 % intervals by bootstrap over records. Hazard (hazard.py): lambda = E[H(C)], survival
exp(-lambda T). Exit status: 0 done, 2 bad input, 1 internal error.

With variants (a cube with a variant axis: epistemic uncertainty, layout at the top of src/io/cube.cpp):
each variant is fitted as an object is; the variants of an object are equally weighted samples of
the epistemic distribution, so the pooled fragility is the mixture P(a) = mean_v P_v(a) of the
lognormals standing for them (the vector fit at the chosen PGV/PGA, or the empirical threshold of a
variant with separated outcomes), reported with its median, the moment-matched lognormal, the
5/50/95 % of theta and beta over variants and the 5-95 % band of P_v(a); the sensitivity of theta
and beta to each varied parameter is sensitivity.py's. `hazard` integrates the pooled fragility
and reports the survival probability's epistemic 5-95 % range over variants beside the aleatory
interval; --variant K uses one variant as if it were an object.
"""
import contextlib
import csv
import json
import math
import os
import sys

try:
    from . import files as cube_files
    from . import nrml
    from .cube import Cube
    from .errors import InputError
    from .fit import DEFAULT_BOOTSTRAP
    from .command_line import OneLineParser, check_completeness, exit_status, warn_incomplete
    from .fragility_report import (csv_rows, json_document, nrml_functions, nrml_range_text, pooled_csv_row,
                                   print_table, print_variant_tables, variant_nrml_functions, vector_coefficients,
                                   vector_nrml_functions)
    from .fragility_store import store
    from .hazard_command import cmd_hazard
    from .object_fits import ObjectFit, analyse_variants, end_progress, start_progress
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"rigid: error: {e}; install python3-numpy python3-h5py python3-scipy python3-matplotlib "
                     f"and run with /usr/bin/python3 (this is {sys.executable})\n")
    sys.exit(2)




def check_nrml_options(args):
    if args.nrml_max_probability != 0 and not 0.5 <= args.nrml_max_probability < 1:
        raise InputError(f"--nrml-max-probability {args.nrml_max_probability}: must be 0 (the campaign's top scale) "
                         f"or in [0.5, 1)")
    if args.nrml_at_pgv_pga is not None:
        if not (args.nrml_at_pgv_pga > 0 and math.isfinite(args.nrml_at_pgv_pga)):
            raise InputError(f"--nrml-at-pgv-pga {args.nrml_at_pgv_pga}: must be a positive number of seconds")
        if not args.nrml:
            raise InputError("--nrml-at-pgv-pga: give --nrml FILE too (the NRML it shapes)")
    if args.nrml_rotd50_ratio is not None and not 0.5 <= args.nrml_rotd50_ratio <= 2:
        raise InputError(f"--nrml-rotd50-ratio {args.nrml_rotd50_ratio}: must be RotD50 / GMRotI50 PGA, between 0.5 "
                         f"and 2 (about 1.0-1.1 for recorded motions)")
    if args.nrml_min_records < 0:
        raise InputError(f"--nrml-min-records {args.nrml_min_records}: must be 0 or more")
    for option, value in (("--nrml-id", args.nrml_id), ("--nrml-asset-category", args.nrml_asset_category),
                          ("--nrml-loss-category", args.nrml_loss_category)):
        if value is not None and (not value.strip() or any(c in value for c in '<>&"')):
            raise InputError(f"{option} {value!r}: must be a non-empty name without < > & \"")


def cmd_fragility(args):
    check_nrml_options(args)
    outputs = [(o, p) for o, p in (("--csv", args.csv), ("--nrml", args.nrml), ("--vector-csv", args.vector_csv)) if p]
    for option, path in outputs:
        cube_files.refuse_output_over_inputs(path, option, [args.cube])
    for i, (option_a, a) in enumerate(outputs):
        for option_b, b in outputs[i + 1:]:
            if cube_files.same_file(a, b) or os.path.abspath(a) == os.path.abspath(b):
                raise InputError(f"{option_a} and {option_b}: the same file {b}")
    if not os.path.isfile(args.cube):
        raise InputError(f"{args.cube}: no such file")
    state = cube_files.campaign_state(args.cube)  # before our own lock, which would look like a campaign's
    # a store holds the cube's lock from the read to the rename: no campaign or second store between
    with contextlib.nullcontext() if args.no_store else cube_files.CubeLock(args.cube):
        return fragility_locked(args, state)


def fit_cube(args, state):
    """(cube, fits, analyses): every chosen object's fits, and per object with variants its
    VariantAnalysis; what `rigid fragility` reports, exports and stores, and rigidpy.fragility returns."""
    cube = Cube(args.cube)
    if args.nrml_at_pgv_pga is not None and cube.variants is not None:
        raise InputError(f"{args.cube}: a cube with variants exports its functions at --pgv-pga S already; "
                         f"give --pgv-pga {args.nrml_at_pgv_pga:g} instead of --nrml-at-pgv-pga")
    check_completeness(cube, state, args)
    objs = cube.select(args.object, args.variant)
    analyses = []
    start_progress(cube, objs, "fragility")
    try:
        if cube.variants is None:
            fits = [ObjectFit(cube, o, args) for o in objs]
        else:
            fits, analyses = analyse_variants(cube, objs, args)
    finally:
        end_progress()
    return cube, fits, analyses


def fragility_locked(args, state):
    cube, fits, analyses = fit_cube(args, state)
    warn_incomplete(args)
    if args.json:
        json.dump(json_document(cube, fits, args, analyses), sys.stdout, indent=1, allow_nan=False)
        print()
    elif cube.variants is None:
        print_table(cube, fits, args)
    else:
        print_variant_tables(cube, fits, analyses, args)
    if args.csv:
        rows = csv_rows(fits) + [pooled_csv_row(a) for a in analyses if a.pooled is not None]

        def write_csv(tmp):
            with open(tmp, "w", newline="") as fh:
                w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
                w.writeheader()
                w.writerows(rows)
        cube_files.write_output(args.csv, "--csv", [args.cube], write_csv)
    if args.nrml:
        skipped, left_out = [], []
        max_p = None if args.nrml_max_probability == 0 else args.nrml_max_probability
        if args.nrml_at_pgv_pga is not None:
            functions, notes = vector_nrml_functions(fits, args.nrml_at_pgv_pga, max_p)
            for note in notes if not args.json else []:
                print(f"note: {note}")
        elif cube.variants is None:
            functions, left_out = nrml_functions(fits, max_p, args.nrml_min_records)
        else:
            functions, skipped = variant_nrml_functions(fits, analyses, max_p)
        if skipped and not args.json:
            print(f"note: no NRML function for {', '.join(skipped)}: an empirical threshold (a step) or no "
                  f"fragility is not a lognormal")
        if left_out and not args.json:
            print(f"note: no NRML function for {', '.join(left_out)}: fewer than --nrml-min-records "
                  f"{args.nrml_min_records} records")
        if not functions:
            raise InputError(f"{args.cube}: no PGV/PGA bin has a finite fit: no NRML written")
        ratio = args.nrml_rotd50_ratio
        if ratio is not None:  # a lognormal of GMRotI50 PGA is one of RotD50 = ratio x GMRotI50, beta unchanged
            functions = [dict(fn, **{k: fn[k] * ratio for k in ("theta_g", "min_iml", "max_iml", "no_damage_limit")})
                         for fn in functions]
        measure = "GMRotI50" if ratio is None else f"RotD50 (taken as {ratio:g} x GMRotI50)"
        tree = nrml.fragility_model(args.nrml_id or os.path.splitext(os.path.basename(args.cube))[0],
                                    f"Overturning fragility of precariously balanced rocks from the Rigid cube "
                                    f"{os.path.basename(args.cube)}: " + (
                                        f"one lognormal function of {measure} PGA (g) per object, its vector fit at the "
                                        f"site's GMRotI50 PGV/PGA {args.nrml_at_pgv_pga:g} s"
                                        if args.nrml_at_pgv_pga is not None else
                                        f"one lognormal function of {measure} PGA (g) per object and PGV/PGA bin (a "
                                        f"site uses the bin holding its PGV/PGA)"
                                        if cube.variants is None else
                                        f"per object one lognormal function of {measure} PGA (g) per variant (id _vK) "
                                        "at the chosen PGV/PGA, and the pooled one (id _pooled: moment-matched "
                                        "lognormal of the equally weighted mixture of the variants)") + nrml_range_text(max_p),
                                    functions, asset_category=args.nrml_asset_category,
                                    loss_category=args.nrml_loss_category)
        cube_files.write_output(args.nrml, "--nrml", [args.cube], lambda tmp: nrml.write(tmp, tree))
    if args.vector_csv:
        write_vector_csv(args, fits)
    if not args.no_store:
        store(args.cube, cube, fits, args, analyses)
    if not args.json:
        wrote = [p for p in (args.csv, args.nrml, args.vector_csv) if p] + ([] if args.no_store else [f"{args.cube} (/fragility)"])
        if wrote:
            print(f"\nwrote {', '.join(wrote)}")
    return 0


def write_vector_csv(args, fits):
    """Each object's vector fit as coefficients a hazard code evaluates at a site's PGV/PGA."""
    rows = [r for r in (vector_coefficients(f) for f in fits) if r is not None]
    if not rows:
        raise InputError(f"{args.cube}: no object has a vector fit with a finite estimate: no --vector-csv written")

    def write(tmp):
        with open(tmp, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows({k: (repr(float(v)) if isinstance(v, float) else v) for k, v in r.items()} for r in rows)
    cube_files.write_output(args.vector_csv, "--vector-csv", [args.cube], write)


# --------------------------------------------------------------------------------------------


def build_parser():
    p = OneLineParser(prog="rigid", description="Fitted fragilities and the survival test of a rock.",
                      epilog="Exit status: 0 done, 2 bad input, 1 internal error.")
    sub = p.add_subparsers(dest="command", required=True, metavar="{fragility,hazard}")

    def common(sp):
        sp.add_argument("cube", help="campaign cube (HDF5)")
        sp.add_argument("--pgv-pga", type=float, help="PGV/PGA (s) at which the vector fit gives a lognormal "
                                                      "(default: the median of the object's records)")
        sp.add_argument("--bootstrap", type=int, default=DEFAULT_BOOTSTRAP,
                        help=f"bootstrap resamples of records (default {DEFAULT_BOOTSTRAP})")
        sp.add_argument("--seed", type=int, default=1, help="seed of the bootstrap (default 1)")
        sp.add_argument("--level", type=float, default=0.9, help="interval level (default 0.9)")
        sp.add_argument("--json", action="store_true", help="JSON on standard output instead of the table")
        sp.add_argument("--require-complete", action="store_true",
                        help="refuse a cube whose campaign has not run every cell (stopped or still running); "
                             "default: fit the cells run so far, with a warning")
        sp.add_argument("--variant", type=int, metavar="K",
                        help="a cube with variants: only variant K (0-based); default: every variant, and "
                             "their pooled fragility")

    f = sub.add_parser("fragility", help="fit fragilities per object: per PGV/PGA bin and at a chosen PGV/PGA")
    common(f)
    f.add_argument("--object", action="append", help="only this object (repeatable; every variant of it); default: all")
    f.add_argument("--csv", help="write one row per object and bin (and the vector fit) to this CSV")
    f.add_argument("--nrml", help="write an OpenQuake NRML 0.5 fragility model (one function per object and bin)")
    f.add_argument("--nrml-at-pgv-pga", type=float, metavar="S",
                   help="the NRML holds one function per object, its vector fit at the site's GMRotI50 PGV/PGA S "
                        "(s), instead of one per PGV/PGA bin")
    f.add_argument("--nrml-rotd50-ratio", type=float, metavar="R",
                   help="the NRML's PGA is RotD50, what NGA-West2 models (and so most hazard models) predict, taken "
                        "as R x the campaign's GMRotI50: theta and the IMLs multiplied by R (docs/hazard.md); "
                        "default: GMRotI50, as fitted")
    f.add_argument("--vector-csv", metavar="FILE",
                   help="write each object's vector fit as coefficients: ln theta = a + b ln(PGV/PGA / 1 s), "
                        "ln beta = c + d ln(PGV/PGA / 1 s), with the PGV/PGA and PGA ranges of its data")
    f.add_argument("--nrml-id", help="id of the NRML fragilityModel (default: the cube's file name without .h5)")
    f.add_argument("--nrml-asset-category", default="buildings",
                   help="assetCategory of the NRML fragilityModel (default buildings, what the engine's exposure "
                        "models use; OpenQuake matches it against the exposure)")
    f.add_argument("--nrml-loss-category", default="structural",
                   help="lossCategory of the NRML fragilityModel (default structural)")
    f.add_argument("--nrml-max-probability", type=float, default=0.99, metavar="P",
                   help="each function's maxIML is the PGA where its lognormal reaches P, or the campaign's top "
                        "scale when higher (OpenQuake holds P at P(maxIML) above it); 0: the campaign's top scale "
                        "(default 0.99)")
    f.add_argument("--nrml-min-records", type=int, default=0, metavar="N",
                   help="leave PGV/PGA bins fitted on fewer than N records out of the NRML (default 0: all; the "
                        "table and CSV flag bins with fewer than 3)")
    f.add_argument("--no-store", action="store_true", help="do not store the fits in the cube's /fragility group")
    f.set_defaults(func=cmd_fragility)

    h = sub.add_parser("hazard", help="toppling rate and survival probability under a PGA hazard curve",
                       epilog="rigid hazard reweight OQ_DIR --rock CUBE:OBJECT --age YEARS ...: reweight the branches "
                              "of an OpenQuake logic tree by the rock's survival (rigid hazard reweight --help)")
    common(h)
    h.add_argument("--object", help="the object (needed when the cube has several)")
    h.add_argument("--curve", required=True, help="hazard curve CSV (PGA g, annual rate; OpenQuake or nshmp-haz layouts)")
    h.add_argument("--site", help="row of a multi-site curve file: its name, lon,lat or 0-based index")
    h.add_argument("--age", type=float, required=True, help="exposure age of the rock (years)")
    h.add_argument("--pgv-pga-dist", help="lognormal:MEDIAN_S,BETA: PGV/PGA distributed (independently of PGA)")
    h.add_argument("--confidence", type=float, default=0.95, help="confidence of the ruling-out test (default 0.95)")
    h.add_argument("--plot", help="PNG of the hazard curve, the fragility and the integrand")
    h.set_defaults(func=cmd_hazard)
    return p


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:2] == ["hazard", "reweight"]:  # a command of its own: an OpenQuake logic tree, not one curve
        from .hazard_reweight import main as reweight
        return reweight(argv[2:])
    parser = build_parser()
    args = parser.parse_args(argv)
    return exit_status(f"rigid {args.command}", lambda: checked_run(args), args)


def checked_run(args):
    check_arguments(args)
    return args.func(args)


def check_arguments(args):
    """The settings `fragility` and `hazard` share (and rigidpy.fragility, rigidpy.hazard), checked."""
    if not 0 <= args.seed < 2 ** 63:
        raise InputError(f"--seed {args.seed}: must be a whole number from 0 to 2^63 - 1")
    if args.bootstrap < 20 or args.bootstrap > 100000:
        raise InputError(f"--bootstrap {args.bootstrap}: must be 20-100000")
    if not 0.5 <= args.level < 1:
        raise InputError(f"--level {args.level}: must be in [0.5, 1)")
    if args.pgv_pga is not None and not (args.pgv_pga > 0 and math.isfinite(args.pgv_pga)):
        raise InputError(f"--pgv-pga {args.pgv_pga}: must be a positive number of seconds")
    if getattr(args, "pgv_pga_dist", None) and args.pgv_pga is not None:
        raise InputError("--pgv-pga and --pgv-pga-dist: give one")


if __name__ == "__main__":
    sys.exit(main())


# rigidpy.fragility(...) is fits_data.fragility (callable_module.py says why)
from .callable_module import call_through  # noqa: E402

call_through(__name__, "rigidpy.fits_data", "fragility")
