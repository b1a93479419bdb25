# Sourced by bench/libfive/*.sh: libfive built from the checkout $1 (the core library only) and
# spheres400's balls written as balls.h into $OUT, then PROGRAM.cpp compiled against both into
# $OUT/PROGRAM. Sets LIBFIVE, ROUNDS, SHARED and OUT (removed on exit).
# usage (from a script in bench/libfive): PROGRAM=heightmap; . bench/libfive/build.sh "$@"
[ $# -ge 1 ] && [ -f "$1/libfive/include/libfive/tree/tree.hpp" ] ||
  { echo "usage: bench/libfive/$PROGRAM.sh LIBFIVE_CHECKOUT [ROUNDS]" >&2; exit 2; }
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
g++ -O3 -march=native -std=c++17 -I "$OUT" -I bench/libfive -I "$LIBFIVE/libfive/include" $(pkg-config --cflags eigen3) \
  "bench/libfive/$PROGRAM.cpp" -L "$LIB" -lfive -Wl,-rpath,"$LIB" -o "$OUT/$PROGRAM"
