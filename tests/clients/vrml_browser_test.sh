#!/usr/bin/env bash
# The VRML97 output in a real VRML97 browser: view3dscene / tovrmlx3d (Castle Game Engine, Debian
# package view3dscene) must read every file we write without a single warning, and must play an
# animated shape: a ball moving along x, exported as frames under a Switch, is screenshot at four
# times and must be where its frame puts it. Skipped (exit 77) when the browser is not installed; a
# failure under CI.
# usage: vrml_browser_test.sh FVRML_RUN SOURCE_DIR
set -u
R="$1"
SRC="$2"
. "$SRC/tests/support/skip.sh"
for tool in tovrmlx3d view3dscene xvfb-run python3; do
  command -v "$tool" > /dev/null ||
    { fs_skip missing vrml_browser "$tool is not installed (apt-get install view3dscene xvfb xauth)" && exit 77; exit 1; }
done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

# tovrmlx3d exits 0 even on errors: any line on standard error is a failure, except that it may
# not download the course files' Inline of http://.../CoordinateAxes.wrl (kept as written; no
# network here).
valid() {
  local err
  err=$(tovrmlx3d "$1" 2>&1 > /dev/null | grep -v 'Downloading network resources .* is not enabled')
  [ -z "$err" ] || fail "tovrmlx3d $2: $(head -3 <<<"$err")"
}

# Static output of every example and corpus file.
SHARED="${FS_SHARED_DIR:-$SRC/../shared}"
[ -d "$SHARED/corpus" ] || fs_skip missing "vrml_browser corpus" "the shared corpus $SHARED/corpus is absent" || fails=$((fails + 1))
n=0
while IFS= read -r -d '' w; do
  head -c 7 "$w" | grep -q BSCRYPT && continue
  "$R" "$w" -o "$T/s.wrl" --resolution-scale 0.2 --keep-going 2> /dev/null
  [ -s "$T/s.wrl" ] || { fail "no output for $w"; continue; }
  valid "$T/s.wrl" "$(basename "$w")"
  n=$((n + 1))
done < <(find "$SRC/examples" "$SHARED/corpus" -name '*.wrl' -print0 2> /dev/null)
echo "$n static outputs read by tovrmlx3d"

# Screenshot at time $2 of $1; prints the mean x of the orange ball's pixels.
ball_x() {
  xvfb-run -a -s "-screen 0 640x480x24" view3dscene "$1" --geometry 300x200 --screenshot "$2" "$T/shot.png" > /dev/null 2>&1
  python3 "$SRC/tests/clients/png_probe.py" "$T/shot.png" 255 128 0 90 |
    python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["x"] if j["count"] > 50 else "none")'
}

# Four frames over a 2 s cycle: the ball at x = -1, -0.5, 0, 0.5. Each screenshot time falls in
# the middle of one frame's interval.
play() {
  local file="$1" name="$2" last="" x
  "$R" "$file" -o "$T/$name.wrl" || { fail "$name: fvrml-run"; return; }
  valid "$T/$name.wrl" "$name"
  grep -q 'Switch' "$T/$name.wrl" || fail "$name: no Switch"
  for t in 0.25 0.75 1.25 1.75; do
    x=$(ball_x "$T/$name.wrl" "$t")
    [ "$x" != none ] || { fail "$name: no ball at t=$t"; continue; }
    if [ -n "$last" ]; then
      python3 -c "import sys; d = $x - $last; sys.exit(0 if 12 < d < 60 else 1)" ||
        fail "$name: at t=$t the ball is at x=$x px, after $last px: not one frame further"
    fi
    last=$x
  done
  echo "$name: the ball moved frame by frame (last at $last px)"
}

cat > "$T/own.wrl" <<'WRL'
#VRML V2.0 utf8
Viewpoint { position 0 0 4 }
DEF Ball FShape { loop TRUE cycleInterval 2 frames 4
  appearance FAppearance { material FMaterial { diffuseColor "r=1; g=0.5; b=0;" } }
  geometry FGeometry { definition "0.3^2-(x-(t*2-1))^2-y^2-z^2" bboxSize 3 1 1 resolution [48 16 16] } }
WRL
play "$T/own.wrl" own-clock

# The same ball driven by a TimeSensor of the scene through set_fraction.
cat > "$T/routed.wrl" <<'WRL'
#VRML V2.0 utf8
Viewpoint { position 0 0 4 }
DEF Clock TimeSensor { loop TRUE cycleInterval 2 }
DEF Ball FShape { frames 4
  appearance FAppearance { material FMaterial { diffuseColor "r=1; g=0.5; b=0;" } }
  geometry FGeometry { definition "0.3^2-(x-(t*2-1))^2-y^2-z^2" bboxSize 3 1 1 resolution [48 16 16] } }
ROUTE Clock.fraction_changed TO Ball.set_fraction
WRL
play "$T/routed.wrl" routed-clock
grep -q 'ROUTE Clock.fraction_changed TO Ball.set_fraction' "$T/routed-clock.wrl" || fail "the scene's ROUTE to set_fraction was dropped"

[ "$fails" = 0 ] && echo "VRML97 browser checks passed"
exit $((fails > 0))
