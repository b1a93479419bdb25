#!/usr/bin/env bash
# Meshing pruned by the octree: the same file bytes as --no-prune, on every backend and thread count.
# usage: pruning.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- fvrml-run prunes implicit meshing by an octree: the same file bytes as --no-prune ----
# same_mesh NAME SCENE ARGS...: pruned (1 and 2 threads) and dense outputs byte for byte, every backend.
same_mesh() {
  local name="$1" scene="$2"
  shift 2
  for be in $BACKENDS; do
    rm -f "$T/dense.ply"  # a failed run must not compare the last scene's files
    "$R" "$scene" "$@" --backend "$be" --no-prune -o "$T/dense.ply" > /dev/null 2>&1 || true
    for th in 1 2; do
      rm -f "$T/pruned.ply"
      "$R" "$scene" "$@" --backend "$be" --threads $th -o "$T/pruned.ply" > /dev/null 2>&1 || true
      n=$((n + 1))
      [ -s "$T/dense.ply" ] && cmp -s "$T/dense.ply" "$T/pruned.ply" ||
        fail "fvrml-run-prune $name ($be, --threads $th): the pruned mesh differs from --no-prune"
    done
  done
}
cat > "$T/csg3d.wrl" <<'WRL'
#VRML V2.0 utf8
FTransform { operation "subtraction" translation "0.1, 0, 0" children [
  FShape { geometry FGeometry { definition "min(0.8^2-x^2-y^2-z^2, 0.6-abs(z))" bboxSize 2 2 2 resolution [61] } }
  FShape { geometry FGeometry { definition "0.3^2-x^2-y^2" bboxSize 2 2 2 resolution [61] } } ] }
WRL
same_mesh csg3d "$T/csg3d.wrl"
same_mesh gyroid-sphere "$SRC/bench/scenes/gyroid-sphere256.wrl" --resolution-scale 0.16
same_mesh figure6 "$P/figure6-blends.wrl" --resolution-scale 0.2 --fraction 0.5
# A union of many balls: each region of the octree meshes on its own short tape (values and gradients).
python3 - "$T/balls.wrl" <<'PY'
import random, sys
random.seed(3)
balls = ["0.04 - (x-(%.3f))*(x-(%.3f)) - (y-(%.3f))*(y-(%.3f)) - (z-(%.3f))*(z-(%.3f))" % (a, a, b, b, c, c)
         for a, b, c in ((random.uniform(-.8, .8), random.uniform(-.8, .8), random.uniform(-.8, .8)) for _ in range(40))]
while len(balls) > 1:  # a balanced tree of max
    balls = ["max(%s, %s)" % tuple(balls[i:i + 2]) if i + 1 < len(balls) else balls[i] for i in range(0, len(balls), 2)]
open(sys.argv[1], "w").write('#VRML V2.0 utf8\nFShape { geometry FGeometry { bboxSize 2 2 2 resolution [99] '
                             'definition "function FRep(x,y,z,t){ return %s; }" } }\n' % balls[0])
PY
same_mesh balls-dc "$T/balls.wrl"
jcheck "fvrml-run --stats: regions of a union of 40 balls mesh on tapes a fraction of the whole" err "
j['prune']['local_tapes']['simplified'] > 20 and j['prune']['local_tapes']['gradient_tapes'] > 0 and
0 < j['prune']['local_tapes']['mean_ops'] < 0.6 * j['prune']['local_tapes']['full_ops']
" -- "$R" "$T/balls.wrl" --stats -o "$T/b.ply"
same_mesh csg3d-dc "$T/csg3d.wrl" --mesher dc
same_mesh gyroid-sphere-dc "$SRC/bench/scenes/gyroid-sphere256.wrl" --resolution-scale 0.16 --mesher dc
jcheck "fvrml-run --stats: the octree decided regions and spared samples" err "
j['prune']['pruned'] and 0 < j['prune']['evaluated'] < j['prune']['points'] == 61 ** 3 and
sum(l['empty'] + l['full'] for l in j['prune']['levels']) > 0
" -- "$R" "$T/csg3d.wrl" --stats -o "$T/c.ply"
jcheck "fvrml-run --no-prune --stats: every sample evaluated" err "
not j['prune']['pruned'] and j['prune']['evaluated'] >= j['prune']['points'] == 61 ** 3
" -- "$R" "$T/csg3d.wrl" --stats --no-prune -o "$T/c.ply"

finish pruning
