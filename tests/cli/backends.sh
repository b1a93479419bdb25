#!/usr/bin/env bash
# The sse and llvm backends from the CLI: eight lanes where the CPU has AVX2, listings, budgets,
# the llvm disk cache (the second run loads what the first stored), unknown backends and commands.
# usage: backends.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# A straight-line kernel runs eight lanes where the CPU has AVX2; four at FSCRIPT_ISA=base.
if grep -q ' avx2 ' /proc/cpuinfo; then
  check emit-asm-sse-wide 0 '; 8 points per iteration \(ymm registers\)' -- "$F" emit-asm "$T/sphere.fs" --backend sse
fi
check emit-asm-sse-base 0 '; 4 points per iteration \(xmm registers\)' -- env FSCRIPT_ISA=base "$F" emit-asm "$T/sphere.fs" --backend sse
check emit-asm-sse-pool 0 '\.float 1, 1, 1, 1' -- "$F" emit-asm "$T/sphere.fs" --backend sse
check backend-sse-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" --backend sse 0
check run-recursion-sse 1 'rec.fs:1:24: error: call depth budget exceeded: more than 1000 nested calls' -- "$F" run "$T/rec.fs" --backend sse 1
check run-fact-sse 0 '^3628800$' -- "$F" run "$T/fact.fs" 10 --backend sse
# The llvm backend, when this build has it (FS_HAVE_LLVM from CMake: off only when asked for).
LLVM=""
[ "${FS_HAVE_LLVM:-1}" = 1 ] && LLVM=1
if [ -n "$LLVM" ]; then
  check backend-llvm 0 '^0$' -- "$F" run "$T/sphere.fs" --backend llvm 1 0 0
  check emit-asm-llvm 0 'v?mulps' -- "$F" emit-asm "$T/sphere.fs" --backend llvm
  check emit-ir-llvm 0 'fmul <(4|8|16) x float>' -- "$F" emit-ir --llvm "$T/sphere.fs"
  check backend-llvm-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" --backend llvm 0
  check run-recursion-llvm 1 'rec.fs:1:24: error: call depth budget exceeded: more than 1000 nested calls' -- "$F" run "$T/rec.fs" --backend llvm 1
  check run-fact-llvm 0 '^3628800$' -- "$F" run "$T/fact.fs" 10 --backend llvm
  check llvm-disk-cache 0 '^3628800$' -- env XDG_CACHE_HOME="$T/xdg" "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
  ls "$T"/xdg/fscript/llvm/*.o > /dev/null 2>&1 || { echo "FAIL llvm-disk-cache wrote no object file"; fails=$((fails + 1)); }
  check llvm-disk-cache-again 0 '^3628800$' -- env XDG_CACHE_HOME="$T/xdg" "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
  check llvm-disk-cache-nowhere 2 'no cache directory' -- env -u XDG_CACHE_HOME -u HOME "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
else
  check emit-ir-llvm-missing 2 'built without the llvm backend' -- "$F" emit-ir --llvm "$T/sphere.fs"
fi
check backend-unknown 2 "unknown backend 'gpu' \\(available: auto, vm, sse" -- "$F" run "$T/sphere.fs" --backend gpu 0 0 0
check usage-unknown-command 2 '' -- "$F" frobnicate
check usage-render-size 2 'size' -- "$F" render2d "$T/sphere.fs" --size 0x5 --bounds -1,1,-1,1
check usage-render-bounds 2 'bounds' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,1

# ---- The llvm disk cache: the second run loads the object the first one stored ----
if [ "${FS_HAVE_LLVM:-1}" = 1 ]; then
  export XDG_CACHE_HOME="$T/xdg"
  check "llvm disk cache: first run" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  before=$(stat -c '%i %Y %s' "$T"/xdg/fscript/llvm/* 2> /dev/null | sort)
  [ -n "$before" ] || fail "llvm disk cache: nothing stored"
  touch -d '2001-01-01' "$T"/xdg/fscript/llvm/*
  before=$(stat -c '%n %i %Y %s' "$T"/xdg/fscript/llvm/* | sort)
  check "llvm disk cache: second run" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  after=$(stat -c '%n %i %Y %s' "$T"/xdg/fscript/llvm/* | sort)
  [ "$before" = "$after" ] || fail "llvm disk cache: the second run compiled and stored again (before: $before; after: $after)"
  # A damaged object is not trusted: the run recompiles, answers right and stores a good one.
  for o in "$T"/xdg/fscript/llvm/*.o; do printf 'garbage' > "$o"; done
  check "llvm disk cache: a damaged object" 0 '^99$' -- "$F" run "$T/down.fs" 99 --backend llvm --llvm-disk-cache
  unset XDG_CACHE_HOME
fi

finish backends
