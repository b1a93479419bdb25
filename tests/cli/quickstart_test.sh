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
for f in ball.png ball.glb rings.png; do [ -s "$work/$f" ] || fail "$f was not made"; done
grep -q 'fscript [0-9]' <<<"$out" || fail "no version line"
grep -q 'wrote ball.png: [0-9,]* triangles, 1 shape' <<<"$out" || fail "no summary line for ball.png"
grep -qx '1' <<<"$out" && grep -qx -- '-1' <<<"$out" || fail "the REPL did not print 1 and -1"
grep -q 'white pixels' <<<"$out" || fail "render2d printed no count"
[ $fails -eq 0 ] && echo "quickstart: every command of docs/quickstart.md ran ($blocks blocks)" || { echo "$out" | tail -20; exit 1; }
