#!/usr/bin/env bash
# Versions, help that reads like a person wrote it, a scene given to a script command, the REPL
# subcommand.
# usage: help.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# Every tool says its version; fscript repl starts the REPL; --help mentions it and fscript < FILE.
LSP="$(dirname "$F")/../../lsp/fscript-lsp"
for tool in "$F" "$R" "$D" "$LSP"; do
  [ -x "$tool" ] && check "version $(basename "$tool")" 0 "^$(basename "$tool") [0-9]+\.[0-9]+\.[0-9]+ \(FVRML toolchain\)$" -- "$tool" --version
done
# Help reads like a person wrote it: ranges in words, no parser hints.
for tool in "$F" "$R"; do
  [ -x "$tool" ] || continue
  "$tool" --help > "$T/help.txt" 2>&1
  n=$((n + 1))
  ! grep -qE 'UINT|FLOAT|4611686018427387904|:POSITIVE' "$T/help.txt" || fail "help-words $(basename "$tool"): $(grep -E 'UINT|FLOAT|POSITIVE' "$T/help.txt" | head -2)"
done
check help-range-words 0 'nested calls allowed, 1 to 100,000 \(default 1,000\)' -- "$F" --help
# A scene given to a script command says which tool to use, with no VRML parse errors.
check wrong-kind-render2d 1 'figure1-morphing.wrl: error: this is a VRML scene; .*fvrml-run' -- "$F" render2d "$SRC/examples/paper/figure1-morphing.wrl" --size 8 --bounds -1,1,-1,1
check wrong-kind-run 1 'this is a VRML scene' -- "$F" run "$SRC/examples/paper/figure1-morphing.wrl"
check wrong-kind-emit-ir 1 'this is a VRML scene' -- "$F" emit-ir "$SRC/examples/paper/figure1-morphing.wrl"
check lsp-unknown-argument 2 "unknown argument '--port'" -- "$LSP" --port 4
check repl-subcommand 0 '^3$' -- sh -c "printf '1+2\n:quit\n' | \"$F\" repl"
check help-mentions-repl 0 'fscript repl.*fscript < FILE' -- sh -c "\"$F\" --help | tr '\n' ' '"

finish help
