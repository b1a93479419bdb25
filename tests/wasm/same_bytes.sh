#!/usr/bin/env bash
# The browser build's fvrml-run (in Node) against the native one on the VM backend: the paper's
# figures, the examples and every corpus file written as glTF, byte for byte, with the same exit
# status and the same diagnostics (docs/browser.md, "The same bytes").
# usage: same_bytes.sh FVRML_RUN WASM_RUN_JS SOURCE_DIR SHARED_DIR [MAX_FILES]
set -uo pipefail
abs() { case "$1" in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
RUN=$(abs "$1") WASM=$(abs "$2") SRC=$(abs "$3") SHARED=$(abs "$4") MAX="${5:-100000}"
. "$SRC/tests/support/skip.sh"
[ -f "$WASM" ] || { fs_skip missing wasm_same_bytes "the browser build is not built ($WASM; ./dev.sh wasm)" && exit 77; exit 1; }
command -v node > /dev/null || { fs_skip missing wasm_same_bytes "node is not installed (Debian nodejs)" && exit 77; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0 n=0 same=0 near=0
files=("$SRC"/examples/paper/*.wrl "$SRC"/examples/*.fs)
while IFS= read -r f; do files+=("$f"); done < <(find "$SHARED/corpus" -name '*.wrl' | sort)
for f in "${files[@]}"; do
  [ "$n" -ge "$MAX" ] && break
  n=$((n + 1))
  # Run where the file is (Inlines are relative to it); the outputs in $T.
  (cd "$(dirname "$f")" && "$RUN" "$(basename "$f")" -o "$T/native.glb" --backend vm > /dev/null 2> "$T/native.err"); a=$?
  (cd "$(dirname "$f")" && node --no-experimental-fetch "$WASM" "$(basename "$f")" -o "$T/wasm.glb" --backend vm \
     > /dev/null 2> "$T/wasm.err"); b=$?
  # The summary line tells the run's time; everything else is the same text.
  for e in native wasm; do grep -av '^wrote ' "$T/$e.err" > "$T/$e.diag"; done
  if [ "$a" != "$b" ]; then
    echo "FAIL $f: exit status $a native, $b in the browser build"; head -5 "$T/wasm.err"; fail=1
  elif ! cmp -s "$T/native.diag" "$T/wasm.diag"; then
    echo "FAIL $f: the diagnostics differ"; diff "$T/native.diag" "$T/wasm.diag" | head -10; fail=1
  elif [ "$a" = 0 ] && ! cmp -s "$T/native.glb" "$T/wasm.glb"; then
    # Not the same bytes: within the bound of glb_close.py (the C libraries' last bits), said.
    if close=$(python3 "$SRC/tests/wasm/glb_close.py" "$T/native.glb" "$T/wasm.glb"); then
      echo "close $f: $close"; near=$((near + 1))
    else
      echo "FAIL $f: the glTF differs: $close"; fail=1
    fi
  else
    same=$((same + 1))
  fi
  rm -f "$T/native.glb" "$T/wasm.glb"
done
echo "$same of $n files: the same glTF bytes, exit status and diagnostics in the browser build; $near within glb_close.py's bound"
exit $fail
