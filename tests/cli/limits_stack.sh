#!/usr/bin/env bash
# limits_test.sh under a stack limit users set (a gibibyte, or none): worker threads must not take
# it as their size. usage: limits_stack.sh LIMIT FSCRIPT SOURCE_DIR FVRML_RUN
set -u
limit="$1"
shift
ulimit -s "$limit" || { echo "FAIL cannot set ulimit -s $limit (hard limit $(ulimit -Hs))"; exit 1; }
exec bash "$(dirname "$0")/limits_test.sh" "$@"
