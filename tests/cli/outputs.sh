#!/usr/bin/env bash
# Outputs never replace inputs: -o naming the scene, an Inline or EXTERNPROTO file, the --check
# mesh or (with --frames) one of the numbered files is refused with a clear error and the file is
# left as it was, for every format, through links too; --force allows it. fvrml-run merge and
# fscript render2d refuse the same.
# usage: outputs.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
D="${4:-}"
. "$SRC/tests/cli/lib.sh"

BALL='FShape { geometry FGeometry { definition "0.3^2 - x^2 - y^2 - z^2" bboxSize 1 1 1 resolution [16] } }'
# kept NAME FILE: FILE still has the bytes of its copy FILE.orig
kept() { cmp -s "$2" "$2.orig" || fail "$1: the file was changed"; }
mkdir -p "$T/o"
for fmt in wrl glb ply obj stl png; do
  printf '#VRML V2.0 utf8\n%s\n' "$BALL" > "$T/o/scene.$fmt"
  cp "$T/o/scene.$fmt" "$T/o/scene.$fmt.orig"
  check "-o the scene itself ($fmt)" 1 "error: the output $T/o/scene.$fmt is the scene this run reads: writing it would replace that file; name another output, or add --force" \
    -- "$R" "$T/o/scene.$fmt" --format "$fmt" -o "$T/o/scene.$fmt"
  kept "-o the scene itself ($fmt)" "$T/o/scene.$fmt"
done
check "-o the scene by another spelling of its path" 1 "is the scene this run reads" -- "$R" "$T/o/scene.wrl" -o "$T/o/../o/./scene.wrl"
ln -s scene.wrl "$T/o/link.wrl"
check "-o a symbolic link to the scene" 1 "is the scene this run reads" -- "$R" "$T/o/scene.wrl" -o "$T/o/link.wrl"
ln "$T/o/scene.wrl" "$T/o/hard.wrl"
check "-o a hard link to the scene" 1 "is the scene this run reads" -- "$R" "$T/o/scene.wrl" -o "$T/o/hard.wrl"
kept "links to the scene" "$T/o/scene.wrl"
(cd "$T/o" && "$R" scene.wrl -o scene.wrl > "$T/rel.txt" 2>&1)
[ $? = 1 ] && grep -q "is the scene this run reads" "$T/rel.txt" || fail "-o the scene, both relative: $(cat "$T/rel.txt")"

# Files the scene reads.
mkdir -p "$T/o/parts"
printf '#VRML V2.0 utf8\n%s\n' "$BALL" > "$T/o/parts/part.wrl"
cp "$T/o/parts/part.wrl" "$T/o/parts/part.wrl.orig"
printf '#VRML V2.0 utf8\nInline { url "parts/part.wrl" }\n' > "$T/o/main.wrl"
check "-o an Inline's file" 1 "error: the output $T/o/parts/part.wrl is a file this scene reads \($T/o/parts/part.wrl\)" \
  -- "$R" "$T/o/main.wrl" -o "$T/o/parts/part.wrl"
kept "-o an Inline's file" "$T/o/parts/part.wrl"
printf '#VRML V2.0 utf8\nPROTO Ball [ ] { %s }\n' "$BALL" > "$T/o/parts/lib.wrl"
cp "$T/o/parts/lib.wrl" "$T/o/parts/lib.wrl.orig"
printf '#VRML V2.0 utf8\nEXTERNPROTO Ball [ ] "parts/lib.wrl#Ball"\nBall { }\n' > "$T/o/ext.wrl"
check "-o an EXTERNPROTO's file" 1 "the output $T/o/parts/lib.wrl is a file this scene reads" -- "$R" "$T/o/ext.wrl" -o "$T/o/parts/lib.wrl"
kept "-o an EXTERNPROTO's file" "$T/o/parts/lib.wrl"
"$R" "$T/o/scene.wrl" -o "$T/o/ref.ply" 2> /dev/null || fail "a reference mesh"
cp "$T/o/ref.ply" "$T/o/ref.ply.orig"
check "-o the --check mesh" 1 "the output $T/o/ref.ply is the reference mesh of --check" -- "$R" "$T/o/scene.wrl" --check "$T/o/ref.ply" -o "$T/o/ref.ply"
kept "-o the --check mesh" "$T/o/ref.ply"
# --frames: any of the numbered files.
printf '#VRML V2.0 utf8\n%s\n' "$BALL" > "$T/o/f-2.ply"
cp "$T/o/f-2.ply" "$T/o/f-2.ply.orig"
check "--frames: a numbered file is the scene" 1 "the output $T/o/f-2.ply is the scene this run reads" -- "$R" "$T/o/f-2.ply" --format ply --frames 4 -o "$T/o/f.ply"
kept "--frames: a numbered file is the scene" "$T/o/f-2.ply"
[ -e "$T/o/f-0.ply" ] && fail "--frames: a refused run still wrote f-0.ply"
# A script given to fvrml-run.
printf '0.3^2 - x^2 - y^2 - z^2\n' > "$T/o/ball.fs"
cp "$T/o/ball.fs" "$T/o/ball.fs.orig"
check "-o the script fvrml-run reads" 1 "the output $T/o/ball.fs is the scene this run reads" -- "$R" "$T/o/ball.fs" --format ply -o "$T/o/ball.fs"
kept "-o the script fvrml-run reads" "$T/o/ball.fs"
check "fscript render2d -o its own script" 2 "error: the output $T/o/ball.fs is the script this command reads" \
  -- "$F" render2d "$T/o/ball.fs" --size 32 --bounds -1,1,-1,1 -o "$T/o/ball.fs"
kept "fscript render2d -o its own script" "$T/o/ball.fs"
# --force: the user asked for it.
cp "$T/o/scene.wrl" "$T/o/forced.wrl"
check "--force lets -o replace the scene" 0 "wrote $T/o/forced.wrl" -- "$R" "$T/o/forced.wrl" -o "$T/o/forced.wrl" --force
grep -q "written by fvrml-run\|IndexedFaceSet" "$T/o/forced.wrl" || fail "--force: the scene was not replaced by the export"
# fvrml-run merge: the output is not one of the parts.
"$R" "$T/o/scene.wrl" --shard 0/1 --format ply -o "$T/o/p0.part" 2> /dev/null || fail "a shard's part"
cp "$T/o/p0.part" "$T/o/p0.part.orig"
check "merge -o one of its parts" 1 "error: -o $T/o/p0.part is a part this merge reads" -- "$R" merge "$T/o/p0.part" -o "$T/o/p0.part"
kept "merge -o one of its parts" "$T/o/p0.part"
check "merge to another name still works" 0 "" -- "$R" merge "$T/o/p0.part" -o "$T/o/merged.ply"

finish outputs
