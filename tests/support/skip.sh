# Skips that cannot hide (sourced by the shell tests; tests/support/skip.h is the Catch2 side).
# Every skip prints one line and is appended to $FS_SKIP_LOG, which ./dev.sh test prints at the
# end. A skip because something is not installed or not found ("missing") is a failure when CI is
# set; only a skip because this machine cannot run the check at all ("machine") stays a skip there.

fs_ci() { case "${CI:-}" in "" | 0 | false | no) return 1 ;; *) return 0 ;; esac; }

# fs_skip missing|machine NAME WHY: returns 0 when the caller may skip, 1 when it must fail.
fs_skip() {
  local kind="$1" name="$2" why="$3"
  if [ "$kind" = missing ] && fs_ci; then
    echo "FAIL $name: $why (CI is set: a check may not be skipped because something is missing)"
    [ -n "${FS_SKIP_LOG:-}" ] && echo "FAILED (not skipped under CI) $name: $why" >> "$FS_SKIP_LOG"
    return 1
  fi
  echo "SKIP $name: $why"
  [ -n "${FS_SKIP_LOG:-}" ] && echo "skipped $name: $why" >> "$FS_SKIP_LOG"
  return 0
}
