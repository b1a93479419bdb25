#!/usr/bin/env bash
# fscript-lsp in a real editor: Neovim (Debian `neovim`, headless) opens a .fs and a .wrl through
# its built-in LSP client (the shared probe ../shared/tools/clients/nvim_lsp_probe.lua), receives
# diagnostics, hover, completion and go-to-definition, edits the buffer and gets fresh
# diagnostics. Skipped (exit 77) when nvim or the probe is missing; a failure under CI.
# usage: lsp_nvim_test.sh FSCRIPT_LSP SOURCE_DIR
set -uo pipefail
LSP=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PROBE="${FS_SHARED_DIR:-$SRC/../shared}/tools/clients/nvim_lsp_probe.lua"
. "$SRC/tests/support/skip.sh"
command -v nvim > /dev/null || { fs_skip missing lsp_nvim "nvim is not installed (Debian neovim)" && exit 77; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
probe() {  # FILETYPE FILE QUERIES EDIT
  LSP_FT=$1 LSP_CMD="[\"$LSP\"]" LSP_FILE=$2 LSP_QUERIES=$3 LSP_EDIT=$4 timeout 60 \
    nvim --headless --clean -n -u NONE -c "luafile $PROBE" 2>&1
}
want() {  # NAME OUTPUT REGEX
  if grep -Eq "$3" <<< "$2"; then echo "ok $1"; else echo "FAIL $1: no /$3/ in:"; echo "$2" | cut -c1-400; fails=$((fails + 1)); fi
}
if [ -f "$PROBE" ]; then  # the shared probe, when ../shared is there
  printf 'function sq(a) {\n  return a * a;\n}\nfunction FRep(x, y, z, t) {\n  var r = sqrt(sq(x) + y * y + z * z);\n  return 1 - r;\n}\n' > "$T/probe.fs"
  out=$(probe fscript "$T/probe.fs" 'textDocument/hover@4:12;textDocument/completion@4:12;textDocument/definition@4:15;textDocument/documentSymbol' '5:  return 1 - rr;')
  want "fs: diagnostics on open" "$out" '"phase": "open", "event": "diagnostics".*"items": \[\]'
  want "fs: hover on a built-in" "$out" '"method": "textDocument/hover", "result": \{.*sqrt\(x\)'
  want "fs: completion" "$out" '"method": "textDocument/completion".*"label": "sqrt"'
  want "fs: definition of a user function" "$out" '"method": "textDocument/definition", "result": \{"uri": "file://[^"]*probe.fs", "range": \{"end": \{"character": 11, "line": 0\}'
  want "fs: symbols" "$out" '"method": "textDocument/documentSymbol".*"name": "FRep"'
  want "fs: diagnostics after an edit" "$out" "\"phase\": \"edit\".*unknown name 'rr'"
  want "fs: clean shutdown" "$out" '"status": 0, "ok": true'
  printf '#VRML V2.0 utf8\nTransform {\n  children FShape {\n    geometry FGeometry { definition "1 - x*x - y*y - z*z" }\n  }\n}\n' > "$T/scene.wrl"
  out=$(probe vrml "$T/scene.wrl" 'textDocument/completion@0:0' '3:    geometry FGeometry { definition "1 - x*x - qq" }')
  want "wrl: diagnostics on open" "$out" '"phase": "open", "event": "diagnostics".*"items": \[\]'
  want "wrl: an FScript error inside the .wrl after an edit" "$out" "\"phase\": \"edit\".*unknown name 'qq'"
  want "wrl: clean shutdown" "$out" '"status": 0, "ok": true'
else
  fs_skip missing "lsp_nvim shared probe" "$PROBE not found (the shared folder is absent)" || fails=$((fails + 1))
fi
# The Neovim set-up the README documents (editors/nvim/lua/fscript.lua), on a .fs and a .wrl:
# loaded as init.lua does (the folder on the runtime path, require), and by :luafile.
printf 'function FRep(x, y, z, t) {\n  return 1 - Q;\n}\n' > "$T/bad.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1 - x*x - QQ" } }\n' > "$T/bad.wrl"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function g(a) { return a * a; }\nfunction FRep(x, y, z, t) { return 1 - g(x) - sqrt(y) - QQ; }" } }\n' > "$T/bad2.wrl"
printf 'vim.opt.runtimepath:append("%s/editors/nvim")\nrequire("fscript")\n' "$SRC" > "$T/init.lua"
LOAD=(-u "$T/init.lua")  # as the README says: init.lua puts the folder on the runtime path and requires it
with_config() {  # FILE QUERIES: Neovim with the set-up, then nvim_config_check.lua
  (cd "$T" && FSCRIPT_LSP="$LSP" QUERIES=$2 timeout 60 nvim --headless --clean -n "${LOAD[@]}" \
     -c "edit $1" -c "luafile $SRC/tests/clients/nvim_config_check.lua" 2>&1)
}
for f in bad.fs bad.wrl; do
  out=$(with_config "$f" "")
  want "require('fscript') from init.lua, on $f" "$out" "clients=fscript-lsp diagnostic=unknown name 'Q"
done
LOAD=(-u NONE -c "luafile $SRC/editors/nvim/lua/fscript.lua")
out=$(with_config bad.fs "")
want ":luafile editors/nvim/lua/fscript.lua, on bad.fs" "$out" "clients=fscript-lsp diagnostic=unknown name 'Q"
LOAD=(-u "$T/init.lua")
# Hover, completion and definition through Neovim's own client, in a .fs and inside a .wrl string.
printf 'function sq(a) {\n  return a * a;\n}\nfunction FRep(x, y, z, t) {\n  return 1 - sqrt(sq(x)) - Q;\n}\n' > "$T/feat.fs"
out=$(with_config feat.fs 'textDocument/hover@4:14;textDocument/completion@4:15;textDocument/definition@4:19')
want "nvim .fs hover" "$out" 'textDocument/hover => .*sqrt\(x\)'
want "nvim .fs completion" "$out" 'textDocument/completion => .*"label": ?"sqrt"'
want "nvim .fs definition" "$out" 'textDocument/definition => .*"start": ?\{"character": ?9, ?"line": ?0\}'
out=$(with_config bad2.wrl 'textDocument/hover@2:47;textDocument/definition@2:39;textDocument/completion@1:11')
want "nvim .wrl diagnostics" "$out" "diagnostic=unknown name 'QQ'"
want "nvim .wrl hover in a script" "$out" 'textDocument/hover => .*sqrt\(x\)'
want "nvim .wrl definition in a script" "$out" 'textDocument/definition => .*"start": ?\{"character": ?51, ?"line": ?1\}'
want "nvim .wrl completion of fields" "$out" 'textDocument/completion => .*"label": ?"geometry"'
# A shape diagnostic: the box cuts a ball that ends just outside it.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1.2 - x*x - y*y - z*z" bboxSize 2 2 2 } }\n' > "$T/cut.wrl"
out=$(with_config cut.wrl "")
want "nvim .wrl shape diagnostic" "$out" "diagnostic=the box cuts the shape on its faces .*bboxSize 2.6 2.6 2.6 holds it whole"
# :FscriptProfile: the lenses of the profile, a line's share on the line (the heavy branch on line 6, a
# tenth of the points), through Neovim's code-lens support.
cat > "$T/prof.wrl" <<'WRL'
#VRML V2.0 utf8
FShape { geometry FGeometry { resolution [96 96 96] bboxSize 2.4 2.4 2.4
  definition "function FRep(x, y, z, t) {
    light = 0.6 - sqrt(x*x + y*y + z*z);
    w = sin(3*x) * cos(5*y) + sin(7*z) * cos(2*x) + sin(4*y) * cos(6*z) + sin(9*x) * sin(8*y);
    heavy = 0.15 - sqrt((x-1.15)*(x-1.15) + (y-1.15)*(y-1.15) + (z-1.15)*(z-1.15)) + 0.01 * w;
    return max(light, heavy);
  }" } }
WRL
out=$(with_config prof.wrl 'profile')
want "nvim :FscriptProfile: the lens that runs it again" "$out" '^codelens 0: Profile evaluation again'
want "nvim :FscriptProfile: a line's share" "$out" '^codelens 4: [0-9.]+% of time · [0-9.]+% of operations · runs at [0-9]\.[0-9]% of points'
# :FvrmlPreview is defined, and what it asks the server gives the live preview's URL.
out=$(FVRML_RUN="${FVRML_RUN:-}" with_config bad2.wrl 'preview')
want "nvim :FvrmlPreview is defined" "$out" '^command FvrmlPreview'
want "nvim fscript.preview gives the page's URL" "$out" 'fscript.preview => \{"url": ?"http://127\.0\.0\.1:[0-9]+/"\}'

[ "$fails" -eq 0 ] && echo "all Neovim checks passed" || echo "$fails Neovim checks failed"
exit $((fails > 0))
