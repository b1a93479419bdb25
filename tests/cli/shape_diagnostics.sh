#!/usr/bin/env bash
# Shape diagnostics (engine/scene/shape_diagnostics.h) from fvrml-run and fscript check: each on a
# shape that has the problem, at its place, and shapes without it that get none.
# usage: shape_diagnostics.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

shape() {  # shape NAME DEFINITION [FIELDS]: a one-FShape scene in $T/NAME.wrl
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry {\n  definition "%s"\n  bboxSize 2 2 2\n  resolution [%s] } }\n' \
    "$2" "${3:-40}" > "$T/$1.wrl"
}
# none NAME -- command: exit 0 and no shape diagnostic in the output.
none() {
  local name="$1"
  shift 2
  n=$((n + 1))
  "$@" > "$T/none.txt" 2>&1 || { fail "$name: exit $?"; return; }
  if grep -qE "(empty|full|inside-out) shape|box cuts|not a number|finer than its grid" "$T/none.txt"; then
    fail "$name: a shape diagnostic where there is no problem"
    head -5 "$T/none.txt"
  fi
}

shape ball "0.8 - x^2 - y^2 - z^2"
shape away "0.3 - (x - 3)^2 - y^2 - z^2"
shape big "4 - x^2 - y^2 - z^2"
shape cut "1.2 - x^2 - y^2 - z^2"
shape plane "y - 0.25"
shape inverted "x^2 + y^2 + z^2 - 0.5"
shape sheet "0.01 - abs(z - 0.003)" 50
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "\nfunction FRep(x, y, z, t) {\n  var r = sqrt(x);\n  return 0.5 - r - y*y - z*z;\n}" bboxSize 2 2 2 resolution [40] } }\n' > "$T/sqrt.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.5 - log(x + y) - z*z" resolution [40] bboxSize 2 2 2 } }\n' > "$T/log.wrl"
printf 'function FRep(x, y, z, t) {\n  var q = (x - x) / (y - y);\n  return 0.5 - q * (x*x + y*y + z*z);\n}\n' > "$T/zero.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.5 - (x*x + y*y) / (x*x + y*y) * (x*x + y*y + z*z)" bboxSize 2 2 2 resolution [41] } }\n' > "$T/line.wrl"
# A sheet at z = 0.012, 0.008 thick, between the samples (z = +-0.02) and the cells' centres (z = 0):
# only intervals over the cells' eighths find it.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "max(0.3 - x*x - y*y - z*z, 0.004 - abs(z - 0.012))" bboxSize 2 2 2 resolution [50] } }\n' > "$T/between.wrl"
# Animations: a ball that shrinks to nothing halfway through its cycle, a solid that fills its box
# for its first frames and is gone after a quarter, and a gyroid that moves but never empties or fills.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "(0.5 - t) - x*x - y*y - z*z" timeSpan 0 1 bboxSize 2 2 2 } }\n' > "$T/shrink.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "(5 - 20 * t) - x*x - y*y - z*z" timeSpan 0 1 bboxSize 2 2 2 } }\n' > "$T/fills.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "min(sin(5*x)*cos(5*y) + sin(5*y)*cos(5*z) + sin(5*z)*cos(5*x) + t, 0.9 - x*x - y*y - z*z)" timeSpan 0 1 bboxSize 2 2 2 } }\n' > "$T/moves.wrl"
printf '#VRML V2.0 utf8\nFTransform { operation "intersection" children [\n FShape { geometry FGeometry { definition "y" bboxSize 2 2 2 } }\n FShape { geometry FGeometry { definition "0.5 - x^2 - y^2 - z^2" bboxSize 2 2 2 } } ] }\n' > "$T/group.wrl"

for tool in run check; do
  if [ $tool = run ]; then run() { "$R" "$@" -o "$T/out.ply"; }; else run() { "$F" check "$@"; }; fi
  check "$tool empty: at the definition, and where the shape is" 0 \
    "away.wrl:3:15: warning: empty shape: f <= 0 everywhere in its box, so nothing is drawn" -- run "$T/away.wrl"
  check "$tool full: the box that holds it" 0 \
    "big.wrl:3:15: warning: full shape: .*bboxCenter 0 0 0 bboxSize 4.4 4.4 4.4 holds it" -- run "$T/big.wrl"
  check "$tool cut by its box, bounded just outside: a warning at bboxSize with the box" 0 \
    "cut.wrl:4:3: warning: the box cuts the shape on its faces -x \(19.8%\), \+x \(19.8%\), -y \(19.8%\), \+y \(19.8%\), -z \(19.8%\), \+z \(19.8%\); the shape ends just outside: bboxCenter 0 0 0 bboxSize 2.6 2.6 2.6 holds it whole" \
    -- run "$T/cut.wrl"
  check "$tool cut by its box, unbounded: a note" 0 \
    "plane.wrl:4:3: note: the box cuts the shape on its faces -x \(37.5%\), \+x \(37.5%\), \+y \(100%\), -z \(37.5%\), \+z \(37.5%\) \(the shape goes on past three times the box\)" \
    -- run "$T/plane.wrl"
  check "$tool inside-out" 0 "inverted.wrl:3:15: warning: inside-out shape: f > 0 on all six faces" -- run "$T/inverted.wrl"
  check "$tool NaN: sqrt of a negative at its call" 0 \
    "sqrt.wrl:4:11: warning: f is not a number in about 50% of the box \(the mesh has a hole there\): .sqrt. of a negative number gives it here first" \
    -- run "$T/sqrt.wrl"
  check "$tool NaN: log at its call in a one-line definition" 0 \
    "log.wrl:2:49: warning: f is not a number in about 48.8% of the box .*.log. of a negative number" -- run "$T/log.wrl"
  check "$tool NaN: 0 / 0 at the operator, in a .fs" 0 \
    "zero.fs:2:19: warning: f is not a number in all of the box .*0 / 0" -- run "$T/zero.fs"
  check "$tool NaN: a line of samples" 0 "f is not a number in 41 of the 68921 samples" -- run "$T/line.wrl"
  check "$tool finer than the grid: the resolution that shows it" 0 \
    "sheet.wrl:5:3: warning: parts of the shape finer than its grid: .*resolution \[100\] shows them" -- run "$T/sheet.wrl"
  check "$tool finer than the grid: and so empty" 0 "sheet.wrl:3:15: warning: empty shape: f > 0 at none of the 50 x 50 x 50 samples" \
    -- run "$T/sheet.wrl"
  check "$tool finer than the grid: a sheet no sample meets, proven by intervals" 0 \
    "between.wrl:2:110: warning: parts of the shape finer than its grid: in [0-9]+ of the [0-9]+ cells checked.*resolution \[100\] shows them" \
    -- run "$T/between.wrl"
  check "$tool empty in some frames of an animation: which" 0 \
    "shrink.wrl:2:43: warning: empty shape in 12 of 24 frames of its animation \(fractions 0.5 to 0.958\): nothing is drawn then" \
    -- run "$T/shrink.wrl"
  check "$tool full at the drawn time and in which frames" 0 \
    "fills.wrl:2:43: warning: full shape: .*; the same in 3 of 24 frames of its animation \(fractions 0 to 0.0833\)" \
    -- run "$T/fills.wrl"
  check "$tool the same shape empty later in its animation" 0 \
    "fills.wrl:2:43: warning: empty shape in 18 of 24 frames of its animation \(fractions 0.25 to 0.958\)" \
    -- run "$T/fills.wrl"
  if [ $tool = run ]; then  # another drawn time
    check "$tool empty at the drawn time, and in which frames" 0 \
      "shrink.wrl:2:43: warning: empty shape: f <= 0 everywhere in its box, so nothing is drawn; the same in 12 of 24 frames" \
      -- run "$T/shrink.wrl" --fraction 0.75
    check "$tool full in some frames, not at the drawn time" 0 \
      "fills.wrl:2:43: warning: full shape in 3 of 24 frames of its animation \(fractions 0 to 0.0833\): a solid block" \
      -- run "$T/fills.wrl" --fraction 0.2
  fi
  none "$tool an animation that never empties or fills" -- run "$T/moves.wrl"
  none "$tool a ball inside its box" -- run "$T/ball.wrl"
  none "$tool children of an FTransform are cut by their boxes on purpose" -- run "$T/group.wrl"
  for f in "$SRC"/examples/paper/*.wrl "$SRC"/examples/*.fs; do
    [ "$(basename "$f")" = blobs.fs ] || none "$tool $(basename "$f")" -- run "$f"
  done
  check "$tool a 2D slice is cut on the z faces: a note" 0 "blobs.fs:1:1: note: the box cuts the shape on its faces -z .*, \+z " \
    -- run "$SRC/examples/blobs.fs"
done
check "check: warnings exit 0" 0 "" -- "$F" check "$T/away.wrl"

jcheck "--stats: the findings as JSON, with the fix" err "
[d['issue'] for d in j['shape_diagnostics']] == ['cut'] and j['shape_diagnostics'][0]['severity'] == 'warning' and
j['shape_diagnostics'][0]['line'] == 4 and j['shape_diagnostics'][0]['col'] == 3 and
j['shape_diagnostics'][0]['bboxSize'] == [2.6, 2.6, 2.6] and j['shape_diagnostics_ms'] >= 0
" -- "$R" "$T/cut.wrl" --stats -o "$T/c.ply"
jcheck "--stats: finer than the grid with its resolution, the NaN share" err "
{d['issue']: d for d in j['shape_diagnostics']}['finer']['resolution'] == 100 and
{d['issue']: d for d in j['shape_diagnostics']}['empty']['line'] == 3
" -- "$R" "$T/sheet.wrl" --stats -o "$T/s.ply"
jcheck "--stats: an inside-out shape is its own issue" err "
[d['issue'] for d in j['shape_diagnostics']] == ['inside-out']
" -- "$R" "$T/inverted.wrl" --stats -o "$T/i.ply"
jcheck "--stats: the NaN share" err "
near(j['shape_diagnostics'][0]['fraction'], 0.5, 0.02) and j['shape_diagnostics'][0]['issue'] == 'nan'
" -- "$R" "$T/sqrt.wrl" --stats -o "$T/q.ply"

finish shape_diagnostics
