#!/usr/bin/env bash
# Behaviour the docs promise, checked by its results rather than by exit statuses: the time model
# through ROUTEs, budgets and their ceilings on every backend, frames and their limit, glTF STEP
# timing, picture sizes and contact sheets, Viewpoints, --format, the llvm disk cache, every
# --stats field, the same bytes for any --threads, pattern colours, blends and mirrored transforms.
# usage: behaviour_test.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
F="$1"
SRC="$2"
R="$3"
D="$4"
. "$SRC/tests/cli/lib.sh"
P="$SRC/examples/paper"
BACKENDS="vm sse"
[ "${FS_HAVE_LLVM:-1}" = 1 ] && BACKENDS="vm sse llvm"

# ---- The time model through ROUTEs (docs/scenes.md, VRML97 TimeSensor rules) ----
# fractions SCENE NODE SPAN0 SPAN1 TIME:FRACTION...: the shape's fraction at each --time, and the t
# of its NODE (colour, texture) mapped onto the node's timeSpan.
fractions() {
  local scene="$1" node="$2" s0="$3" s1="$4"
  shift 4
  for tf in "$@"; do
    local t=${tf%%:*} f=${tf#*:}
    jcheck "$(basename "$scene") at --time $t: fraction $f" err \
      "near(j['shapes'][0]['fraction'], $f) and near(j['shapes'][0]['$node']['t'], $s0 + $f * ($s1 - $s0), 1e-6)" \
      -- "$R" "$scene" --stats --time "$t"
  done
}
# Figure 3: a 5 s looping TimeSensor routed to the shape's set_fraction. The end of a cycle gives
# 1.0, not 0.0.
fractions "$P/figure3-colour.wrl" colour -3.1415926 3.1415926 0:0 2:0.4 5:1 9.5:0.9 12.5:0.5
# Figure 2: the shape's own single 5 s cycle, restarted by a 7 s loop's cycleTime routed to its
# startTime.
fractions "$P/figure2-texture.wrl" texture 0 0.4 3:0.6 6:1 9.5:0.5 13:1 15:0.2
# A sensor whose single cycle ended exactly at load (time 0) never sends an event; one that ends
# just after load does (a stopTime before the startTime is ignored); the default stopTime 0, after
# a negative startTime, stops it at load.
printf '#VRML V2.0 utf8\nDEF S FShape { startTime -1 stopTime -2 cycleInterval 1 geometry FGeometry { definition "0.5-x*x-y*y-z*z" } }\n' > "$T/ended.wrl"
jcheck "a cycle that ended at load never ran" err "j['shapes'][0]['fraction'] == 0 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 3
sed -i 's/startTime -1/startTime -0.5/' "$T/ended.wrl"
jcheck "a cycle that ended after load holds 1.0" err "j['shapes'][0]['fraction'] == 1 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 3
jcheck "a cycle running at --time 0.25" err "near(j['shapes'][0]['fraction'], 0.75) and j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 0.25
sed -i 's/ stopTime -2//' "$T/ended.wrl"
jcheck "stopTime 0 after a negative startTime stops the sensor at load" err "j['shapes'][0]['fraction'] == 0 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 0.25
jcheck "--fraction overrides the clock" err "near(j['shapes'][0]['fraction'], 0.3)" \
  -- "$R" "$P/figure3-colour.wrl" --stats --time 9.5 --fraction 0.3

# ---- Budgets and their ceilings, the same on every backend ----
printf 'function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n' > "$T/down.fs"
printf 'function f(n) { var a = new Array(n); a[0] = 2; return a[0] + a.length; }\n' > "$T/arr.fs"
printf 'function f(n) { var s = 0; for (var i = 0; i < n; i++) s = s + 1; return s; }\n' > "$T/loop.fs"
for b in $BACKENDS; do
  # down(n) makes n + 1 nested calls.
  check "call depth 5 allows down(4) on $b" 0 '^4$' -- "$F" run "$T/down.fs" 4 --max-call-depth 5 --backend "$b"
  check "call depth 5 refuses down(5) on $b" 1 'down.fs:1:53: error: call depth budget exceeded: more than 5 nested calls' \
    -- "$F" run "$T/down.fs" 5 --max-call-depth 5 --backend "$b"
  check "the call depth ceiling, 100,000, reached on $b" 0 '^99999$' -- "$F" run "$T/down.fs" 99999 --max-call-depth 100000 --backend "$b"
  check "default call depth 1,000 on $b" 1 'more than 1000 nested calls' -- "$F" run "$T/down.fs" 1000 --backend "$b"
  check "array of the budget's size on $b" 0 '^1002$' -- "$F" run "$T/arr.fs" 1000 --max-array-elements 1000 --backend "$b"
  check "array one over the budget on $b" 1 "arr.fs:1:25: error: array 'a' of 1001 elements: .*budget of 1000 elements" \
    -- "$F" run "$T/arr.fs" 1001 --max-array-elements 1000 --backend "$b"
  check "loop of the budget's length on $b" 0 '^50$' -- "$F" run "$T/loop.fs" 50 --max-loop-iterations 50 --backend "$b"
  check "loop one over the budget on $b" 1 'loop.fs:1:28: error: loop iteration budget exceeded: more than 50 iterations' \
    -- "$F" run "$T/loop.fs" 51 --max-loop-iterations 50 --backend "$b"
done
# A runaway loop stops the whole job at its first point's budget (the VM used to take its 512-lane
# chunk times the budget: 41 s for render2d, 79 s for fvrml-run); `timeout` only stops a hang.
printf 'function FRep(x, y, z, t) {\n  while (1) {}\n  return 1;\n}\n' > "$T/runaway.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z, t) { while (1) {} return 1; }" } }\n' > "$T/runaway.wrl"
for b in $BACKENDS; do
  check "a runaway loop fails fast in render2d on $b" 1 'runaway.fs:2:3: error: loop iteration budget exceeded' \
    -- timeout 20 "$F" render2d "$T/runaway.fs" --size 64 --bounds -1,1,-1,1 --backend "$b" -o "$T/runaway.png"
  check "a runaway loop fails fast in fvrml-run on $b" 1 'runaway.wrl:2:71: error: loop iteration budget exceeded' \
    -- timeout 20 "$R" "$T/runaway.wrl" --backend "$b" -o "$T/runaway.ply"
done
# A runtime error in a .wrl names one place: the script's own line and column in the .wrl, and shows
# the line with a caret, as a compile error does.
printf '#VRML V2.0 utf8\n# a comment\nFShape {\n  geometry FGeometry {\n    definition "function FRep(x, y, z, t) {\n      var s = 0;\n      while (1) { s = s + 1; }\n      return s;\n    }"\n  }\n}\n' > "$T/loop7.wrl"
check "a runtime error points at its line in the .wrl" 1 'loop7.wrl:7:7: error: loop iteration budget exceeded: more than 1000 iterations in one evaluation$' \
  -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply" --max-loop-iterations 1000
check "and shows that line" 1 '^      while \(1\) \{ s = s \+ 1; \}$' -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply"
check "with a caret under the loop" 1 '^      \^$' -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply" --max-loop-iterations 1000
# A long but finite loop (2^17 iterations a point, past the point where the VM goes lane by lane).
printf 'function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 131072; i++) s = s + 1; return s - 131072 + x; }\n' > "$T/long.fs"
check "a long loop finishes with every point on the VM" 0 '^2048 white pixels' -- "$F" render2d "$T/long.fs" -o "$T/long.png" --size 64 --bounds -1,1,-1,1 --backend vm
check "call depth above the ceiling" 2 'max-call-depth: Value 100001 not in range 1 to 100000' -- "$F" run "$T/down.fs" 1 --max-call-depth 100001
check "fvrml-run call depth above the ceiling" 2 'max-call-depth' -- "$R" "$P/figure1-morphing.wrl" --stats --max-call-depth 100001
# A resolution whose points are over the limit is refused before any work (it aborted with
# bad_alloc), and writes nothing.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x*x-y*y-z*z" bboxSize 2 2 2 resolution [100000] } }\n' > "$T/huge.wrl"
check "a resolution over the limit" 1 'huge.wrl:2:73: error: resolution \[100000 100000 100000\] of this implicit shape asks for 1e\+15 sample points, over the limit of 6.88e\+10 for one shape$' -- "$R" "$T/huge.wrl" -o "$T/huge.ply"
[ -e "$T/huge.ply" ] && { echo "FAIL a refused scene wrote $T/huge.ply"; fails=$((fails + 1)); }
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x*x" resolution [3000] } }\n' > "$T/wide.wrl"
check "a scaled resolution over the limit" 1 'resolution \[6000 6000 6000\] \(after --resolution-scale 2\) of this implicit shape asks for 2.16e\+11 sample points' -- "$R" "$T/wide.wrl" -o "$T/wide.ply" --resolution-scale 2

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

# ---- --format: the format named, whatever the file is called ----
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [8] } }\n' > "$T/ball.wrl"
for fm in ply:ply obj:'v ' wrl:'#VRML V2.0 utf8' glb:glTF png:PNG; do
  check "--format ${fm%%:*}" 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format "${fm%%:*}"
  head -c 64 "$T/ball.out" | tr -d '\000' | grep -qa -- "${fm#*:}" || fail "--format ${fm%%:*} did not write ${fm%%:*}"
done
# Binary STL: an 80-byte header, the triangle count, 50 bytes per triangle.
check "--format stl" 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format stl
python3 -c "
import struct, sys
d = open(sys.argv[1], 'rb').read()
sys.exit(0 if len(d) > 84 and len(d) == 84 + 50 * struct.unpack('<I', d[80:84])[0] else 1)" "$T/ball.out" ||
  fail "--format stl did not write binary STL"
check "--format unknown" 2 "format" -- "$R" "$T/ball.wrl" -o "$T/ball.out" --format dxf

# ---- The llvm disk cache: the second run loads the object the first one stored ----
if [ "${FS_HAVE_LLVM:-1}" = 1 ]; then
  export XDG_CACHE_HOME="$T/xdg"
  check "llvm disk cache: first run" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  before=$(stat -c '%i %Y %s' "$T"/xdg/fscript/llvm/* 2> /dev/null | sort)
  [ -n "$before" ] || fail "llvm disk cache: nothing stored"
  touch -d '2001-01-01' "$T"/xdg/fscript/llvm/*
  before=$(stat -c '%n %i %Y %s' "$T"/xdg/fscript/llvm/* | sort)
  check "llvm disk cache: second run" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  after=$(stat -c '%n %i %Y %s' "$T"/xdg/fscript/llvm/* | sort)
  [ "$before" = "$after" ] || fail "llvm disk cache: the second run compiled and stored again (before: $before; after: $after)"
  # A damaged object is not trusted: the run recompiles, answers right and stores a good one.
  for o in "$T"/xdg/fscript/llvm/*.o; do printf 'garbage' > "$o"; done
  check "llvm disk cache: a damaged object" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  unset XDG_CACHE_HOME
fi

# ---- Every --stats field ----
jcheck "--stats fields of a single run" err "
set(j) == {'compile_ms', 'dual_contouring', 'evaluation_ms', 'ftransforms', 'huge_heap_mib', 'parse_ms', 'polygonize_ms', 'prune', 'row_split', 'shapes', 'tiers', 'write_ms'} and
set(j['dual_contouring']) == {'max_qef_error_cells', 'merged_cells', 'normals', 'shapes', 'triangles', 'vertices'} and
set(j['prune']) == {'evaluated', 'evaluated_fraction', 'fallbacks', 'levels', 'points', 'pruned'} and
j['prune']['pruned'] and j['prune']['points'] == 512 and j['prune']['fallbacks'] == 0 and
[l['size'] for l in j['prune']['levels']] == [64, 32, 16, 8] and
all(j[k] >= 0 for k in ('compile_ms', 'evaluation_ms', 'parse_ms', 'polygonize_ms', 'write_ms')) and
set(j['shapes'][0]) == {'active', 'domain', 'fraction', 'frames', 'geometry', 'kind', 'line', 'resolution', 'transform', 'triangles', 'vertices'} and
j['shapes'][0]['kind'] == 'implicit' and j['shapes'][0]['line'] == 2 and j['shapes'][0]['resolution'] == [8, 8, 8] and
j['shapes'][0]['domain'] == [-1, 1, -1, 1, -1, 1] and j['shapes'][0]['triangles'] > 0 and
j['shapes'][0]['vertices'] >= j['dual_contouring']['vertices'] and
j['dual_contouring']['vertices'] * 2 - 4 == j['dual_contouring']['triangles'] == j['shapes'][0]['triangles'] and
set(j['shapes'][0]['geometry']) == {'field', 't', 'timeSpan'}
" -- "$R" "$T/ball.wrl" --stats -o "$T/b.ply"
jcheck "--stats fields of an FTransform" err "
set(j['ftransforms'][0]) == {'affine', 'fraction', 'ftransforms', 'operation', 'parent', 'shapes', 'type'} and
j['ftransforms'][0]['type'] == 'analytical' and j['ftransforms'][0]['shapes'] == [0, 1] and j['ftransforms'][0]['parent'] == -1 and
all(s['ftransform'] == 0 for s in j['shapes'])
" -- "$R" "$P/listing1-operation.wrl" --stats
jcheck "--stats fields of animated output" err "
set(j['animations'][0]) == {'bytes_per_triangle', 'cache_bytes', 'constant', 'frames', 'line', 'triangles'} and
j['animations'][0]['frames'] == 4 and not j['animations'][0]['constant'] and
near(j['animations'][0]['bytes_per_triangle'], j['animations'][0]['cache_bytes'] / j['animations'][0]['triangles'])
" -- "$R" "$P/figure1-morphing.wrl" --frames 4 -o "$T/a.wrl" --stats --resolution-scale 0.3
jcheck "--stats fields of numbered frames" err "
[f['fraction'] for f in j['frames']] == [0, 0.5] and all(f['triangles'] > 0 and f['vertices'] > 0 for f in j['frames'])
" -- "$R" "$P/figure1-morphing.wrl" --frames 2 -o "$T/fr.ply" --stats --resolution-scale 0.3

# ---- The same bytes for any --threads, every format, several scenes ----
for w in figure1-morphing figure2-texture figure6-blends listing1-operation; do
  for fmt in wrl glb ply obj stl png; do
    for th in 1 2 3 7; do
      "$R" "$P/$w.wrl" -o "$T/th$th.$fmt" --threads "$th" --resolution-scale 0.2 --width 48 --height 48 2> /dev/null ||
        fail "$w.$fmt with --threads $th"
    done
    n=$((n + 1))
    for th in 2 3 7; do
      cmp -s "$T/th1.$fmt" "$T/th$th.$fmt" || fail "$w.$fmt: --threads $th differs from --threads 1"
    done
  done
done

# Dual contouring too, frames (the frame cache) and colours included.
for th in 1 2 3; do
  "$R" "$P/figure6-blends.wrl" --mesher dc -o "$T/dc-th$th.glb" --threads "$th" --resolution-scale 0.5 2> /dev/null ||
    fail "figure6-blends --mesher dc with --threads $th"
  "$R" "$P/figure2-texture.wrl" --mesher dc --frames 3 -o "$T/dc-fr-th$th.wrl" --threads "$th" --resolution-scale 0.3 2> /dev/null ||
    fail "figure2-texture --mesher dc --frames 3 with --threads $th"
done
for th in 2 3; do
  n=$((n + 1))
  cmp -s "$T/dc-th1.glb" "$T/dc-th$th.glb" || fail "figure6-blends --mesher dc: --threads $th differs from --threads 1"
  cmp -s "$T/dc-fr-th1.wrl" "$T/dc-fr-th$th.wrl" || fail "figure2-texture --mesher dc --frames 3: --threads $th differs"
done

# ---- Colours through patternKey / patternColor: piecewise linear in the value, clamped ----
printf '#VRML V2.0 utf8\nFShape { appearance FAppearance { material FMaterial { diffuseColor "x" patternKey [-0.5 0 0.5] patternColor [1 0 0, 0 1 0, 0 0 1] } }\n geometry FGeometry { definition "0.8^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [12] } }\n' > "$T/pattern.wrl"
"$R" "$T/pattern.wrl" -o "$T/pattern-out.wrl" 2> /dev/null
jcheck "patternKey/patternColor: every vertex coloured by its x" out "
len(j['points']) > 100 and all(len(p) == 6 for p in j['points']) and all(
  max(abs(a - b) for a, b in zip(p[3:], [min(1, max(0, -2 * p[0])), max(0, 1 - 2 * abs(p[0])), min(1, max(0, 2 * p[0]))])) < 2e-3
  for p in j['points'])
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/pattern-out.wrl" --vertices

# ---- Blends: Figure 6's blended spheres are one closed surface, bigger than the plain union ----
"$R" "$P/figure6-blends.wrl" --fraction 0.5 -o "$T/f6.obj" --resolution-scale 0.4 2> /dev/null
jcheck "Figure 6: the blend is closed, oriented and 2-manifold" out "
all(j['a'][k] for k in ('watertight', 'oriented', 'manifold')) and j['a']['euler'] % 2 == 0
" -- "$D" "$T/f6.obj" "$T/f6.obj"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function frep(x,y,z,t){ var f = 0.3^2-(x-0.35)^2-y^2-z^2; var g = 0.3^2-(x+0.35)^2-y^2-z^2; return BODY; }" bboxSize 2 2 2 resolution [48] } }\n' > "$T/blend.tpl"
sed 's|BODY|max(f, g)|' "$T/blend.tpl" > "$T/union.wrl"
sed 's|BODY|f + g + sqrt(f*f + g*g) + 0.02 / (1 + (f/0.1)^2 + (g/0.1)^2)|' "$T/blend.tpl" > "$T/blend.wrl"
"$R" "$T/union.wrl" -o "$T/union.obj" 2> /dev/null
"$R" "$T/blend.wrl" -o "$T/blend.obj" 2> /dev/null
python3 - "$SRC/tests/clients/mesh_probe.py" "$T" <<'PY' || fail "a blend union: one body, more volume than the plain union, less than its box"
import json, math, subprocess, sys
probe, d = sys.argv[1], sys.argv[2]
vol = lambda n: json.loads(subprocess.run([sys.executable, probe, f"{d}/{n}.obj"], capture_output=True, text=True, check=True).stdout)["volume"]
u, b = vol("union"), vol("blend")
spheres = 2 * 4 / 3 * math.pi * 0.3 ** 3
print(u, b, spheres)
sys.exit(0 if abs(u - spheres) < 0.03 * spheres and spheres * 1.02 < b < spheres * 2 else 1)
PY
n=$((n + 1))

# ---- A mirroring Transform keeps faces outward (the winding flips with the matrix) ----
for s in "1 1 1" "-1 1 1" "-1 -1 -1" "1 -2 1"; do
  printf '#VRML V2.0 utf8\nTransform { scale %s children FShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [16] } } }\n' "$s" > "$T/mirror.wrl"
  "$R" "$T/mirror.wrl" -o "$T/mirror.obj" 2> /dev/null
  jcheck "scale $s: faces outward (positive volume)" out "j['volume'] > 0.9 * 4 / 3 * 3.14159 * 0.125 * abs($(tr ' ' '*' <<< "$s"))" \
    -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/mirror.obj"
done

# ---- render2d prunes by interval arithmetic: the same PNG bytes as --no-prune, any --threads ----
# same_picture NAME FILE ARGS...: pruned and dense pictures byte for byte, on every backend.
same_picture() {
  local name="$1" file="$2"
  shift 2
  for be in $BACKENDS; do
    "$F" render2d "$file" "$@" --backend "$be" --no-prune -o "$T/dense.png" > "$T/dense.txt" 2>&1 || true
    for th in 1 3; do
      "$F" render2d "$file" "$@" --backend "$be" --threads $th -o "$T/pruned.png" > "$T/pruned.txt" 2>&1 || true
      n=$((n + 1))
      cmp -s "$T/dense.png" "$T/pruned.png" && [ "$(head -1 "$T/dense.txt")" = "$(head -1 "$T/pruned.txt")" ] ||
        fail "render2d-prune $name ($be, --threads $th): the pruned picture differs from --no-prune"
    done
  done
}
printf 'function FRep(x, y, z, t) { return min(0.9 - sqrt(x * x + y * y), max(abs(x) - 0.3, abs(y) - 0.2)); }\n' > "$T/csg2d.fs"
same_picture csg2d "$T/csg2d.fs" --size 333x211 --bounds -1.2,1.1,-1,1.3
same_picture blobs "$SRC/examples/blobs.fs" --size 200 --bounds -2,2,-2,2
for f in "$SHARED"/bench/*.fs; do [ -f "$f" ] && same_picture "$(basename "$f")" "$f" --size 160x90 --bounds -1,1,-1,1; done
if [ -f "$SHARED/data/prospero.fs" ]; then
  same_picture prospero "$SHARED/data/prospero.fs" --size 1024 --bounds -1,1,-1,1
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
same_picture loop "$T/loop2d.fs" --size 64 --bounds -1,1,-1,1

# ---- progress on a terminal: one line redrawn in place, erased at the end; nothing on a pipe ----
# (FVRML_PROGRESS_AFTER=0 shows it from the first redraw, a quarter second in, instead of after 1 s.)
TTY="$SRC/tests/cli/tty_run.py"
GY="$SRC/bench/scenes/gyroid-sphere256.wrl"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$R" "$GY" --threads 1 -o "$T/progress.ply" > "$T/progress-tty.txt" 2>&1
grep -qE $'\rfvrml-run: 0/1 meshes, [0-9]+%' "$T/progress-tty.txt" || { fail "fvrml-run on a terminal: no progress line"; cat -v "$T/progress-tty.txt" | head -5; }
grep -qE $'\r\x1b\[Kwrote [^ ]*progress.ply' "$T/progress-tty.txt" || fail "fvrml-run on a terminal: the progress line is not erased before the summary"
FVRML_PROGRESS_AFTER=0 "$R" "$GY" --threads 1 -o "$T/progress.ply" 2> "$T/progress-pipe.txt"
grep -q $'\r' "$T/progress-pipe.txt" && fail "fvrml-run on a pipe: progress written to standard error"
grep -q '^wrote [^ ]*progress.ply' "$T/progress-pipe.txt" || fail "fvrml-run on a pipe: no summary line"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$R" "$SRC/examples/paper/figure6-blends.wrl" --frames 6 --threads 1 -o "$T/progress.glb" > "$T/progress-frames.txt" 2>&1
grep -qE $'\rfvrml-run: [0-6]/6 frames, [0-9]+%' "$T/progress-frames.txt" || { fail "fvrml-run --frames on a terminal: no frames in the progress line"; cat -v "$T/progress-frames.txt" | head -5; }
printf 'function FRep(x, y, z, t) {\n  var s = 0;\n  for (var i = 0; i < 3000; i = i + 1) s = s + sin(x * i + y);\n  return s;\n}\n' > "$T/slow2d.fs"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$F" render2d "$T/slow2d.fs" --size 512 --bounds -1,1,-1,1 --no-prune -o "$T/slow2d.png" > "$T/progress-2d.txt" 2>&1
grep -qE $'\rfscript render2d: 0/1 pictures, [0-9]+%' "$T/progress-2d.txt" || { fail "render2d on a terminal: no progress line"; cat -v "$T/progress-2d.txt" | head -5; }
FVRML_PROGRESS_AFTER=0 "$F" render2d "$T/slow2d.fs" --size 512 --bounds -1,1,-1,1 --no-prune -o "$T/slow2d.png" > /dev/null 2> "$T/progress-2d-pipe.txt"
grep -q $'\r' "$T/progress-2d-pipe.txt" && fail "render2d on a pipe: progress written to standard error"

# ---- fvrml-run FILE.fs: an implicit script as one FShape; errors at the script's own lines ----
printf '// a ball\nfunction FRep(x, y, z, t) {\n  return 0.8 - sqrt(x*x + y*y + z*z);\n}\n' > "$T/ball.fs"
check "fvrml-run a script" 0 '^wrote [^ ]*ball-fs.obj: [0-9,]+ triangles, 1 shape' -- "$R" "$T/ball.fs" -o "$T/ball-fs.obj"
# (The default box is 10 wide in 50 cells: dual contouring's vertices lie within a tenth of a cell.)
jcheck "fvrml-run a script: the ball of radius 0.8, in the default box" out "
near(j['volume'], 4 / 3 * 3.14159265 * 0.8 ** 3, 0.05) and near(j['bbox'][3], 0.8, 0.02)
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/ball-fs.obj"
printf '0.7^2 - x^2 - y^2 - z^2\n' > "$T/expr.fs"
check "fvrml-run an expression script" 0 'triangles, 1 shape' -- "$R" "$T/expr.fs" -o "$T/expr.ply"
printf 'function FRep(x, y, z, t) {\n  return 0.8 - sqrt(x*x + y*y + z*z) +;\n}\n' > "$T/bad.fs"
check "fvrml-run a script with a syntax error" 1 'bad.fs:2:39: error: expected an expression' -- "$R" "$T/bad.fs" -o "$T/bad.ply"
# --mesher dc: dual contouring keeps a turned cube's corners with a closed mesh of fewer triangles.
printf 'function FRep(x, y, z, t) {\n  var a = 0.8 * x + 0.6 * y, b = -0.6 * x + 0.8 * y;\n  return 0.5 - max(max(abs(a), abs(b)), abs(z));\n}\n' > "$T/turned.fs"
check "fvrml-run --mesher mt" 0 'wrote [^ ]*turned-mt.ply' -- "$R" "$T/turned.fs" --mesher mt -o "$T/turned-mt.ply"
jcheck "fvrml-run --mesher dc: closed, oriented, genus 0, under half the triangles" out "
j['watertight'] and j['manifold'] and j['euler'] == 2 and j['triangles'] < 912 / 2 and j['hausdorff'] < 0.2
" -- "$R" "$T/turned.fs" --mesher dc --check "$T/turned-mt.ply" -o "$T/turned-dc.ply"
check "fvrml-run --mesher other" 2 'mesher: xx not in' -- "$R" "$T/turned.fs" --mesher xx -o "$T/turned-xx.ply"
# Adaptive: flat faces merge into large cells; --tolerance 0 keeps one vertex per sheet of every cell.
jcheck "fvrml-run --mesher dc --stats: merged cells, fewer triangles, QEF error" err "
j['dual_contouring']['shapes'] == 1 and j['dual_contouring']['merged_cells'] > 0 and
j['dual_contouring']['triangles'] < 288 / 2 and j['dual_contouring']['max_qef_error_cells'] < 0.02
" -- "$R" "$T/turned.fs" --mesher dc --stats -o "$T/turned-dc2.ply"
# Normals from the function's gradient (a straight-line script); noise of x has none: differences.
jcheck "fvrml-run --stats: the turned cube's normals from its gradient" err "
j['dual_contouring']['normals']['gradient'] > 100 and j['dual_contouring']['normals']['differences'] == 0
" -- "$R" "$T/turned.fs" --stats -o "$T/turned-dc4.ply"
printf 'function FRep(x, y, z, t) { return 0.5 - sqrt(x*x + y*y + z*z) + 0.05 * noise(4*x, 4*y, 4*z); }\n' > "$T/noisy.fs"
jcheck "fvrml-run --stats: noise has no gradient, its normals come from differences" err "
j['dual_contouring']['normals']['gradient'] == 0 and j['dual_contouring']['normals']['differences'] > 100
" -- "$R" "$T/noisy.fs" --stats -o "$T/noisy.ply"
jcheck "fvrml-run --mesher dc --tolerance 0: no merged cells" err "
j['dual_contouring']['merged_cells'] == 0 and j['dual_contouring']['triangles'] == 288
" -- "$R" "$T/turned.fs" --mesher dc --tolerance 0 --stats -o "$T/turned-dc3.ply"
check "fvrml-run --tolerance below 0" 2 'tolerance: Value -1 not in range' -- "$R" "$T/turned.fs" --mesher dc --tolerance -1 -o "$T/turned-neg.ply"
[ -e "$T/turned-neg.ply" ] && fail "fvrml-run --tolerance -1 wrote turned-neg.ply"
check "fvrml-run --tolerance with --mesher mt warns" 0 'warning: --tolerance has no effect with --mesher mt' -- \
  "$R" "$T/turned.fs" --mesher mt --tolerance 0.1 -o "$T/turned-mt2.ply"
# Dual contouring through everything a shape can have and every output: colour by pattern, a
# displacement texture, a time-dependent definition, frames; PLY, OBJ, STL, glTF, VRML97 and PNG.
printf '#VRML V2.0 utf8\nFShape { cycleInterval 2 loop TRUE\n appearance FAppearance { material FMaterial { diffuseColor "x" patternKey [-0.5 0 0.5] patternColor [1 0 0, 0 1 0, 0 0 1] }\n  texture3D FTexture3D { definition "DISP" type "displacement" } }\n geometry FGeometry { definition "(0.6+0.2*t)^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [24] } }\n' > "$T/dc-all.tpl"
sed 's|DISP|0.04*sin(8*x)|' "$T/dc-all.tpl" > "$T/dc-all.wrl"
sed 's|DISP|0|' "$T/dc-all.tpl" > "$T/dc-plain.wrl"
for ext in ply obj stl glb wrl png; do
  check "fvrml-run --mesher dc -o .$ext" 0 "wrote [^ ]*dc-out.$ext" -- "$R" "$T/dc-all.wrl" --mesher dc --time 0 -o "$T/dc-out.$ext"
done
for ext in ply obj stl; do
  jcheck "--mesher dc .$ext: closed, oriented, 2-manifold" out "all(j['a'][k] for k in ('watertight', 'oriented', 'manifold'))" \
    -- "$D" "$T/dc-out.$ext" "$T/dc-out.ply"
done
head -c 8 "$T/dc-out.png" | od -An -c | grep -q 'P   N   G' || fail "--mesher dc -o .png is not a PNG"
# The VRML97 file carries the gradient's normals (vertices split at the sharp edges), as glTF does.
grep -q 'normal Normal' "$T/dc-out.wrl" || fail "--mesher dc -o .wrl: no Normal node on its IndexedFaceSet"
"$R" "$T/dc-all.wrl" --mesher mt -o "$T/mt-out.wrl" 2> /dev/null
grep -q 'creaseAngle' "$T/mt-out.wrl" && fail "--mesher mt -o .wrl: a creaseAngle beside its normals"
jcheck "--mesher dc: every vertex coloured by its x through the pattern" out "
len(j['points']) > 100 and all(len(p) == 6 for p in j['points']) and all(
  max(abs(a - b) for a, b in zip(p[3:], [min(1, max(0, -2 * p[0])), max(0, 1 - 2 * abs(p[0])), min(1, max(0, 2 * p[0]))])) < 2e-3
  for p in j['points'])
" -- python3 "$SRC/tests/clients/mesh_probe.py" "$T/dc-out.wrl" --vertices
"$R" "$T/dc-plain.wrl" --mesher dc -o "$T/dc-plain.ply" 2> /dev/null
jcheck "--mesher dc: the displacement texture moves the surface (by up to 0.04)" out "
0.02 < j['hausdorff'] < 0.06
" -- "$D" "$T/dc-plain.ply" "$T/dc-out.ply"
"$R" "$T/dc-all.wrl" --mesher dc --time 1 -o "$T/dc-t1.ply" 2> /dev/null
jcheck "--mesher dc --time 1 (t = 0.5): the time-dependent radius grows by 0.1" out "
0.08 < j['hausdorff'] < 0.16
" -- "$D" "$T/dc-out.ply" "$T/dc-t1.ply"
jcheck "--mesher dc --frames 3: three frames of the animation, each meshed by dual contouring" err "
j['dual_contouring']['shapes'] == 3 and j['dual_contouring']['triangles'] > 3 * 1000
" -- "$R" "$T/dc-all.wrl" --mesher dc --frames 3 --stats -o "$T/dc-anim.glb"
[ -s "$T/dc-anim.glb" ] || fail "--mesher dc --frames 3 wrote no dc-anim.glb"
[ -e "$T/bad.ply" ] && fail "fvrml-run a script with a syntax error wrote bad.ply"
printf 'function FRep(x, y, z, t) {\n  var s = 0;\n  while (1) { s = s + 1; }\n  return s;\n}\n' > "$T/loop.fs"
check "fvrml-run a script: a runtime error at its line" 1 '^loop.fs:3:3: error: loop iteration budget|/loop.fs:3:3: error: loop iteration budget' \
  -- "$R" "$T/loop.fs" -o "$T/loop.ply" --max-loop-iterations 1000
check "fvrml-run --mesher dc --threads 2: a runtime error at its line" 1 '/loop.fs:3:3: error: loop iteration budget' \
  -- "$R" "$T/loop.fs" -o "$T/loop-dc.ply" --max-loop-iterations 1000 --mesher dc --threads 2
[ -e "$T/loop-dc.ply" ] && fail "fvrml-run --mesher dc with a runtime error wrote loop-dc.ply"
printf 'function parametric_x(u,v,w,t){return u;}\nfunction parametric_y(u,v,w,t){return v;}\nfunction parametric_z(u,v,w,t){return 0;}\n' > "$T/flat.fs"
check "fvrml-run a parametric script says what to do" 1 'takes an implicit script.*FShape of a .wrl' -- "$R" "$T/flat.fs" -o "$T/flat.ply"
[ -e "$T/flat.ply" ] && fail "fvrml-run a parametric script wrote flat.ply"

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

# ---- fvrml-run prunes implicit meshing by an octree: the same file bytes as --no-prune ----
# same_mesh NAME SCENE ARGS...: pruned (1 and 2 threads) and dense outputs byte for byte, every backend.
same_mesh() {
  local name="$1" scene="$2"
  shift 2
  for be in $BACKENDS; do
    "$R" "$scene" "$@" --backend "$be" --no-prune -o "$T/dense.ply" > /dev/null 2>&1 || true
    for th in 1 2; do
      "$R" "$scene" "$@" --backend "$be" --threads $th -o "$T/pruned.ply" > /dev/null 2>&1 || true
      n=$((n + 1))
      [ -s "$T/dense.ply" ] && cmp -s "$T/dense.ply" "$T/pruned.ply" ||
        fail "fvrml-run-prune $name ($be, --threads $th): the pruned mesh differs from --no-prune"
    done
  done
}
cat > "$T/csg3d.wrl" <<'WRL'
#VRML V2.0 utf8
FTransform { operation "subtraction" translation "0.1, 0, 0" children [
  FShape { geometry FGeometry { definition "min(0.8^2-x^2-y^2-z^2, 0.6-abs(z))" bboxSize 2 2 2 resolution [61] } }
  FShape { geometry FGeometry { definition "0.3^2-x^2-y^2" bboxSize 2 2 2 resolution [61] } } ] }
WRL
same_mesh csg3d "$T/csg3d.wrl"
same_mesh gyroid-sphere "$SRC/bench/scenes/gyroid-sphere256.wrl" --resolution-scale 0.16
same_mesh figure6 "$P/figure6-blends.wrl" --resolution-scale 0.2 --fraction 0.5
same_mesh csg3d-dc "$T/csg3d.wrl" --mesher dc
same_mesh gyroid-sphere-dc "$SRC/bench/scenes/gyroid-sphere256.wrl" --resolution-scale 0.16 --mesher dc
jcheck "fvrml-run --stats: the octree decided regions and spared samples" err "
j['prune']['pruned'] and 0 < j['prune']['evaluated'] < j['prune']['points'] == 61 ** 3 and
sum(l['empty'] + l['full'] for l in j['prune']['levels']) > 0
" -- "$R" "$T/csg3d.wrl" --stats -o "$T/c.ply"
jcheck "fvrml-run --no-prune --stats: every sample evaluated" err "
not j['prune']['pruned'] and j['prune']['evaluated'] >= j['prune']['points'] == 61 ** 3
" -- "$R" "$T/csg3d.wrl" --stats --no-prune -o "$T/c.ply"

finish behaviour
