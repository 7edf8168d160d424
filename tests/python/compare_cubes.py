#!/usr/bin/python3
"""Compares two Rigid fragility cubes (HDF5) dataset by dataset, bit for bit.

    compare_cubes.py A.h5 B.h5 [--show N] [--other-build]

Exit status: 0 identical, 1 different, 2 unreadable file or bad usage. Prints the first
differences (up to N per dataset, default 5).

Compared: the set of groups and datasets; each dataset's dtype, shape and raw values (floats as
their bit patterns, so NaN equals NaN only with the same bits); the attributes of the root, of
every group and of every dataset. Ignored: datasets named in IGNORED_DATASETS (wall-clock times
differ between runs), root attributes named in IGNORED_ROOT_ATTRS, and HDF5's dimension-scale
bookkeeping (DIMENSION_LIST, REFERENCE_LIST), which holds object addresses, not data.
--other-build also ignores the root's software_version (the cubes of two builds of the same
results, as tests/campaign/same_outputs.sh compares them).
Needs numpy and h5py (Debian: /usr/bin/python3 with python3-h5py).
"""
import sys

import h5py
import numpy as np

IGNORED_DATASETS = {"wall_s"}
IGNORED_ROOT_ATTRS = set()  # none today; a creation time would go here
ADDRESS_ATTRS = {"DIMENSION_LIST", "REFERENCE_LIST"}


def objects(f):
    """Every group and dataset below the root, by path."""
    found = {}

    def visit(name, obj):
        found[name] = obj  # returns None: a value would stop visititems

    f.visititems(visit)
    return found


def values(x):
    """An attribute or dataset value as a numpy array (strings as bytes, for an exact comparison)."""
    if isinstance(x, h5py.Dataset):
        x = x.asstr()[()] if h5py.check_string_dtype(x.dtype) else x[()]
    if isinstance(x, (str, bytes)):  # scalar strings: compare values, not fixed-width dtypes
        return np.array(x.encode("utf-8") if isinstance(x, str) else bytes(x), dtype=object)
    a = np.asarray(x)
    if a.dtype.kind == "O":  # variable-length strings
        a = np.array([v.encode("utf-8") if isinstance(v, str) else bytes(v) for v in a.ravel()], dtype=object)
    return a


def show_value(v):
    """repr, with the bits of a NaN (two NaNs can differ)."""
    if isinstance(v, np.floating) and np.isnan(v):
        return f"nan(0x{int(np.asarray(v).view(f'u{v.itemsize}')):0{2 * v.itemsize}x})"
    return repr(v.item() if isinstance(v, np.generic) else v)


def differences(a, b, show):
    """Descriptions of the first `show` differences between two arrays, [] when identical."""
    if a.dtype != b.dtype or a.shape != b.shape:
        return [f"dtype/shape {a.dtype}{a.shape} != {b.dtype}{b.shape}"]
    if a.dtype.kind in "fiub" and a.dtype.itemsize in (1, 2, 4, 8):
        raw = f"u{a.dtype.itemsize}"  # bit patterns: NaN == NaN only with the same bits
        diff = a.view(raw) != b.view(raw)
    elif a.dtype.kind in "OSU":
        diff = np.asarray(a != b, dtype=bool)
    else:  # compound or other: compare the bytes whole
        return [] if a.tobytes() == b.tobytes() else ["raw bytes differ"]
    diff = np.atleast_1d(diff)
    where = np.argwhere(diff)
    out = []
    for idx in where[:show]:
        i = tuple(int(k) for k in idx)
        x, y = (show_value(np.atleast_1d(a)[i]), show_value(np.atleast_1d(b)[i]))
        out.append(f"[{', '.join(map(str, i))}]: {x} != {y}")
    if len(where) > show:
        out.append(f"... {len(where) - show} more")
    return out


def compare_attrs(path, x, y, ignored, show, report):
    names = (set(x.attrs) | set(y.attrs)) - ignored - ADDRESS_ATTRS
    for n in sorted(names):
        where = f"{path or '/'} @{n}"
        if n not in x.attrs or n not in y.attrs:
            report(where, ["present in only one file"])
            continue
        report(where, differences(values(x.attrs[n]), values(y.attrs[n]), show))


def compare(path_a, path_b, show=5, ignored_root=IGNORED_ROOT_ATTRS, out=sys.stdout):
    """Returns True when the two cubes are identical (up to the ignored items)."""
    different = False

    def report(where, lines):
        nonlocal different
        if lines:
            different = True
            for line in lines:
                print(f"{where}: {line}", file=out)

    with h5py.File(path_a, "r") as a, h5py.File(path_b, "r") as b:
        compare_attrs("", a, b, ignored_root, show, report)
        oa, ob = objects(a), objects(b)
        for name in sorted(set(oa) | set(ob)):
            if name.rsplit("/", 1)[-1] in IGNORED_DATASETS:
                continue
            if name not in oa or name not in ob:
                report(name, [f"only in {path_a if name in oa else path_b}"])
                continue
            x, y = oa[name], ob[name]
            if type(x) is not type(y):
                report(name, ["a group in one file, a dataset in the other"])
                continue
            if isinstance(x, h5py.Dataset):
                report(name, differences(values(x), values(y), show))
            compare_attrs(name, x, y, set(), show, report)
    return not different


def main(argv):
    args = list(argv[1:])
    show = 5
    ignored_root = set(IGNORED_ROOT_ATTRS)
    if "--other-build" in args:
        args.remove("--other-build")
        ignored_root.add("software_version")
    if "--show" in args:
        i = args.index("--show")
        try:
            show = int(args[i + 1])
        except (IndexError, ValueError):
            print("compare_cubes.py: --show needs a number", file=sys.stderr)
            return 2
        del args[i:i + 2]
    if len(args) != 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    try:
        same = compare(args[0], args[1], show, ignored_root)
    except OSError as e:
        print(f"compare_cubes.py: {e}", file=sys.stderr)
        return 2
    print(f"{args[0]} and {args[1]}: " + ("identical" if same else "DIFFERENT") +
          f" (ignoring {', '.join(sorted(IGNORED_DATASETS))})")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
