#!/usr/bin/env bash
# Side by side with the open-source CPU renderer of the Prospero challenge: `Janos95/prospero_vm`
# (C++, interval tape simplification, OpenMP), built here with clang-19 -O3 -march=native
# -fopenmp (Debian: clang-19, libomp-19-dev) from a checkout you name, against `fscript render2d`
# on prospero at 1024^2, one and two threads, alternated ROUNDS times in the same minutes. The peer
# prints its mean over 500 renders; render2d its best of 30. Nothing is downloaded: clone the peer
# yourself (git clone https://github.com/Janos95/prospero_vm).
# usage: bench/peers.sh PROSPERO_VM_CHECKOUT [ROUNDS]   (SHARED=DIR, default ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
F=build/tools/fscript/fscript
[ -x "$F" ] || { echo "build first: ./dev.sh build" >&2; exit 2; }
[ $# -ge 1 ] && [ -f "$1/vm.cpp" ] || { echo "usage: bench/peers.sh PROSPERO_VM_CHECKOUT [ROUNDS]" >&2; exit 2; }
ROUNDS=${2:-3}
SHARED=${SHARED:-../shared}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
cp "$1/vm.cpp" "$1/prospero.vm" "$OUT/"
# -include atomic: its main() uses std::atomic_int without including <atomic> (libc++ pulls it in).
clang++-19 -O3 -march=native -fopenmp -std=c++17 -include atomic -o "$OUT/vm" "$OUT/vm.cpp"
printf '%-6s %8s %12s %12s\n' round threads peer_ms render2d_ms
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    peer=$(cd "$OUT" && OMP_NUM_THREADS=$threads ./vm | sed -n 's/.* at \([0-9.]*\)ms\/frame/\1/p')
    ours=$("$F" render2d "$SHARED/data/prospero.fs" --size 1024 --bounds -1,1,-1,1 -o "$OUT/p.png" --repeat 30 \
      --threads "$threads" 2>/dev/null | sed -n 2p | cut -d' ' -f1)
    printf '%-6s %8s %12s %12s\n' "$round" "$threads" "$peer" "$ours"
  done
done
