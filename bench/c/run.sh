#!/usr/bin/env bash
# Builds and runs the C baseline of the shared benchmarks with the flags the issues name:
# gcc -O3 -march=x86-64-v2 -fno-math-errno (the SSE backend's target) and, when clang is there,
# clang -O3 -march=native -fno-math-errno (the LLVM backend's).
set -euo pipefail
cd "$(dirname "$0")"
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
gcc -O3 -march=x86-64-v2 -fno-math-errno -o "$OUT/gcc" baseline.c -lm
gcc -O3 -march=x86-64-v2 -fno-math-errno -o "$OUT/gcc-rows" shapes.c -lm
for f in gyroid csg8; do echo "gcc -O3 -march=x86-64-v2 $f: $("$OUT/gcc" "$f" "${1:-2000000}")"; done
for f in gyroid csg8; do echo "gcc -O3 -march=x86-64-v2 $f row by row: $("$OUT/gcc-rows" "$f" "${1:-2000000}")"; done
P=../../../shared/data/prospero.fs
if [ -f "$P" ]; then
  sed -E -f prospero.sed "$P" > "$OUT/prospero_body.h"
  gcc -O3 -march=x86-64-v2 -fno-math-errno -I"$OUT" -o "$OUT/prospero" prospero_main.c
  echo "gcc -O3 -march=x86-64-v2 prospero 1024^2: $("$OUT/prospero")"
  if command -v clang > /dev/null; then
    clang -O3 -march=native -fno-math-errno -I"$OUT" -o "$OUT/prospero-native" prospero_main.c
    echo "clang -O3 -march=native prospero 1024^2: $("$OUT/prospero-native")"
  fi
fi
if command -v clang > /dev/null; then
  clang -O3 -march=native -fno-math-errno -o "$OUT/clang" baseline.c -lm
  clang -O3 -march=native -fno-math-errno -o "$OUT/clang-rows" shapes.c -lm
  for f in gyroid csg8; do echo "clang -O3 -march=native $f: $("$OUT/clang" "$f" "${1:-2000000}")"; done
  for f in gyroid csg8; do echo "clang -O3 -march=native $f row by row: $("$OUT/clang-rows" "$f" "${1:-2000000}")"; done
fi
