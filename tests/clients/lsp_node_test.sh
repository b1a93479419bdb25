#!/usr/bin/env bash
# Runs tests/clients/lsp_node.test.mjs (node's test runner, Microsoft's LSP client libraries) on
# fscript-lsp; skipped (exit 77) when node or the npm packages are not installed, a failure under CI.
# usage: lsp_node_test.sh FSCRIPT_LSP NPM_DIR
set -uo pipefail
. "$(dirname "$0")/../support/skip.sh"
command -v node > /dev/null || { fs_skip missing lsp_node "node is not installed (Debian nodejs)" && exit 77; exit 1; }
[ -d "$2/node_modules/vscode-jsonrpc" ] && [ -d "$2/node_modules/vscode-languageserver-protocol" ] ||
  { fs_skip missing lsp_node "vscode-jsonrpc and vscode-languageserver-protocol are not installed in $2 (./dev.sh test installs them)" && exit 77; exit 1; }
LSP_SERVER=$1 LSP_NPM_DIR=$2 exec node --test "$(dirname "$0")/lsp_node.test.mjs"
