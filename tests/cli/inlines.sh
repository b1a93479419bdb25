#!/usr/bin/env bash
# Inline and EXTERNPROTO files: read relative to the file that names them, meshed and drawn; a
# missing or remote Inline is a warning (an error with --strict) and the scene is drawn without it;
# broken, circular or too deep files, and EXTERNPROTOs that do not read, are errors.
# usage: inlines.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"

# ---- Inline of local files: read (relative to the file that names them), meshed and drawn ----
mkdir -p "$T/inl/parts"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.3^2 - x^2 - y^2 - z^2" bboxSize 1 1 1 resolution [16] } }\nInline { url "box.wrl" }\n' > "$T/inl/parts/ball.wrl"
printf '#VRML V2.0 utf8\nTransform { translation 1 0 0 children [ Shape { geometry Box { size 0.2 0.2 0.2 } } ] }\n' > "$T/inl/parts/box.wrl"
printf '#VRML V2.0 utf8\nTransform { translation 0 2 0 children [ Inline { url "parts/ball.wrl" } ] }\nInline { url "http://example.com/axes.wrl" }\n' > "$T/inl/main.wrl"
check "Inline: a local file's FShape is meshed; a remote URL still warns" 0 "warning: Inline 'http://example.com/axes.wrl' is not fetched" \
  -- "$R" "$T/inl/main.wrl" -o "$T/inl/main.obj"
jcheck "Inline: the inlined ball, moved by the Transform around the Inline" out "
j['triangles'] > 100 and near(j['bbox'][1], 1.7, 0.02) and near(j['bbox'][4], 2.3, 0.02) and near(j['bbox'][0], -0.3, 0.02)
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/inl/main.obj"
check "Inline: a picture of the inlined FShape and the box its own Inline names" 0 'wrote [^ ]*main.png' -- "$R" "$T/inl/main.wrl" --size 120x80 -o "$T/inl/main.png"
printf '#VRML V2.0 utf8\nInline { url "http://example.com/axes.wrl" }\n' > "$T/inl/remote.wrl"
"$R" "$T/inl/remote.wrl" --size 120x80 -o "$T/inl/remote.png" 2> /dev/null
[ -s "$T/inl/remote.png" ] || fail "Inline: a scene of one remote Inline draws no (empty) picture"
cmp -s "$T/inl/main.png" "$T/inl/remote.png" && fail "Inline: the picture does not show the Inline's contents"
# A missing file, as a student has a course file without its CoordinateAxes.wrl: a warning at the
# URL naming the path looked at, the rest of the scene drawn; --strict makes it an error.
printf '#VRML V2.0 utf8\nInline { url "missing.wrl" }\nFShape { geometry FGeometry { definition "0.3^2 - x^2 - y^2 - z^2" bboxSize 1 1 1 resolution [16] } }\n' > "$T/inl/lost.wrl"
mkdir -p "$T/inl/out"
for fmt in ply obj stl glb wrl png; do
  check "Inline: a missing file is a warning at its URL ($fmt)" 0 "lost.wrl:2:15: warning: Inline 'missing.wrl': cannot read $T/inl/missing.wrl: No such file or directory; the scene is drawn without it" \
    -- "$R" "$T/inl/lost.wrl" -o "$T/inl/out/lost.$fmt"
  [ -s "$T/inl/out/lost.$fmt" ] || fail "Inline: a missing file wrote no lost.$fmt"
done
jcheck "Inline: the rest of the scene is there" out "j['triangles'] > 100 and near(j['bbox'][0], -0.3, 0.02)" \
  -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/inl/out/lost.obj"
grep -q 'missing.wrl"' "$T/inl/out/lost.wrl" || fail "Inline: the VRML97 output lost the missing Inline's reference"
"$R" "$T/inl/lost.wrl" --stats -o "$T/inl/lost2.ply" 2> "$T/inl/stats.txt"
python3 - "$T/inl/stats.txt" "$T/inl/missing.wrl" <<'PY' || fail "Inline: --stats lists the missing Inline"
import json, sys
j = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
m = j["missing_inlines"]
sys.exit(0 if len(m) == 1 and m[0]["url"] == "missing.wrl" and m[0]["line"] == 2 and m[0]["column"] == 15
         and m[0]["looked_at"] == sys.argv[2] and m[0]["reason"] == "No such file or directory" else 1)
PY
rm -f "$T/inl/strict.ply"
check "Inline: --strict makes a missing file an error" 1 "lost.wrl:2:15: error: Inline 'missing.wrl': cannot read .*, and --strict makes a missing Inline an error" \
  -- "$R" "$T/inl/lost.wrl" --strict -o "$T/inl/strict.ply"
[ -e "$T/inl/strict.ply" ] && fail "Inline: --strict with a missing file still wrote strict.ply"
check "Inline: --strict makes a remote-only Inline an error" 1 "remote.wrl:2:15: error: Inline 'http://example.com/axes.wrl': not fetched \(no network\), and --strict" \
  -- "$R" "$T/inl/remote.wrl" --strict -o "$T/inl/strict.ply"
check "Inline: fscript check warns about a missing file" 0 "lost.wrl:2:15: warning: Inline 'missing.wrl': cannot read" -- "$F" check "$T/inl/lost.wrl"
check "Inline: a remote URL's warning says how to draw a local copy" 0 'name it first: url \["axes.wrl" "http://example.com/axes.wrl"\]' \
  -- "$R" "$T/inl/remote.wrl" -o "$T/inl/remote.ply"
# VRML97: the first URL that reads. A missing one, then a remote one, then a file that is there.
printf '#VRML V2.0 utf8\nInline { url [ "missing.wrl" "http://example.com/ball.wrl" "parts/ball.wrl" ] }\n' > "$T/inl/second.wrl"
"$R" "$T/inl/second.wrl" -o "$T/inl/second.obj" 2> "$T/inl/second.txt" || fail "Inline: a list of URLs whose third reads"
grep -q "warning" "$T/inl/second.txt" && fail "Inline: a list of URLs whose third reads still warns: $(cat "$T/inl/second.txt")"
jcheck "Inline: the third URL's ball is drawn" out "j['triangles'] > 100 and near(j['bbox'][0], -0.3, 0.02)" \
  -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/inl/second.obj"
printf '#VRML V2.0 utf8\nInline { url [ "none.wrl" "http://example.com/none.wrl" ] }\n' > "$T/inl/gone.wrl"
check "Inline: none of its URLs reads: the warning names each" 0 "warning: Inline 'none.wrl': cannot read $T/inl/none.wrl, http://example.com/none.wrl: not fetched" \
  -- "$R" "$T/inl/gone.wrl" -o "$T/inl/gone.ply"
mkdir -p "$T/inl/nested"
printf '#VRML V2.0 utf8\nInline { url "axes.wrl" }\n' > "$T/inl/nested/part.wrl"
printf '#VRML V2.0 utf8\nInline { url "nested/part.wrl" }\n' > "$T/inl/outer.wrl"
check "Inline: a missing file inside an Inline, at its own file's line" 0 "nested/part.wrl:2:15: warning: Inline 'axes.wrl': cannot read $T/inl/nested/axes.wrl" \
  -- "$R" "$T/inl/outer.wrl" -o "$T/inl/outer.ply"
printf '#VRML V2.0 utf8\nInline { url "big.wrl.gz" }\n' > "$T/inl/bomb.wrl"
python3 -c "import gzip,sys; sys.stdout.buffer.write(gzip.compress(b'#VRML V2.0 utf8\n' + b' ' * (300 << 20)))" > "$T/inl/big.wrl.gz"
check "Inline: a file that is there but refused (a gzip bomb) stays an error" 1 "bomb.wrl:2:15: error: Inline 'big.wrl.gz': the gzip data inflates" \
  -- "$R" "$T/inl/bomb.wrl" -o "$T/inl/bomb.ply"
printf '#VRML V2.0 utf8\nInline { url "b.wrl" }\n' > "$T/inl/a.wrl"
printf '#VRML V2.0 utf8\nInline { url "a.wrl" }\n' > "$T/inl/b.wrl"
check "Inline: a file that includes itself through another" 1 "b.wrl:2:15: error: Inline 'a.wrl' includes a file that includes it" -- "$R" "$T/inl/a.wrl" -o "$T/inl/a.ply"
for i in $(seq 0 17); do printf '#VRML V2.0 utf8\nInline { url "deep%d.wrl" }\n' $((i + 1)) > "$T/inl/deep$i.wrl"; done
printf '#VRML V2.0 utf8\n' > "$T/inl/deep18.wrl"
check "Inline: nesting past 16 levels is refused at the URL" 1 "deep16.wrl:2:15: error: Inline 'deep17.wrl': files nested more than 16 deep" \
  -- "$R" "$T/inl/deep0.wrl" -o "$T/inl/deep.ply"
[ -e "$T/inl/deep.ply" ] && fail "Inline: too deep a nesting still wrote deep.ply"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x,y,z,t) { while (1) { x = x + 1; } return x; }" } }\n' > "$T/inl/parts/loop.wrl"
printf '#VRML V2.0 utf8\nInline { url "parts/loop.wrl" }\n' > "$T/inl/runerr.wrl"
check "Inline: a runtime error in the inlined file's script, at its own line" 1 'parts/loop.wrl:2:68: error: loop iteration budget' \
  -- "$R" "$T/inl/runerr.wrl" -o "$T/inl/runerr.ply" --max-loop-iterations 100

# ---- EXTERNPROTO of a local file: its PROTO (named by the #fragment) is read and instantiated ----
mkdir -p "$T/ext/lib"
printf '#VRML V2.0 utf8\nPROTO Other [ ] { Group { } }\nPROTO Ball [ exposedField SFString shape "0.5^2 - x^2 - y^2 - z^2" field SFVec3f at 0 0 0 ] {\n  Transform { translation IS at children FShape { geometry FGeometry { definition IS shape bboxSize 2 2 2 resolution [16] } } }\n}\n' > "$T/ext/lib/balls.wrl"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ exposedField SFString shape field SFVec3f at ] "lib/balls.wrl#Ball"\nBall { }\nBall { shape "0.3^2 - x^2 - y^2 - z^2" at 2 0 0 }\n' > "$T/ext/main.wrl"
check "EXTERNPROTO: a local file's PROTO, with its defaults and the instance's values" 0 'wrote [^ ]*main.obj' -- "$R" "$T/ext/main.wrl" -o "$T/ext/main.obj"
jcheck "EXTERNPROTO: both balls, the second moved by the field IS'd to its Transform" out "
j['triangles'] > 100 and near(j['bbox'][0], -0.5, 0.02) and near(j['bbox'][3], 2.3, 0.02)
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/ext/main.obj"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ exposedField SFString shape ] "lib/balls.wrl#Bal"\nBall { }\n' > "$T/ext/noname.wrl"
check "EXTERNPROTO: no PROTO of that name in the file" 1 "noname.wrl:2:1: error: EXTERNPROTO Ball 'lib/balls.wrl#Bal': the file has no PROTO Bal" -- "$R" "$T/ext/noname.wrl" -o "$T/ext/x.ply"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ exposedField SFFloat shape ] "lib/balls.wrl#Ball"\nBall { }\n' > "$T/ext/type.wrl"
check "EXTERNPROTO: a field declared otherwise than in the PROTO" 1 "type.wrl:2:.*error: EXTERNPROTO Ball 'lib/balls.wrl#Ball': field 'shape' is exposedField SFString in the PROTO" -- "$R" "$T/ext/type.wrl" -o "$T/ext/x.ply"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ ] [ "missing.wrl#Ball" "http://example.com/balls.wrl#Ball" ]\nBall { }\n' > "$T/ext/lost.wrl"
check "EXTERNPROTO: a missing local file" 1 "lost.wrl:2:1: error: EXTERNPROTO Ball 'missing.wrl#Ball': cannot read" -- "$R" "$T/ext/lost.wrl" -o "$T/ext/x.ply"
[ -e "$T/ext/x.ply" ] && fail "EXTERNPROTO: a broken one still wrote x.ply"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ ] "http://example.com/balls.wrl#Ball"\nBall { }\n' > "$T/ext/remote.wrl"
check "EXTERNPROTO: a remote one still warns" 0 "warning: EXTERNPROTO 'Ball' is not fetched" -- "$R" "$T/ext/remote.wrl" -o "$T/ext/remote.wrl.out.wrl"
printf '#VRML V2.0 utf8\nShape { geometry Box { }\n' > "$T/inl/parts/broken.wrl"
printf '#VRML V2.0 utf8\nInline { url "parts/broken.wrl" }\n' > "$T/inl/broken.wrl"
check "Inline: a syntax error in the inlined file, at its own line" 1 "parts/broken.wrl:3:1: error: expected '}' to close 'Shape'" \
  -- "$R" "$T/inl/broken.wrl" -o "$T/inl/broken.ply"


# The VRML97 output names an Inline's file as seen from the output's folder.
mkdir -p "$T/inl/elsewhere/deeper"
"$R" "$T/inl/main.wrl" -o "$T/inl/elsewhere/deeper/copy.wrl" 2> /dev/null || fail "Inline: a VRML97 output in another folder"
grep -q '"../../parts/ball.wrl"' "$T/inl/elsewhere/deeper/copy.wrl" || fail "Inline: the URL not rewritten for the output's folder: $(grep -A1 Inline "$T/inl/elsewhere/deeper/copy.wrl")"
grep -q '"http://example.com/axes.wrl"' "$T/inl/elsewhere/deeper/copy.wrl" || fail "Inline: a remote URL was changed"
check "Inline: the output read again finds the inlined file" 0 "wrote" -- "$R" "$T/inl/elsewhere/deeper/copy.wrl" -o "$T/inl/elsewhere/copy.obj"
jcheck "Inline: and meshes the inlined ball" out "j['triangles'] > 100" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/inl/elsewhere/copy.obj"
"$R" "$T/inl/main.wrl" -o "$T/inl/same.wrl" 2> /dev/null
grep -q '"parts/ball.wrl"' "$T/inl/same.wrl" || fail "Inline: an output beside the scene changed the URL"
printf '#VRML V2.0 utf8
EXTERNPROTO Ball [ ] "lib/balls.wrl#Ball"
Ball { }
' > "$T/ext/plain.wrl"
"$R" "$T/ext/plain.wrl" -o "$T/inl/elsewhere/ext.wrl" 2> /dev/null || fail "EXTERNPROTO: a VRML97 output in another folder"
grep -q '"../../ext/lib/balls.wrl#Ball"' "$T/inl/elsewhere/ext.wrl" || fail "EXTERNPROTO: the URL not rewritten: $(grep -A2 EXTERNPROTO "$T/inl/elsewhere/ext.wrl")"

finish inlines
