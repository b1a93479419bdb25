#!/usr/bin/env bash
# libfive's heightmap renderer beside `fscript render3d` on spheres400 at 1024^2 (1024 depth
# steps), one and two threads, alternated ROUNDS times. libfive is built here from a checkout you
# name (its Debian dependencies: libeigen3-dev, libboost-dev, libpng-dev; nothing downloaded:
# git clone https://github.com/libfive/libfive yourself), the core library only.
# usage: bench/libfive/heightmap.sh LIBFIVE_CHECKOUT [ROUNDS]   (SHARED=DIR, default ../shared)
set -euo pipefail
cd "$(dirname "$0")/../.."
F=build/tools/fscript/fscript
[ -x "$F" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
[ $# -ge 1 ] && [ -f "$1/libfive/include/libfive/render/discrete/heightmap.hpp" ] ||
  { echo "usage: bench/libfive/heightmap.sh LIBFIVE_CHECKOUT [ROUNDS]" >&2; exit 2; }
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
  bench/libfive/heightmap.cpp -L "$LIB" -lfive -Wl,-rpath,"$LIB" -o "$OUT/heightmap"
printf '%-6s %8s %12s %14s\n' round threads libfive_ms render3d_ms
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    peer=$("$OUT/heightmap" "$threads" | tail -1 | cut -d' ' -f1)
    ours=$("$F" render3d "$SHARED/data/spheres400.fs" --size 1024 -o "$OUT/p.png" --repeat 7 --threads "$threads" \
      2>/dev/null | sed -n 2p | cut -d' ' -f1)
    printf '%-6s %8s %12s %14s\n' "$round" "$threads" "$peer" "$ours"
  done
done
