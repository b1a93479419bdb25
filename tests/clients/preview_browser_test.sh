#!/usr/bin/env bash
# fvrml-run --serve on a copy of the paper's Figure 1, looked at by headless Chromium
# (tests/clients/preview_browser.mjs). Skipped (exit 77) when node, Chromium or playwright-core are
# not installed, a failure under CI; a Chromium that cannot start here is a machine skip.
# usage: preview_browser_test.sh FVRML_RUN SOURCE_DIR NPM_DIR
set -uo pipefail
RUN="$1" SRC="$2" NPM="$3"
. "$SRC/tests/support/skip.sh"
command -v node > /dev/null || { fs_skip missing preview_browser "node is not installed (Debian nodejs)" && exit 77; exit 1; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { fs_skip missing preview_browser "Chromium is not installed (Debian chromium; ./dev.sh test installs it)" && exit 77; exit 1; }
[ -d "$NPM/node_modules/playwright-core" ] || { fs_skip missing preview_browser "playwright-core is not installed in $NPM (./dev.sh test installs it)" && exit 77; exit 1; }
T=$(mktemp -d)
cp "$SRC/examples/paper/figure1-morphing.wrl" "$T/scene.wrl"
"$RUN" "$T/scene.wrl" --serve --port 0 > "$T/serve.out" 2> "$T/serve.err" &
pid=$!
trap 'kill -INT $pid 2> /dev/null; wait $pid 2> /dev/null; rm -rf "$T"' EXIT
for _ in $(seq 100); do grep -q 'http://' "$T/serve.out" && break; sleep 0.1; done
URL=$(grep -o 'http://[^ ]*' "$T/serve.out")
[ -n "$URL" ] || { echo "FAIL preview_browser: fvrml-run --serve printed no URL"; cat "$T/serve.err"; exit 1; }
# The first launch tells whether Chromium can run here at all.
if ! NODE_PATH="$NPM/node_modules" node -e "
  const { chromium } = require('playwright-core');
  chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args: ['--no-sandbox'] })
    .then((b) => b.close()).catch((e) => { console.error(e.message); process.exit(1); });" 2> "$T/launch.err"; then
  fs_skip machine preview_browser "Chromium cannot start here: $(head -c 300 "$T/launch.err")" && exit 77
  exit 1
fi
cp "$SRC/tests/clients/preview_browser.mjs" "$SRC/tests/support/chromium.mjs" "$NPM/"  # beside node_modules, for their imports
FS_SOURCE_DIR="$SRC" node "$NPM/preview_browser.mjs" "$URL" "$T/scene.wrl"
