#!/usr/bin/env bash
# The C++ sources as clang-format-19 writes them (.clang-format): `format.sh` rewrites them,
# `format.sh --check` lists the files that differ and fails (ctest `format`). The .def tables stay as written.
set -uo pipefail
cd "$(dirname "$0")/../.."
. tests/support/skip.sh
if ! command -v clang-format-19 > /dev/null; then
  fs_skip missing format "clang-format-19 is not installed (./dev.sh setup installs it)" && exit 77
  exit 1
fi
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h')
else  # a copy without git: the source folders
  mapfile -t files < <(find frontend ir backends engine runtime tools lsp tests -name '*.cpp' -o -name '*.h' | sort)
fi
if [ "${1:-}" != --check ]; then
  clang-format-19 -i "${files[@]}"
  echo "formatted ${#files[@]} files"
  exit 0
fi
out=$(mktemp)
trap 'rm -f "$out"' EXIT
if clang-format-19 --dry-run --Werror "${files[@]}" 2> "$out"; then
  echo "ok: ${#files[@]} files formatted"
  exit 0
fi
grep -o '^[^:]*:[0-9]*:[0-9]*: error' "$out" | cut -d: -f1 | sort -u | sed 's/$/: not formatted (.\/dev.sh format rewrites it)/'
head -20 "$out"
exit 1
