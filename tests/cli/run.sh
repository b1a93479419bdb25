#!/usr/bin/env bash
# `fscript run`: results, entry points, arguments, errors at their line:col, budgets.
# usage: run.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

check run-frep 0 '^0$' -- "$F" run "$T/sphere.fs" 1 0 0
check run-frep-nan-arg 0 '^nan$' -- "$F" run "$T/sphere.fs" nan 0 0
check run-frep-inf-arg 0 '^-inf$' -- "$F" run "$T/sphere.fs" -inf 0 0
check run-args-in-order 0 'x=-inf' -- "$F" run "$T/parts.fs" -inf 2 3
check run-args-in-order-z 0 'z=inf' -- "$F" run "$T/parts.fs" 1 -1 -inf
check run-entry-case 0 '^1$' -- "$F" run "$T/sphere.fs" --entry frep 0 0 0
check run-assignments 0 'x=1' -- "$F" run "$T/parts.fs" 1 2 3
check run-assignments-y 0 'y=4' -- "$F" run "$T/parts.fs" 1 2 3
check run-stdin 0 'z=-0' -- bash -c "\"$F\" < \"$T/parts.fs\""
check run-nan-domain 0 '^nan$' -- "$F" run "$T/nan.fs" -1
check run-too-many-args 2 'too many arguments' -- "$F" run "$T/sphere.fs" 1 2 3 4 5
check run-bad-number 2 'not a number' -- "$F" run "$T/sphere.fs" 1 abc
check run-missing-file 1 'cannot read' -- "$F" run "$T/none.fs"
check run-syntax 1 'bad.fs:2:14: error: expected an expression' -- "$F" run "$T/bad.fs" --entry f
check run-caret 1 '^ +\^' -- "$F" run "$T/bad.fs" --entry f
check run-two-errors 1 "unknown function 'h'" -- "$F" check "$T/bad.fs"
check run-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" 0
check run-loop-flag 1 'more than 50 iterations' -- "$F" run "$T/loop.fs" --max-loop-iterations 50 0
check run-recursion 1 'rec.fs:1:24: error: call depth budget exceeded' -- "$F" run "$T/rec.fs" 0
printf 'function a(x) { return x; }\nfunction b(x) { return x; }\n' > "$T/two.fs"
check run-no-entry 1 'no entry point' -- "$F" run "$T/two.fs"
check run-unknown-entry 1 "no function named 'nope'" -- "$F" run "$T/rec.fs" --entry nope
check backend-sse 0 '^0$' -- "$F" run "$T/sphere.fs" --backend sse 1 0 0
check emit-asm-sse 0 'mulps [xy]mm[0-9]+, [xy]mm[0-9]+' -- "$F" emit-asm "$T/sphere.fs" --backend sse

finish run
