"""Rigid's Python side: reading campaign cubes and turning them into fragilities, hazard, figures
and exports (src/python/README.md). One module per job:

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
