#!/usr/bin/env bash
# Pictures of standard geometry: IndexedLineSet lines in their own colours (a Color node per
# polyline or per vertex, else the Material's emissiveColor), as VRML97 browsers draw them.
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

finish pictures
