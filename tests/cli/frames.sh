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
D="${4:-}"
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


# Frames: the limit, glTF STEP timing, contact sheets.
. "$SRC/tests/cli/fixtures.sh"
# ---- Frames: the limit, glTF STEP timing, contact sheets ----
printf '#VRML V2.0 utf8\nFShape { frames 1500 geometry FGeometry { definition "0.5^2-x^2-y^2-z^2+0.01*t" bboxSize 2 2 2 resolution [4] } }\n' > "$T/many.wrl"
check "a file's frames above 1000 are an error at the field" 1 'many.wrl:2:10: error: frames 1500 is over the limit of 1000 for one node' \
  -- "$R" "$T/many.wrl" --stats -o "$T/many.glb"
[ -e "$T/many.glb" ] && fail "a refused animation wrote many.glb"
sed -i 's/frames 1500/frames 1000/' "$T/many.wrl"
jcheck "a file's frames of 1000 are made" err "j['animations'][0]['frames'] == 1000" -- "$R" "$T/many.wrl" --stats -o "$T/many.glb"
check "--frames above 1000 is refused" 2 'frames: Value 1001 not in range 1 to 1000' -- "$R" "$T/many.wrl" --frames 1001 -o "$T/x.glb"
"$R" "$P/figure1-morphing.wrl" --frames 4 -o "$T/anim.glb" --resolution-scale 0.3 2> /dev/null
# Figure 1's cycleInterval is 5: frame k shows during [1.25k, 1.25(k+1)), a last key at 5 repeats the first.
jcheck "glTF: 4 frames switched by STEP scale keys over the 5 s cycle" out "
len(j['channels']) == 4 and all(c['interpolation'] == 'STEP' and c['path'] == 'scale' for c in j['channels']) and
all(near(a, b, 1e-6) for c in j['channels'] for a, b in zip(c['times'], [0, 1.25, 2.5, 3.75, 5])) and
all(len(c['times']) == 5 for c in j['channels']) and
all(c['values'][i] == ([1.0, 1.0, 1.0] if i % 4 == k else [0.0, 0.0, 0.0]) for k, c in enumerate(j['channels']) for i in range(5))
" -- python3 "$SRC/tests/clients/gltf_probe.py" "$T/anim.glb"
"$R" "$P/figure1-morphing.wrl" --frames 4 -o "$T/sheet.png" --width 128 --height 96 2> /dev/null
# A 2 x 2 sheet of 64 x 48 tiles, each holding a drawn frame, the frames different.
jcheck "contact sheet: 2 x 2 tiles of 64 x 48, each drawn, the morph changing" out "
j['width'] == 128 and j['height'] == 96 and len(j['tiles']) == 4 and
all(t['drawn'] > 200 for t in j['tiles']) and len(set(t['digest'] for t in j['tiles'])) == 4
" -- python3 "$SRC/tests/clients/png_probe.py" "$T/sheet.png" --tiles 2 2
finish frames
