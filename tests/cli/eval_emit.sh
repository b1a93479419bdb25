#!/usr/bin/env bash
# `fscript eval` of rows, `fscript check` of scenes (gzip, positions), `emit-ir` and its passes.
# usage: eval_emit.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

printf '0,0,0\n# a comment\n\n1,0,0\n0.5,0.5,0\nnan,0,0\n' > "$T/pts.csv"
check eval-rows 0 '^0\.5$' -- "$F" eval "$T/sphere.fs" --entry FRep --points "$T/pts.csv"
out=$("$F" eval "$T/sphere.fs" --entry FRep --points "$T/pts.csv")
[ "$out" = $'1\n0\n0.5\nnan' ] || { echo "FAIL eval-exact: got [$out]"; fails=$((fails + 1)); }
printf '0,0,0\n1,zero,0\n' > "$T/badpts.csv"
check eval-bad-row 1 'badpts.csv:2: error' -- "$F" eval "$T/sphere.fs" --entry FRep --points "$T/badpts.csv"
check eval-stdin 0 '^1$' -- bash -c "echo 0,0,0 | \"$F\" eval \"$T/sphere.fs\" --entry FRep"

cat > "$T/ftransform.wrl" <<'WRL'
#VRML V2.0 utf8
FTransform { operation "union" translation "0.5*t, sin(t), 0" scale "1 1 1"
  rotation "0, 0, 1,
            2*t + oops" children [] }
WRL
check wrl-affine 1 'ftransform.wrl:4:19: error: unknown name .oops.' -- "$F" check "$T/ftransform.wrl"
gzip -c "$T/scene.wrl" > "$T/scene.wrl.gz"
check wrl-gzip 1 'scene.wrl.gz:4:23: error: unknown name' -- "$F" check "$T/scene.wrl.gz"
check wrl-missing 1 'none.wrl:1:1: error: cannot read' -- "$F" check "$T/none.wrl"
check wrl-positions 1 'scene.wrl:4:23: error: unknown name' -- "$F" check "$T/scene.wrl"
check emit-ir 0 'fn @kernel\(4\) -> 1 kernel' -- "$F" emit-ir "$T/sphere.fs" --opt
check emit-ir-passes 0 'fmul' -- "$F" emit-ir "$T/sphere.fs" --passes inline,fold
check emit-ir-bad-pass 1 "unknown pass 'nope'" -- "$F" emit-ir "$T/sphere.fs" --passes nope

finish eval_emit
