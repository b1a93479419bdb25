#!/usr/bin/env bash
# Standard geometry in pictures and glTF: IndexedLineSet lines in their own colours (a Color node
# per polyline or per vertex, else the Material's emissiveColor), as VRML97 browsers draw them.
# usage: pictures.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"

cat > "$T/axes.wrl" <<'WRL'
#VRML V2.0 utf8
Shape { appearance Appearance { material Material { emissiveColor 1 0 0 } }
  geometry IndexedLineSet { coord Coordinate { point [ -1 0 0, 1 0 0 ] } coordIndex [ 0 1 -1 ] } }
Shape { geometry IndexedLineSet { coord Coordinate { point [ 0 -1 0, 0 1 0, 0 0 -1, 0 0 1 ] }
  color Color { color [ 0 1 0, 0 0 1 ] } colorPerVertex FALSE colorIndex [ 0 1 ] coordIndex [ 0 1 -1 2 3 -1 ] } }
Shape { geometry IndexedLineSet { coord Coordinate { point [ 0.5 0.5 0, 0.9 0.9 0 ] }
  color Color { color [ 1 1 0 ] } colorIndex [ 0 0 ] coordIndex [ 0 1 ] } }
Shape { geometry Sphere { radius 0.2 } }
WRL
"$R" "$T/axes.wrl" --size 200 -o "$T/axes.png" 2> /dev/null || fail "a picture of coloured lines"
probe() { python3 "$SRC/tests/clients/png_probe.py" "$T/axes.png" "$@"; }
jcheck "the x axis red, from its Material's emissiveColor" out "j['count'] > 100" -- probe 255 0 0 60
jcheck "the y axis green, from its Color node (per polyline)" out "j['count'] > 100" -- probe 0 255 0 60
jcheck "the z axis blue, the second polyline's colour" out "j['count'] > 50" -- probe 0 0 255 60
jcheck "a yellow line, per vertex through colorIndex" out "j['count'] > 30" -- probe 255 255 0 60

# glTF carries the same standard geometry: the lines as a LINES primitive beside the shapes'
# triangles, which keep their own normals (the axes do not take them away).
printf 'FShape { geometry FGeometry { definition "0.4^2 - x^2 - y^2 - z^2" bboxSize 1 1 1 resolution [16] } }\n' >> "$T/axes.wrl"
"$R" "$T/axes.wrl" -o "$T/axes.glb" 2> /dev/null || fail "a glTF of shapes and lines"
python3 - "$T/axes.glb" <<'PY' || fail "glTF: one LINES and one TRIANGLES primitive, the triangles with normals"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
n = struct.unpack("<I", data[12:16])[0]
doc = json.loads(data[20:20 + n])
prims = [p for m in doc["meshes"] for p in m["primitives"]]
modes = sorted(p.get("mode", 4) for p in prims)
tri = [p for p in prims if p.get("mode", 4) == 4]
sys.exit(0 if modes == [1, 4] and "NORMAL" in tri[0]["attributes"] and "COLOR_0" in tri[0]["attributes"] else 1)
PY


# Picture sizes, the Viewpoint, automatic framing, --view, --zoom and --size.
. "$SRC/tests/cli/fixtures.sh"
# ---- Pictures: size options, the Viewpoint ----
printf '#VRML V2.0 utf8\nViewpoint { position 0 0 3 }\nFShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [16] } }\n' > "$T/vp3.wrl"
sed 's/position 0 0 3/position 0 0 6/' "$T/vp3.wrl" > "$T/vp6.wrl"
sed 's/position 0 0 3/position 0.6 0 3/' "$T/vp3.wrl" > "$T/vpx.wrl"
for v in vp3 vp6 vpx; do "$R" "$T/$v.wrl" -o "$T/$v.png" --width 80 --height 60 2> /dev/null; done
jcheck "--width 80 --height 60 gives an 80 x 60 picture" out "j['width'] == 80 and j['height'] == 60" \
  -- python3 "$SRC/tests/clients/png_probe.py" "$T/vp3.png" --tiles 1 1
# The ball (radius 0.5) seen from 3 units covers about twice the width it covers from 6 (a
# quarter of the pixels), centred; a camera moved right sees it to the left of the centre.
python3 - "$SRC/tests/clients/png_probe.py" "$T" <<'PY' || fail "Viewpoint position: the ball's size and place follow the camera"
import json, subprocess, sys
probe, d = sys.argv[1], sys.argv[2]
def drawn(name):
    return json.loads(subprocess.run([sys.executable, probe, f"{d}/{name}.png", "--tiles", "1", "1"],
                                     capture_output=True, text=True, check=True).stdout)["tiles"][0]
near, far, moved = drawn("vp3"), drawn("vp6"), drawn("vpx")
ratio = near["drawn"] / max(1, far["drawn"])
print(near, far, moved, ratio)
ok = 3.0 < ratio < 5.5 and abs(near["x"] - 39.5) < 2 and abs(near["y"] - 29.5) < 2 and moved["x"] < near["x"] - 5
sys.exit(0 if ok else 1)
PY
n=$((n + 1))

# ---- Pictures: automatic framing fills about 80%; --view, --zoom and --size set the camera ----
PNGP="$SRC/tests/clients/png_probe.py"
"$R" "$T/ball.fs" -o "$T/frame.png" --size 200x150 > /dev/null 2>&1
jcheck "framing: the ball fills about 80% of the smaller side, centred" out "
j['width'] == 200 and j['height'] == 150 and 0.7 <= j['bbox_height'] / 150 <= 0.88 and
abs((j['bbox'][0] + j['bbox'][2]) / 2 - 99.5) <= 3 and abs((j['bbox'][1] + j['bbox'][3]) / 2 - 74.5) <= 3
" -- python3 "$PNGP" "$T/frame.png" --bbox
"$R" "$T/ball.fs" -o "$T/zoom.png" --size 200x150 --zoom 1.3 > /dev/null 2>&1
jcheck "--zoom 1.3 comes closer" out "j['bbox_width'] >= 1.2 * 114" -- python3 "$PNGP" "$T/zoom.png" --bbox
printf 'min(0.9 - abs(x), min(0.2 - abs(y), 0.2 - abs(z)))\n' > "$T/bar.fs"
"$R" "$T/bar.fs" -o "$T/bar-front.png" --size 200 --view 0,0 > /dev/null 2>&1
jcheck "--view 0,0 sees the bar along its length" out "j['bbox_width'] > 3 * j['bbox_height'] and j['bbox_width'] >= 150" \
  -- python3 "$PNGP" "$T/bar-front.png" --bbox
"$R" "$T/bar.fs" -o "$T/bar-side.png" --size 200 --view 90,0 > /dev/null 2>&1
jcheck "--view 90,0 sees the bar end on" out "0.8 <= j['bbox_width'] / j['bbox_height'] <= 1.25" \
  -- python3 "$PNGP" "$T/bar-side.png" --bbox
check "--size WxH" 0 "wrote" -- "$R" "$T/ball.fs" -o "$T/size.png" --size 300x100
jcheck "--size WxH: the picture's size" out "j['width'] == 300 and j['height'] == 100" -- python3 "$PNGP" "$T/size.png" --bbox
check "--size without a height" 2 "error: --size wants WxH" -- "$R" "$T/ball.fs" -o "$T/x.png" --size 20x
check "--size too small" 2 "error: --size wants WxH" -- "$R" "$T/ball.fs" -o "$T/x.png" --size 8x8
check "--view needs two angles" 2 "error: --view wants AZ,EL" -- "$R" "$T/ball.fs" -o "$T/x.png" --view 30
check "--view elevation in range" 2 "error: --view wants AZ,EL" -- "$R" "$T/ball.fs" -o "$T/x.png" --view 0,90
check "--zoom out of range" 2 "zoom" -- "$R" "$T/ball.fs" -o "$T/x.png" --zoom 0
finish pictures
