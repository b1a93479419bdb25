#!/usr/bin/env bash
# The same bytes for any --threads, every format, several scenes, dual contouring and frames.
# usage: threads.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- The same bytes for any --threads, every format, several scenes ----
for w in figure1-morphing figure2-texture figure6-blends listing1-operation; do
  for fmt in wrl glb ply obj stl png; do
    for th in 1 2 3 7; do
      "$R" "$P/$w.wrl" -o "$T/th$th.$fmt" --threads "$th" --resolution-scale 0.2 --width 48 --height 48 2> /dev/null ||
        fail "$w.$fmt with --threads $th"
    done
    n=$((n + 1))
    for th in 2 3 7; do
      cmp -s "$T/th1.$fmt" "$T/th$th.$fmt" || fail "$w.$fmt: --threads $th differs from --threads 1"
    done
  done
done

# Dual contouring too, frames (the frame cache) and colours included.
for th in 1 2 3; do
  "$R" "$P/figure6-blends.wrl" --mesher dc -o "$T/dc-th$th.glb" --threads "$th" --resolution-scale 0.5 2> /dev/null ||
    fail "figure6-blends --mesher dc with --threads $th"
  "$R" "$P/figure2-texture.wrl" --mesher dc --frames 3 -o "$T/dc-fr-th$th.wrl" --threads "$th" --resolution-scale 0.3 2> /dev/null ||
    fail "figure2-texture --mesher dc --frames 3 with --threads $th"
done
for th in 2 3; do
  n=$((n + 1))
  cmp -s "$T/dc-th1.glb" "$T/dc-th$th.glb" || fail "figure6-blends --mesher dc: --threads $th differs from --threads 1"
  cmp -s "$T/dc-fr-th1.wrl" "$T/dc-fr-th$th.wrl" || fail "figure2-texture --mesher dc --frames 3: --threads $th differs"
done

finish threads
