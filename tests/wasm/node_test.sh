#!/usr/bin/env bash
# A test program of the browser build (tests/wasm/CMakeLists.txt), run in Node: skipped (exit 77)
# when the browser build or node is missing, a failure under CI.
# usage: node_test.sh NAME PROGRAM.js SOURCE_DIR [ARGS...]
set -uo pipefail
NAME="$1" JS="$2" SRC="$3"
shift 3
. "$SRC/tests/support/skip.sh"
[ -f "$JS" ] || { fs_skip missing "$NAME" "the browser build is not built ($JS; ./dev.sh wasm)" && exit 77; exit 1; }
command -v node > /dev/null || { fs_skip missing "$NAME" "node is not installed (Debian nodejs)" && exit 77; exit 1; }
exec node --no-experimental-fetch "$JS" "$@"
