#!/usr/bin/env bash
# `fvrml-meshdiff`: known answers, formats, topology of one mesh, bad input; `fvrml-run --check`.
# usage: meshdiff.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# fvrml-meshdiff: known answers, formats, bad input.
if [ -n "$D" ] && [ -n "$R" ]; then
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x^2-y^2-z^2" bboxSize 3 3 3 resolution [24] } }\n' > "$T/r1.wrl"
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1.1^2-x^2-y^2-z^2" bboxSize 3 3 3 resolution [24] } }\n' > "$T/r11.wrl"
  "$R" "$T/r1.wrl" -o "$T/r1.ply" && "$R" "$T/r11.wrl" -o "$T/r11.stl" && "$R" "$T/r1.wrl" -o "$T/r1.obj"
  # Spheres of radius 1 and 1.1: both distances are 0.1, give or take the meshes' own error.
  jcheck meshdiff-spheres out "near(j['hausdorff'], 0.1, 0.01) and near(j['chamfer'], 0.1, 0.005) and
    near(j['hausdorff_relative'], j['hausdorff'] / j['bbox_diagonal_a']) and j['a']['triangles'] > 1000" -- "$D" "$T/r1.ply" "$T/r11.stl"
  check meshdiff-watertight 0 '"watertight": true' -- "$D" "$T/r1.obj" "$T/r11.stl"
  check meshdiff-euler 0 '"euler": 2' -- "$D" "$T/r1.ply" "$T/r1.obj"
  check meshdiff-missing 1 'cannot read' -- "$D" "$T/none.ply" "$T/r1.ply"
  printf 'not a mesh' > "$T/bad.ply"
  check meshdiff-bad 1 'bad.ply: error: not a PLY file' -- "$D" "$T/bad.ply" "$T/r1.ply"
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//5\n' > "$T/badn.obj"
  check meshdiff-bad-normal 1 'badn.obj: error: OBJ: a face names normal 5 of 1' -- "$D" "$T/badn.obj"
  printf 'v 0 0 0\nvn 0 1\n' > "$T/shortn.obj"
  check meshdiff-short-normal 1 'shortn.obj: error: OBJ line 2: a normal needs three numbers' -- "$D" "$T/shortn.obj"
  check meshdiff-usage 2 '' -- "$D"
  # One mesh: its topology alone, with its components and the inside-out ones.
  jcheck meshdiff-one out "j['a']['components'] == 1 and j['a']['inverted_components'] == 0 and j['a']['watertight'] and 'hausdorff' not in j" \
    -- "$D" "$T/r1.ply"
  jcheck fvrml-run-check out "near(j['hausdorff'], 0.1, 0.01) and near(j['chamfer'], 0.1, 0.005) and j['watertight']" \
    -- "$R" "$T/r1.wrl" --check "$T/r11.stl"
  jcheck fvrml-run-check-self out "j['hausdorff'] < 1e-6 and j['chamfer'] < 1e-6 and j['euler'] == 2" -- "$R" "$T/r1.wrl" --check "$T/r1.ply"
  check fvrml-run-check-missing 1 'none.ply: error: cannot read' -- "$R" "$T/r1.wrl" --check "$T/none.ply"
fi

finish meshdiff
