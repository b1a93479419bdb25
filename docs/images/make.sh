#!/usr/bin/env bash
# Makes every picture of the README from the repository's examples; each line is the command that
# made the picture of the same name. ctest `doc_images` runs it into a scratch folder, so the
# commands cannot drift from the tools.
# usage: docs/images/make.sh [OUT_DIR] [FVRML_RUN] [SHARED_DIR]   (defaults: docs/images, the build's, ../shared)
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT="${1:-docs/images}"
RUN="${2:-build/tools/fvrml-run/fvrml-run}"
SHARED="${3:-../shared}"
P=examples/paper
mkdir -p "$OUT"
"$RUN" $P/figure1-morphing.wrl --fraction 0 --size 400x300 -o "$OUT/figure1-t0.png"
"$RUN" $P/figure1-morphing.wrl --fraction 1 --size 400x300 -o "$OUT/figure1-t1.png"
"$RUN" $P/figure6-blends.wrl --fraction 0.5 --size 400x300 -o "$OUT/figure6-t05.png"
"$RUN" $P/figure2-texture.wrl --size 400x300 -o "$OUT/figure2.png"
"$RUN" $P/figure3-colour.wrl --size 400x300 -o "$OUT/figure3.png"
"$RUN" $P/listing1-operation.wrl --frames 6 --size 600x400 -o "$OUT/listing1-frames.png"
"$RUN" $P/figure1-morphing.wrl --frames 6 --size 600x400 -o "$OUT/figure1-frames.png"
"$RUN" examples/csg.fs --mesher mt --size 400x300 -o "$OUT/csg-mt.png"
"$RUN" examples/csg.fs --mesher dc --size 400x300 -o "$OUT/csg-dc.png"
"$RUN" examples/gyroid-ball.fs --mesher mt --size 400x300 -o "$OUT/gyroid-ball-mt.png"
"$RUN" examples/gyroid-ball.fs --mesher dc --size 400x300 -o "$OUT/gyroid-ball-dc.png"
if [ -f "$SHARED/corpus/wilsonteng97-CZ2003-CGV/Lab 4/lab4.wrl" ]; then
  "$RUN" "$SHARED/corpus/wilsonteng97-CZ2003-CGV/Lab 4/lab4.wrl" --size 480x360 -o "$OUT/lab4.png"
fi
