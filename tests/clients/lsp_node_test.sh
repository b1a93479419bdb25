#!/usr/bin/env bash
# Runs tests/clients/lsp_node.test.mjs (node's test runner, Microsoft's LSP client libraries) on
# fscript-lsp; exit 77 (skipped) when node or the npm packages are not installed.
# usage: lsp_node_test.sh FSCRIPT_LSP NPM_DIR
set -uo pipefail
command -v node > /dev/null || { echo "skipped: no node"; exit 77; }
[ -d "$2/node_modules/vscode-jsonrpc" ] && [ -d "$2/node_modules/vscode-languageserver-protocol" ] ||
  { echo "skipped: vscode-jsonrpc and vscode-languageserver-protocol are not installed in $2"; exit 77; }
LSP_SERVER=$1 LSP_NPM_DIR=$2 exec node --test "$(dirname "$0")/lsp_node.test.mjs"
