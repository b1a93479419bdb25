#!/usr/bin/env bash
# One entry point for setting up, building and testing, on a fresh Debian bookworm machine.
#   ./dev.sh demo    install what is missing, build, render the paper's Figure 1 to out/ (PNG, VRML97)
#   ./dev.sh test    install what is missing, build, run every test (ctest)
#   ./dev.sh test --fast   build, then every test but the third-party clients, fuzzing and the
#                    slow ones (ctest -LE 'clients|fuzz|slow'): the inner loop, under 2 minutes warm
#   SANITIZE=1 ./dev.sh test   the same with AddressSanitizer + UndefinedBehaviorSanitizer
#   ./dev.sh build   build only
#   ./dev.sh setup   install every Debian and npm package the build and the tests use, build nothing
#   ./dev.sh install PREFIX   build, then put the tools in PREFIX/bin (cmake --install; e.g. ~/.local)
#   ./dev.sh format [--check]   rewrite the C++ sources as clang-format-19 writes them (.clang-format),
#                    or only list the ones that differ (ctest `format` runs the check)
#   ./dev.sh mutation [--only ID,...]   mutation testing (tests/mutation/run.sh; docs/testing.md)
#   ./dev.sh fuzz [TARGET|all] [SECONDS]   coverage-guided fuzzing with clang-19's libFuzzer
#                    (tests/fuzz; docs/reliability.md); ./dev.sh test runs every target briefly
#   ./dev.sh campaign TARGET [SECONDS] [WORKERS]   a long run of one target on the UBSan-only
#                    build, WORKERS processes (default: the cores) that yield to other work
#   ./dev.sh oracle [SECONDS]   generated programs on every backend and under node, fresh seeds
#                    for SECONDS (default 300; tests/oracle; docs/testing.md)
#   ./dev.sh wasm    the browser build with Debian's Emscripten (build-wasm/web: open index.html),
#                    then its tests against the native build (docs/browser.md); ./dev.sh test builds it too
# With CI set (CI=true ./dev.sh test), a test skipped because something is missing fails instead.
# FVRML_SHARED=DIR names the shared folder (corpus, paper data) when it is not ../shared.
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(cmake ninja-build ccache g++ python3 catch2 nlohmann-json3-dev libcli11-dev libpng-dev libedit-dev llvm-19-dev libeigen3-dev libcpp-httplib-dev libjs-three pkg-config)
# For the tests only: a real VRML97 browser (view3dscene, run under a virtual X server), Neovim as
# a real LSP client, objdump (binutils) for the x86 encoder, node for the glTF validator and the
# LSP client libraries (npm below), Chromium for the preview page (with npm's playwright-core),
# Slurm and munge for a one-node cluster that runs the sharding example; clang-format-19 for the
# sources' format check.
TEST_PACKAGES=(view3dscene xvfb xauth binutils neovim nodejs chromium slurm-wlm munge clang-format-19)
# The fuzz build (build-fuzz) and the replay of the fuzz corpora in the normal build.
FUZZ_PACKAGES=(clang-19 libfuzzer-19-dev)
# The browser build (preset wasm): Emscripten, Node for its tools, the header-only libraries it
# links from Debian, three.js for the page.
WASM_PACKAGES=(emscripten nodejs libjs-three nlohmann-json3-dev libeigen3-dev libcli11-dev catch2)
FUZZ_TARGETS=(fscript_frontend ir_reader vrml_reader lsp_server backend_diff straight_diff interval_sound)

install_missing() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

build() {
  # The presets of CMakePresets.json: dev (build/) or asan (build-asan/), warnings as errors.
  local preset=dev dir=build extra=()
  # ccache (when installed) keyed by paths relative to the folder above the checkout, so a second
  # checkout beside this one (a CI clone) reuses what this one compiled.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
  if [ "${SANITIZE:-0}" = 1 ]; then
    preset=asan dir=build-asan
  fi
  [ -n "${FVRML_SHARED:-}" ] && extra+=(-DFS_SHARED_DIR="$(cd "$FVRML_SHARED" && pwd)")
  cmake --preset "$preset" "${extra[@]}" >/dev/null
  ninja -C "$dir" -k 0 >&2  # -k 0: every failing file in one build (a table change names every missing case)
  BUILD_DIR=$dir
}

build_wasm() {
  install_missing "${WASM_PACKAGES[@]}" || { echo "note: could not install ${WASM_PACKAGES[*]}; the browser build's tests will be skipped"; return 0; }
  # Emscripten's tools load Debian's node modules (acorn): a node that is not Debian's own does not
  # look for them there.
  export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
  local extra=()
  [ -n "${FVRML_SHARED:-}" ] && extra+=(-DFS_SHARED_DIR="$(cd "$FVRML_SHARED" && pwd)")
  cmake --preset wasm "${extra[@]}" > /dev/null
  ninja -C build-wasm -k 0 >&2
}

cmd="${1:-demo}"
if [ "$cmd" = format ]; then  # no build: only the formatter
  install_missing clang-format-19
  exec tests/support/format.sh "${@:2}"
fi
install_missing "${PACKAGES[@]}"
case "$cmd" in
  test | fuzz | campaign | oracle) install_missing "${FUZZ_PACKAGES[@]}" || echo "note: could not install ${FUZZ_PACKAGES[*]}; fuzzing will be skipped" ;;
esac
if [ "$cmd" = setup ]; then BUILD_DIR=build; else build; fi
SHARED_DIR="${FVRML_SHARED:-../shared}"

# build-fuzz: every library instrumented for libFuzzer + ASan + UBSan (clang-19), the targets only.
have_fuzz_toolchain() {
  command -v clang++-19 > /dev/null && [ -n "$(find /usr/lib/llvm-19 -name libclang_rt.fuzzer-x86_64.a 2>/dev/null)" ]
}
build_fuzz() {
  cmake --preset fuzz > /dev/null
  ninja -C build-fuzz >&2
}
# Fuzzing's part of ./dev.sh test: every target for 60 s, two at a time (3 minutes on 2 cores).
# build-fuzz-ub: the same without ASan, for long campaigns (three to four times the executions).
build_fuzz_ub() {
  CC=clang-19 CXX=clang++-19 cmake -S . -B build-fuzz-ub -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFS_FUZZ=ON \
    -DFS_WERROR=ON -DFS_FUZZ_SANITIZERS=undefined > /dev/null
  ninja -C build-fuzz-ub >&2
}
fuzz_briefly() {
  . tests/support/skip.sh
  if ! have_fuzz_toolchain; then
    fs_skip missing fuzz "clang-19 with libFuzzer (${FUZZ_PACKAGES[*]}) is not installed"
    return
  fi
  build_fuzz && FUZZ_SEED=1 tests/fuzz/run.sh build-fuzz "$SHARED_DIR" 60 2 "${FUZZ_TARGETS[@]}"
}
# npm tools for the tests: the Khronos glTF validator and Microsoft's LSP client libraries; the
# checks that need one that could not be installed are skipped out loud (failures under CI).
NPM_TOOLS=(gltf-validator@2.0.0-dev.3.10 vscode-jsonrpc@10.0.0 vscode-languageserver-protocol@3.18.5 playwright-core@1.65.1)
install_npm_tools() {
  command -v npm > /dev/null || install_missing npm || true
  command -v npm > /dev/null || { echo "note: npm could not be installed"; return 0; }
  local missing=()
  for t in "${NPM_TOOLS[@]}"; do [ -d "$BUILD_DIR/npm/node_modules/${t%@*}" ] || missing+=("$t"); done
  [ ${#missing[@]} -eq 0 ] && return 0
  mkdir -p "$BUILD_DIR/npm"
  (cd "$BUILD_DIR/npm" && npm install --no-audit --no-fund --silent "${missing[@]}" > /dev/null 2>&1) ||
    echo "note: could not install ${missing[*]} from npm; their checks will be skipped"
}

case "$cmd" in
  build) ;;
  setup)  # everything the build and the tests use, nothing built
    install_missing "${TEST_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"
    install_npm_tools
    echo "setup: the Debian packages and npm tools of the build and the tests are installed"
    ;;
  test)
    export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    rm -f "$BUILD_DIR/skipped.txt"
    status=0
    if [ "${2:-}" = --fast ]; then  # the inner loop: no third-party clients, no fuzzing, nothing slow
      (cd "$BUILD_DIR" && ctest --output-on-failure -j "$(nproc)" -LE 'clients|fuzz|slow') || status=$?
    else
      install_missing "${TEST_PACKAGES[@]}" || echo "note: could not install ${TEST_PACKAGES[*]}; the VRML97 browser test will be skipped"
      install_npm_tools
      build_wasm || status=$?
      (cd "$BUILD_DIR" && ctest --output-on-failure -j "$(nproc)") || status=$?
      FS_SKIP_LOG="$PWD/$BUILD_DIR/skipped.txt" fuzz_briefly || status=1
    fi
    # Every skip, in CI or not, shows here (tests/support/skip.*).
    if [ -s "$BUILD_DIR/skipped.txt" ]; then
      echo "---- skipped checks ($(wc -l < "$BUILD_DIR/skipped.txt")):"
      sort "$BUILD_DIR/skipped.txt"
    else
      echo "---- no check was skipped"
    fi
    exit "$status"
    ;;
  demo)
    mkdir -p out
    run="$BUILD_DIR/tools/fvrml-run/fvrml-run"
    "$run" examples/paper/figure1-morphing.wrl --fraction 0.5 -o out/figure1.png
    "$run" examples/paper/figure1-morphing.wrl --frames 8 -o out/figure1.wrl
    echo "wrote out/figure1.png (the paper's Figure 1 halfway through the morph) and out/figure1.wrl"
    echo "(VRML97: the morph as 8 frames under a Switch driven by a TimeSensor; open it in any VRML97 browser)"
    ;;
  fuzz)
    targets=("${FUZZ_TARGETS[@]}")
    [ -n "${2:-}" ] && [ "$2" != all ] && targets=("$2")
    have_fuzz_toolchain || { echo "fuzz: clang-19 with libFuzzer (${FUZZ_PACKAGES[*]}) is not installed" >&2; exit 1; }
    build_fuzz
    exec tests/fuzz/run.sh build-fuzz "$SHARED_DIR" "${3:-300}" "$(nproc)" "${targets[@]}"
    ;;
  campaign)
    [ -n "${2:-}" ] || { echo "usage: ./dev.sh campaign TARGET [SECONDS] [WORKERS]   (TARGET: ${FUZZ_TARGETS[*]})" >&2; exit 2; }
    have_fuzz_toolchain || { echo "campaign: clang-19 with libFuzzer (${FUZZ_PACKAGES[*]}) is not installed" >&2; exit 1; }
    build_fuzz && build_fuzz_ub
    exec tests/fuzz/campaign.sh build-fuzz-ub build-fuzz "$SHARED_DIR" "${3:-3600}" "${4:-$(nproc)}" "$2"
    ;;
  oracle)
    install_missing nodejs
    [ -x "$BUILD_DIR/tests/oracle/js_oracle" ] || { echo "oracle: not built (it needs libfuzzer-19-dev's FuzzedDataProvider.h)" >&2; exit 1; }
    seed=$(date +%s)
    echo "oracle: fresh seeds from $seed for ${2:-300} s (./dev.sh oracle SECONDS); a difference prints both programs"
    exec "$BUILD_DIR/tests/oracle/js_oracle" --prelude tests/oracle/prelude.js --seed "$seed" --seconds "${2:-300}"
    ;;
  wasm)
    install_missing "${TEST_PACKAGES[@]}" || true
    install_npm_tools
    build_wasm
    echo "built build-wasm/web (open build-wasm/web/index.html in a browser); its tests:"
    (cd "$BUILD_DIR" && ctest --output-on-failure -L wasm)
    ;;
  mutation)
    shift
    exec tests/mutation/run.sh "$@"
    ;;
  install)
    [ $# -ge 2 ] || { echo "usage: ./dev.sh install PREFIX   (e.g. ~/.local: the tools go to PREFIX/bin)" >&2; exit 2; }
    cmake --install "$BUILD_DIR" --prefix "$2" > /dev/null
    echo "installed fscript, fvrml-run, fvrml-meshdiff and fscript-lsp in $2/bin"
    case ":$PATH:" in *":$2/bin:"*) ;; *) echo "note: $2/bin is not on PATH; add it for editors to find fscript-lsp" ;; esac
    ;;
  *) echo "usage: ./dev.sh demo|test [--fast]|build|setup|format [--check]|install PREFIX|mutation|fuzz [TARGET|all] [SECONDS]|campaign TARGET [SECONDS] [WORKERS]|oracle [SECONDS]|wasm" >&2; exit 2 ;;
esac
