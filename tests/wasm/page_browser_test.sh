#!/usr/bin/env bash
# The browser build's page from file:// in headless Chromium (tests/wasm/page_browser.mjs): the
# paper's Figure 1 by the file picker, a course file dropped on the page. Skipped (exit 77) when
# the browser build, node, Chromium or playwright-core is missing, a failure under CI.
# usage: page_browser_test.sh SITE_DIR SOURCE_DIR SHARED_DIR NPM_DIR
set -uo pipefail
SITE="$1" SRC="$2" SHARED="$3" NPM="$4"
. "$SRC/tests/support/skip.sh"
[ -f "$SITE/fvrml-web.js" ] || { fs_skip missing wasm_page "the browser build is not built ($SITE; ./dev.sh wasm)" && exit 77; exit 1; }
command -v node > /dev/null || { fs_skip missing wasm_page "node is not installed (Debian nodejs)" && exit 77; exit 1; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { fs_skip missing wasm_page "Chromium is not installed (Debian chromium)" && exit 77; exit 1; }
[ -d "$NPM/node_modules/playwright-core" ] || { fs_skip missing wasm_page "playwright-core is not installed in $NPM (./dev.sh test installs it)" && exit 77; exit 1; }
[ -d "$NPM/node_modules/gltf-validator" ] || { fs_skip missing wasm_page "gltf-validator is not installed in $NPM (./dev.sh test installs it)" && exit 77; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
cp "$SRC/tests/wasm/page_browser.mjs" "$SRC/tests/support/chromium.mjs" "$NPM/"  # beside node_modules, for their imports
node "$NPM/page_browser.mjs" "$SITE" "$SRC/examples/paper/figure1-morphing.wrl" \
  "$SHARED/corpus/wilsonteng97-CZ2003-CGV/FVRML code templates/solid.wrl" "$T"
