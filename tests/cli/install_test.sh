#!/usr/bin/env bash
# The install step: `cmake --install BUILD --prefix P` puts the four tools in P/bin, and they work
# from there with nothing from the source or build tree (run from another folder, on the installed
# examples).
# usage: install_test.sh BUILD_DIR
set -u
BUILD="$1"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
cmake --install "$BUILD" --prefix "$T/prefix" > "$T/install.log" 2>&1 || { cat "$T/install.log"; fail "cmake --install"; }
for tool in fscript fvrml-run fvrml-meshdiff fscript-lsp; do
  [ -x "$T/prefix/bin/$tool" ] || { fail "$tool is not in PREFIX/bin"; continue; }
  "$T/prefix/bin/$tool" --version 2>&1 | grep -q "^$tool " || fail "$tool --version from PREFIX/bin"
done
[ -f "$T/prefix/share/fvrml/editors/nvim/lua/fscript.lua" ] ||
  fail "the editor set-ups are not in PREFIX/share/fvrml/editors"
[ -f "$T/prefix/share/fvrml/docs/quickstart.md" ] || fail "docs/quickstart.md is not in PREFIX/share/fvrml/docs"
mkdir -p "$T/elsewhere"
(cd "$T/elsewhere" && "$T/prefix/bin/fvrml-run" "$T/prefix/share/fvrml/examples/paper/figure6-blends.wrl" \
  --resolution-scale 0.2 --fraction 0.5 -o f6.png > out.txt 2>&1) || { cat "$T/elsewhere/out.txt"; fail "installed fvrml-run on an installed example"; }
[ -s "$T/elsewhere/f6.png" ] || fail "installed fvrml-run wrote no picture"
printf 'function FRep(x, y, z, t) { return 0.5 - x * x - y * y; }\n' > "$T/elsewhere/disc.fs"
(cd "$T/elsewhere" && "$T/prefix/bin/fscript" render2d disc.fs --size 32 --bounds -1,1,-1,1 > r.txt 2>&1) || fail "installed fscript render2d"
grep -q "wrote disc.png" "$T/elsewhere/r.txt" || { cat "$T/elsewhere/r.txt"; fail "installed fscript render2d summary"; }
# The llvm backend is a module loaded on first use: the installed one, found next to the binary.
if [ "${FS_HAVE_LLVM:-1}" = 1 ]; then
  module=$(find "$T/prefix" -name libfs_llvm.so | head -n 1)
  [ -n "$module" ] || fail "the llvm module is not installed"
  (cd "$T/elsewhere" && LD_DEBUG=libs "$T/prefix/bin/fscript" run --backend llvm disc.fs 0.25 0.5 0 0 > l.txt 2> ld.txt) ||
    { cat "$T/elsewhere/l.txt"; fail "installed fscript --backend llvm"; }
  grep -q "^0.1875$" "$T/elsewhere/l.txt" || { cat "$T/elsewhere/l.txt"; fail "installed fscript --backend llvm result"; }
  grep -q "calling init: $T/prefix/.*libfs_llvm.so" "$T/elsewhere/ld.txt" || fail "the installed binary did not load the installed llvm module"
  # A job that never compiles natively never loads LLVM.
  (cd "$T/elsewhere" && LD_DEBUG=libs "$T/prefix/bin/fscript" run disc.fs 0.25 0.5 0 0 > /dev/null 2> ld2.txt)
  if grep -q "libLLVM" "$T/elsewhere/ld2.txt"; then fail "a small job loaded LLVM"; fi
  # Without the module (FSCRIPT_LLVM_MODULE names a file that is not there): --backend llvm says
  # why, and everything else still works.
  export FSCRIPT_LLVM_MODULE="$T/none/libfs_llvm.so"
  (cd "$T/elsewhere" && "$T/prefix/bin/fscript" run --backend llvm disc.fs 0.25 0.5 0 0 > m.txt 2>&1)
  status=$?
  [ "$status" -ne 0 ] || fail "--backend llvm without the module succeeded"
  grep -q "backend 'llvm' cannot start: the llvm backend's module could not be loaded: $T/none/libfs_llvm.so: cannot open" "$T/elsewhere/m.txt" ||
    { cat "$T/elsewhere/m.txt"; fail "--backend llvm without the module: message"; }
  (cd "$T/elsewhere" && "$T/prefix/bin/fscript" run disc.fs 0.25 0.5 0 0 > a.txt 2>&1) || fail "auto without the module"
  (cd "$T/elsewhere" && "$T/prefix/bin/fvrml-run" "$T/prefix/share/fvrml/examples/paper/figure6-blends.wrl" \
    --fraction 0.5 -o f6b.png --stats > f6b.txt 2>&1) || { cat "$T/elsewhere/f6b.txt"; fail "a big job without the module"; }
  grep -q '"native":"sse"' "$T/elsewhere/f6b.txt" || fail "a big job without the module: native code from the sse emitter"
  unset FSCRIPT_LLVM_MODULE
  grep -q "^0.1875$" "$T/elsewhere/a.txt" || { cat "$T/elsewhere/a.txt"; fail "auto without the module: result"; }
fi
if [ "$fails" -gt 0 ]; then echo "install: $fails failures"; exit 1; fi
echo "install: ok"
