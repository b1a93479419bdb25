#!/usr/bin/env bash
# The layering check bites: the real tree passes; a copy with one include pointing up (and one
# sideways) fails, naming the file, the line and the rule.
set -u
root=$1
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }

python3 "$here/check_layers.py" "$root" || bad "the tree itself breaks the layering"

for d in runtime ir frontend backends engine lsp; do cp -r "$root/$d" "$tmp/"; done
python3 "$here/check_layers.py" "$tmp" || bad "a plain copy of the tree fails"

printf '#include "engine/scene/scene_model.h"\n' >> "$tmp/ir/eval.cpp"
printf '#include "ir/passes/passes.h"\n' >> "$tmp/frontend/check.cpp"
printf '#include "tools/fscript/common.h"\n' >> "$tmp/engine/mesh/mesh.cpp"
out=$(python3 "$here/check_layers.py" "$tmp" 2>&1); rc=$?
[ $rc -eq 1 ] || bad "an include pointing up gave status $rc, not 1"
n=$(wc -l < "$tmp/ir/eval.cpp")
for want in "ir/eval.cpp:$n: error: ir includes engine/scene/scene_model.h (engine/scene)" \
            "frontend/check.cpp:" "frontend includes ir/passes/passes.h (ir/passes)" \
            "engine/mesh includes tools/fscript/common.h, which is the top layer" "3 include(s)"; do
  grep -qF -- "$want" <<< "$out" || bad "missing from the report: $want (got: $out)"
done

mkdir -p "$tmp/runtime/newthing" && printf '// x\n' > "$tmp/runtime/newthing/a.cpp"
out=$(python3 "$here/check_layers.py" "$tmp" 2>&1)
grep -qF "runtime/newthing/a.cpp:1: error: no layer for this file" <<< "$out" || bad "a folder without a layer passed"

[ $fails -eq 0 ] && echo "layers: all checks passed" || exit 1
