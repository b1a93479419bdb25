#!/usr/bin/env bash
# fvrml-run pictures of implicit shapes without meshing (the default; --render mesh rasterises the
# mesh): the same coverage as the meshed picture, shapes in front of and behind meshed ones in one
# depth buffer, colours at the surface, runtime errors at their line, contact sheets, and a
# function whose intervals bound nothing meshed instead.
# usage: direct_pictures.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"
PNGP="$SRC/tests/clients/png_probe.py"
drawn() { python3 "$PNGP" "$1" --tiles 1 1 | python3 -c "import json, sys; print(json.load(sys.stdin)['tiles'][0]['drawn'])"; }

# Direct and meshed pictures of the examples cover the same pixels within a few percent (the
# meshes' facets cut inside the true outline).
for ex in csg gyroid-ball; do
  "$R" "$SRC/examples/$ex.fs" -o "$T/$ex-direct.png" --size 240x180 --stats 2> "$T/$ex.json" ||
    fail "direct picture of $ex"
  "$R" "$SRC/examples/$ex.fs" -o "$T/$ex-mesh.png" --size 240x180 --render mesh 2> /dev/null ||
    fail "meshed picture of $ex"
  a=$(drawn "$T/$ex-direct.png") b=$(drawn "$T/$ex-mesh.png")
  python3 -c "import sys; a, b = $a, $b; sys.exit(0 if b > 1000 and abs(a - b) <= 0.05 * b else 1)" ||
    fail "$ex: the direct picture covers $a pixels, the meshed one $b"
  grep -q '"direct_shapes":\[1\]' "$T/$ex.json" || fail "$ex: --stats does not name the shape drawn directly"
  cmp -s "$T/$ex-direct.png" "$T/$ex-mesh.png" && fail "$ex: --render mesh made the same picture"
done
# The same picture on every backend and thread count.
for be in $BACKENDS; do
  for th in 1 2; do
    "$R" "$SRC/examples/csg.fs" -o "$T/csg-$be-$th.png" --size 240x180 --backend "$be" --threads $th 2> /dev/null
    cmp -s "$T/csg-$be-$th.png" "$T/csg-direct.png" || fail "csg: the direct picture differs with --backend $be --threads $th"
  done
done
check usage-render 2 'render' -- "$R" "$SRC/examples/csg.fs" -o "$T/x.png" --render raytrace

# One depth buffer: a red Box (meshed standard geometry) in front of a green implicit ball hides
# its middle; moved behind it, the ball shows there.
scene() {  # scene Z: the box at depth Z, the ball at the origin
  cat <<WRL
#VRML V2.0 utf8
Viewpoint { position 0 0 5 }
Transform { translation 0 0 $1 children Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }
  geometry Box { size 0.6 0.6 0.1 } } }
FShape { appearance FAppearance { material FMaterial { diffuseColor "r = 0; g = 1; b = 0;" } }
  geometry FGeometry { definition "1 - x^2 - y^2 - z^2" bboxSize 2.5 2.5 2.5 resolution [32] } }
WRL
}
scene 1.5 > "$T/front.wrl"
scene -1.5 > "$T/behind.wrl"
for w in front behind; do "$R" "$T/$w.wrl" -o "$T/$w.png" --size 100 2> /dev/null || fail "picture of $w.wrl"; done
jcheck "a box in front of the direct ball hides its middle" out "j['count'] > 100 and abs(j['x'] - 49.5) < 3" \
  -- python3 "$PNGP" "$T/front.png" 255 0 0 120
jcheck "the direct ball in front of a box hides it" out "j['count'] == 0" -- python3 "$PNGP" "$T/behind.png" 255 0 0 120
jcheck "the ball green where its FMaterial says" out "j['count'] > 1500" -- python3 "$PNGP" "$T/behind.png" 0 200 0 120

# An FVRML parametric square (meshed) in front of the ball hides its middle the same way.
cat > "$T/param.wrl" <<'WRL'
#VRML V2.0 utf8
Viewpoint { position 0 0 5 }
FShape { appearance FAppearance { material FMaterial { diffuseColor "r = 0; g = 0; b = 1;" } }
  geometry FGeometry { type "parametric" definition "x = u; y = v; z = 1.5;" parameters [-0.3 0.3 -0.3 0.3] resolution [4 4] } }
FShape { appearance FAppearance { material FMaterial { diffuseColor "r = 0; g = 1; b = 0;" } }
  geometry FGeometry { definition "1 - x^2 - y^2 - z^2" bboxSize 2.5 2.5 2.5 resolution [32] } }
WRL
"$R" "$T/param.wrl" -o "$T/param.png" --size 100 2> /dev/null || fail "picture of param.wrl"
jcheck "a parametric square in front of the direct ball hides its middle" out "j['count'] > 100 and abs(j['x'] - 49.5) < 3" \
  -- python3 "$PNGP" "$T/param.png" 0 0 255 120

# A runtime error in a shape drawn directly: at its line, exit status 1, no picture.
cat > "$T/oob.wrl" <<'WRL'
#VRML V2.0 utf8
FShape { geometry FGeometry { bboxSize 2 2 2 resolution [16] definition "
function FRep(x, y, z, t) {
  var a = [1, 2];
  return a[floor(x * 10) + 10] - x*x - y*y - z*z;
}" } }
WRL
check direct-runtime-error 1 'oob.wrl:5:[0-9]+: error: .*index' -- "$R" "$T/oob.wrl" -o "$T/oob.png"
[ -e "$T/oob.png" ] && fail "a failed direct picture was written"

# A contact sheet draws each frame directly: the shape moves across the frames.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3^2 - (x - t + 0.5)^2 - y^2 - z^2" bboxSize 2 2 2 resolution [24] } }\n' > "$T/move.wrl"
check direct-sheet 0 'wrote' -- "$R" "$T/move.wrl" -o "$T/move.png" --frames 4 --size 200
jcheck "the sheet shows a ball in each of its four frames" out "all(t['drawn'] > 50 for t in j['tiles'])" \
  -- python3 "$PNGP" "$T/move.png" --tiles 2 2

# Blends bound nothing by intervals (sqrt(f^2 + g^2) loses its link to f + g), in the paper's
# figure and in blobs.fs: such shapes are meshed.
check direct-blend-meshed 0 '"direct_shapes":\[\]' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/blend.png" --size 120 --stats
check direct-blobs-meshed 0 '"direct_shapes":\[\]' -- "$R" "$SRC/examples/blobs.fs" -o "$T/blobs.png" --size 120 --stats

finish direct_pictures
