#!/usr/bin/env bash
# Time in outputs: a scene that changes in time is an animation in glTF and VRML97 by default (24
# frames a cycle, or its `frames` field, or --frames N), one instant with --time or --fraction; a
# format of one instant (PLY, OBJ, STL, a PNG) says so and how to get frames; a still scene stays
# still; "wrote" names exactly the files written (numbered files, a contact sheet).
# usage: frames.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
. "$SRC/tests/cli/lib.sh"

mkdir -p "$T/f"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3 + 0.2*t - sqrt(x^2+y^2+z^2)" bboxSize 2 2 2 resolution [12] } }\n' > "$T/f/grow.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3 - sqrt(x^2+y^2+z^2)" bboxSize 2 2 2 resolution [12] } }\n' > "$T/f/still.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3 + 0.2*t - sqrt(x^2+y^2+z^2)" bboxSize 2 2 2 resolution [12] } frames 5 }\n' > "$T/f/five.wrl"
probe() { python3 "$SRC/tests/clients/gltf_probe.py" "$1"; }

check "glb of a scene in time: an animation by default" 0 "^wrote $T/f/grow.glb: animated, 24 frames a cycle, " -- "$R" "$T/f/grow.wrl" -o "$T/f/grow.glb"
jcheck "glb of a scene in time: 24 meshes, each shown by its own channel" out "j['meshes'] == 24 and len(j['channels']) == 24" -- probe "$T/f/grow.glb"
check "wrl of a scene in time: an animation by default" 0 "^wrote $T/f/grow.out.wrl: animated, 24 frames a cycle" -- "$R" "$T/f/grow.wrl" -o "$T/f/grow.out.wrl"
[ "$(grep -c IndexedFaceSet "$T/f/grow.out.wrl")" = 24 ] || fail "wrl of a scene in time: 24 frames in the Switch"
grep -q "ROUTE FVRML_clock.fraction_changed" "$T/f/grow.out.wrl" || fail "wrl of a scene in time: the clock that plays it"
check "the shape's own frames field" 0 "animated, 5 frames a cycle" -- "$R" "$T/f/five.wrl" -o "$T/f/five.glb"
check "--frames N over the default" 0 "animated, 7 frames a cycle" -- "$R" "$T/f/grow.wrl" --frames 7 -o "$T/f/seven.glb"
jcheck "--frames 7: 7 meshes" out "j['meshes'] == 7" -- probe "$T/f/seven.glb"
for opt in "--fraction 0.5" "--time 0.25"; do
  check "$opt: one instant in glb" 0 "^wrote $T/f/instant.glb: [0-9,]+ triangles, 1 shape" -- "$R" "$T/f/grow.wrl" $opt -o "$T/f/instant.glb"
  jcheck "$opt: one mesh, no animation" out "j['meshes'] == 1 and j['channels'] == []" -- probe "$T/f/instant.glb"
done
check "a still scene stays still in glb" 0 "^wrote $T/f/still.glb: [0-9,]+ triangles, 1 shape" -- "$R" "$T/f/still.wrl" -o "$T/f/still.glb"
jcheck "a still scene: one mesh, no animation" out "j['meshes'] == 1 and j['channels'] == []" -- probe "$T/f/still.glb"
grep -q "note:" "$T/out.txt" && fail "a still scene gets a note about time"
for fmt in ply obj stl; do
  check "$fmt of a scene in time: says it holds one instant" 0 "note: the scene changes in time and ${fmt^^} holds one instant: this is the scene at time 0; --frames N writes N files" \
    -- "$R" "$T/f/grow.wrl" -o "$T/f/one.$fmt"
done
check "png of a scene in time: says it holds one instant" 0 "note: the scene changes in time and a picture holds one instant.*--frames N writes N frames on a contact sheet" \
  -- "$R" "$T/f/grow.wrl" --size 64 -o "$T/f/one.png"
check "ply of a still scene: no note" 0 "" -- "$R" "$T/f/still.wrl" -o "$T/f/still.ply"
grep -q "note:" "$T/out.txt" && fail "ply of a still scene gets a note about time"
check "ply at a --fraction: no note" 0 "" -- "$R" "$T/f/grow.wrl" --fraction 0.5 -o "$T/f/half.ply"
grep -q "note:" "$T/out.txt" && fail "ply at a --fraction gets a note about time"
# "wrote" says what was written.
check "--frames 4 -o m.ply names the numbered files" 0 "^wrote $T/f/m-0.ply \.\.\. $T/f/m-3.ply: 4 frame files" -- "$R" "$T/f/grow.wrl" --frames 4 -o "$T/f/m.ply"
for i in 0 1 2 3; do [ -s "$T/f/m-$i.ply" ] || fail "--frames 4: m-$i.ply"; done
[ -e "$T/f/m.ply" ] && fail "--frames 4 wrote m.ply too"
check "--frames 6 -o sheet.png says one contact sheet" 0 "^wrote $T/f/sheet.png: a contact sheet of 6 frames" -- "$R" "$T/f/grow.wrl" --frames 6 --size 64 -o "$T/f/sheet.png"
[ -e "$T/f/sheet-0.png" ] && fail "--frames 6 -o sheet.png wrote numbered pictures"
check "--frames 12 -o m.stl: two-digit numbers" 0 "^wrote $T/f/t-00.stl \.\.\. $T/f/t-11.stl: 12 frame files" -- "$R" "$T/f/grow.wrl" --frames 12 -o "$T/f/t.stl"

finish frames
