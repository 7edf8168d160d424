"""OpenQuake classical-calculation CSV exports written for the tests, in the layout the engine's
manual documents (independently of rigidpy): `realizations_<id>.csv` with a comment line and
`rlz_id,branch_path,weight`, and per realization `hazard_curve-rlz-NNN-PGA_<id>.csv` whose first
line is a comment holding investigation_time and imt, then `lon,lat,depth,poe-IML...`, one row per
site. PoEs are written with 7 significant digits, as the engine writes them."""
import os

CALC_ID = "42"


def header(kind, investigation_time, imt="PGA", levels=0):
    return ("#" + "," * (levels + 2) + f"\"generated_by='test layout', start_date='2026-01-01T00:00:00', "
            f"checksum=0, kind='{kind}', investigation_time={investigation_time!r}, imt='{imt}'\"\n")


def write_realizations(folder, rows, calc_id=CALC_ID):
    """rows: [(rlz_id, branch_path, weight)]"""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"realizations_{calc_id}.csv")
    with open(path, "w") as f:
        f.write("#,,\"generated_by='test layout'\"\nrlz_id,branch_path,weight\n")
        for rlz, branch, w in rows:
            f.write(f"{rlz},{branch},{w:.7E}\n")
    return path


def write_curve(folder, kind, imls, sites, investigation_time, calc_id=CALC_ID, imt="PGA", name=None, poe_format="{:.6E}"):
    """sites: [((lon, lat), [PoE per IML])]; kind 'rlz-000', 'mean', 'quantile-0.16'; poe_format "{!r}" keeps
    every digit."""
    if name is None:
        stem = {"mean": "hazard_curve-mean"}.get(kind, f"hazard_curve-{kind}")
        if kind.startswith("quantile-"):
            stem = f"quantile_curve-{kind[len('quantile-'):]}"
        name = f"{stem}-{imt}_{calc_id}.csv"
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(header(kind, investigation_time, imt, len(imls)))
        f.write("lon,lat,depth," + ",".join(f"poe-{a:.7f}" for a in imls) + "\n")
        for (lon, lat), poes in sites:
            f.write(f"{lon:.5f},{lat:.5f},0.00000," + ",".join(poe_format.format(p) for p in poes) + "\n")
    return path


def write_export(folder, branches, imls, investigation_time, site=(0.0, 0.0), calc_id=CALC_ID, poe_format="{:.6E}"):
    """branches: [(branch_path, weight, [PoE per IML])]: the realizations and their curves at one site."""
    write_realizations(folder, [(i, b, w) for i, (b, w, _) in enumerate(branches)], calc_id)
    for i, (_, _, poes) in enumerate(branches):
        write_curve(folder, f"rlz-{i:03d}", imls, [(site, poes)], investigation_time, calc_id, poe_format=poe_format)
    return folder
