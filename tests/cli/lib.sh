# Helpers shared by the CLI test scripts (sourced): `check` for exit status and output patterns,
# `jcheck` for JSON answers with numeric tolerances, `fail` for anything else. They count into
# $n and $fails; the script ends with `finish NAME`.
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
n=0
SHARED="${FS_SHARED_DIR:-$SRC/../shared}"
. "$SRC/tests/support/skip.sh"
# skip_missing NAME WHY: a visible skip, or a failure under CI.
skip_missing() { fs_skip missing "cli $1" "$2" || fails=$((fails + 1)); }
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

# check NAME WANT_STATUS WANT_PATTERN(grep -E on stdout+stderr, "" for none) -- command...
check() {
  local name="$1" want="$2" pat="$3"
  shift 4
  n=$((n + 1))
  local out status
  "$@" > "$T/out.txt" 2>&1
  status=$?
  out=$(tr -d '\000' < "$T/out.txt")
  if [ "$status" != "$want" ]; then
    echo "FAIL $name: exit $status, wanted $want"; echo "$out" | head -20; fails=$((fails + 1)); return
  fi
  if [ -n "$pat" ] && ! grep -qE -- "$pat" <<<"$out"; then
    echo "FAIL $name: output does not match /$pat/"; echo "$out" | head -20; fails=$((fails + 1)); return
  fi
}

# jcheck NAME out|err CONDITION -- command...: the command exits 0 and the JSON it prints on standard
# output (out) or standard error (err), bound to `j`, makes the Python CONDITION true. `near(a, b,
# tol)` compares numbers with a tolerance.
jcheck() {
  local name="$1" stream="$2" cond="$3"
  shift 4
  n=$((n + 1))
  local status
  "$@" > "$T/j.out" 2> "$T/j.err"
  status=$?
  if [ "$status" != 0 ]; then
    echo "FAIL $name: exit $status"; head -c 800 "$T/j.err"; echo; fails=$((fails + 1)); return
  fi
  python3 - "$T/j.$stream" "$cond" <<'PY' || { echo "FAIL $name: not true: $cond"; head -c 1500 "$T/j.$stream"; echo; fails=$((fails + 1)); }
import json, sys
try:
    j = json.loads(open(sys.argv[1]).read())
except ValueError as e:
    print(f"not JSON: {e}")
    sys.exit(1)
near = lambda a, b, tol=1e-9: abs(a - b) <= tol
sys.exit(0 if eval("(" + sys.argv[2] + "\n)") else 1)
PY
}

# same_picture CMD NAME FILE ARGS...: `$F CMD FILE ARGS` (render2d, render3d) writes the same PNG
# bytes and the same first line pruned and dense (--no-prune), on every backend in $BACKENDS and
# at one and three threads.
same_picture() {
  local cmd="$1" name="$2" file="$3"
  shift 3
  for be in $BACKENDS; do
    "$F" "$cmd" "$file" "$@" --backend "$be" --no-prune -o "$T/dense.png" > "$T/dense.txt" 2>&1 || true
    for th in 1 3; do
      "$F" "$cmd" "$file" "$@" --backend "$be" --threads $th -o "$T/pruned.png" > "$T/pruned.txt" 2>&1 || true
      n=$((n + 1))
      cmp -s "$T/dense.png" "$T/pruned.png" && [ "$(head -1 "$T/dense.txt")" = "$(head -1 "$T/pruned.txt")" ] ||
        fail "$cmd-prune $name ($be, --threads $th): the pruned picture differs from --no-prune"
    done
  done
}

finish() {
  echo "$((n - fails)) of $n $1 checks passed"
  [ "$fails" = 0 ]
}
