#!/usr/bin/env bash
# Picture benchmark: `fscript render2d FILE --size 1024 --bounds -1,1,-1,1` for prospero, the shared
# benchmark functions, examples/blobs.fs and a disc, on each backend, pruned (the quadtree, default)
# and dense (--no-prune): the best of RUNS processes of --repeat 5 renders each, in ms (compile
# excluded, as render2d prints it), and the dense/pruned ratio.
# usage: bench/render2d.sh [RUNS]   (SHARED=DIR for the shared data, default ../shared; THREADS=N, default 1)
set -euo pipefail
cd "$(dirname "$0")/.."
F=build/tools/fscript/fscript
[ -x "$F" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
RUNS=${1:-3}
SHARED=${SHARED:-../shared}
THREADS=${THREADS:-1}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo '0.8 - sqrt(x*x + y*y)' > "$OUT/disc.fs"
best() {  # best time of RUNS processes
  for _ in $(seq "$RUNS"); do
    "$F" render2d "$@" --size 1024 --bounds -1,1,-1,1 -o "$OUT/p.png" --repeat 5 --threads "$THREADS" 2>/dev/null | sed -n 2p
  done | sort -n | head -1 | cut -d' ' -f1
}
printf '%-14s %8s %10s %10s %7s\n' function backend pruned_ms dense_ms ratio
for file in "$SHARED/data/prospero.fs" "$SHARED/bench/gyroid.fs" "$SHARED/bench/csg8.fs" examples/blobs.fs "$OUT/disc.fs"; do
  for backend in vm sse llvm; do
    p=$(best "$file" --backend "$backend")
    d=$(best "$file" --backend "$backend" --no-prune)
    printf '%-14s %8s %10s %10s %7.1f\n' "$(basename "$file")" "$backend" "$p" "$d" "$(python3 -c "print($d / $p)")"
  done
done
