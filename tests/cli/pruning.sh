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
    "$R" "$scene" "$@" --backend "$be" --no-prune -o "$T/dense.ply" > /dev/null 2>&1 || true
    for th in 1 2; do
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
