"""Rigid's Python side: reading campaign cubes and turning them into fragilities, hazard, figures
and exports (src/python/README.md), and the API a notebook uses (docs/python.md):

- open_cube(path): a whole cube as one xarray Dataset (cube_dataset);
- fragility(cube, ...), hazard(cube, curve, age, ...): the fits of `rigid fragility` and the
  survival test of `rigid hazard` as data (fits_data);
- run(scene, motion=..., target_pga=..., rotation=..., contact=...): one simulation through the
  C++ engine (the extension rigidpy._engine) as a time history (simulation);
- plot_history(ds), animate_history(ds, path): its figure and animation (history_figure).

They are imported on first use, so the commands below need neither xarray nor the extension.
One module per job:

- cube: the one reader of a cube; outcomes: the outcome codes and the probability rules;
  checksums: the cube's checksums; files: writing beside or into a cube without damaging it;
- fit: the probit fits and their bootstrap; map_fit: the fit a map draws (normalisation, contours);
  object_fits: the fits of a cube's objects and the pool of variants; hazard: hazard curves and the
  toppling rate; exposure_age: survival over an uncertain age; openquake_export: OpenQuake's logic-tree
  exports; logic_tree_weights: the survival-weighted logic tree; nrml: OpenQuake's fragility format; sensitivity: rank sensitivity across variants;
  progress: the fits' progress line;
- figures: the figures of `rigid plot`; fragility_report, fragility_store, hazard_command: what
  `rigid fragility` prints, exports and stores and what `rigid hazard` computes; hazard_reweight,
  reweight_figure: `rigid hazard reweight`; command_line: what
  the commands share on their command lines;
- the commands (each `python3 -m rigidpy.NAME`, or the launcher beside this folder that the
  rigid executable runs): plot (`rigid plot`), fragility (`rigid fragility` and `rigid hazard`),
  shaketable (`rigid shaketable fragility`'s fits), accuracy (`rigid study accuracy`'s figure),
  outcome_agreement (a developer's comparison of cubes).
"""

__version__ = "0.1.0"

# fragility and hazard are modules of the package too, made callable (callable_module.py)
_API = {"open_cube": "cube_dataset", "fragility": "fragility", "hazard": "hazard", "run": "simulation",
        "history_from_csv": "simulation", "plot_history": "history_figure", "animate_history": "history_figure",
        "InputError": "errors"}
__all__ = sorted(_API)


def __getattr__(name):
    """The API's functions, imported when first asked for (PEP 562)."""
    if name not in _API:
        raise AttributeError(f"module 'rigidpy' has no attribute {name!r}")
    import importlib
    module = importlib.import_module(f".{_API[name]}", __name__)
    value = module if name in ("fragility", "hazard") else getattr(module, name)
    globals()[name] = value
    return value
