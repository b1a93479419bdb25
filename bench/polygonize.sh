#!/usr/bin/env bash
# Polygonization benchmark: best of N runs of `fvrml-run SCENE -o out.ply --stats` for each scene,
# thread count and mode (pruned by the octree, the default, or --no-prune); prints polygonize_ms
# (meshing only), evaluation_ms (time inside function evaluation, summed over threads), write_ms,
# the whole process's wall time, the share of grid points evaluated and the triangle count.
# usage: bench/polygonize.sh [RUNS] [SCENE.wrl ...]   (default: 5 runs, bench/scenes/*.wrl and Figure 6)
#   BACKENDS="vm sse llvm" THREADS="1" bench/polygonize.sh ...   other backends, thread counts (default vm; 1 2)
#   MESHERS="mt dc" MODES=pruned bench/polygonize.sh ...          meshers (default mt), modes (default pruned dense)
set -euo pipefail
cd "$(dirname "$0")/.."
RUN=build/tools/fvrml-run/fvrml-run
[ -x "$RUN" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
RUNS=${1:-5}
shift || true
SCENES=("$@")
[ ${#SCENES[@]} -gt 0 ] || SCENES=(bench/scenes/*.wrl examples/paper/figure6-blends.wrl)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
BACKENDS=${BACKENDS:-vm}
THREADS=${THREADS:-1 2}
MESHERS=${MESHERS:-mt}
MODES=${MODES:-pruned dense}
printf '%-26s %6s %7s %7s %9s %13s %13s %8s %8s %9s %10s\n' scene mesher backend threads mode polygonize_ms evaluation_ms write_ms \
  total_ms evaluated triangles
for scene in "${SCENES[@]}"; do
  for mesher in $MESHERS; do
  for backend in $BACKENDS; do
  for threads in $THREADS; do
    for mode in $MODES; do
      flag=""
      [ "$mode" = dense ] && flag=--no-prune
      for _ in $(seq "$RUNS"); do
        t0=$(date +%s%N)
        line=$("$RUN" "$scene" -o "$OUT/out.ply" --stats --threads "$threads" --backend "$backend" --mesher "$mesher" --fraction 0.5 $flag 2>&1 >/dev/null | tail -1)
        t1=$(date +%s%N)
        python3 -c 'import json, sys; j = json.loads(sys.argv[1]); j["total_ms"] = int(sys.argv[2]) / 1e6; print(json.dumps(j))' \
          "$line" "$((t1 - t0))"
      done | python3 -c '
import json, sys
runs = [json.loads(l) for l in sys.stdin if l.startswith("{")]
best = min(runs, key=lambda j: j["total_ms"])
tris = sum(s.get("triangles", 0) for s in best["shapes"]) + sum(g.get("triangles", 0) for g in best["ftransforms"])
print("%-26s %6s %7s %7s %9s %13.1f %13.1f %8.1f %8.1f %8.1f%% %10d" % (sys.argv[1], sys.argv[5], sys.argv[4], sys.argv[2], sys.argv[3], best["polygonize_ms"],
      best["evaluation_ms"], best.get("write_ms", 0), best["total_ms"], 100 * best["prune"]["evaluated_fraction"], tris))
'  "$(basename "$scene")" "$threads" "$mode" "$backend" "$mesher"
    done
  done
  done
  done
done
