"""Outcome agreement of campaign cubes against a reference cube (docs/accuracy.md: how the default
accuracy preset is chosen).

    python3 -m rigidpy.outcome_agreement REFERENCE.h5 CANDIDATE.h5 [CANDIDATE.h5 ...] [--json]

The cubes must come from the same job (same objects, records, scales, rotations). Per object and
over all objects, for every candidate:

- agreement: the fraction of cells whose outcome class is the same in both cubes, over the cells
  known in both. Classes: overturned (simulated overturned, or inferred by the stop rule: the
  cube's `probability` counts both as overturned), survived. not-run and failed cells are not
  known and are left out (their count is printed).
- simulated agreement: the same over the cells simulated in both (no inferred cell), i.e. the
  runs that can be compared one to one.
- wall: the sum of the per-task wall times (`wall_s`) of the simulated cells (unit: s), and the
  number of simulated cells.

The convergence study (docs/accuracy.md, "Convergence of the contact solve") compares cubes in
pairs, each the same job at the default settings and at `--accuracy reference`:

    python3 -m rigidpy.outcome_agreement --pair REFERENCE.h5 DEFAULT.h5 [--pair ...]
        [--markdown FILE] [--csv FILE] [--flips-csv FILE] [--json] [--check]

Per (job, object) and over all: the cells simulated in both, the flipped ones (overturned in one,
survived in the other; up = only the default overturned), the cells whose contact solve stopped at
its sweep cap in some step (the cube's unconverged_steps) in each cube and those steps' count, the
scalar lognormal fragility fitted to each cube (median theta, dispersion beta: rigidpy.fit, every
record, variants pooled) and their relative differences; and how close each flipped cell stood to
the failure rule: the peak tilt of the run that survived over the block's critical tilt (its
rocking angle alpha, past which it falls without further push, or the scene's tilt rule when
smaller; NaN when the scene has no single rocking block), with the flips counted by that margin.
--check exits 1 unless the study's targets hold (TARGETS). Without --markdown the tables go to
standard output.

Needs numpy and h5py (Debian: /usr/bin/python3 with python3-h5py). Exit status 0, 2 bad input.
"""
import argparse
import csv
import json
import math
import os
import sys

try:
    import numpy as np
    from . import fit
    from .cube import Cube
    from .errors import InputError
    from . import outcomes
    from .outcomes import RAN, SIMULATED_KNOWN
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"outcome_agreement: error: {e}; run with /usr/bin/python3\n")
    sys.exit(2)


def read(path):
    """{object: outcome and wall_s}, the whole dataset of each object (variants stacked on the
    first axis, as stored), and the root's physics_json."""
    cube = Cube(path, wall_times=True)  # the outcomes compared are the ones the campaign wrote
    out = {}
    for name in cube.base_names():
        parts = [o for o in cube.objects if o.name == name]
        if parts[0].variant is None:
            out[name] = dict(outcome=parts[0].outcome.astype(int), wall=parts[0].wall_s)
        else:
            out[name] = dict(outcome=np.stack([o.outcome for o in parts]).astype(int),
                             wall=np.stack([o.wall_s for o in parts]))
    physics = cube.root_attrs.get("physics_json", "")
    return out, physics.decode() if isinstance(physics, bytes) else physics


def compare(ref, cand):
    rows = {}
    tot = dict(cells=0, known=0, agree=0, sim=0, sim_agree=0, unknown=0, wall=0.0, simulated=0,
               ref_wall=0.0, ref_simulated=0, differ=[])
    for name, r in ref.items():
        if name not in cand:
            raise ValueError(f"object {name} missing from a candidate")
        a, b = r["outcome"], cand[name]["outcome"]
        if a.shape != b.shape:
            raise ValueError(f"object {name}: shapes {a.shape} and {b.shape} differ")
        known_a = outcomes.known(a)
        known_b = outcomes.known(b)
        known = known_a & known_b
        over_a = outcomes.counts_as_overturned(a)
        over_b = outcomes.counts_as_overturned(b)
        agree = known & (over_a == over_b)
        sim = np.isin(a, SIMULATED_KNOWN) & np.isin(b, SIMULATED_KNOWN)
        sim_agree = sim & (a == b)
        simulated_b = np.isin(b, RAN)
        simulated_a = np.isin(a, RAN)
        row = dict(cells=int(a.size), known=int(known.sum()), agree=int(agree.sum()), sim=int(sim.sum()),
                   sim_agree=int(sim_agree.sum()), unknown=int((~known).sum()),
                   wall=float(np.nansum(cand[name]["wall"][simulated_b])), simulated=int(simulated_b.sum()),
                   ref_wall=float(np.nansum(r["wall"][simulated_a])), ref_simulated=int(simulated_a.sum()),
                   differ=[list(map(int, idx)) for idx in np.argwhere(known & ~agree)])
        rows[name] = row
        for k in tot:
            if k == "differ":
                tot[k] += [[name] + d for d in row["differ"]]
            else:
                tot[k] += row[k]
    rows["all"] = tot
    for row in rows.values():
        row["agreement"] = row["agree"] / row["known"] if row["known"] else float("nan")
        row["simulated_agreement"] = row["sim_agree"] / row["sim"] if row["sim"] else float("nan")
    return rows


# ---------------------------------------------------------------------------------------------
# The convergence study: pairs of (reference, default) cubes of one job

# The targets (fractions): flipped cells of the simulated ones, cells with a capped contact
# solve at the default and at the reference, relative change of the fitted median and dispersion.
TARGETS = dict(flipped=0.02, capped_default=0.01, capped_reference=0.0, theta=0.02, beta=0.02)
# Bins of the tilt margin (peak tilt of the surviving run / critical tilt) for the flip counts.
MARGIN_EDGES = (0.0, 0.25, 0.5, 0.75, 0.9, 1.0, math.inf)


def critical_tilt_deg(attrs):
    """The tilt at which the object's failure rule is as good as met (unit: degree): its rocking
    angle alpha (a block tipped past it falls without further push), or the scene's tilt rule when
    that is smaller; NaN when neither is known (a stack, a compound scene without one rocking block)."""
    alpha = attrs.get("alpha_rad")
    critical = math.degrees(float(alpha)) if alpha is not None and math.isfinite(float(alpha)) else math.nan
    text = attrs.get("physics_json", "")
    try:
        physics = json.loads(text.decode() if isinstance(text, bytes) else text) if text else {}
    except ValueError:
        physics = {}
    if physics.get("failure_rule") == "tilt":
        rule = float(physics.get("failure_tilt_deg", math.nan))
        critical = rule if not math.isfinite(critical) else min(critical, rule)
    return critical


def read_cells(path):
    """{object: cells} of a cube for the convergence study, variants stacked on the first axis:
    outcome, max_tilt_deg, max_slip_m, unconverged_steps, the critical tilt broadcast to the cells,
    and for the fits the cells as records (variants pooled: [V*R, S, A]) with their PGV/PGA."""
    cube = Cube(path, peaks=True)
    out = {}
    for name in cube.base_names():
        parts = [o for o in cube.objects if o.name == name]

        def stacked(key):
            return np.stack([getattr(o, key) for o in parts])  # [V, R, S, A], V = 1 without variants

        outcome = stacked("outcome").astype(int)
        critical = np.array([critical_tilt_deg(o.attrs) for o in parts], float)
        out[name] = dict(outcome=outcome, tilt=stacked("max_tilt_deg"), slip=stacked("max_slip_m"),
                         steps=stacked("unconverged_steps").astype(np.int64),
                         critical=np.broadcast_to(critical[:, None, None, None], outcome.shape),
                         scales=np.asarray(cube.scales, float),
                         pgv_pga=np.tile(np.asarray(cube.pgv_pga, float), len(parts)))
    return out


def fit_cells(cells):
    """An object's cells as rigidpy.fit sees them, variants pooled as records ([V*R, S, A])."""
    return fit.Cells(cells["outcome"].reshape((-1,) + cells["outcome"].shape[2:]), cells["scales"], cells["pgv_pga"])


def lognormal(data, records, weights=None):
    """(theta_g, beta) of the scalar lognormal fit to the simulated cells of `records` (weighted by
    bootstrap counts), NaN when there is no finite estimate."""
    result = fit.lognormal_fit(*fit.scalar_rows(data, records, weights))
    return (result["theta_g"], result["beta"]) if result else (math.nan, math.nan)


def relative(candidate, reference):
    return candidate / reference - 1 if reference and math.isfinite(reference) else math.nan


# Paired bootstrap of the fits' changes: records drawn with replacement, the same draw for both
# cubes, so the interval is that of the change itself (the records' sampling noise largely cancels).
BOOTSTRAP_REPLICATES = 200
BOOTSTRAP_SEED = 33
INTERVAL_LEVEL = 0.9


def fit_changes(ref, cand):
    """Fitted theta and beta of both cubes of one object, their relative changes and the changes'
    paired-bootstrap 90 % intervals (NaN where no fit)."""
    data_r, data_c = fit_cells(ref), fit_cells(cand)
    records = np.intersect1d(data_r.records_with_cells(), data_c.records_with_cells())
    (theta_r, beta_r), (theta_c, beta_c) = lognormal(data_r, records), lognormal(data_c, records)
    out = dict(theta_default=theta_c, theta_reference=theta_r, theta_change=relative(theta_c, theta_r),
               beta_default=beta_c, beta_reference=beta_r, beta_change=relative(beta_c, beta_r))
    draws = {"theta": [], "beta": []}
    if math.isfinite(theta_r) and math.isfinite(theta_c) and len(records) >= fit.MIN_RECORDS_FOR_INTERVAL:
        rng = np.random.default_rng(BOOTSTRAP_SEED)
        for counts in fit.bootstrap_counts(rng, len(records), BOOTSTRAP_REPLICATES):
            (tr, br), (tc, bc) = lognormal(data_r, records, counts), lognormal(data_c, records, counts)
            draws["theta"].append(relative(tc, tr))
            draws["beta"].append(relative(bc, br))
    for key in ("theta", "beta"):
        values = [v for v in draws[key] if math.isfinite(v)]
        tail = 50 * (1 - INTERVAL_LEVEL)
        out[f"{key}_change_interval"] = [float(v) for v in np.percentile(values, [tail, 100 - tail])] \
            if values else [math.nan, math.nan]
    return out


def convergence(ref, cand, label):
    """Rows per object of one pair (reference cube, default cube of the same job) and the flipped
    cells, each with the distance of its surviving run from the failure rule."""
    rows, flips = [], []
    for name, r in ref.items():
        if name not in cand:
            raise ValueError(f"{label}: object {name} missing from the default cube")
        c = cand[name]
        if r["outcome"].shape != c["outcome"].shape:
            raise ValueError(f"{label}: object {name}: shapes {r['outcome'].shape} and {c['outcome'].shape} differ")
        sim = np.isin(r["outcome"], SIMULATED_KNOWN) & np.isin(c["outcome"], SIMULATED_KNOWN)
        over_r, over_c = r["outcome"] == outcomes.OVERTURNED, c["outcome"] == outcomes.OVERTURNED
        flipped = sim & (over_r != over_c)
        # the run that survived: both, or the one of a flipped cell; its peak tilt over the critical one
        survivor_tilt = np.where(over_r, c["tilt"], r["tilt"])
        with np.errstate(invalid="ignore", divide="ignore"):
            margin = survivor_tilt / r["critical"]
        some_survivor = sim & ~(over_r & over_c)
        bins = np.digitize(margin, MARGIN_EDGES[1:-1])
        row = dict(job=label, object=name, simulated=int(sim.sum()), flipped=int(flipped.sum()),
                   up=int((flipped & over_c).sum()), down=int((flipped & over_r).sum()),
                   ran_default=int(np.isin(c["outcome"], RAN).sum()), ran_reference=int(np.isin(r["outcome"], RAN).sum()),
                   capped_default=int((c["steps"] > 0).sum()), capped_reference=int((r["steps"] > 0).sum()),
                   capped_steps_default=int(c["steps"][c["steps"] > 0].sum()),
                   capped_steps_reference=int(r["steps"][r["steps"] > 0].sum()),
                   **fit_changes(r, c),
                   survived_by_margin=[int((some_survivor & ~np.isnan(margin) & (bins == b)).sum())
                                       for b in range(len(MARGIN_EDGES) - 1)],
                   flipped_by_margin=[int((flipped & ~np.isnan(margin) & (bins == b)).sum())
                                      for b in range(len(MARGIN_EDGES) - 1)],
                   flipped_no_margin=int((flipped & np.isnan(margin)).sum()))
        rows.append(row)
        for idx in np.argwhere(flipped):
            i = tuple(idx)
            flips.append(dict(job=label, object=name, variant=int(i[0]), record=int(i[1]), scale_g=float(r["scales"][i[2]]),
                              rotation=int(i[3]), reference="overturned" if over_r[i] else "survived",
                              default="overturned" if over_c[i] else "survived",
                              tilt_reference_deg=float(r["tilt"][i]), tilt_default_deg=float(c["tilt"][i]),
                              critical_tilt_deg=float(r["critical"][i]), margin=float(margin[i]),
                              slip_reference_m=float(r["slip"][i]), slip_default_m=float(c["slip"][i]),
                              capped_default=int(c["steps"][i]), capped_reference=int(r["steps"][i])))
    return rows, flips


def total(rows):
    """The row over all jobs and objects; the fits are per object, so the total carries the largest
    |change| of any object's median and dispersion instead."""
    out = dict(job="all", object="")
    for key in ("simulated", "flipped", "up", "down", "ran_default", "ran_reference", "capped_default",
                "capped_reference", "capped_steps_default", "capped_steps_reference", "flipped_no_margin"):
        out[key] = sum(r[key] for r in rows)
    for key in ("survived_by_margin", "flipped_by_margin"):
        out[key] = [sum(v) for v in zip(*(r[key] for r in rows))]
    for key in ("theta_change", "beta_change"):
        changes = [r[key] for r in rows if math.isfinite(r[key])]
        out[key] = max(changes, key=abs) if changes else math.nan
    return out


def shares(row):
    """The row's fractions: flipped of the simulated cells, capped of the runs at each setting."""
    return dict(flipped=row["flipped"] / row["simulated"] if row["simulated"] else math.nan,
                capped_default=row["capped_default"] / row["ran_default"] if row["ran_default"] else math.nan,
                capped_reference=row["capped_reference"] / row["ran_reference"] if row["ran_reference"] else math.nan)


def missed_targets(rows):
    """What misses the targets (TARGETS), one line each: the shares over all, the fits per object."""
    all_row = total(rows)
    share = shares(all_row)
    missed = [f"{key.replace('_', ' ')}: {100 * share[key]:.2f} % > {100 * TARGETS[key]:g} %"
              for key in ("flipped", "capped_default", "capped_reference") if not share[key] <= TARGETS[key]]
    for r in rows:
        for key in ("theta", "beta"):
            change = r[f"{key}_change"]
            if math.isfinite(change) and abs(change) > TARGETS[key]:
                missed.append(f"{r['job']}/{r['object']}: {key} changes by {_change(r, key)} "
                              f"(target within {100 * TARGETS[key]:g} %)")
    return missed


STUDY_COLUMNS = ("job", "object", "simulated", "flipped", "flipped_share", "up", "down", "ran_default",
                 "capped_default", "capped_default_share", "capped_steps_default", "ran_reference", "capped_reference",
                 "capped_steps_reference", "theta_default", "theta_reference", "theta_change", "theta_change_low",
                 "theta_change_high", "beta_default", "beta_reference", "beta_change", "beta_change_low",
                 "beta_change_high")
FLIP_COLUMNS = ("job", "object", "variant", "record", "scale_g", "rotation", "reference", "default",
                "tilt_reference_deg", "tilt_default_deg", "critical_tilt_deg", "margin", "slip_reference_m",
                "slip_default_m", "capped_default", "capped_reference")


def _pct(v, digits=2):
    return f"{100 * v:.{digits}f} %" if math.isfinite(v) else "-"


def _num(v):
    return f"{v:.4g}" if isinstance(v, float) and math.isfinite(v) else ("" if isinstance(v, float) else str(v))


def _change(row, key):
    """The relative change of a fitted parameter with its paired-bootstrap interval."""
    change = row[f"{key}_change"]
    if not math.isfinite(change):
        return "-"
    low, high = row[f"{key}_change_interval"]
    interval = f"; {100 * INTERVAL_LEVEL:.0f} %: {100 * low:+.1f} to {100 * high:+.1f} %" if math.isfinite(low) else ""
    return f"{100 * change:+.1f} %{interval}"


def csv_rows(rows):
    table = []
    for r in rows + [total(rows)]:
        share = shares(r)
        full = dict(r, flipped_share=share["flipped"], capped_default_share=share["capped_default"])
        for key in ("theta", "beta"):
            low, high = r.get(f"{key}_change_interval", (math.nan, math.nan))
            full.update({f"{key}_change_low": low, f"{key}_change_high": high})
        table.append([_num(full.get(k, math.nan)) for k in STUDY_COLUMNS])
    return table


def markdown(rows):
    """The study table and the flips by distance from the failure rule, as markdown."""
    lines = ["| job | object | cells simulated in both | flipped (up / down) | capped cells, default | capped steps, "
             "default | capped cells, reference | median theta (g): default / reference (change; paired "
             "bootstrap interval) | dispersion beta: default / reference (change; interval) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows + [total(rows)]:
        share = shares(r)
        fits = ("largest change " + _pct(r["theta_change"], 1), "largest change " + _pct(r["beta_change"], 1)) \
            if r["job"] == "all" else (
                f"{_num(r['theta_default']) or '-'} / {_num(r['theta_reference']) or '-'} ({_change(r, 'theta')})",
                f"{_num(r['beta_default']) or '-'} / {_num(r['beta_reference']) or '-'} ({_change(r, 'beta')})")
        bold = "**" if r["job"] == "all" else ""
        lines.append(f"| {bold}{r['job']}{bold} | {r['object']} | {r['simulated']} | {r['flipped']} = "
                     f"{_pct(share['flipped'])} ({r['up']} / {r['down']}) | {r['capped_default']} = "
                     f"{_pct(share['capped_default'])} | {r['capped_steps_default']} | {r['capped_reference']} | "
                     f"{fits[0]} | {fits[1]} |")
    all_row = total(rows)
    lines += ["", "| tilt margin of the surviving run (peak tilt / critical tilt) | cells with a survivor | flipped | "
              "flipped share |", "|---|---|---|---|"]
    for b in range(len(MARGIN_EDGES) - 1):
        n, f = all_row["survived_by_margin"][b], all_row["flipped_by_margin"][b]
        hi = MARGIN_EDGES[b + 1]
        span = f"{MARGIN_EDGES[b]:g} - {hi:g}" if math.isfinite(hi) else f">= {MARGIN_EDGES[b]:g}"
        lines.append(f"| {span} | {n} | {f} | {_pct(f / n) if n else '-'} |")
    lines.append(f"| no critical tilt (stacks) | | {all_row['flipped_no_margin']} | |")
    return "\n".join(lines) + "\n"


def write_csv(path, header, table):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(table)


def study_main(args):
    try:
        rows, flips = [], []
        for ref_path, cand_path in args.pair:
            label = os.path.basename(ref_path).split(".")[0]
            r, f = convergence(read_cells(ref_path), read_cells(cand_path), label)
            rows += r
            flips += f
    except (OSError, ValueError, KeyError, InputError) as e:
        sys.stderr.write(f"outcome_agreement: error: {e}\n")
        return 2
    if args.json:
        print(json.dumps(dict(rows=rows, total=total(rows), flips=flips, missed=missed_targets(rows))))
    text = markdown(rows)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)
    elif not args.json:
        print(text)
    if args.csv:
        write_csv(args.csv, STUDY_COLUMNS, csv_rows(rows))
    if args.flips_csv:
        write_csv(args.flips_csv, FLIP_COLUMNS, [[_num(flip[k]) for k in FLIP_COLUMNS] for flip in flips])
    missed = missed_targets(rows)
    for line in missed:
        sys.stderr.write(f"outcome_agreement: target missed: {line}\n")
    return 1 if args.check and missed else 0


def study_parser():
    p = argparse.ArgumentParser(prog="python3 -m rigidpy.outcome_agreement",
                                description="The convergence study: pairs of cubes of one job, the reference first")
    p.add_argument("--pair", nargs=2, action="append", required=True, metavar=("REFERENCE.h5", "DEFAULT.h5"))
    p.add_argument("--markdown", help="write the tables here (else standard output)")
    p.add_argument("--csv", help="the study table, one row per job and object and one over all")
    p.add_argument("--flips-csv", help="one row per flipped cell")
    p.add_argument("--json", action="store_true", help="print rows, total, flips and missed targets as JSON")
    p.add_argument("--check", action="store_true", help="exit 1 unless the targets hold")
    return p


def main(argv):
    if "--pair" in argv:
        return study_main(study_parser().parse_args(argv))
    as_json = "--json" in argv
    args = [a for a in argv if a != "--json"]
    if len(args) < 2:
        sys.stderr.write(__doc__)
        return 2
    try:
        ref, ref_physics = read(args[0])
        results = {}
        for path in args[1:]:
            cand, physics = read(path)
            results[path] = (compare(ref, cand), physics)
    except (OSError, ValueError, KeyError, InputError) as e:
        sys.stderr.write(f"outcome_agreement: error: {e}\n")
        return 2
    if as_json:
        print(json.dumps({p: rows for p, (rows, _) in results.items()}))
        return 0
    print(f"reference: {args[0]}\n  {ref_physics}")
    for path, (rows, physics) in results.items():
        print(f"\n{path}\n  {physics}")
        print("| object | cells | known in both | agreement | simulated in both | agreement (simulated) | "
              "wall, candidate (s) | wall, reference (s) |")
        print("|---|---|---|---|---|---|---|---|")
        for name, r in rows.items():
            print(f"| {name} | {r['cells']} | {r['known']} | {r['agree']}/{r['known']} = {100 * r['agreement']:.2f} % | "
                  f"{r['sim']} | {100 * r['simulated_agreement']:.2f} % | {r['wall']:.1f} ({r['simulated']} runs) | "
                  f"{r['ref_wall']:.1f} ({r['ref_simulated']} runs) |")
        differ = rows["all"]["differ"]
        if differ:
            print("cells that differ [object, record, scale, rotation]: " +
                  ", ".join(str(d) for d in differ[:40]) + (" ..." if len(differ) > 40 else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
