#!/usr/bin/env bash
# libfive's dual contouring beside `fvrml-run` meshing spheres400 in a box of 2 at 256^3 (a PLY),
# one and two threads, alternated ROUNDS times; each figure the best of 3 runs, whole process for
# fvrml-run, the render call for libfive. libfive is built here from a checkout you name (its
# Debian dependencies: libeigen3-dev, libboost-dev, libpng-dev; nothing downloaded: git clone
# https://github.com/libfive/libfive yourself), the core library only.
# usage: bench/libfive/mesh.sh LIBFIVE_CHECKOUT [ROUNDS]   (SHARED=DIR, default ../shared)
set -euo pipefail
cd "$(dirname "$0")/../.."
R=build/tools/fvrml-run/fvrml-run
[ -x "$R" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
PROGRAM=mesh
. bench/libfive/build.sh "$@"
{ printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { bboxSize 2 2 2 resolution [256] definition "'
  cat "$SHARED/data/spheres400.fs"
  printf '" } }\n'; } > "$OUT/spheres400.wrl"
best() { sort -n | head -1; }
wall() {
  for _ in 1 2 3; do
    local t0 t1
    t0=$(date +%s%N)
    "$R" "$OUT/spheres400.wrl" -o "$OUT/x.ply" --force "$@" > /dev/null 2>&1
    t1=$(date +%s%N)
    echo $(((t1 - t0) / 1000000))
  done | best
}
"$OUT/mesh" 1 | head -1 | sed 's/^/libfive: /'
"$R" "$OUT/spheres400.wrl" -o "$OUT/x.ply" --force > /dev/null 2>&1
echo "fvrml-run: $(grep -a -m1 '^element face' "$OUT/x.ply" | cut -d' ' -f3) triangles"
printf '%-6s %8s %12s %14s %14s\n' round threads libfive_ms fvrml_run_ms fvrml_run_sse_ms
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    peer=$("$OUT/mesh" "$threads" | tail -1 | cut -d' ' -f1)
    printf '%-6s %8s %12s %14s %14s\n' "$round" "$threads" "$peer" "$(wall --threads "$threads")" \
      "$(wall --threads "$threads" --backend sse)"
  done
done
