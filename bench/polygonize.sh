#!/usr/bin/env bash
# Polygonization benchmark: best of N runs of `fvrml-run SCENE -o out.ply --stats` for each scene
# and thread count; prints polygonize_ms (meshing only), evaluation_ms (time inside function
# evaluation, summed over threads), write_ms and the triangle count.
# usage: bench/polygonize.sh [RUNS] [SCENE.wrl ...]   (default: 5 runs, bench/scenes/*.wrl and Figure 6)
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
printf '%-28s %7s %14s %14s %10s %11s\n' scene threads polygonize_ms evaluation_ms write_ms triangles
for scene in "${SCENES[@]}"; do
  for threads in 1 2; do
    for _ in $(seq "$RUNS"); do
      "$RUN" "$scene" -o "$OUT/out.ply" --stats --threads "$threads" --fraction 0.5 2>&1 >/dev/null | tail -1
    done | python3 -c '
import json, sys
runs = [json.loads(l) for l in sys.stdin if l.startswith("{")]
best = min(runs, key=lambda j: j["polygonize_ms"])
tris = sum(s.get("triangles", 0) for s in best["shapes"]) + sum(g.get("triangles", 0) for g in best["ftransforms"])
print("%-28s %7s %14.1f %14.1f %10.1f %11d" % (sys.argv[1], sys.argv[2], best["polygonize_ms"], best["evaluation_ms"], best.get("write_ms", 0), tris))
' "$(basename "$scene")" "$threads"
  done
done
