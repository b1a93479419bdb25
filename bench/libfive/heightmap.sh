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
PROGRAM=heightmap
. bench/libfive/build.sh "$@"
printf '%-6s %8s %12s %14s\n' round threads libfive_ms render3d_ms
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    peer=$("$OUT/heightmap" "$threads" | tail -1 | cut -d' ' -f1)
    ours=$("$F" render3d "$SHARED/data/spheres400.fs" --size 1024 -o "$OUT/p.png" --repeat 7 --threads "$threads" \
      2>/dev/null | sed -n 2p | cut -d' ' -f1)
    printf '%-6s %8s %12s %14s\n' "$round" "$threads" "$peer" "$ours"
  done
done
