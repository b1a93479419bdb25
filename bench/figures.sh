#!/usr/bin/env bash
# The current figures of docs/performance.md in one run: evaluation of the shared benchmarks on
# every backend (points, grid rows, one point), the C baselines compiled now, prospero's picture
# dense and pruned, and whole processes (small scenes, meshes). One thread; best of RUNS. Prints
# the tables as Markdown with the machine, the date and the commit they were taken on.
# usage: bench/figures.sh [RUNS]   (SHARED=DIR for the shared data, default ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
F=build/tools/fscript/fscript
R=build/tools/fvrml-run/fvrml-run
[ -x "$F" ] && [ -x "$R" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
RUNS=${1:-5}
SHARED=${SHARED:-../shared}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
BACKENDS="vm sse llvm"

best() { sort -g | head -1 | xargs printf '%.3g\n' 2>/dev/null || true; }
# ns per point of `fscript bench` (best of RUNS)
ns() { for _ in $(seq "$RUNS"); do "$F" bench "$@" 2>/dev/null | sed -n 's/^\([0-9.]*\) ns\/eval$/\1/p'; done | best; }
# ms of one render2d picture (best of RUNS processes of --repeat 5)
pic() {
  for _ in $(seq "$RUNS"); do
    "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 1024 --bounds -1,1,-1,1 -o "$OUT/p.png" \
      --repeat 5 --threads 1 "$@" 2>/dev/null | sed -n 2p | cut -d' ' -f1
  done | best
}
# whole-process wall time in ms (best of RUNS, or of N for `N=3 wall ...`)
wall() {
  for _ in $(seq "${N:-$RUNS}"); do
    local t0 t1
    t0=$(date +%s%N)
    "$R" "$@" --threads 1 --force > /dev/null 2>&1
    t1=$(date +%s%N)
    echo $(((t1 - t0) / 1000000))
  done | best
}

cpu() { grep -m1 "^$1" /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'; }
isa=AVX2; grep -qw avx512f /proc/cpuinfo && isa=AVX-512
echo "Machine: $(cpu 'model name') (family $(cpu 'cpu family') model $(cpu 'model'), $isa), $(nproc) cores;" \
  "$(date -u +%Y-%m-%d); commit $(git rev-parse --short HEAD); one thread, best of $RUNS."
echo
C=$(for _ in 1 2 3; do bench/c/run.sh 2>/dev/null || true; done)  # the best of three runs of each C program
cval() { grep -F "$1" <<< "$C" | sed -E 's/.*: *([0-9.]+).*/\1/' | best; }
echo "| ns per point | vm | sse | llvm | C gcc -O3 -march=x86-64-v2 | C clang -O3 -march=native |"
echo "|---|---|---|---|---|---|"
for fn in gyroid csg8; do
  row="| $fn, points |"
  for b in $BACKENDS; do row+=" $(ns "$SHARED/bench/$fn.fs" --entry FRep --points 2000000 --backend "$b") |"; done
  echo "$row $(cval "x86-64-v2 $fn:") | $(cval "native $fn:") |"
  row="| $fn, grid rows |"
  for b in $BACKENDS; do row+=" $(ns "$SHARED/bench/$fn.fs" --entry FRep --points 2000000 --backend "$b" --grid) |"; done
  echo "$row $(cval "x86-64-v2 $fn row by row") | $(cval "native $fn row by row") |"
done
row="| gyroid, one point per call |"
for b in $BACKENDS; do row+=" $(ns "$SHARED/bench/gyroid.fs" --entry FRep --points 200000 --backend "$b" --one-point) |"; done
echo "$row | |"
echo
echo "| prospero 1024^2 (ms) | vm | sse | llvm | C gcc -O3 -march=x86-64-v2 | C clang -O3 -march=native |"
echo "|---|---|---|---|---|---|"
row="| dense (every pixel) |"
for b in $BACKENDS; do row+=" $(pic --backend "$b" --no-prune) |"; done
echo "$row $(cval "x86-64-v2 prospero") | $(cval "native prospero") |"
row="| pruned (quadtree, simplified tapes) |"
for b in $BACKENDS; do row+=" $(pic --backend "$b") |"; done
echo "$row | |"
echo
echo "| whole process, wall (ms) | vm | sse | llvm | auto |"
echo "|---|---|---|---|---|"
for job in examples/paper/figure1-morphing.wrl examples/paper/figure2-texture.wrl examples/paper/figure3-colour.wrl \
           bench/scenes/sphere256.wrl bench/scenes/gyroid-sphere256.wrl; do
  ext=glb
  case "$job" in bench/*) ext=ply ;; esac
  row="| $(basename "$job" .wrl) ($ext) |"
  for b in $BACKENDS auto; do row+=" $(wall "$job" -o "$OUT/x.$ext" --backend "$b") |"; done
  echo "$row"
done
# The union of 400 balls (about 3,200 operations) in a box of 2 at 256^3: seconds a run, so best of 3.
if [ -f "$SHARED/data/spheres400.fs" ]; then
  { printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { bboxSize 2 2 2 resolution [256] definition "'
    cat "$SHARED/data/spheres400.fs"
    printf '" } }\n'; } > "$OUT/spheres400.wrl"
  row="| spheres400 at 256^3 (ply) |"
  for b in $BACKENDS auto; do row+=" $(N=3 wall "$OUT/spheres400.wrl" -o "$OUT/x.ply" --backend "$b") |"; done
  echo "$row"
fi
