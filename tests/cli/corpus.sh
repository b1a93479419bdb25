#!/usr/bin/env bash
# The shared corpus through `fscript check`, and prospero's known answer on every backend.
# usage: corpus.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# The shared corpus and the paper's data (a skip when absent, a failure under CI).
[ -d "$SHARED/corpus" ] || skip_missing corpus "the shared corpus $SHARED/corpus is absent"
[ -f "$SHARED/data/prospero.fs" ] || skip_missing prospero "$SHARED/data/prospero.fs is absent"
if [ -d "$SHARED/corpus" ]; then
  while IFS= read -r -d '' w; do
    if head -c 7 "$w" | grep -q BSCRYPT; then
      # One course file is encrypted (BS Contact's BSCRYPT): a clear error, never a crash.
      check "corpus-check $(basename "$w")" 1 'encrypted' -- "$F" check "$w"
    else
      check "corpus-check $(basename "$w")" 0 '' -- "$F" check "$w"
    fi
  done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
fi
if [ -f "$SHARED/data/prospero.fs" ]; then
  check prospero-256 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1
  check prospero-256-sse 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1 --backend sse
  [ -n "$LLVM" ] && check prospero-256-llvm 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1 --backend llvm
  check prospero-asm-bounded 0 '^; inputs finite with \|x\| <= 65536' -- "$F" emit-asm "$SHARED/data/prospero.fs" --backend sse
fi

finish corpus
