#!/usr/bin/env bash
# fscript fmt on a .wrl scene: every script inside it formatted in place in the text (one-line
# scripts stay on one line, a block keeps its indentation), the rest of the file byte for byte;
# -i and --check as for scripts; a script that does not parse is reported at the scene's own
# line:col and nothing is written.
# usage: fmt.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"

cat > "$T/s.wrl" <<'WRL'
#VRML V2.0 utf8
# a comment the formatter keeps
FShape { geometry FGeometry { definition "0.5^2-x*x-y*y-z*z" bboxSize 2 2 2 resolution [12] }
  appearance FAppearance { material FMaterial { diffuseColor "r=1;g=x;b=0;" } } }
FShape { geometry FGeometry { definition "
    function FRep(x,y,z,t) {
    var k=2;
    return k*0.1-sqrt(x*x+y*y+(z-1)*(z-1));}" bboxSize 2 2 4 resolution [12] } }
WRL
cat > "$T/want.wrl" <<'WRL'
#VRML V2.0 utf8
# a comment the formatter keeps
FShape { geometry FGeometry { definition "0.5 ^ 2 - x * x - y * y - z * z" bboxSize 2 2 2 resolution [12] }
  appearance FAppearance { material FMaterial { diffuseColor "r = 1; g = x; b = 0;" } } }
FShape { geometry FGeometry { definition "
    function FRep(x, y, z, t) {
      var k = 2;
      return k * 0.1 - sqrt(x * x + y * y + (z - 1) * (z - 1));
    }" bboxSize 2 2 4 resolution [12] } }
WRL
"$F" fmt "$T/s.wrl" > "$T/got.wrl" || fail "fmt of a scene: exit $?"
cmp -s "$T/got.wrl" "$T/want.wrl" || fail "fmt of a scene: $(diff "$T/want.wrl" "$T/got.wrl")"
check "fmt --check of an unformatted scene" 1 "s.wrl: not formatted \(fscript fmt -i .*s.wrl formats it\)" -- "$F" fmt --check "$T/s.wrl"
"$R" "$T/s.wrl" -o "$T/before.ply" 2> /dev/null || fail "the scene runs"
cp "$T/s.wrl" "$T/i.wrl"
check "fmt -i of a scene" 0 "" -- "$F" fmt -i "$T/i.wrl"
cmp -s "$T/i.wrl" "$T/want.wrl" || fail "fmt -i of a scene wrote something else"
check "fmt --check of a formatted scene" 0 "" -- "$F" fmt --check "$T/i.wrl"
"$R" "$T/i.wrl" -o "$T/after.ply" 2> /dev/null || fail "the formatted scene runs"
cmp -s "$T/before.ply" "$T/after.ply" || fail "the formatted scene meshes to other bytes"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry {\n  definition "1 - x*x + (y" } }\n' > "$T/bad.wrl"
cp "$T/bad.wrl" "$T/bad.wrl.orig"
check "fmt -i of a scene whose script does not parse: at the scene's line:col" 1 "bad.wrl:3:.*error: " -- "$F" fmt -i "$T/bad.wrl"
cmp -s "$T/bad.wrl" "$T/bad.wrl.orig" || fail "fmt -i changed a scene whose script does not parse"
gzip -c "$T/s.wrl" > "$T/z.wrl.gz"
check "fmt of a gzipped scene prints it" 0 "r = 1; g = x; b = 0;" -- "$F" fmt "$T/z.wrl.gz"
check "fmt -i of a gzipped scene is refused" 2 "is gzipped: fmt prints it formatted, and -i would write it uncompressed" -- "$F" fmt -i "$T/z.wrl.gz"


# fmt of scripts.
. "$SRC/tests/cli/fixtures.sh"
# fmt: canonical output, idempotent
printf 'function f(x){var a=x*2;if(a>1){return a}else{return -a^2}}\n' > "$T/ugly.fs"
"$F" fmt "$T/ugly.fs" > "$T/pretty.fs"
"$F" fmt "$T/pretty.fs" > "$T/pretty2.fs"
cmp -s "$T/pretty.fs" "$T/pretty2.fs" || { echo "FAIL fmt-idempotent"; fails=$((fails + 1)); }
check fmt-layout 0 '^  if \(a > 1\) \{$' -- "$F" fmt "$T/ugly.fs"
check fmt-error 1 'expected an expression' -- "$F" fmt "$T/bad.fs"
# fmt --check says whether a file is formatted; -i rewrites it (and never a file that does not parse).
cp "$T/ugly.fs" "$T/inplace.fs"
check fmt-check-ugly 1 'inplace.fs: not formatted \(fscript fmt -i' -- "$F" fmt --check "$T/inplace.fs"
check fmt-in-place 0 '' -- "$F" fmt -i "$T/inplace.fs"
cmp -s "$T/inplace.fs" "$T/pretty.fs" || fail "fmt-in-place: the file is not what fmt prints"
check fmt-check-pretty 0 '' -- "$F" fmt --check "$T/inplace.fs"
cp "$T/bad.fs" "$T/bad-copy.fs"
check fmt-in-place-error 1 'expected an expression' -- "$F" fmt -i "$T/bad-copy.fs"
cmp -s "$T/bad.fs" "$T/bad-copy.fs" || fail "fmt-in-place-error: a file with errors was rewritten"
check fmt-in-place-stdin 2 'standard input has none' -- "$F" fmt -i - < "$T/ugly.fs"
finish fmt
