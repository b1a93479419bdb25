#!/usr/bin/env bash
# Script budgets and their ceilings, the same on every backend, inside scenes and pictures; a
# runtime error in a .wrl at the script's own line; a resolution over the limit refused.
# usage: budgets.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- Budgets and their ceilings, the same on every backend ----
printf 'function down(n) { if (n <= 0) return 0; return 1 + down(n - 1); }\n' > "$T/down.fs"
printf 'function f(n) { var a = new Array(n); a[0] = 2; return a[0] + a.length; }\n' > "$T/arr.fs"
printf 'function f(n) { var s = 0; for (var i = 0; i < n; i++) s = s + 1; return s; }\n' > "$T/loop.fs"
for b in $BACKENDS; do
  # down(n) makes n + 1 nested calls.
  check "call depth 5 allows down(4) on $b" 0 '^4$' -- "$F" run "$T/down.fs" 4 --max-call-depth 5 --backend "$b"
  check "call depth 5 refuses down(5) on $b" 1 'down.fs:1:53: error: call depth budget exceeded: more than 5 nested calls' \
    -- "$F" run "$T/down.fs" 5 --max-call-depth 5 --backend "$b"
  check "the call depth ceiling, 100,000, reached on $b" 0 '^99999$' -- "$F" run "$T/down.fs" 99999 --max-call-depth 100000 --backend "$b"
  check "default call depth 1,000 on $b" 1 'more than 1000 nested calls' -- "$F" run "$T/down.fs" 1000 --backend "$b"
  check "array of the budget's size on $b" 0 '^1002$' -- "$F" run "$T/arr.fs" 1000 --max-array-elements 1000 --backend "$b"
  check "array one over the budget on $b" 1 "arr.fs:1:25: error: array 'a' of 1001 elements: .*budget of 1000 elements" \
    -- "$F" run "$T/arr.fs" 1001 --max-array-elements 1000 --backend "$b"
  check "loop of the budget's length on $b" 0 '^50$' -- "$F" run "$T/loop.fs" 50 --max-loop-iterations 50 --backend "$b"
  check "loop one over the budget on $b" 1 'loop.fs:1:28: error: loop iteration budget exceeded: more than 50 iterations' \
    -- "$F" run "$T/loop.fs" 51 --max-loop-iterations 50 --backend "$b"
done
# A runaway loop stops the whole job at its first point's budget (the VM used to take its 512-lane
# chunk times the budget: 41 s for render2d, 79 s for fvrml-run); `timeout` only stops a hang.
printf 'function FRep(x, y, z, t) {\n  while (1) {}\n  return 1;\n}\n' > "$T/runaway.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z, t) { while (1) {} return 1; }" } }\n' > "$T/runaway.wrl"
for b in $BACKENDS; do
  check "a runaway loop fails fast in render2d on $b" 1 'runaway.fs:2:3: error: loop iteration budget exceeded' \
    -- timeout 20 "$F" render2d "$T/runaway.fs" --size 64 --bounds -1,1,-1,1 --backend "$b" -o "$T/runaway.png"
  check "a runaway loop fails fast in fvrml-run on $b" 1 'runaway.wrl:2:71: error: loop iteration budget exceeded' \
    -- timeout 20 "$R" "$T/runaway.wrl" --backend "$b" -o "$T/runaway.ply"
done
# A runtime error in a .wrl names one place: the script's own line and column in the .wrl, and shows
# the line with a caret, as a compile error does.
printf '#VRML V2.0 utf8\n# a comment\nFShape {\n  geometry FGeometry {\n    definition "function FRep(x, y, z, t) {\n      var s = 0;\n      while (1) { s = s + 1; }\n      return s;\n    }"\n  }\n}\n' > "$T/loop7.wrl"
check "a runtime error points at its line in the .wrl" 1 'loop7.wrl:7:7: error: loop iteration budget exceeded: more than 1000 iterations in one evaluation$' \
  -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply" --max-loop-iterations 1000
check "and shows that line" 1 '^      while \(1\) \{ s = s \+ 1; \}$' -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply"
check "with a caret under the loop" 1 '^      \^$' -- "$R" "$T/loop7.wrl" -o "$T/loop7.ply" --max-loop-iterations 1000
# A long but finite loop (2^17 iterations a point, past the point where the VM goes lane by lane).
printf 'function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 131072; i++) s = s + 1; return s - 131072 + x; }\n' > "$T/long.fs"
check "a long loop finishes with every point on the VM" 0 '^2048 white pixels' -- "$F" render2d "$T/long.fs" -o "$T/long.png" --size 64 --bounds -1,1,-1,1 --backend vm
check "call depth above the ceiling" 2 'max-call-depth: Value 100001 not in range 1 to 100000' -- "$F" run "$T/down.fs" 1 --max-call-depth 100001
check "fvrml-run call depth above the ceiling" 2 'max-call-depth' -- "$R" "$P/figure1-morphing.wrl" --stats --max-call-depth 100001
# A resolution whose points are over the limit is refused before any work (it aborted with
# bad_alloc), and writes nothing.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x*x-y*y-z*z" bboxSize 2 2 2 resolution [100000] } }\n' > "$T/huge.wrl"
check "a resolution over the limit" 1 'huge.wrl:2:73: error: resolution \[100000 100000 100000\] of this implicit shape asks for 1e\+15 sample points, over the limit of 6.88e\+10 for one shape$' -- "$R" "$T/huge.wrl" -o "$T/huge.ply"
[ -e "$T/huge.ply" ] && { echo "FAIL a refused scene wrote $T/huge.ply"; fails=$((fails + 1)); }
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x*x" resolution [3000] } }\n' > "$T/wide.wrl"
check "a scaled resolution over the limit" 1 'resolution \[6000 6000 6000\] \(after --resolution-scale 2\) of this implicit shape asks for 2.16e\+11 sample points' -- "$R" "$T/wide.wrl" -o "$T/wide.ply" --resolution-scale 2

finish budgets
