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
[ $# -ge 1 ] && [ -f "$1/libfive/include/libfive/render/brep/mesh.hpp" ] ||
  { echo "usage: bench/libfive/mesh.sh LIBFIVE_CHECKOUT [ROUNDS]" >&2; exit 2; }
LIBFIVE=$(cd "$1" && pwd)
ROUNDS=${2:-3}
SHARED=${SHARED:-../shared}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
cmake -S "$LIBFIVE" -B "$OUT/libfive" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_STUDIO_APP=OFF \
  -DBUILD_GUILE_BINDINGS=OFF -DBUILD_PYTHON_BINDINGS=OFF -DBUILD_TESTS=OFF -DENABLE_DEBUG=OFF > /dev/null
ninja -C "$OUT/libfive" libfive > /dev/null
python3 - "$SHARED/data/spheres400.fs" "$OUT/balls.h" <<'PY'
import re, sys
balls = re.findall(r'max\(f, ([0-9.]+) - \(x - ([-0-9.]+)\)\*\(x - [-0-9.]+\) - \(y - ([-0-9.]+)\)\*\(y - [-0-9.]+\) - '
                   r'\(z - ([-0-9.]+)\)\*\(z - [-0-9.]+\)\);', open(sys.argv[1]).read())
assert len(balls) == 400, len(balls)
with open(sys.argv[2], 'w') as f:
    f.write('static const double kBalls[][4] = {\n' + ''.join(f'  {{{r}, {x}, {y}, {z}}},\n' for r, x, y, z in balls) + '};\n')
PY
LIB=$(dirname "$(find "$OUT/libfive" -name 'libfive.so' | head -1)")
g++ -O3 -march=native -std=c++17 -I "$OUT" -I "$LIBFIVE/libfive/include" $(pkg-config --cflags eigen3) \
  bench/libfive/mesh.cpp -L "$LIB" -lfive -Wl,-rpath,"$LIB" -o "$OUT/mesh"
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
