#!/usr/bin/env bash
# docs/images/make.sh, the commands that made the README's pictures, run into a scratch folder:
# every picture is made again (the commands cannot drift from the tools).
# usage: doc_images_test.sh SOURCE_DIR FVRML_RUN SHARED_DIR
set -u
SRC="$1" RUN="$2" SHARED="$3"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
. "$SRC/tests/support/skip.sh"
bash "$SRC/docs/images/make.sh" "$T" "$RUN" "$SHARED" > "$T/log.txt" 2>&1 || { cat "$T/log.txt"; echo "FAIL docs/images/make.sh"; exit 1; }
fails=0
for f in "$SRC"/docs/images/*.png; do
  name=$(basename "$f")
  if [ "$name" = lab4.png ] && [ ! -d "$SHARED/corpus" ]; then
    fs_skip missing "doc_images lab4.png" "the shared corpus" || fails=$((fails + 1))
    continue
  fi
  [ -s "$T/$name" ] || { echo "FAIL docs/images/$name is not made by docs/images/make.sh"; fails=$((fails + 1)); }
  grep -q "$name" "$SRC/README.md" || { echo "FAIL docs/images/$name is not shown in the README"; fails=$((fails + 1)); }
done
[ "$fails" -eq 0 ] && echo "doc_images: every README picture made by its command" || exit 1
