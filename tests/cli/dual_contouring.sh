#!/usr/bin/env bash
# `fvrml-run FILE.fs` (a script as one FShape) and dual contouring: corners kept, adaptive cells,
# normals from the gradient, every output format with colours, displacement, time and frames.
# usage: dual_contouring.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- fvrml-run FILE.fs: an implicit script as one FShape; errors at the script's own lines ----
printf '// a ball\nfunction FRep(x, y, z, t) {\n  return 0.8 - sqrt(x*x + y*y + z*z);\n}\n' > "$T/ball.fs"
check "fvrml-run a script" 0 '^wrote [^ ]*ball-fs.obj: [0-9,]+ triangles, 1 shape' -- "$R" "$T/ball.fs" -o "$T/ball-fs.obj"
# (The default box is 10 wide in 50 cells: dual contouring's vertices lie within a tenth of a cell.)
jcheck "fvrml-run a script: the ball of radius 0.8, in the default box" out "
near(j['volume'], 4 / 3 * 3.14159265 * 0.8 ** 3, 0.05) and near(j['bbox'][3], 0.8, 0.02)
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/ball-fs.obj"
printf '0.7^2 - x^2 - y^2 - z^2\n' > "$T/expr.fs"
check "fvrml-run an expression script" 0 'triangles, 1 shape' -- "$R" "$T/expr.fs" -o "$T/expr.ply"
printf 'function FRep(x, y, z, t) {\n  return 0.8 - sqrt(x*x + y*y + z*z) +;\n}\n' > "$T/bad.fs"
check "fvrml-run a script with a syntax error" 1 'bad.fs:2:39: error: expected an expression' -- "$R" "$T/bad.fs" -o "$T/bad.ply"
# --mesher dc: dual contouring keeps a turned cube's corners with a closed mesh of fewer triangles.
printf 'function FRep(x, y, z, t) {\n  var a = 0.8 * x + 0.6 * y, b = -0.6 * x + 0.8 * y;\n  return 0.5 - max(max(abs(a), abs(b)), abs(z));\n}\n' > "$T/turned.fs"
check "fvrml-run --mesher mt" 0 'wrote [^ ]*turned-mt.ply' -- "$R" "$T/turned.fs" --mesher mt -o "$T/turned-mt.ply"
jcheck "fvrml-run --mesher dc: closed, oriented, genus 0, under half the triangles" out "
j['watertight'] and j['manifold'] and j['euler'] == 2 and j['triangles'] < 912 / 2 and j['hausdorff'] < 0.2
" -- "$R" "$T/turned.fs" --mesher dc --check "$T/turned-mt.ply" -o "$T/turned-dc.ply"
check "fvrml-run --mesher other" 2 'mesher: xx not in' -- "$R" "$T/turned.fs" --mesher xx -o "$T/turned-xx.ply"
# Adaptive: flat faces merge into large cells; --tolerance 0 keeps one vertex per sheet of every cell.
jcheck "fvrml-run --mesher dc --stats: merged cells, fewer triangles, QEF error" err "
j['dual_contouring']['shapes'] == 1 and j['dual_contouring']['merged_cells'] > 0 and
j['dual_contouring']['triangles'] < 288 / 2 and j['dual_contouring']['max_qef_error_cells'] < 0.02
" -- "$R" "$T/turned.fs" --mesher dc --stats -o "$T/turned-dc2.ply"
# Normals from the function's gradient (a straight-line script); noise of x has none: differences.
jcheck "fvrml-run --stats: the turned cube's normals from its gradient" err "
j['dual_contouring']['normals']['gradient'] > 100 and j['dual_contouring']['normals']['differences'] == 0
" -- "$R" "$T/turned.fs" --stats -o "$T/turned-dc4.ply"
printf 'function FRep(x, y, z, t) { return 0.5 - sqrt(x*x + y*y + z*z) + 0.05 * noise(4*x, 4*y, 4*z); }\n' > "$T/noisy.fs"
jcheck "fvrml-run --stats: noise has no gradient, its normals come from differences" err "
j['dual_contouring']['normals']['gradient'] == 0 and j['dual_contouring']['normals']['differences'] > 100
" -- "$R" "$T/noisy.fs" --stats -o "$T/noisy.ply"
jcheck "fvrml-run --mesher dc --tolerance 0: no merged cells" err "
j['dual_contouring']['merged_cells'] == 0 and j['dual_contouring']['triangles'] == 288
" -- "$R" "$T/turned.fs" --mesher dc --tolerance 0 --stats -o "$T/turned-dc3.ply"
check "fvrml-run --tolerance below 0" 2 'tolerance: Value -1 not in range' -- "$R" "$T/turned.fs" --mesher dc --tolerance -1 -o "$T/turned-neg.ply"
[ -e "$T/turned-neg.ply" ] && fail "fvrml-run --tolerance -1 wrote turned-neg.ply"
check "fvrml-run --tolerance with --mesher mt warns" 0 'warning: --tolerance has no effect with --mesher mt' -- \
  "$R" "$T/turned.fs" --mesher mt --tolerance 0.1 -o "$T/turned-mt2.ply"
# Dual contouring through everything a shape can have and every output: colour by pattern, a
# displacement texture, a time-dependent definition, frames; PLY, OBJ, STL, glTF, VRML97 and PNG.
printf '#VRML V2.0 utf8\nFShape { cycleInterval 2 loop TRUE\n appearance FAppearance { material FMaterial { diffuseColor "x" patternKey [-0.5 0 0.5] patternColor [1 0 0, 0 1 0, 0 0 1] }\n  texture3D FTexture3D { definition "DISP" type "displacement" } }\n geometry FGeometry { definition "(0.6+0.2*t)^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [24] } }\n' > "$T/dc-all.tpl"
sed 's|DISP|0.04*sin(8*x)|' "$T/dc-all.tpl" > "$T/dc-all.wrl"
sed 's|DISP|0|' "$T/dc-all.tpl" > "$T/dc-plain.wrl"
for ext in ply obj stl glb wrl png; do
  check "fvrml-run --mesher dc -o .$ext" 0 "wrote [^ ]*dc-out.$ext" -- "$R" "$T/dc-all.wrl" --mesher dc --time 0 -o "$T/dc-out.$ext"
done
for ext in ply obj stl; do
  jcheck "--mesher dc .$ext: closed, oriented, 2-manifold" out "all(j['a'][k] for k in ('watertight', 'oriented', 'manifold'))" \
    -- "$D" "$T/dc-out.$ext" "$T/dc-out.ply"
done
head -c 8 "$T/dc-out.png" | od -An -c | grep -q 'P   N   G' || fail "--mesher dc -o .png is not a PNG"
# The VRML97 file carries the gradient's normals (vertices split at the sharp edges), as glTF does.
grep -q 'normal Normal' "$T/dc-out.wrl" || fail "--mesher dc -o .wrl: no Normal node on its IndexedFaceSet"
"$R" "$T/dc-all.wrl" --mesher mt -o "$T/mt-out.wrl" 2> /dev/null
grep -q 'creaseAngle' "$T/mt-out.wrl" && fail "--mesher mt -o .wrl: a creaseAngle beside its normals"
jcheck "--mesher dc: every vertex coloured by its x through the pattern" out "
len(j['points']) > 100 and all(len(p) == 6 for p in j['points']) and all(
  max(abs(a - b) for a, b in zip(p[3:], [min(1, max(0, -2 * p[0])), max(0, 1 - 2 * abs(p[0])), min(1, max(0, 2 * p[0]))])) < 2e-3
  for p in j['points'])
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/dc-out.wrl" --vertices
"$R" "$T/dc-plain.wrl" --mesher dc -o "$T/dc-plain.ply" 2> /dev/null
jcheck "--mesher dc: the displacement texture moves the surface (by up to 0.04)" out "
0.02 < j['hausdorff'] < 0.06
" -- "$D" "$T/dc-plain.ply" "$T/dc-out.ply"
"$R" "$T/dc-all.wrl" --mesher dc --time 1 -o "$T/dc-t1.ply" 2> /dev/null
jcheck "--mesher dc --time 1 (t = 0.5): the time-dependent radius grows by 0.1" out "
0.08 < j['hausdorff'] < 0.16
" -- "$D" "$T/dc-out.ply" "$T/dc-t1.ply"
jcheck "--mesher dc --frames 3: three frames of the animation, each meshed by dual contouring" err "
j['dual_contouring']['shapes'] == 3 and j['dual_contouring']['triangles'] > 3 * 1000
" -- "$R" "$T/dc-all.wrl" --mesher dc --frames 3 --stats -o "$T/dc-anim.glb"
[ -s "$T/dc-anim.glb" ] || fail "--mesher dc --frames 3 wrote no dc-anim.glb"
[ -e "$T/bad.ply" ] && fail "fvrml-run a script with a syntax error wrote bad.ply"
printf 'function FRep(x, y, z, t) {\n  var s = 0;\n  while (1) { s = s + 1; }\n  return s;\n}\n' > "$T/loop.fs"
check "fvrml-run a script: a runtime error at its line" 1 '^loop.fs:3:3: error: loop iteration budget|/loop.fs:3:3: error: loop iteration budget' \
  -- "$R" "$T/loop.fs" -o "$T/loop.ply" --max-loop-iterations 1000
check "fvrml-run --mesher dc --threads 2: a runtime error at its line" 1 '/loop.fs:3:3: error: loop iteration budget' \
  -- "$R" "$T/loop.fs" -o "$T/loop-dc.ply" --max-loop-iterations 1000 --mesher dc --threads 2
[ -e "$T/loop-dc.ply" ] && fail "fvrml-run --mesher dc with a runtime error wrote loop-dc.ply"
printf 'function parametric_x(u,v,w,t){return u;}\nfunction parametric_y(u,v,w,t){return v;}\nfunction parametric_z(u,v,w,t){return 0;}\n' > "$T/flat.fs"
check "fvrml-run a parametric script says what to do" 1 'takes an implicit script.*FShape of a .wrl' -- "$R" "$T/flat.fs" -o "$T/flat.ply"
[ -e "$T/flat.ply" ] && fail "fvrml-run a parametric script wrote flat.ply"

finish dual_contouring
