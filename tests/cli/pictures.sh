#!/usr/bin/env bash
# Standard geometry in pictures and glTF: IndexedLineSet lines in their own colours (a Color node
# per polyline or per vertex, else the Material's emissiveColor), as VRML97 browsers draw them.
# usage: pictures.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
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

finish pictures
