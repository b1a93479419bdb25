#!/usr/bin/env bash
# The limits for untrusted scenes and scripts (docs/reliability.md, "Limits"): each one hit, each
# refusal a clear error with its place, exit status 1, fast, and no output file (nor a temporary).
# usage: limits_test.sh FSCRIPT SOURCE_DIR FVRML_RUN
set -u
F="$1"
SRC="$2"
R="$3"
. "$SRC/tests/cli/lib.sh"

# refused NAME PATTERN OUTPUT -- command...: exit 1, the message, within 20 s, and OUTPUT not written.
refused() {
  local name="$1" pat="$2" out="$3"
  shift 4
  rm -f "$out" "$out.tmp"
  local t0=$SECONDS
  check "$name" 1 "$pat" -- timeout 60 "$@"
  [ $((SECONDS - t0)) -le 20 ] || fail "$name: took $((SECONDS - t0)) s to refuse"
  [ -e "$out" ] && fail "$name: wrote $out"
  [ -e "$out.tmp" ] && fail "$name: left $out.tmp"
}
sphere='FShape { geometry FGeometry { definition "1-x*x-y*y-z*z" resolution [8] } }'

# ---- Files: size before reading, gzip size and ratio while inflating ----
truncate -s 70M "$T/huge.wrl"
refused "a scene over 64 MiB" 'huge.wrl:1:1: error: cannot read the file: the file is 70 MiB, over the limit of 64 MiB' \
  "$T/o.ply" -- "$R" "$T/huge.wrl" -o "$T/o.ply"
truncate -s 70M "$T/huge.fs"
refused "a script over 64 MiB (fvrml-run)" 'huge.fs:1:1: error: .*70 MiB, over the limit of 64 MiB' "$T/o.ply" -- "$R" "$T/huge.fs" -o "$T/o.ply"
check "a script over 64 MiB (fscript)" 1 'huge.fs:1:1: error: cannot read the file: the file is 70 MiB' -- "$F" run "$T/huge.fs"
check "a scene over 64 MiB (fscript check)" 1 'huge.wrl:1:1: error: .*over the limit of 64 MiB' -- "$F" check "$T/huge.wrl"
python3 - "$T" <<'PY'
import gzip, sys
t = sys.argv[1]
# 300 MiB of comment: 0.3 MiB compressed, a ratio of about 1000.
open(f"{t}/bomb.wrl.gz", "wb").write(gzip.compress(b"#VRML V2.0 utf8\n" + b"#" * (300 << 20), 9))
# 80 MiB of varied text inflating about 12 times: within the ratio, over the size.
body = b"".join(b"Group { children [] } # %d\n" % i for i in range(3_000_000))
open(f"{t}/large.wrl.gz", "wb").write(gzip.compress(b"#VRML V2.0 utf8\n" + body, 6))
PY
refused "a gzip bomb" 'bomb.wrl.gz:1:1: error: the gzip data inflates more than 250 times' "$T/o.ply" -- "$R" "$T/bomb.wrl.gz" -o "$T/o.ply"
refused "gzip inflating past 64 MiB" 'large.wrl.gz:1:1: error: the gzip data inflates to more than 64 MiB' "$T/o.ply" \
  -- "$R" "$T/large.wrl.gz" -o "$T/o.ply"

# ---- The scene graph: PROTO and USE expansion ("billion laughs"), nesting ----
python3 - "$T" "$sphere" <<'PY'
import sys
t, sphere = sys.argv[1], sys.argv[2]
lines = ["#VRML V2.0 utf8", "PROTO L0 [] { Group {} }"]
for i in range(1, 10):  # L9 is 10^9 Groups
    lines.append(f"PROTO L{i} [] {{ Group {{ children [ {' '.join(f'L{i - 1} {{}}' for _ in range(10))} ] }} }}")
open(f"{t}/protos.wrl", "w").write("\n".join(lines + ["L9 {}", sphere]) + "\n")
lines = ["#VRML V2.0 utf8", "DEF A0 Group {}"]
for i in range(1, 40):  # A39 is 2^39 Groups
    lines.append(f"DEF A{i} Group {{ children [ USE A{i - 1} USE A{i - 1} ] }}")
open(f"{t}/uses.wrl", "w").write("\n".join(lines + [sphere]) + "\n")
lines = ["#VRML V2.0 utf8", "PROTO P0 [] { Group {} }"]
for i in range(1, 2100):  # each body one instance of the last: 2100 levels, 2100 nodes
    lines.append(f"PROTO P{i} [] {{ P{i - 1} {{}} }}")
open(f"{t}/chain.wrl", "w").write("\n".join(lines + ["P2099 {}", sphere]) + "\n")
open(f"{t}/deep.wrl", "w").write("#VRML V2.0 utf8\n" + "Group { children [ " * 1200 + "]}" * 1200 + "\n")
PY
refused "a PROTO explosion" 'protos.wrl:3:70: error: the scene expands to more than 1000000 nodes' "$T/o.ply" \
  -- "$R" "$T/protos.wrl" -o "$T/o.ply"
refused "a USE explosion" 'uses.wrl:2:8: error: the scene expands to more than 1000000 nodes' "$T/o.glb" -- "$R" "$T/uses.wrl" -o "$T/o.glb"
refused "PROTO instances nested too deep" 'chain.wrl:101:16: error: nodes nested more than 2000 deep through PROTO instances' \
  "$T/o.ply" -- "$R" "$T/chain.wrl" -o "$T/o.ply"
refused "nodes nested too deep" 'deep.wrl:2:19020: error: nodes nested deeper than 1000 levels' "$T/o.ply" -- "$R" "$T/deep.wrl" -o "$T/o.ply"

# ---- Frames, resolution and sample points per run ----
printf '#VRML V2.0 utf8\nFShape { frames 1001 geometry FGeometry { definition "1-x*x-y*y-z*z+t" resolution [8] } }\n' > "$T/frames.wrl"
refused "frames over 1000" 'frames.wrl:2:10: error: frames 1001 is over the limit of 1000 for one node' "$T/o.glb" \
  -- "$R" "$T/frames.wrl" -o "$T/o.glb"
printf '#VRML V2.0 utf8\nFTransform { frames 5000 children [ %s ] }\n' "$sphere" > "$T/gframes.wrl"
refused "an FTransform's frames over 1000" 'gframes.wrl:2:14: error: frames 5000 is over the limit' "$T/o.glb" \
  -- "$R" "$T/gframes.wrl" -o "$T/o.glb"
# Shapes are refused by what they cost (points by their own dimension, and memory), not per axis.
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x*x-y*y-z*z" resolution [100000 100000 100000] } }\n' > "$T/res.wrl"
refused "a solid grid of 10^15 points" 'res.wrl:2:58: error: resolution \[100000 100000 100000\] of this implicit shape asks for 1e\+15 sample points, over the limit of 6.88e\+10 for one shape' \
  "$T/o.ply" -- "$R" "$T/res.wrl" -o "$T/o.ply"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { type "parametric" definition "x = u; y = v; z = 0;" parameters [0 1 0 1] resolution [30000 30000] } }\n' > "$T/sheet.wrl"
refused "a surface of 30000^2 points by memory" 'sheet.wrl:2:104: error: resolution \[30000 30000\] of this parametric surface needs about 268 GiB of memory \(9e\+08 sample points\), over the 7.81 GiB of --max-memory' \
  "$T/o.ply" -- "$R" "$T/sheet.wrl" --max-memory 8000 -o "$T/o.ply"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { type "parametric" definition "x = u; y = 0; z = 0;" parameters [0 1] resolution [2147483647] } }\n' > "$T/line.wrl"
refused "a curve of 2^31 points, whatever the memory" 'line.wrl:2:100: error: resolution \[2147483647\] of this parametric curve asks for 2.15e\+09 sample points, over the limit of 1e\+09 for one shape' \
  "$T/o.ply" -- "$R" "$T/line.wrl" --max-memory 1000000 -o "$T/o.ply"
refused "an infinite resolution" 'res.wrl:2:58: error: resolution \[1e\+305 1e\+305 1e\+305\] \(after --resolution-scale 1e\+300\) of this implicit shape asks for inf sample points' \
  "$T/o.ply" -- "$R" "$T/res.wrl" --resolution-scale 1e300 -o "$T/o.ply"
for r in 5000 20000; do
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { type "parametric" definition "x = cos(u); y = sin(u); z = 0;" parameters [0 6.3] resolution [%s] } }\n' $r > "$T/curve$r.wrl"
  check "a curve of $r points runs" 0 '"vertices":'$((r + 1)) -- "$R" "$T/curve$r.wrl" --stats -o "$T/curve$r.ply"
done
printf '#VRML V2.0 utf8\nFShape { frames 100 geometry FGeometry { definition "1-x*x-y*y-z*z+t" resolution [1000] } }\n' > "$T/cells.wrl"
refused "implicit samples over the run's limit" \
  'cells.wrl:2:71: error: the run asks for 1e\+11 sample points \(this shape: 1e\+09, times 100 frames\), over the limit of 6.88e\+10' \
  "$T/o.glb" -- "$R" "$T/cells.wrl" -o "$T/o.glb"
refused "--frames counts too" 'cells.wrl:2:71: error: the run asks for 1e\+11 sample points' \
  "$T/o-000.ply" -- "$R" "$T/cells.wrl" --frames 100 -o "$T/o.ply"
check "one frame of it is within the limit" 0 '' -- "$R" "$T/cells.wrl" --resolution-scale 0.05 -o "$T/one.ply"
python3 - "$T" <<'PY'
import sys
shape = 'FShape { geometry FGeometry { type "parametric" definition "x = u; y = v; z = %d;" parameters [0 1 0 1] resolution [4000 4000] } }'
open(f"{sys.argv[1]}/param.wrl", "w").write("#VRML V2.0 utf8\n" + "\n".join(shape % k for k in range(5)) + "\n")
PY
refused "parametric shapes over the run's memory" 'param.wrl:2:104: error: the run needs about 23.9 GiB of memory \(this shape: 4.77 GiB, 1 frame\), over the 7.81 GiB of --max-memory' \
  "$T/o.ply" -- "$R" "$T/param.wrl" --max-memory 8000 -o "$T/o.ply"

# ---- Time: --max-seconds ends a run, with no output; --serve has its own (serve_test.py) ----
printf 'function main() { var s = 0; for (var i = 0; i < 1e12; i++) s += sin(i); return s; }\n' > "$T/long.fs"
refused "fscript run --max-seconds" '^fscript: error: the run took longer than 1 s \(--max-seconds 1\); stopped' "$T/none" \
  -- "$F" run -e main --max-loop-iterations 2000000000000 --max-seconds 1 "$T/long.fs"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z) { var s = 0; for (var i = 0; i < 1e6; i++) s += sin(x * i); return 1 - x * x - y * y - z * z + s; }" resolution [64] } }\n' > "$T/long.wrl"
for out in long.ply long.png long.glb; do
  refused "fvrml-run --max-seconds to $out" '^fvrml-run: error: the run took longer than 1.5 s \(--max-seconds 1.5\); stopped' \
    "$T/$out" -- "$R" "$T/long.wrl" --max-loop-iterations 2000000 --max-seconds 1.5 -o "$T/$out"
done
check "--max-seconds takes seconds, not words" 2 'max-seconds' -- "$R" "$T/long.wrl" --max-seconds soon -o "$T/x.ply"
check "a run within --max-seconds is unaffected" 0 '' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --max-seconds 60 -o "$T/fig.ply"
[ -s "$T/fig.ply" ] || fail "a run within --max-seconds wrote no fig.ply"

# ---- Memory: --max-memory (not under AddressSanitizer, whose shadow memory is not the run's) ----
if [ "${FS_SANITIZED:-0}" = 1 ]; then
  echo "note: --max-memory is not enforced under the sanitizers; its checks are left out of this build"
else
  printf 'function main(n) { var a = new Array(n); for (var i = 0; i < n; i++) a[i] = i; return a[n - 1]; }\n' > "$T/big.fs"
  refused "fscript --max-memory" '^fscript: error: the run needs more than 100 MiB of memory \(--max-memory 100\); stopped' \
    "$T/none" -- "$F" run -e main --max-array-elements 4294967296 --max-memory 100 -b vm "$T/big.fs" 100000000
  check "fscript within --max-memory" 0 '^99999$' -- "$F" run -e main --max-memory 100 -b vm "$T/big.fs" 100000
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z) { var s = 0; for (var i = 0; i < 8; i++) s += sin(9 * x * i) * cos(9 * y * i); return s + 0.5 - z * z; }" resolution [400] } }\n' > "$T/wavy.wrl"
  refused "fvrml-run --max-memory" '^fvrml-run: error: the run needs more than 64 MiB of memory \(--max-memory 64\); stopped' \
    "$T/wavy.ply" -- "$R" "$T/wavy.wrl" --max-memory 64 -o "$T/wavy.ply"
  check "--max-memory under 64 is a usage error" 2 'max-memory' -- "$R" "$T/wavy.wrl" --max-memory 10 -o "$T/x.ply"
  # Worker threads under --max-memory, whatever the stack limit (ulimit -s $(ulimit -s) here): a
  # thread's stack is its own size, not the limit (a gibibyte each under ulimit -s 1048576).
  G="$SRC/bench/scenes/gyroid-sphere256.wrl"
  check "two threads within --max-memory 1024 (ulimit -s $(ulimit -s))" 0 "wrote" \
    -- "$R" "$G" --threads 2 --max-memory 1024 --resolution-scale 0.4 --time 0 -o "$T/g.ply"
  check "an animation on two threads within --max-memory 1024 (ulimit -s $(ulimit -s))" 0 "animated" \
    -- "$R" "$G" --threads 2 --max-memory 1024 --resolution-scale 0.2 -o "$T/g.glb"
  check "fscript bench on two threads within --max-memory 256 (ulimit -s $(ulimit -s))" 0 "" \
    -- "$F" bench "$SRC/examples/gyroid-ball.fs" --threads 2 --points 200000 --max-memory 256
  # The huge heap (docs/performance.md) is reserved inside the cap, a quarter of it: the refusal
  # above still comes at 64 MiB, and a run that fits is unaffected.
  printf '#VRML V2.0 utf8\n%s\n' "$sphere" > "$T/small.wrl"
  if grep -q '\[never\]' /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || [ ! -e /sys/kernel/mm/transparent_hugepage/enabled ]; then
    heap=0
  else
    heap=16
  fi
  check "the huge heap within --max-memory 64" 0 "\"huge_heap_mib\":$heap[,}]" -- "$R" "$T/small.wrl" --max-memory 64 --stats -o "$T/small.ply"
  check "FSCRIPT_HUGE_PAGES=0 keeps the plain heap" 0 '"huge_heap_mib":0[,}]' -- env FSCRIPT_HUGE_PAGES=0 "$R" "$T/small.wrl" --stats -o "$T/small.ply"
fi

# ---- Script budgets inside a scene: the error at the script's line in the .wrl ----
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function d(n) { return n <= 0 ? 0 : 1 + d(n - 1); } function FRep(x, y, z) { return d(5000) - 10; }" } }\n' > "$T/deeprec.wrl"
refused "recursion past the call depth in a scene" 'deeprec.wrl:2:[0-9]+: error: call depth budget exceeded: more than 1000 nested calls' \
  "$T/o.ply" -- "$R" "$T/deeprec.wrl" -o "$T/o.ply"
printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z) { var a = new Array(2000000); return 1; }" } }\n' > "$T/bigarr.wrl"
refused "an array past its budget in a scene" "bigarr.wrl:2:[0-9]+: error: array 'a' of 2000000 elements" "$T/o.ply" \
  -- "$R" "$T/bigarr.wrl" -o "$T/o.ply"

finish limits
