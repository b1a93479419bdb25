#!/usr/bin/env bash
# Runs every ```sh block of docs/quickstart.md, in order, in an empty folder, with the built tools
# on PATH as the page says; then checks what the commands made. The page cannot drift from the tools.
# usage: quickstart_test.sh SOURCE_DIR BUILD_DIR
set -u
SRC=$(cd "$1" && pwd)
BUILD=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$SRC/docs/quickstart.md" > "$work/steps.sh" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
blocks = re.findall(r"```sh\n(.*?)```", text, re.S)
print("set -e")
for b in blocks:
    print(b)
PY
blocks=$(grep -c '^```sh' "$SRC/docs/quickstart.md")
[ "$blocks" -ge 4 ] || { echo "FAIL: only $blocks sh blocks in docs/quickstart.md"; exit 1; }
# The first block sets PATH relative to the checkout ("$PWD/build/..."): run it from a folder whose
# build/ is this build, then work in the empty folder.
mkdir -p "$work/checkout" && ln -s "$BUILD" "$work/checkout/build"
cd "$work/checkout" && sed -i '2a cd "'"$work"'"' "$work/steps.sh"
out=$(bash "$work/steps.sh" 2>&1); status=$?
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
[ $status -eq 0 ] || fail "the page's commands stopped with status $status:
$out"
for f in ball.png ball.glb rings.png lab.glb lab.png lab-0.ply lab-3.ply lab-out.wrl; do [ -s "$work/$f" ] || fail "$f was not made"; done
grep -q "lab.wrl:6:[0-9]*: warning: Inline 'http://www3.ntu.edu.sg/home/assourin/FVRML/CoordinateAxes.wrl' is not fetched" <<<"$out" ||
  fail "no warning about the course file's axes"
grep -q 'wrote lab.glb: animated, 24 frames a cycle' <<<"$out" || fail "the course file's glTF is not animated"
grep -q 'note: the scene changes in time and a picture holds one instant' <<<"$out" || fail "no note on the course file's picture"
grep -q 'wrote lab-0.ply ... lab-3.ply: 4 frame files' <<<"$out" || fail "no frame files line"
grep -q 'ok: 1 script, no errors' <<<"$out" && fail "fscript check printed its terminal word on a pipe"
grep -q 'fscript [0-9]' <<<"$out" || fail "no version line"
grep -q 'wrote ball.png: [0-9,]* triangles, 1 shape' <<<"$out" || fail "no summary line for ball.png"
grep -qx '1' <<<"$out" && grep -qx -- '-1' <<<"$out" || fail "the REPL did not print 1 and -1"
grep -q 'white pixels' <<<"$out" || fail "render2d printed no count"
[ $fails -eq 0 ] && echo "quickstart: every command of docs/quickstart.md ran ($blocks blocks)" || { echo "$out" | tail -20; exit 1; }
