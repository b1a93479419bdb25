#!/usr/bin/env bash
# The progress line on a terminal (one line redrawn, erased at the end) and none on a pipe.
# usage: progress.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- progress on a terminal: one line redrawn in place, erased at the end; nothing on a pipe ----
# (FVRML_PROGRESS_AFTER=0 shows it from the first redraw, a quarter second in, instead of after 1 s.)
TTY="$SRC/tests/cli/tty_run.py"
GY="$SRC/bench/scenes/gyroid-sphere256.wrl"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$R" "$GY" --threads 1 -o "$T/progress.ply" > "$T/progress-tty.txt" 2>&1
grep -qE $'\rfvrml-run: 0/1 meshes, [0-9]+%' "$T/progress-tty.txt" || { fail "fvrml-run on a terminal: no progress line"; cat -v "$T/progress-tty.txt" | head -5; }
grep -qE $'\r\x1b\[Kwrote [^ ]*progress.ply' "$T/progress-tty.txt" || fail "fvrml-run on a terminal: the progress line is not erased before the summary"
FVRML_PROGRESS_AFTER=0 "$R" "$GY" --threads 1 -o "$T/progress.ply" 2> "$T/progress-pipe.txt"
grep -q $'\r' "$T/progress-pipe.txt" && fail "fvrml-run on a pipe: progress written to standard error"
grep -q '^wrote [^ ]*progress.ply' "$T/progress-pipe.txt" || fail "fvrml-run on a pipe: no summary line"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$R" "$SRC/examples/paper/figure6-blends.wrl" --frames 6 --threads 1 -o "$T/progress.glb" > "$T/progress-frames.txt" 2>&1
grep -qE $'\rfvrml-run: [0-6]/6 frames, [0-9]+%' "$T/progress-frames.txt" || { fail "fvrml-run --frames on a terminal: no frames in the progress line"; cat -v "$T/progress-frames.txt" | head -5; }
printf 'function FRep(x, y, z, t) {\n  var s = 0;\n  for (var i = 0; i < 3000; i = i + 1) s = s + sin(x * i + y);\n  return s;\n}\n' > "$T/slow2d.fs"
FVRML_PROGRESS_AFTER=0 python3 "$TTY" "$F" render2d "$T/slow2d.fs" --size 512 --bounds -1,1,-1,1 --no-prune -o "$T/slow2d.png" > "$T/progress-2d.txt" 2>&1
grep -qE $'\rfscript render2d: 0/1 pictures, [0-9]+%' "$T/progress-2d.txt" || { fail "render2d on a terminal: no progress line"; cat -v "$T/progress-2d.txt" | head -5; }
FVRML_PROGRESS_AFTER=0 "$F" render2d "$T/slow2d.fs" --size 512 --bounds -1,1,-1,1 --no-prune -o "$T/slow2d.png" > /dev/null 2> "$T/progress-2d-pipe.txt"
grep -q $'\r' "$T/progress-2d-pipe.txt" && fail "render2d on a pipe: progress written to standard error"

n=$((n + 7))  # the seven checks above report through `fail`
finish progress
