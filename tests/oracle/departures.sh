#!/usr/bin/env bash
# Where FScript departs from JavaScript on purpose (docs/language.md, "Departures from JavaScript"):
# each case runs in FScript (fscript run, every backend) and as plain JavaScript under node, and
# both behaviours are checked, so a departure can neither vanish nor appear unnoticed. The node
# oracle's prelude (prelude.js) implements the same list.
# usage: departures.sh FSCRIPT SOURCE_DIR
set -u
F="$1"
SRC="$2"
. "$SRC/tests/cli/lib.sh"
if ! command -v node > /dev/null; then
  skip_missing departures 'node not found (apt-get install nodejs)'
  finish departures
  exit
fi
backends="vm sse"
[ "${FS_HAVE_LLVM:-}" = 1 ] && backends="vm sse llvm"

# departure NAME FSCRIPT_BODY FSCRIPT_WANT JS_EXPRESSION JS_WANT: FScript's f() returns the body's
# value (FSCRIPT_WANT: the printed number, or "error: PATTERN" for a runtime error); node prints
# String(JS_EXPRESSION).
departure() {
  local name="$1" body="$2" fs_want="$3" js="$4" js_want="$5"
  printf 'function f() {\n%s\n}\n' "$body" > "$T/d.fs"
  for b in $backends; do
    if [[ "$fs_want" == error:* ]]; then
      check "$name: FScript ($b)" 1 "${fs_want#error: }" -- "$F" run --backend="$b" "$T/d.fs"
    else
      check "$name: FScript ($b)" 0 "^$fs_want\$" -- "$F" run --backend="$b" "$T/d.fs"
    fi
  done
  check "$name: JavaScript" 0 "^$js_want\$" -- node -e "console.log(String($js))"
}

departure "min of equal zeros is the first" "return 1 / min(0, -0);" "inf" "1 / Math.min(0, -0)" "-Infinity"
departure "max of equal zeros is the first" "return 1 / max(-0, 0);" "-inf" "1 / Math.max(-0, 0)" "Infinity"
departure "&& yields 1 or 0" "return 2 && 3;" "1" "2 && 3" "3"
departure "|| yields 1 or 0" "return 0 || 5;" "1" "0 || 5" "5"
departure "| is union (max)" "return 1 | 2.5;" "2.5" "1 | 2.5" "3"
departure "& is intersection (min)" "return 6 & 3;" "3" "6 & 3" "2"
departure "^ is power" "return 2 ^ 3;" "8" "2 ^ 3" "1"
departure "comparisons yield 1 or 0" "return 1 < 2;" "1" "1 < 2" "true"
departure "an index is rounded" "var a = [1, 2, 3]; return a[1.6];" "3" "[1, 2, 3][1.6]" "undefined"
departure "an index out of range is an error" "var a = [1, 2, 3]; return a[3];" \
  "error: index 3 is out of range for array 'a' of 3 elements" "[1, 2, 3][3]" "undefined"
departure "new Array(n) holds zeros" "var b = new Array(2); return b[1];" "0" "new Array(2)[1]" "undefined"
departure "an unset local is NaN" "if (pi > 4) { var v = 1; } return v == v;" "0" \
  "(function () { if (Math.PI > 4) { var v = 1; } return v == v; })()" "true"
# A decimal literal is rounded once to float; JavaScript rounds it to double, then Math.fround
# rounds again (1 + 2^-24 exactly, a tie, then rounds to even: 1).
departure "a literal is rounded once" "return 1.0000000596046447753906251 - 1;" "1.1920929e-07" \
  "Math.fround(Math.fround(1.0000000596046447753906251) - 1)" "0"

finish departures
