#!/usr/bin/env bash
# Sharded jobs (docs/sharding.md): shards made in any order merge into exactly the bytes of the run
# on one machine (glTF and VRML97, frames by a node's own `frames` and by --frames; numbered mesh
# files and contact sheets of --frames N; a still scene's implicit shapes in slabs, welded), and
# every way a set of parts can be wrong is refused with its reason, exit 1, and no output.
# usage: shard_test.sh SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
SRC="$1"
R="$2"
FVRML_MESHDIFF="$3"
. "$SRC/tests/cli/lib.sh"
S="$SRC/examples/paper/figure1-morphing.wrl"

# same NAME SCENE FORMAT M ARGS...: the single run and the merge of M shards (made last to first).
same() {
  local name="$1" scene="$2" format="$3" m="$4"
  shift 4
  rm -f "$T"/part-*.fvc
  "$R" "$scene" "$@" -o "$T/single.$format" 2> /dev/null || { fail "$name: the single run failed"; return; }
  for ((k = m - 1; k >= 0; k--)); do
    check "$name: shard $k of $m" 0 "^wrote .*part-$k.fvc: shard $k of $m, [0-9]+ frames?$" \
      -- "$R" "$scene" "$@" --format "$format" --shard "$k/$m" -o "$T/part-$k.fvc"
  done
  check "$name: merge" 0 "^wrote .*merged.$format: animated" -- "$R" merge "$T"/part-*.fvc -o "$T/merged.$format"
  cmp -s "$T/single.$format" "$T/merged.$format" || fail "$name: the merged $format differs from the single run's"
}
same "Figure 1, 8 frames, glTF, 3 shards" "$S" glb 3 --frames 8 --resolution-scale 0.5
same "Figure 1, 6 frames, VRML97, 4 shards" "$S" wrl 4 --frames 6 --resolution-scale 0.5
same "more shards than frames" "$S" glb 5 --frames 3 --resolution-scale 0.3
printf '#VRML V2.0 utf8\nFShape { frames 5 cycleInterval 2 geometry FGeometry { definition "0.5 - x*x - y*y - z*z + 0.2*t" bboxSize 2 2 2 resolution [12] } }\nFShape { geometry FGeometry { definition "0.1 - (x-1)*(x-1) - y*y - z*z" bboxSize 2 2 2 resolution [8] } }\nFShape { frames 3 geometry FGeometry { definition "0.1 - (x+1)*(x+1) - y*y - z*z" bboxSize 2 2 2 resolution [8] } }\n' > "$T/own.wrl"
same "a node's own frames, a static shape, a still animation" "$T/own.wrl" glb 2

# --frames N with mesh files and a contact sheet: whole frames in the parts, the same files.
mkdir -p "$T/one" "$T/many"
"$R" "$S" --frames 5 --resolution-scale 0.5 -o "$T/one/f.ply" 2> /dev/null
for k in 2 0 1; do "$R" "$S" --frames 5 --resolution-scale 0.5 --format ply --shard "$k/3" -o "$T/f$k.fvc" 2> /dev/null; done
check "numbered ply frames: merge" 0 'wrote .*f-0.ply \.\.\. .*f-4.ply: 5 frame files' -- "$R" merge "$T"/f?.fvc -o "$T/many/f.ply"
for f in "$T"/one/f-*.ply; do cmp -s "$f" "$T/many/$(basename "$f")" || fail "numbered ply frames: $(basename "$f") differs"; done
[ "$(ls "$T/many" | wc -l)" = 5 ] || fail "numbered ply frames: $(ls "$T/many" | wc -l) files, not 5"
"$R" "$S" --frames 6 --resolution-scale 0.5 --size 300x200 -o "$T/sheet.png" 2> /dev/null
for k in 0 1; do "$R" "$S" --frames 6 --resolution-scale 0.5 --size 300x200 --format png --shard "$k/2" -o "$T/s$k.fvc" 2> /dev/null; done
check "a contact sheet: merge" 0 'wrote .*merged.png' -- "$R" merge "$T"/s?.fvc -o "$T/merged.png"
cmp -s "$T/sheet.png" "$T/merged.png" || fail "a contact sheet: the merged png differs from the single run's"

# ---- What the merge refuses ----
for k in 0 1 2; do "$R" "$S" --frames 6 --format glb --shard "$k/3" -o "$T/p$k.fvc" --resolution-scale 0.3 2> /dev/null; done
refuse() {  # NAME PATTERN STATUS -- merge arguments
  local name="$1" pat="$2" status="$3"
  shift 4
  rm -f "$T/x.glb" "$T/x.wrl"
  check "$name" "$status" "$pat" -- "$R" merge "$@"
  [ -e "$T/x.glb" ] || [ -e "$T/x.wrl" ] && fail "$name: wrote an output"
}
refuse "a missing shard" '^error: shard 1 of 3 missing \(run it with --shard 1/3\)$' 1 -- "$T/p0.fvc" "$T/p2.fvc" -o "$T/x.glb"
refuse "a shard twice" 'p1.fvc and .*p1.fvc are both shard 1 of 3' 1 -- "$T/p0.fvc" "$T/p1.fvc" "$T/p1.fvc" "$T/p2.fvc" -o "$T/x.glb"
"$R" "$S" --frames 5 --format glb --shard 1/3 -o "$T/other.fvc" --resolution-scale 0.3 2> /dev/null
refuse "a shard of another job" 'other.fvc: a shard of another job' 1 -- "$T/p0.fvc" "$T/other.fvc" "$T/p2.fvc" -o "$T/x.glb"
head -c 600 "$T/p1.fvc" > "$T/cut.fvc"
refuse "a truncated part" 'cut.fvc: error: the part is truncated or damaged' 1 -- "$T/p0.fvc" "$T/cut.fvc" "$T/p2.fvc" -o "$T/x.glb"
echo "#VRML V2.0 utf8" > "$T/not.fvc"
refuse "not a part" 'not.fvc: error: not a part file' 1 -- "$T/not.fvc" -o "$T/x.glb"
refuse "an output of another format" '^error: the shards were made for glb output' 2 -- "$T"/p?.fvc -o "$T/x.wrl"
cp "$S" "$T/edit.wrl"
for k in 0 1; do "$R" "$T/edit.wrl" --frames 4 --format glb --shard "$k/2" -o "$T/e$k.fvc" 2> /dev/null; done
echo "# an edit" >> "$T/edit.wrl"
refuse "the scene edited after the shards" "edit.wrl: error: the scene's files changed since the shards were made" 1 \
  -- "$T/e0.fvc" "$T/e1.fvc" -o "$T/x.glb"

# ---- What --shard refuses ----
check "--shard without --format" 2 'needs --format, the format of the merged output' -- "$R" "$S" --frames 4 --shard 0/2 -o "$T/q.fvc"
check "--shard K/M out of range" 2 'wants K/M with 0 <= K < M <= 10000, got 2/2' -- "$R" "$S" --frames 4 --format glb --shard 2/2 -o "$T/q.fvc"
check "--shard with words" 2 "wants K/M \(shard K of M, from 0\) or auto, got 'half'" -- "$R" "$S" --frames 4 --format glb --shard half -o "$T/q.fvc"
check "--shard auto outside Slurm" 2 'SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, which are not set' \
  -- env -u SLURM_ARRAY_TASK_ID "$R" "$S" --frames 4 --format glb --shard auto -o "$T/q.fvc"
check "--shard auto in a Slurm array (ids from 1)" 0 'shard 2 of 4' \
  -- env SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=4 "$R" "$S" --frames 4 --format glb --shard auto -o "$T/q.fvc"
check "--shard auto rerunning one task (FVRML_SHARDS)" 0 'shard 2 of 4' \
  -- env SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_MIN=2 SLURM_ARRAY_TASK_COUNT=1 FVRML_SHARDS=4 "$R" "$S" --frames 4 --format glb --shard auto -o "$T/q.fvc"

# ---- One big shape in slabs: a still scene's implicit shapes split into block layers ----
G="$SRC/bench/scenes/gyroid-sphere256.wrl"
# slabs NAME SCENE FORMAT M ARGS...: the single run (one thread) and the merge of M shards (made
# last to first, on two threads).
slabs() {
  local name="$1" scene="$2" format="$3" m="$4" what="$5"
  shift 5
  rm -f "$T"/part-*.fvc
  "$R" "$scene" "$@" --threads 1 -o "$T/single.$format" 2> /dev/null || { fail "$name: the single run failed"; return; }
  for ((k = m - 1; k >= 0; k--)); do
    check "$name: shard $k of $m" 0 "^wrote .*part-$k.fvc: shard $k of $m, $what$" \
      -- "$R" "$scene" "$@" --threads 2 --format "$format" --shard "$k/$m" -o "$T/part-$k.fvc"
  done
  check "$name: merge" 0 "^wrote .*merged.$format: " -- "$R" merge "$T"/part-*.fvc -o "$T/merged.$format"
  cmp -s "$T/single.$format" "$T/merged.$format" || fail "$name: the merged $format differs from the single run's"
}
slabs "gyroid in a sphere, PLY, 3 slabs" "$G" ply 3 'its slab of 1 shape' --resolution-scale 0.4
# Its topology on the OBJ, which writes a vertex split for its normals once (PLY holds the copies).
slabs "gyroid in a sphere, OBJ, 3 slabs" "$G" obj 3 'its slab of 1 shape' --resolution-scale 0.4
"$FVRML_MESHDIFF" "$T/merged.obj" > "$T/topology.json" 2>&1
grep -q '"watertight": true' "$T/topology.json" && grep -q '"manifold": true' "$T/topology.json" ||
  fail "gyroid in a sphere in slabs: the merged mesh is not a closed manifold"
slabs "gyroid in a sphere, glTF, 4 slabs" "$G" glb 4 'its slab of 1 shape' --resolution-scale 0.3 --time 0
slabs "gyroid in a sphere, VRML97, 2 slabs" "$G" wrl 2 'its slab of 1 shape' --resolution-scale 0.3 --time 0
slabs "gyroid in a sphere, a picture, 2 slabs" "$G" png 2 'its slab of 1 shape' --resolution-scale 0.3 --size 200x150
slabs "more shards than layers of blocks" "$G" stl 9 'its slab of 1 shape' --resolution-scale 0.2
slabs "merged up the octree, no tolerance" "$G" obj 3 'its slab of 1 shape' --resolution-scale 0.3 --tolerance 0
slabs "a coloured surface and a blend (Figure 6)" "$SRC/examples/paper/figure6-blends.wrl" ply 2 'its slab of 1 shape'
slabs "a parametric scene: the merge makes it" "$SRC/examples/paper/figure3-colour.wrl" ply 2 'no slab \(the merge makes every shape\)'
slabs "marching tetrahedra: the merge makes it" "$G" ply 2 'no slab \(the merge makes every shape\)' --resolution-scale 0.2 --mesher mt
for k in 0 1 2; do "$R" "$G" --resolution-scale 0.3 --format ply --shard "$k/3" -o "$T/g$k.fvc" 2> /dev/null; done
refuse "a missing slab" '^error: shard 2 of 3 missing \(run it with --shard 2/3\)$' 1 -- "$T/g0.fvc" "$T/g1.fvc" -o "$T/x.glb"
refuse "slabs and frames mixed" 'p1.fvc: a shard of another job' 1 -- "$T/g0.fvc" "$T/p1.fvc" "$T/g2.fvc" -o "$T/x.glb"
head -c 2000 "$T/g1.fvc" > "$T/gcut.fvc"
refuse "a truncated slab" 'gcut.fvc: error: the part is truncated or damaged' 1 -- "$T/g0.fvc" "$T/gcut.fvc" "$T/g2.fvc" -o "$T/x.glb"
printf 'FVRML-PART 1\n' > "$T/old.fvc"
refuse "a part of the previous version" 'old.fvc: error: not a part file of fvrml-run --shard \(or of another version\)' 1 \
  -- "$T/old.fvc" -o "$T/x.glb"

finish shard
