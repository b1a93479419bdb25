#!/usr/bin/env bash
# `fvrml-run`'s scene layer: --stats on the paper's examples, PROTOs, FTransforms, unused fields,
# default outputs and summaries, every format, bad scenes at their line:col.
# usage: scenes.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# fvrml-run: the scene layer (--stats) on the paper's examples, the corpus and bad scenes.
if [ -n "$R" ]; then
  for w in "$SRC"/examples/paper/*.wrl; do
    check "fvrml-run-stats $(basename "$w")" 0 '"shapes":\[\{' -- "$R" "$w" --stats
    check "fscript-check $(basename "$w")" 0 '' -- "$F" check "$w"
  done
  jcheck fvrml-run-time err "near(j['shapes'][0]['fraction'], 0.6)" -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --stats --time 3
  jcheck fvrml-run-fraction err "near(j['shapes'][0]['geometry']['t'], 0.25)" -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --stats --fraction 0.25
  check fvrml-run-kind 0 '"kind":"implicit"' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" --stats
  # --stats-file: the object in a file, with the scene's view, and the file written beside it.
  check fvrml-run-stats-file 0 '' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" -o "$T/sf.glb" --stats-file "$T/sf.json"
  jcheck fvrml-run-stats-file-json out "j['view']['background'] == [1.0, 1.0, 1.0] and j['animations'][0]['frames'] == 24" -- cat "$T/sf.json"
  [ -s "$T/sf.glb" ] || fail "fvrml-run-stats-file: no glTF written"
  check fvrml-run-stats-file-bad 1 'error: .*nowhere' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" -o "$T/sf2.glb" --stats-file "$T/nowhere/s.json"
  check fvrml-run-script-error 1 'scene.wrl:4:23: error: unknown name' -- "$R" "$T/scene.wrl" --stats
  printf '#VRML V2.0 utf8\nTransform { translation 1 2 }\n' > "$T/badfield.wrl"
  check fvrml-run-bad-field 1 'badfield.wrl:2:29: error: expected 3 numbers \(SFVec3f\)' -- "$R" "$T/badfield.wrl" --stats
  cat > "$T/proto.wrl" <<'WRL'
#VRML V2.0 utf8
PROTO Ball [ field SFString f "0.5^2-x^2-y^2-z^2" field SFVec3f at 0 0 0 ] {
  Transform { translation IS at children [ FShape { geometry FGeometry { definition IS f bboxSize 2 2 2 } } ] }
}
Ball { at 1 2 3 }
Ball { f "0.25-x^2-y^2-zz^2" }
WRL
  check fvrml-run-proto-error 1 'proto.wrl:6:24: error: unknown name .zz.' -- "$R" "$T/proto.wrl" --stats
  sed -i 's/zz/z/' "$T/proto.wrl"
  check fvrml-run-proto 0 '"transform":\[1\.0,0\.0,0\.0,0\.0,0\.0,1\.0,0\.0,0\.0,0\.0,0\.0,1\.0,0\.0,1\.0,2\.0,3\.0,1\.0\]' -- "$R" "$T/proto.wrl" --stats
  printf '#VRML V2.0 utf8\nFTransform { translation "0.5*t, sin(t), 0" rotation "0 0 1 t" children [ FShape { geometry FGeometry { definition "1-x*x" } } ] }\nInline { url "http://example.com/o.wrl" }\n' > "$T/ft.wrl"
  check fvrml-run-affine 0 '"affine":\{"rotation":4,"translation":3\}' -- "$R" "$T/ft.wrl" --stats
  check fvrml-run-inline 0 "warning: Inline 'http://example.com/o.wrl' is not fetched" -- "$R" "$T/ft.wrl" --stats
  printf '#VRML V2.0 utf8\nFTransform { translation "1 2" }\n' > "$T/ft2.wrl"
  check fvrml-run-affine-count 1 'ft2.wrl:2:27: error: .translation. of FTransform needs 3 components, found 2' -- "$R" "$T/ft2.wrl" --stats
  printf '#VRML V2.0 utf8\nTransform { translation 1 0 0 children FShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [16] } } }\n' > "$T/ball.wrl"
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry {\n  definition "0.5-x*x-y*y-z*z"\n  parameters [0 1 0 1]\n} }\n' > "$T/unused.wrl"
  check fvrml-run-unused-field 0 "unused.wrl:4:3: warning: 'parameters' is not used by an implicit shape" -- "$R" "$T/unused.wrl" -o "$T/unused.ply"
  # On a terminal without -o: a picture in the current folder, said so; -o - is VRML97 on stdout.
  RABS="$(cd "$(dirname "$R")" && pwd)/$(basename "$R")" SRCABS="$(cd "$SRC" && pwd)"
  rm -f "$T/ball.png"
  check fvrml-run-tty-default 0 'no -o given: writing ball.png .*wrote ball.png: [0-9,]+ triangles' -- \
    sh -c "cd '$T' && python3 '$SRCABS/tests/cli/tty_run.py' '$RABS' ball.wrl | tr '\n' ' '"
  [ -s "$T/ball.png" ] || fail "fvrml-run-tty-default: no ball.png"
  check fvrml-run-stdout 0 '^#VRML V2.0 utf8' -- "$R" "$T/ball.wrl" -o -
  check fvrml-run-summary 0 "^wrote $T/ball-summary.ply: [0-9,]+ triangles, 1 shape, [0-9.]+ s$" -- "$R" "$T/ball.wrl" -o "$T/ball-summary.ply"
  check fvrml-run-summary-png 0 "^wrote $T/ball-summary.png: [0-9,]+ triangles, 1 shape" -- "$R" "$T/ball.wrl" -o "$T/ball-summary.png"
  check fvrml-run-no-summary-with-stats 0 '^\{' -- sh -c "'$R' '$T/ball.wrl' -o '$T/ball-stats.ply' --stats 2>&1 >/dev/null | head -1"
  for fmt in ply obj stl; do
    check "fvrml-run-$fmt" 0 '"triangles":[1-9]' -- "$R" "$T/ball.wrl" -o "$T/ball.$fmt" --stats
  done
  head -c 3 "$T/ball.ply" | grep -q ply || { echo "FAIL ply-magic"; fails=$((fails + 1)); }
  grep -q '^f ' "$T/ball.obj" || { echo "FAIL obj-faces"; fails=$((fails + 1)); }
  python3 - "$T/ball.obj" <<'PY' || { echo "FAIL obj-translated"; fails=$((fails + 1)); }
import sys
xs = [float(l.split()[1]) for l in open(sys.argv[1]) if l.startswith('v ')]
sys.exit(0 if abs(sum(xs) / len(xs) - 1.0) < 0.05 else 1)
PY
  check fvrml-run-threads1 0 '' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/t1.ply" --threads 1 --resolution-scale 0.3
  check fvrml-run-threads2 0 '' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/t2.ply" --threads 2 --resolution-scale 0.3
  cmp -s "$T/t1.ply" "$T/t2.ply" || { echo "FAIL fvrml-run-threads-identical"; fails=$((fails + 1)); }
  check fvrml-run-frames 0 '"frames":\[' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 3 -o "$T/fr.ply" --stats --resolution-scale 0.3
  for k in 0 1 2; do [ -s "$T/fr-$k.ply" ] || { echo "FAIL frames file $k"; fails=$((fails + 1)); }; done
  check fvrml-run-frames-needs-o 2 'needs -o' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 3 --format ply
  # Animated VRML97: the frames under a Switch, a TimeSensor with the node's timing, a Script.
  check fvrml-run-frames-wrl 0 '"bytes_per_triangle":' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 4 -o "$T/anim.wrl" --resolution-scale 0.3 --stats
  for want in 'Switch \{' 'whichChoice 0' 'TimeSensor \{' 'Script \{' 'eventIn SFFloat set_fraction' \
              'ROUTE [A-Za-z_0-9]+\.frame_changed TO [A-Za-z_0-9]+\.set_whichChoice' 'fraction_changed TO'; do
    grep -qE "$want" "$T/anim.wrl" || { echo "FAIL animated wrl lacks /$want/"; fails=$((fails + 1)); }
  done
  [ "$(grep -c 'geometry IndexedFaceSet' "$T/anim.wrl")" = 4 ] || { echo "FAIL animated wrl: 4 frames wanted"; fails=$((fails + 1)); }
  check fvrml-run-frames-wrl-reads 0 '' -- "$F" check "$T/anim.wrl"
  # A node with frames whose shape does not move stays one static shape.
  check fvrml-run-frames-constant 0 '"constant":true' -- "$R" "$T/ball.wrl" --frames 3 -o "$T/still.wrl" --stats
  grep -q 'Switch' "$T/still.wrl" && { echo "FAIL a constant animation became a Switch"; fails=$((fails + 1)); }
  # The file's own `frames 10` animates by default.
  check fvrml-run-frames-field 0 '"frames":10' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/f6.wrl" --resolution-scale 0.15 --stats
  grep -q 'Switch' "$T/f6.wrl" || { echo "FAIL figure 6 is not animated"; fails=$((fails + 1)); }
  check fvrml-run-frames-glb 0 '"animations":\[\{' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 4 -o "$T/anim.glb" --resolution-scale 0.3 --stats
  check fvrml-run-png 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.png" --width 64 --height 48
  head -c 8 "$T/ball.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' || { echo "FAIL fvrml-run-png-magic"; fails=$((fails + 1)); }
  # Pictures keep the standard geometry and the Background of the scene.
  printf '#VRML V2.0 utf8\nBackground { skyColor 0 0 1 }\nShape { appearance Appearance { material Material { diffuseColor 1 0 0 } } geometry Box { } }\n' > "$T/box.wrl"
  check fvrml-run-png-standard 0 '' -- "$R" "$T/box.wrl" -o "$T/box.png" --width 64 --height 48
  # 64 x 48 = 3,072 pixels: the blue sky around, the red box in the middle.
  jcheck fvrml-run-png-sky out "500 <= j['count'] <= 2400" -- python3 "$SRC/tests/clients/png_probe.py" "$T/box.png" 0 0 255 8
  jcheck fvrml-run-png-box out "200 <= j['count'] <= 1999 and abs(j['x'] - 31.5) < 3 and abs(j['y'] - 23.5) < 3" \
    -- python3 "$SRC/tests/clients/png_probe.py" "$T/box.png" 200 0 0 120
  check fvrml-run-glb 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.glb"
  head -c 4 "$T/ball.glb" | grep -q glTF || { echo "FAIL glb-magic"; fails=$((fails + 1)); }
  # The Khronos glTF validator, when dev.sh test could install it (npm).
  if command -v node > /dev/null && [ -d "${GLTF_VALIDATOR_DIR:-/nonexistent}/gltf-validator" ]; then
    for w in "$T/ball.wrl" "$SRC"/examples/paper/figure1-morphing.wrl "$SRC"/examples/paper/figure6-blends.wrl; do
      "$R" "$w" -o "$T/v.glb" --resolution-scale 0.2 2> /dev/null
      check "gltf-validator $(basename "$w")" 0 '"numErrors":0,"numWarnings":0' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T/v.glb"
    done
    check "gltf-validator animated" 0 '"numErrors":0,"numWarnings":0' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T/anim.glb"
    # Every corpus file as glTF, validated in one run of the validator.
    if [ -d "$SHARED/corpus" ]; then
      mkdir -p "$T/glb"
      k=0
      while IFS= read -r -d '' w; do
        head -c 7 "$w" | grep -q BSCRYPT && continue
        k=$((k + 1))
        "$R" "$w" -o "$T/glb/$k.glb" --resolution-scale 0.2 --keep-going 2> /dev/null || true
        [ -s "$T/glb/$k.glb" ] || { echo "FAIL no glb for $w"; fails=$((fails + 1)); }
      done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
      check "gltf-validator corpus ($k files)" 0 '' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T"/glb/*.glb
    fi
  else
    skip_missing gltf-validator "the Khronos glTF validator is not installed in ${GLTF_VALIDATOR_DIR:-?} (./dev.sh test installs it with npm)"
  fi
  check fvrml-run-format 2 "unsupported output format 'gltf': fvrml-run writes wrl, glb, ply, obj, stl and png" -- "$R" "$T/ball.wrl" -o "$T/ball.gltf"
  check fvrml-run-unwritable 1 'cannot write' -- "$R" "$T/ball.wrl" -o "$T/no/dir/x.ply"
  [ ! -e "$T/no/dir/x.ply" ] || { echo "FAIL half-written"; fails=$((fails + 1)); }
  check fvrml-run-listing1 0 '"triangles":[1-9]' -- "$R" "$SRC/examples/paper/listing1-operation.wrl" -o "$T/l1.ply" --stats
  printf '#VRML V2.0 utf8\nFTransform { children [ FShape { geometry FGeometry { definition "x=u; y=v; z=0;" resolution [4 4] } }\n  FShape { geometry FGeometry { definition "0.5-x*x-y*y-z*z" } } ] }\nFShape { geometry FGeometry { definition "0.5-x*x-y*y-z*z" resolution [8] } }\n' > "$T/mixed.wrl"
  check fvrml-run-ftransform 1 'mixed.wrl:2:1: error: FTransform: an FTransform cannot mix implicit and parametric children' -- "$R" "$T/mixed.wrl" -o "$T/l.ply"
  [ ! -e "$T/l.ply" ] || { echo "FAIL no-output-on-error"; fails=$((fails + 1)); }
  check fvrml-run-keep-going 1 'warning: FTransform: an FTransform cannot mix' -- "$R" "$T/mixed.wrl" -o "$T/l.ply" --keep-going
  check fvrml-run-wrl-stdout 0 'geometry IndexedFaceSet' -- "$R" "$T/ball.wrl"
  for w in "$SRC"/examples/paper/figure1-morphing.wrl "$SRC"/examples/paper/figure6-blends.wrl; do
    check "fvrml-run-wrl $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/out.wrl" --resolution-scale 0.2
    check "fvrml-run-wrl-reads $(basename "$w")" 0 '' -- "$F" check "$T/out.wrl"
    grep -q 'FShape\|FGeometry\|ROUTE Time.fraction_changed TO shape' "$T/out.wrl" && { echo "FAIL FVRML nodes left in $(basename "$w")"; fails=$((fails + 1)); }
  done
  check fvrml-run-bad-backend 2 "unknown backend 'gpu'" -- "$R" "$T/badfield.wrl" --stats --backend gpu
  check fvrml-run-missing 1 'cannot read' -- "$R" "$T/none.wrl" --stats
  if [ -d "$SHARED/corpus" ]; then
    while IFS= read -r -d '' w; do
      head -c 7 "$w" | grep -q BSCRYPT && continue
      check "fvrml-run-corpus $(basename "$w")" 0 '"shapes"' -- "$R" "$w" --stats -o "$T/c.wrl" --resolution-scale 0.3 --keep-going
      check "fvrml-run-corpus-reads $(basename "$w")" 0 '' -- "$F" check "$T/c.wrl"
    done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
  fi
  # A file's meshes follow the scene's order (they once followed the nodes' addresses, which moved with
  # the heap: a backend that allocated more put the shapes of one scene in another order).
  for order in "-2 2 0" "2 0 -2" "0 -2 2"; do
    { echo "#VRML V2.0 utf8"
      for x in $order; do
        echo "Transform { translation $x 0 0 children FShape { geometry FGeometry { definition \"0.3-x*x-y*y-z*z\" bboxSize 2 2 2 resolution [16] } } }"
      done; } > "$T/order.wrl"
    for b in vm sse ${LLVM:+llvm}; do
      "$R" "$T/order.wrl" -o "$T/order.obj" --backend "$b" > /dev/null 2>&1
      got=$(awk '/^v /{ x = $2 + 0; c = x < -1 ? -2 : x > 1 ? 2 : 0; if (c != last) { printf "%s ", c; last = c } }' last=9 "$T/order.obj")
      [ "$got" = "$order " ] || { echo "FAIL shapes out of order ($b): want '$order', got '$got'"; fails=$((fails + 1)); }
    done
  done
  # Every corpus file and example: the same mesh, byte for byte, with the sse and llvm backends as with the VM,
  # the VM's without the row split (every grid point a point) and the others' with it (grid rows).
  while IFS= read -r -d '' w; do
    head -c 7 "$w" | grep -q BSCRYPT && continue
    FSCRIPT_ROW_SPLIT=0 "$R" "$w" -o "$T/vm.ply" --resolution-scale 0.3 --backend vm 2> /dev/null
    check "fvrml-run-sse $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/sse.ply" --resolution-scale 0.3 --backend sse
    cmp -s "$T/vm.ply" "$T/sse.ply" || { echo "FAIL sse mesh differs from vm: $w"; fails=$((fails + 1)); }
    # auto, made to switch tiers after 2,000 points of each kernel: some batches on each.
    check "fvrml-run-auto $(basename "$w")" 0 '' -- env FSCRIPT_AUTO_SWITCH_AFTER=2000 "$R" "$w" -o "$T/auto.ply" --resolution-scale 0.3 --backend auto
    cmp -s "$T/vm.ply" "$T/auto.ply" || { echo "FAIL auto (switched mid-job) mesh differs from vm: $w"; fails=$((fails + 1)); }
    [ -z "$LLVM" ] && continue
    check "fvrml-run-llvm $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/llvm.ply" --resolution-scale 0.3 --backend llvm
    cmp -s "$T/vm.ply" "$T/llvm.ply" || { echo "FAIL llvm mesh differs from vm: $w"; fails=$((fails + 1)); }
  done < <(find "$SRC/examples" "$SHARED/corpus" -name '*.wrl' -print0 2> /dev/null)
fi

finish scenes
