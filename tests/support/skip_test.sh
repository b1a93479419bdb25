#!/usr/bin/env bash
# The skip rules themselves (tests/support/skip.sh): a skip because something is missing
# fails under CI and is allowed (and logged) otherwise; a skip the machine forces is always allowed.
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/skip.sh"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
expect() {  # NAME WANT_STATUS COMMAND...
  local name="$1" want="$2"
  shift 2
  "$@" > "$T/out" 2>&1
  local got=$?
  [ "$got" = "$want" ] || { echo "FAIL $name: status $got, wanted $want"; cat "$T/out"; fails=$((fails + 1)); }
}
export FS_SKIP_LOG="$T/log"
expect "missing, outside CI: a skip" 0 env -u CI bash -c ". '$here/skip.sh'; fs_skip missing a 'no tool'"
expect "missing, CI=false: a skip" 0 env CI=false bash -c ". '$here/skip.sh'; fs_skip missing b 'no tool'"
expect "missing, under CI: a failure" 1 env CI=true bash -c ". '$here/skip.sh'; fs_skip missing c 'no tool'"
expect "machine, under CI: a skip" 0 env CI=1 bash -c ". '$here/skip.sh'; fs_skip machine d 'no AVX-512'"
want=$'skipped a: no tool\nskipped b: no tool\nFAILED (not skipped under CI) c: no tool\nskipped d: no AVX-512'
[ "$(cat "$T/log")" = "$want" ] || { echo "FAIL the skip log:"; cat "$T/log"; fails=$((fails + 1)); }
[ "$fails" = 0 ] && echo "skip rules: all checks passed"
exit $((fails > 0))
