#!/usr/bin/env bash
# `fscript render3d`: a ball's outline counted independently, the images it offers, every bad
# argument refused, and the same PNG bytes pruned or dense on every backend and thread count.
# usage: render3d.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# The unit ball in the box [-1.5, 1.5]^3 seen down z: a pixel is on it where its centre's x, y
# lie in the unit disc (counted here in double; rays within a step of the outline may go either way).
check render3d 0 'pixels on the shape' -- "$F" render3d "$T/sphere.fs" --size 80 --bounds -1.5,1.5,-1.5,1.5,-1.5,1.5 -o "$T/ball.png"
read -r lo hi < <(python3 -c "
lo=hi=0
for r in range(80):
  for c in range(80):
    x=-1.5+(c+0.5)*3/80; y=1.5-(r+0.5)*3/80; q=x*x+y*y
    lo += q < 0.995; hi += q <= 1.005
print(lo, hi)")
got=$("$F" render3d "$T/sphere.fs" --size 80 --bounds -1.5,1.5,-1.5,1.5,-1.5,1.5 -o "$T/ball2.png" | head -1 | cut -d' ' -f1)
[ "$got" -ge "$lo" ] && [ "$got" -le "$hi" ] || fail "render3d-count: got $got pixels, want $lo to $hi"
head -c 8 "$T/ball.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' || fail "render3d-png: not a PNG"
for image in depth normal shaded; do
  check render3d-image-$image 0 "wrote $T/ball-$image.png: 64x48" -- "$F" render3d "$T/sphere.fs" --size 64x48 --image $image -o "$T/ball-$image.png"
done
cmp -s "$T/ball-depth.png" "$T/ball-normal.png" && fail "render3d-image: depth and normal images are the same"
check render3d-stats 0 'level 4x4 x 8 steps: [0-9]+ empty, [0-9]+ full, [0-9]+ ambiguous' -- "$F" render3d "$T/sphere.fs" --size 64 --stats -o "$T/s.png"
check render3d-stats-points 0 'step points evaluated: [0-9]+ \(' -- "$F" render3d "$T/sphere.fs" --size 64 --stats -o "$T/s.png"
check render3d-stats-time 0 'time: compiling [0-9.]+ ms, tracing [0-9.]+ ms \(the best of 2\), shading [0-9.]+ ms, writing the PNG [0-9.]+ ms' -- "$F" render3d "$T/sphere.fs" --size 64 --stats --repeat 2 -o "$T/s.png"
check render3d-no-prune-stats 0 'pruning: off' -- "$F" render3d "$T/sphere.fs" --size 32 --stats --no-prune -o "$T/s.png"
check render3d-view 0 'pixels on the shape' -- "$F" render3d "$T/sphere.fs" --size 32 --view 30,-20 --steps 50 -o "$T/s.png"
rm -f "$T/sphere.png"
FABS="$(cd "$(dirname "$F")" && pwd)/$(basename "$F")"
check render3d-default-output 0 'wrote sphere.png: 40x40' -- sh -c "cd '$T' && '$FABS' render3d sphere.fs --size 40"
[ -s "$T/sphere.png" ] || fail "render3d-default-output: no sphere.png next to where it ran"

# Bad arguments: usage errors (2), named; a script that is not a 3D shape and an unwritable file: 1.
check usage-render3d-size 2 '--size wants' -- "$F" render3d "$T/sphere.fs" --size 0 -o "$T/x.png"
check usage-render3d-bounds 2 '--bounds wants six' -- "$F" render3d "$T/sphere.fs" --size 8 --bounds -1,1,-1,1 -o "$T/x.png"
check usage-render3d-bounds-order 2 'X0 < X1' -- "$F" render3d "$T/sphere.fs" --size 8 --bounds 1,-1,-1,1,-1,1 -o "$T/x.png"
check usage-render3d-view 2 '--view wants' -- "$F" render3d "$T/sphere.fs" --size 8 --view 30 -o "$T/x.png"
check usage-render3d-image 2 '--image wants shaded, depth or normal' -- "$F" render3d "$T/sphere.fs" --size 8 --image colour -o "$T/x.png"
check usage-render3d-steps 2 'steps' -- "$F" render3d "$T/sphere.fs" --size 8 --steps 1 -o "$T/x.png"
check usage-render3d-same-file 2 'is the script this command reads' -- "$F" render3d "$T/sphere.fs" --size 8 -o "$T/sphere.fs"
printf 'function f(x, y) { return x - y; }\n' > "$T/plane2.fs"
check render3d-two-inputs 1 'render3d needs an entry of x, y, z' -- "$F" render3d "$T/plane2.fs" --size 8 -o "$T/x.png"
[ -e "$T/x.png" ] && fail "render3d: a refused run wrote its output"
check render3d-unwritable 1 'cannot write' -- "$F" render3d "$T/sphere.fs" --size 8 -o "$T/no/such/dir/x.png"
printf 'function FRep(x, y, z, t) { return 0.5 - sqrt(x - 2) * x - y * y - z * z; }\n' > "$T/nan3d.fs"
check render3d-nan 0 '^0 pixels on the shape' -- "$F" render3d "$T/nan3d.fs" --size 16 -o "$T/x.png"

# ---- pruned and dense pictures byte for byte, on every backend and thread count ----
printf 'function FRep(x, y, z, t) { return min(0.8 - sqrt(x * x + y * y + z * z), max(abs(x) - 0.3, abs(z) - 0.2) + 0.1 * y); }\n' > "$T/csg3d.fs"
same_picture render3d csg3d "$T/csg3d.fs" --size 70x53 --view 25,30
same_picture render3d csg3d-normal "$T/csg3d.fs" --size 41 --image normal --bounds -1,1.2,-0.9,1,-1,1
same_picture render3d blobs "$SRC/examples/blobs.fs" --size 60 --bounds -2,2,-2,2,-2,2 --image depth
same_picture render3d csg "$SRC/examples/csg.fs" --size 64x48 --view 30,20
same_picture render3d gyroid-ball "$SRC/examples/gyroid-ball.fs" --size 48 --bounds -1.2,1.2,-1.2,1.2,-1.2,1.2
# A kernel intervals cannot bound (a loop) is drawn densely.
printf 'function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 3; i = i + 1) s = s + x; return 0.5 - s * s - y * y - z * z; }\n' > "$T/loop3d.fs"
same_picture render3d loop "$T/loop3d.fs" --size 24
check render3d-loop-dense 0 'pruning: off' -- "$F" render3d "$T/loop3d.fs" --size 16 --stats -o "$T/x.png"
# A ring extruded along y, seen down y (--view 0,90): its regions' tapes drop y and are probed once
# a ray, with the dense picture's bytes; tilted, none is.
cat > "$T/extruded.fs" <<'EOF2'
function FRep(x, y, z, t) { return min(0.15 - abs(sqrt(x*x + z*z) - 0.55), 0.5 - abs(y)); }
EOF2
check render3d-constant-along-rays 0 'regions constant along their rays, probed once a ray: [1-9][0-9]*$' -- "$F" render3d "$T/extruded.fs" --size 96 --view 0,90 --stats -o "$T/x.png"
check render3d-constant-tilted 0 'regions constant along their rays, probed once a ray: 0$' -- "$F" render3d "$T/extruded.fs" --size 64 --view 10,80 --stats -o "$T/x.png"
same_picture render3d extruded "$T/extruded.fs" --size 96 --view 0,90
if [ -f "$SHARED/data/spheres400.fs" ]; then
  same_picture render3d spheres400 "$SHARED/data/spheres400.fs" --size 48 --steps 48
else
  skip_missing "render3d on spheres400" "the shared folder's data/spheres400.fs"
fi

finish render3d
