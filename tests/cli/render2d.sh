#!/usr/bin/env bash
# `fscript render2d`: the disc's count computed independently, --repeat, default output, and
# pruning by interval arithmetic: the same PNG bytes as --no-prune on every backend and thread count.
# usage: render2d.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# render2d: a disc of radius 1 sampled on 101x101 over [-1.5, 1.5]^2; the count is computed
# independently here (float arithmetic as the tool samples it).
check render2d 0 'white pixels' -- "$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc.png"
want=$(python3 -c "
import struct
def f32(v): return struct.unpack('f', struct.pack('f', v))[0]
c=0
for r in range(101):
  for i in range(101):
    x=f32(-1.5+f32(i*f32(f32(3.0)/100))); y=f32(1.5-f32(r*f32(f32(3.0)/100)))
    c += 1-x*x-y*y >= 0
print(c)")
got=$("$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc2.png" | head -1 | cut -d' ' -f1)
[ "$got" = "$want" ] || { echo "FAIL render2d-count: got $got want $want"; fails=$((fails + 1)); }
# --repeat N renders N times (the same picture) and prints the best time once.
got=$("$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc3.png" --repeat 3)
[ "$(echo "$got" | head -1 | cut -d' ' -f1)" = "$want" ] && [ "$(echo "$got" | grep -c ' ms$')" = 1 ] ||
  { echo "FAIL render2d-repeat: $got"; fails=$((fails + 1)); }
check usage-render-repeat 2 'repeat' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,-1,1 --repeat 0
head -c 8 "$T/disc.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' || { echo "FAIL render2d-png: not a PNG"; fails=$((fails + 1)); }
# Without -o the picture goes to the current folder, named after the script; every write says so.
rm -f "$T/sphere.png"
FABS="$(cd "$(dirname "$F")" && pwd)/$(basename "$F")"
check render2d-default-output 0 'wrote sphere.png: 101x101, [0-9]+ white pixels' -- sh -c "cd '$T' && '$FABS' render2d sphere.fs --size 101 --bounds -1.5,1.5,-1.5,1.5"
[ -s "$T/sphere.png" ] || fail "render2d-default-output: no sphere.png next to where it ran"
check render2d-summary 0 "wrote $T/disc2.png: 101x101" -- "$F" render2d "$T/sphere.fs" --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc2.png"
check render2d-unwritable 1 'cannot write' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,-1,1 -o "$T/no/such/dir/x.png"

# ---- render2d prunes by interval arithmetic: the same PNG bytes as --no-prune, any --threads ----
# same_picture (tests/cli/lib.sh): pruned and dense pictures byte for byte, on every backend.
printf 'function FRep(x, y, z, t) { return min(0.9 - sqrt(x * x + y * y), max(abs(x) - 0.3, abs(y) - 0.2)); }\n' > "$T/csg2d.fs"
same_picture render2d csg2d "$T/csg2d.fs" --size 333x211 --bounds -1.2,1.1,-1,1.3
same_picture render2d blobs "$SRC/examples/blobs.fs" --size 200 --bounds -2,2,-2,2
for f in "$SHARED"/bench/*.fs; do [ -f "$f" ] && same_picture render2d "$(basename "$f")" "$f" --size 160x90 --bounds -1,1,-1,1; done
if [ -f "$SHARED/data/prospero.fs" ]; then
  same_picture render2d prospero "$SHARED/data/prospero.fs" --size 1024 --bounds -1,1,-1,1
  P=("$F" render2d "$SHARED/data/prospero.fs" -o "$T/prospero.png")
  check prospero-1024-pruned 0 '^132033 white pixels' -- "${P[@]}" --size 1024 --bounds -1,1,-1,1
  check render2d-stats 0 'points evaluated: [0-9]+ of 1048576' -- "${P[@]}" --size 1024 --bounds -1,1,-1,1 --stats
  check render2d-stats-levels 0 'level 4x4: [0-9]+ empty, [0-9]+ full, [0-9]+ ambiguous' -- "${P[@]}" --size 1024 --bounds -1,1,-1,1 --stats
  check render2d-stats-direct 0 'batches run straight from their tape: [1-9][0-9]*$' -- "${P[@]}" --size 1024 --bounds -1,1,-1,1 --stats
  check render2d-no-prune-stats 0 'pruning: off' -- "${P[@]}" --size 64 --bounds -1,1,-1,1 --stats --no-prune
else
  skip_missing "render2d pruning on prospero" "the shared folder's data/prospero.fs"
fi
# A kernel intervals cannot bound (a loop) renders densely, and says so.
printf 'function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 3; i = i + 1) s = s + x; return 0.5 - s * s - y * y; }\n' > "$T/loop2d.fs"
same_picture render2d loop "$T/loop2d.fs" --size 64 --bounds -1,1,-1,1

finish render2d
