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

Needs numpy and h5py (Debian: /usr/bin/python3 with python3-h5py). Exit status 0, 2 bad input.
"""
import json
import sys

try:
    import numpy as np
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


def main(argv):
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
