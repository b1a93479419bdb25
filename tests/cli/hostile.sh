#!/usr/bin/env bash
# Hostile input: deep nesting, a 1 MB expression, an unterminated comment, bytes that are not text.
# usage: hostile.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# Hostile input: deep nesting, a 1 MB expression, an unterminated comment.
python3 -c "print('function f(x) { return ' + '('*100000 + 'x' + ')'*100000 + '; }')" > "$T/deep.fs"
check deep-nesting 1 'nesting deeper than' -- "$F" check "$T/deep.fs"
python3 -c "print('function FRep(x, y, z) { return 0' + ' + x'*260000 + '; }')" > "$T/long.fs"
check long-expression 0 '^260000$' -- "$F" run "$T/long.fs" 1 0 0
printf 'function f(x) { return x; }\n/* open\n' > "$T/open.fs"
check unterminated-comment 1 'open.fs:2:1: error: unterminated comment' -- "$F" check "$T/open.fs"
printf 'function f(x) { return x; }\n\xff\xfe\n' > "$T/binary.fs"
check invalid-bytes 1 'binary.fs:2:1: error: unexpected byte' -- "$F" check "$T/binary.fs"

finish hostile
