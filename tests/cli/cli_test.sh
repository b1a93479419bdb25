#!/usr/bin/env bash
# CLI tests: exit statuses, messages and outputs of `fscript` as a user sees them.
# usage: cli_test.sh FSCRIPT SOURCE_DIR
set -u
F="$1"
SRC="$2"
R="${3:-}"  # fvrml-run
D="${4:-}"  # fvrml-meshdiff
. "$SRC/tests/cli/lib.sh"

cat > "$T/sphere.fs" <<'FS'
function FRep(x, y, z, t) { return 1 - x*x - y*y - z*z; }
FS
cat > "$T/parts.fs" <<'FS'
x=u; y=v*2; z=-w;
FS
cat > "$T/bad.fs" <<'FS'
function f(x) {
  return x + ;
}
function g(y) { return h(y); }
FS
cat > "$T/loop.fs" <<'FS'
function f(x) {
  while (true) {
    x = x + 1;
  }
  return x;
}
FS
cat > "$T/rec.fs" <<'FS'
function f(x) { return f(x + 1); }
FS
cat > "$T/fact.fs" <<'FS'
function fact(n) { if (n <= 1) return 1; return n * fact(n - 1); }
FS
cat > "$T/nan.fs" <<'FS'
function f(x) { return sqrt(x) + log(x); }
FS
cat > "$T/scene.wrl" <<'WRL'
#VRML V2.0 utf8
FShape { geometry FGeometry {
  definition "function frep(x,y,z,t){
     return 1 - x*x - undefined_thing;
  }"
} }
WRL

check run-frep 0 '^0$' -- "$F" run "$T/sphere.fs" 1 0 0
check run-frep-nan-arg 0 '^nan$' -- "$F" run "$T/sphere.fs" nan 0 0
check run-frep-inf-arg 0 '^-inf$' -- "$F" run "$T/sphere.fs" -inf 0 0
check run-entry-case 0 '^1$' -- "$F" run "$T/sphere.fs" --entry frep 0 0 0
check run-assignments 0 'x=1' -- "$F" run "$T/parts.fs" 1 2 3
check run-assignments-y 0 'y=4' -- "$F" run "$T/parts.fs" 1 2 3
check run-stdin 0 'z=-0' -- bash -c "\"$F\" < \"$T/parts.fs\""
check run-nan-domain 0 '^nan$' -- "$F" run "$T/nan.fs" -1
check run-too-many-args 2 'too many arguments' -- "$F" run "$T/sphere.fs" 1 2 3 4 5
check run-bad-number 2 'not a number' -- "$F" run "$T/sphere.fs" 1 abc
check run-missing-file 1 'cannot read' -- "$F" run "$T/none.fs"
check run-syntax 1 'bad.fs:2:14: error: expected an expression' -- "$F" run "$T/bad.fs" --entry f
check run-caret 1 '^ +\^' -- "$F" run "$T/bad.fs" --entry f
check run-two-errors 1 "unknown function 'h'" -- "$F" check "$T/bad.fs"
check run-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" 0
check run-loop-flag 1 'more than 50 iterations' -- "$F" run "$T/loop.fs" --max-loop-iterations 50 0
check run-recursion 1 'rec.fs:1:24: error: call depth budget exceeded' -- "$F" run "$T/rec.fs" 0
printf 'function a(x) { return x; }\nfunction b(x) { return x; }\n' > "$T/two.fs"
check run-no-entry 1 'no entry point' -- "$F" run "$T/two.fs"
check run-unknown-entry 1 "no function named 'nope'" -- "$F" run "$T/rec.fs" --entry nope
check backend-sse 0 '^0$' -- "$F" run "$T/sphere.fs" --backend sse 1 0 0
check emit-asm-sse 0 'mulps [xy]mm[0-9]+, [xy]mm[0-9]+' -- "$F" emit-asm "$T/sphere.fs" --backend sse
# A straight-line kernel runs eight lanes where the CPU has AVX2; four at FSCRIPT_ISA=base.
if grep -q ' avx2 ' /proc/cpuinfo; then
  check emit-asm-sse-wide 0 '; 8 points per iteration \(ymm registers\)' -- "$F" emit-asm "$T/sphere.fs" --backend sse
fi
check emit-asm-sse-base 0 '; 4 points per iteration \(xmm registers\)' -- env FSCRIPT_ISA=base "$F" emit-asm "$T/sphere.fs" --backend sse
check emit-asm-sse-pool 0 '\.float 1, 1, 1, 1' -- "$F" emit-asm "$T/sphere.fs" --backend sse
check backend-sse-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" --backend sse 0
check run-recursion-sse 1 'rec.fs:1:24: error: call depth budget exceeded: more than 1000 nested calls' -- "$F" run "$T/rec.fs" --backend sse 1
check run-fact-sse 0 '^3628800$' -- "$F" run "$T/fact.fs" 10 --backend sse
# The llvm backend, when this build has it (FS_HAVE_LLVM from CMake: off only when asked for).
LLVM=""
[ "${FS_HAVE_LLVM:-1}" = 1 ] && LLVM=1
if [ -n "$LLVM" ]; then
  check backend-llvm 0 '^0$' -- "$F" run "$T/sphere.fs" --backend llvm 1 0 0
  check emit-asm-llvm 0 'v?mulps' -- "$F" emit-asm "$T/sphere.fs" --backend llvm
  check emit-ir-llvm 0 'fmul <(4|8|16) x float>' -- "$F" emit-ir --llvm "$T/sphere.fs"
  check backend-llvm-loop 1 'loop.fs:2:3: error: loop iteration budget' -- "$F" run "$T/loop.fs" --backend llvm 0
  check run-recursion-llvm 1 'rec.fs:1:24: error: call depth budget exceeded: more than 1000 nested calls' -- "$F" run "$T/rec.fs" --backend llvm 1
  check run-fact-llvm 0 '^3628800$' -- "$F" run "$T/fact.fs" 10 --backend llvm
  check llvm-disk-cache 0 '^3628800$' -- env XDG_CACHE_HOME="$T/xdg" "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
  ls "$T"/xdg/fscript/llvm/*.o > /dev/null 2>&1 || { echo "FAIL llvm-disk-cache wrote no object file"; fails=$((fails + 1)); }
  check llvm-disk-cache-again 0 '^3628800$' -- env XDG_CACHE_HOME="$T/xdg" "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
  check llvm-disk-cache-nowhere 2 'no cache directory' -- env -u XDG_CACHE_HOME -u HOME "$F" run "$T/fact.fs" 10 --backend llvm --llvm-disk-cache
else
  check emit-ir-llvm-missing 2 'built without the llvm backend' -- "$F" emit-ir --llvm "$T/sphere.fs"
fi
check backend-unknown 2 "unknown backend 'gpu' \\(available: auto, vm, sse" -- "$F" run "$T/sphere.fs" --backend gpu 0 0 0
check usage-unknown-command 2 '' -- "$F" frobnicate
check usage-render-size 2 'size' -- "$F" render2d "$T/sphere.fs" --size 0x5 --bounds -1,1,-1,1
check usage-render-bounds 2 'bounds' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,1

printf '0,0,0\n# a comment\n\n1,0,0\n0.5,0.5,0\nnan,0,0\n' > "$T/pts.csv"
check eval-rows 0 '^0\.5$' -- "$F" eval "$T/sphere.fs" --entry FRep --points "$T/pts.csv"
out=$("$F" eval "$T/sphere.fs" --entry FRep --points "$T/pts.csv")
[ "$out" = $'1\n0\n0.5\nnan' ] || { echo "FAIL eval-exact: got [$out]"; fails=$((fails + 1)); }
printf '0,0,0\n1,zero,0\n' > "$T/badpts.csv"
check eval-bad-row 1 'badpts.csv:2: error' -- "$F" eval "$T/sphere.fs" --entry FRep --points "$T/badpts.csv"
check eval-stdin 0 '^1$' -- bash -c "echo 0,0,0 | \"$F\" eval \"$T/sphere.fs\" --entry FRep"

cat > "$T/ftransform.wrl" <<'WRL'
#VRML V2.0 utf8
FTransform { operation "union" translation "0.5*t, sin(t), 0" scale "1 1 1"
  rotation "0, 0, 1,
            2*t + oops" children [] }
WRL
check wrl-affine 1 'ftransform.wrl:4:19: error: unknown name .oops.' -- "$F" check "$T/ftransform.wrl"
gzip -c "$T/scene.wrl" > "$T/scene.wrl.gz"
check wrl-gzip 1 'scene.wrl.gz:4:23: error: unknown name' -- "$F" check "$T/scene.wrl.gz"
check wrl-missing 1 'none.wrl:1:1: error: cannot read' -- "$F" check "$T/none.wrl"
check wrl-positions 1 'scene.wrl:4:23: error: unknown name' -- "$F" check "$T/scene.wrl"
check emit-ir 0 'fn @kernel\(4\) -> 1 kernel' -- "$F" emit-ir "$T/sphere.fs" --opt
check emit-ir-passes 0 'fmul' -- "$F" emit-ir "$T/sphere.fs" --passes inline,fold
check emit-ir-bad-pass 1 "unknown pass 'nope'" -- "$F" emit-ir "$T/sphere.fs" --passes nope
# --gradient: f and its three partial derivatives, what the meshers evaluate for normals.
check emit-ir-gradient 0 'fn @kernel.gradient\(4\) -> 4 kernel' -- "$F" emit-ir --gradient "$T/sphere.fs"
"$F" emit-ir --gradient "$T/sphere.fs" | grep -Eq '^  ret v[0-9]+, v[0-9]+, v[0-9]+, v[0-9]+$' || fail "emit-ir --gradient: four outputs"
printf 'function FRep(x, y, z, t) { return noise(x, y, z) - 0.1; }\n' > "$T/noisy.fs"
check emit-ir-gradient-none 1 'noisy.fs: error: this kernel has no gradient' -- "$F" emit-ir --gradient "$T/noisy.fs"
n=$((n + 1))
check emit-asm-vm 0 'registers' -- "$F" emit-asm "$T/sphere.fs" --backend vm
# A kernel the row split wraps still lists (it did not: "no listing for backend 'vm'"), with its
# sin and cos pairs.
printf 'function f(x, y) { return sin(x) * cos(y) + cos(x) * sin(y); }\n' > "$T/trig.fs"
check emit-asm-vm-pairs 0 'sin r[0-9]+ \(and its cos into r[0-9]+\)' -- "$F" emit-asm "$T/trig.fs" --backend vm
check emit-asm-auto-pairs 0 'computed with its pair' -- "$F" emit-asm "$T/trig.fs"
# bench: the operation count of the kernel, and evals/s and ns/eval that describe the same rate.
bench_ok() {
  python3 -c "
import re, sys
t = sys.stdin.read()
ops = re.search(r'compile: [0-9.e+-]+ ms for ([0-9]+) IR operations', t)
rate = re.search(r'^([0-9.e+]+) evals/s$', t, re.M)
ns = re.search(r'^([0-9.e+]+) ns/eval$', t, re.M)
ok = ops and rate and ns and int(ops.group(1)) > 0 and abs(float(rate.group(1)) * float(ns.group(1)) / 1e9 - 1) < 0.01
sys.exit(0 if ok else 1)"
}
"$F" bench "$T/sphere.fs" --entry FRep --points 10000 --threads 2 2>&1 | bench_ok || fail "bench: figures"
"$F" bench "$T/sphere.fs" --entry FRep --points 1000 --one-point 2>&1 | bench_ok || fail "bench --one-point: figures"
n=$((n + 2))
# bench --grid: the same figures by rows, and what the row split hoisted (the gyroid: y and z work).
printf 'function FRep(x, y, z, t) { var k = 12.566370614359172; var X = x * k + t; var Y = y * k; var Z = z * k;\n  return sin(X) * cos(Y) + sin(Y) * cos(Z) + sin(Z) * cos(X); }\n' > "$T/gyroid.fs"
for b in vm sse ${LLVM:+llvm} auto; do
  "$F" bench "$T/gyroid.fs" --entry FRep --points 20000 --grid --backend $b > "$T/grid.txt" 2>&1
  bench_ok < "$T/grid.txt" || fail "bench --grid $b: figures"
  grep -q '^row split: 7 operations once per row, 8 per point, 4 values per row$' "$T/grid.txt" || fail "bench --grid $b: the split"
  n=$((n + 1))
done
check bench-grid-unsplit 0 '^row split: none' -- "$F" bench "$T/sphere.fs" --entry FRep --points 1000 --grid
check bench-grid-one-point 2 'excludes' -- "$F" bench "$T/gyroid.fs" --entry FRep --grid --one-point

# render2d: a disc of radius 1 sampled on 101x101 over [-1.5, 1.5]^2; the count is computed
# independently here (float arithmetic as the tool samples it).
check render2d 0 'white pixels' -- "$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc.png"
want=$(python3 -c "
import struct
def f32(v): return struct.unpack('f', struct.pack('f', v))[0]
c=0
for r in range(101):
  for i in range(101):
    x=f32(-1.5+f32(i*f32(f32(3.0)/100))); y=f32(1.5-f32(r*f32(f32(3.0)/100)))
    c += 1-x*x-y*y >= 0
print(c)")
got=$("$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc2.png" | head -1 | cut -d' ' -f1)
[ "$got" = "$want" ] || { echo "FAIL render2d-count: got $got want $want"; fails=$((fails + 1)); }
# --repeat N renders N times (the same picture) and prints the best time once.
got=$("$F" render2d "$T/sphere.fs" --entry FRep --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc3.png" --repeat 3)
[ "$(echo "$got" | head -1 | cut -d' ' -f1)" = "$want" ] && [ "$(echo "$got" | grep -c ' ms$')" = 1 ] ||
  { echo "FAIL render2d-repeat: $got"; fails=$((fails + 1)); }
check usage-render-repeat 2 'repeat' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,-1,1 --repeat 0
head -c 8 "$T/disc.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' || { echo "FAIL render2d-png: not a PNG"; fails=$((fails + 1)); }
# Without -o the picture goes to the current folder, named after the script; every write says so.
rm -f "$T/sphere.png"
FABS="$(cd "$(dirname "$F")" && pwd)/$(basename "$F")"
check render2d-default-output 0 'wrote sphere.png: 101x101, [0-9]+ white pixels' -- sh -c "cd '$T' && '$FABS' render2d sphere.fs --size 101 --bounds -1.5,1.5,-1.5,1.5"
[ -s "$T/sphere.png" ] || fail "render2d-default-output: no sphere.png next to where it ran"
check render2d-summary 0 "wrote $T/disc2.png: 101x101" -- "$F" render2d "$T/sphere.fs" --size 101 --bounds -1.5,1.5,-1.5,1.5 -o "$T/disc2.png"
check render2d-unwritable 1 'cannot write' -- "$F" render2d "$T/sphere.fs" --size 4 --bounds -1,1,-1,1 -o "$T/no/such/dir/x.png"

# fmt: canonical output, idempotent
printf 'function f(x){var a=x*2;if(a>1){return a}else{return -a^2}}\n' > "$T/ugly.fs"
"$F" fmt "$T/ugly.fs" > "$T/pretty.fs"
"$F" fmt "$T/pretty.fs" > "$T/pretty2.fs"
cmp -s "$T/pretty.fs" "$T/pretty2.fs" || { echo "FAIL fmt-idempotent"; fails=$((fails + 1)); }
check fmt-layout 0 '^  if \(a > 1\) \{$' -- "$F" fmt "$T/ugly.fs"
check fmt-error 1 'expected an expression' -- "$F" fmt "$T/bad.fs"
# fmt --check says whether a file is formatted; -i rewrites it (and never a file that does not parse).
cp "$T/ugly.fs" "$T/inplace.fs"
check fmt-check-ugly 1 'inplace.fs: not formatted \(fscript fmt -i' -- "$F" fmt --check "$T/inplace.fs"
check fmt-in-place 0 '' -- "$F" fmt -i "$T/inplace.fs"
cmp -s "$T/inplace.fs" "$T/pretty.fs" || fail "fmt-in-place: the file is not what fmt prints"
check fmt-check-pretty 0 '' -- "$F" fmt --check "$T/inplace.fs"
cp "$T/bad.fs" "$T/bad-copy.fs"
check fmt-in-place-error 1 'expected an expression' -- "$F" fmt -i "$T/bad-copy.fs"
cmp -s "$T/bad.fs" "$T/bad-copy.fs" || fail "fmt-in-place-error: a file with errors was rewritten"
check fmt-in-place-stdin 2 'standard input has none' -- "$F" fmt -i - < "$T/ugly.fs"
# Every tool says its version; fscript repl starts the REPL; --help mentions it and fscript < FILE.
LSP="$(dirname "$F")/../../lsp/fscript-lsp"
for tool in "$F" "$R" "$D" "$LSP"; do
  [ -x "$tool" ] && check "version $(basename "$tool")" 0 "^$(basename "$tool") [0-9]+\.[0-9]+\.[0-9]+ \(FVRML toolchain\)$" -- "$tool" --version
done
# Help reads like a person wrote it: ranges in words, no parser hints.
for tool in "$F" "$R"; do
  [ -x "$tool" ] || continue
  "$tool" --help > "$T/help.txt" 2>&1
  n=$((n + 1))
  ! grep -qE 'UINT|FLOAT|4611686018427387904|:POSITIVE' "$T/help.txt" || fail "help-words $(basename "$tool"): $(grep -E 'UINT|FLOAT|POSITIVE' "$T/help.txt" | head -2)"
done
check help-range-words 0 'nested calls allowed, 1 to 100,000 \(default 1,000\)' -- "$F" --help
# A scene given to a script command says which tool to use, with no VRML parse errors.
check wrong-kind-render2d 1 'figure1-morphing.wrl: error: this is a VRML scene; .*fvrml-run' -- "$F" render2d "$SRC/examples/paper/figure1-morphing.wrl" --size 8 --bounds -1,1,-1,1
check wrong-kind-run 1 'this is a VRML scene' -- "$F" run "$SRC/examples/paper/figure1-morphing.wrl"
check wrong-kind-emit-ir 1 'this is a VRML scene' -- "$F" emit-ir "$SRC/examples/paper/figure1-morphing.wrl"
check lsp-unknown-argument 2 "unknown argument '--port'" -- "$LSP" --port 4
check repl-subcommand 0 '^3$' -- sh -c "printf '1+2\n:quit\n' | \"$F\" repl"
check help-mentions-repl 0 'fscript repl.*fscript < FILE' -- sh -c "\"$F\" --help | tr '\n' ' '"

# Hostile input: deep nesting, a 1 MB expression, an unterminated comment.
python3 -c "print('function f(x) { return ' + '('*100000 + 'x' + ')'*100000 + '; }')" > "$T/deep.fs"
check deep-nesting 1 'nesting deeper than' -- "$F" check "$T/deep.fs"
python3 -c "print('function FRep(x, y, z) { return 0' + ' + x'*260000 + '; }')" > "$T/long.fs"
check long-expression 0 '^260000$' -- "$F" run "$T/long.fs" 1 0 0
printf 'function f(x) { return x; }\n/* open\n' > "$T/open.fs"
check unterminated-comment 1 'open.fs:2:1: error: unterminated comment' -- "$F" check "$T/open.fs"
printf 'function f(x) { return x; }\n\xff\xfe\n' > "$T/binary.fs"
check invalid-bytes 1 'binary.fs:2:1: error: unexpected byte' -- "$F" check "$T/binary.fs"

# The shared corpus and the paper's data (a skip when absent, a failure under CI).
[ -d "$SHARED/corpus" ] || skip_missing corpus "the shared corpus $SHARED/corpus is absent"
[ -f "$SHARED/data/prospero.fs" ] || skip_missing prospero "$SHARED/data/prospero.fs is absent"
if [ -d "$SHARED/corpus" ]; then
  while IFS= read -r -d '' w; do
    if head -c 7 "$w" | grep -q BSCRYPT; then
      # One course file is encrypted (BS Contact's BSCRYPT): a clear error, never a crash.
      check "corpus-check $(basename "$w")" 1 'encrypted' -- "$F" check "$w"
    else
      check "corpus-check $(basename "$w")" 0 '' -- "$F" check "$w"
    fi
  done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
fi
if [ -f "$SHARED/data/prospero.fs" ]; then
  check prospero-256 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1
  check prospero-256-sse 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1 --backend sse
  [ -n "$LLVM" ] && check prospero-256-llvm 0 '^8150 white pixels' -- "$F" render2d "$SHARED/data/prospero.fs" --entry FRep --size 256 --bounds -1,1,-1,1 --backend llvm
  check prospero-asm-bounded 0 '^; inputs finite with \|x\| <= 65536' -- "$F" emit-asm "$SHARED/data/prospero.fs" --backend sse
fi

# fvrml-run: the scene layer (--stats) on the paper's examples, the corpus and bad scenes.
if [ -n "$R" ]; then
  for w in "$SRC"/examples/paper/*.wrl; do
    check "fvrml-run-stats $(basename "$w")" 0 '"shapes":\[\{' -- "$R" "$w" --stats
    check "fscript-check $(basename "$w")" 0 '' -- "$F" check "$w"
  done
  jcheck fvrml-run-time err "near(j['shapes'][0]['fraction'], 0.6)" -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --stats --time 3
  jcheck fvrml-run-fraction err "near(j['shapes'][0]['geometry']['t'], 0.25)" -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --stats --fraction 0.25
  check fvrml-run-kind 0 '"kind":"implicit"' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" --stats
  check fvrml-run-script-error 1 'scene.wrl:4:23: error: unknown name' -- "$R" "$T/scene.wrl" --stats
  printf '#VRML V2.0 utf8\nTransform { translation 1 2 }\n' > "$T/badfield.wrl"
  check fvrml-run-bad-field 1 'badfield.wrl:2:29: error: expected 3 numbers \(SFVec3f\)' -- "$R" "$T/badfield.wrl" --stats
  cat > "$T/proto.wrl" <<'WRL'
#VRML V2.0 utf8
PROTO Ball [ field SFString f "0.5^2-x^2-y^2-z^2" field SFVec3f at 0 0 0 ] {
  Transform { translation IS at children [ FShape { geometry FGeometry { definition IS f bboxSize 2 2 2 } } ] }
}
Ball { at 1 2 3 }
Ball { f "0.25-x^2-y^2-zz^2" }
WRL
  check fvrml-run-proto-error 1 'proto.wrl:6:24: error: unknown name .zz.' -- "$R" "$T/proto.wrl" --stats
  sed -i 's/zz/z/' "$T/proto.wrl"
  check fvrml-run-proto 0 '"transform":\[1\.0,0\.0,0\.0,0\.0,0\.0,1\.0,0\.0,0\.0,0\.0,0\.0,1\.0,0\.0,1\.0,2\.0,3\.0,1\.0\]' -- "$R" "$T/proto.wrl" --stats
  printf '#VRML V2.0 utf8\nFTransform { translation "0.5*t, sin(t), 0" rotation "0 0 1 t" children [ FShape { geometry FGeometry { definition "1-x*x" } } ] }\nInline { url "http://example.com/o.wrl" }\n' > "$T/ft.wrl"
  check fvrml-run-affine 0 '"affine":\{"rotation":4,"translation":3\}' -- "$R" "$T/ft.wrl" --stats
  check fvrml-run-inline 0 "warning: Inline 'http://example.com/o.wrl' is not fetched" -- "$R" "$T/ft.wrl" --stats
  printf '#VRML V2.0 utf8\nFTransform { translation "1 2" }\n' > "$T/ft2.wrl"
  check fvrml-run-affine-count 1 'ft2.wrl:2:27: error: .translation. of FTransform needs 3 components, found 2' -- "$R" "$T/ft2.wrl" --stats
  printf '#VRML V2.0 utf8\nTransform { translation 1 0 0 children FShape { geometry FGeometry { definition "0.5^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [16] } } }\n' > "$T/ball.wrl"
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry {\n  definition "0.5-x*x-y*y-z*z"\n  parameters [0 1 0 1]\n} }\n' > "$T/unused.wrl"
  check fvrml-run-unused-field 0 "unused.wrl:4:3: warning: 'parameters' is not used by an implicit shape" -- "$R" "$T/unused.wrl" -o "$T/unused.ply"
  # On a terminal without -o: a picture in the current folder, said so; -o - is VRML97 on stdout.
  RABS="$(cd "$(dirname "$R")" && pwd)/$(basename "$R")" SRCABS="$(cd "$SRC" && pwd)"
  rm -f "$T/ball.png"
  check fvrml-run-tty-default 0 'no -o given: writing ball.png .*wrote ball.png: [0-9,]+ triangles' -- \
    sh -c "cd '$T' && python3 '$SRCABS/tests/cli/tty_run.py' '$RABS' ball.wrl | tr '\n' ' '"
  [ -s "$T/ball.png" ] || fail "fvrml-run-tty-default: no ball.png"
  check fvrml-run-stdout 0 '^#VRML V2.0 utf8' -- "$R" "$T/ball.wrl" -o -
  check fvrml-run-summary 0 "^wrote $T/ball-summary.ply: [0-9,]+ triangles, 1 shape, [0-9.]+ s$" -- "$R" "$T/ball.wrl" -o "$T/ball-summary.ply"
  check fvrml-run-summary-png 0 "^wrote $T/ball-summary.png: [0-9,]+ triangles, 1 shape" -- "$R" "$T/ball.wrl" -o "$T/ball-summary.png"
  check fvrml-run-no-summary-with-stats 0 '^\{' -- sh -c "'$R' '$T/ball.wrl' -o '$T/ball-stats.ply' --stats 2>&1 >/dev/null | head -1"
  for fmt in ply obj stl; do
    check "fvrml-run-$fmt" 0 '"triangles":[1-9]' -- "$R" "$T/ball.wrl" -o "$T/ball.$fmt" --stats
  done
  head -c 3 "$T/ball.ply" | grep -q ply || { echo "FAIL ply-magic"; fails=$((fails + 1)); }
  grep -q '^f ' "$T/ball.obj" || { echo "FAIL obj-faces"; fails=$((fails + 1)); }
  python3 - "$T/ball.obj" <<'PY' || { echo "FAIL obj-translated"; fails=$((fails + 1)); }
import sys
xs = [float(l.split()[1]) for l in open(sys.argv[1]) if l.startswith('v ')]
sys.exit(0 if abs(sum(xs) / len(xs) - 1.0) < 0.05 else 1)
PY
  check fvrml-run-threads1 0 '' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/t1.ply" --threads 1 --resolution-scale 0.3
  check fvrml-run-threads2 0 '' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/t2.ply" --threads 2 --resolution-scale 0.3
  cmp -s "$T/t1.ply" "$T/t2.ply" || { echo "FAIL fvrml-run-threads-identical"; fails=$((fails + 1)); }
  check fvrml-run-frames 0 '"frames":\[' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 3 -o "$T/fr.ply" --stats --resolution-scale 0.3
  for k in 0 1 2; do [ -s "$T/fr-$k.ply" ] || { echo "FAIL frames file $k"; fails=$((fails + 1)); }; done
  check fvrml-run-frames-needs-o 2 'needs -o' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 3 --format ply
  # Animated VRML97: the frames under a Switch, a TimeSensor with the node's timing, a Script.
  check fvrml-run-frames-wrl 0 '"bytes_per_triangle":' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 4 -o "$T/anim.wrl" --resolution-scale 0.3 --stats
  for want in 'Switch \{' 'whichChoice 0' 'TimeSensor \{' 'Script \{' 'eventIn SFFloat set_fraction' \
              'ROUTE [A-Za-z_0-9]+\.frame_changed TO [A-Za-z_0-9]+\.set_whichChoice' 'fraction_changed TO'; do
    grep -qE "$want" "$T/anim.wrl" || { echo "FAIL animated wrl lacks /$want/"; fails=$((fails + 1)); }
  done
  [ "$(grep -c 'geometry IndexedFaceSet' "$T/anim.wrl")" = 4 ] || { echo "FAIL animated wrl: 4 frames wanted"; fails=$((fails + 1)); }
  check fvrml-run-frames-wrl-reads 0 '' -- "$F" check "$T/anim.wrl"
  # A node with frames whose shape does not move stays one static shape.
  check fvrml-run-frames-constant 0 '"constant":true' -- "$R" "$T/ball.wrl" --frames 3 -o "$T/still.wrl" --stats
  grep -q 'Switch' "$T/still.wrl" && { echo "FAIL a constant animation became a Switch"; fails=$((fails + 1)); }
  # The file's own `frames 10` animates by default.
  check fvrml-run-frames-field 0 '"frames":10' -- "$R" "$SRC/examples/paper/figure6-blends.wrl" -o "$T/f6.wrl" --resolution-scale 0.15 --stats
  grep -q 'Switch' "$T/f6.wrl" || { echo "FAIL figure 6 is not animated"; fails=$((fails + 1)); }
  check fvrml-run-frames-glb 0 '"animations":\[\{' -- "$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 4 -o "$T/anim.glb" --resolution-scale 0.3 --stats
  check fvrml-run-png 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.png" --width 64 --height 48
  head -c 8 "$T/ball.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' || { echo "FAIL fvrml-run-png-magic"; fails=$((fails + 1)); }
  # Pictures keep the standard geometry and the Background of the scene.
  printf '#VRML V2.0 utf8\nBackground { skyColor 0 0 1 }\nShape { appearance Appearance { material Material { diffuseColor 1 0 0 } } geometry Box { } }\n' > "$T/box.wrl"
  check fvrml-run-png-standard 0 '' -- "$R" "$T/box.wrl" -o "$T/box.png" --width 64 --height 48
  # 64 x 48 = 3,072 pixels: the blue sky around, the red box in the middle.
  jcheck fvrml-run-png-sky out "500 <= j['count'] <= 2400" -- python3 "$SRC/tests/clients/png_probe.py" "$T/box.png" 0 0 255 8
  jcheck fvrml-run-png-box out "200 <= j['count'] <= 1999 and abs(j['x'] - 31.5) < 3 and abs(j['y'] - 23.5) < 3" \
    -- python3 "$SRC/tests/clients/png_probe.py" "$T/box.png" 200 0 0 120
  check fvrml-run-glb 0 '' -- "$R" "$T/ball.wrl" -o "$T/ball.glb"
  head -c 4 "$T/ball.glb" | grep -q glTF || { echo "FAIL glb-magic"; fails=$((fails + 1)); }
  # The Khronos glTF validator, when dev.sh test could install it (npm).
  if command -v node > /dev/null && [ -d "${GLTF_VALIDATOR_DIR:-/nonexistent}/gltf-validator" ]; then
    for w in "$T/ball.wrl" "$SRC"/examples/paper/figure1-morphing.wrl "$SRC"/examples/paper/figure6-blends.wrl; do
      "$R" "$w" -o "$T/v.glb" --resolution-scale 0.2 2> /dev/null
      check "gltf-validator $(basename "$w")" 0 '"numErrors":0,"numWarnings":0' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T/v.glb"
    done
    check "gltf-validator animated" 0 '"numErrors":0,"numWarnings":0' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T/anim.glb"
    # Every corpus file as glTF, validated in one run of the validator.
    if [ -d "$SHARED/corpus" ]; then
      mkdir -p "$T/glb"
      k=0
      while IFS= read -r -d '' w; do
        head -c 7 "$w" | grep -q BSCRYPT && continue
        k=$((k + 1))
        "$R" "$w" -o "$T/glb/$k.glb" --resolution-scale 0.2 --keep-going 2> /dev/null || true
        [ -s "$T/glb/$k.glb" ] || { echo "FAIL no glb for $w"; fails=$((fails + 1)); }
      done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
      check "gltf-validator corpus ($k files)" 0 '' -- node "$SRC/tests/clients/gltf_validate.mjs" "$T"/glb/*.glb
    fi
  else
    skip_missing gltf-validator "the Khronos glTF validator is not installed in ${GLTF_VALIDATOR_DIR:-?} (./dev.sh test installs it with npm)"
  fi
  check fvrml-run-format 2 "unsupported output format 'gltf': fvrml-run writes wrl, glb, ply, obj, stl and png" -- "$R" "$T/ball.wrl" -o "$T/ball.gltf"
  check fvrml-run-unwritable 1 'cannot write' -- "$R" "$T/ball.wrl" -o "$T/no/dir/x.ply"
  [ ! -e "$T/no/dir/x.ply" ] || { echo "FAIL half-written"; fails=$((fails + 1)); }
  check fvrml-run-listing1 0 '"triangles":[1-9]' -- "$R" "$SRC/examples/paper/listing1-operation.wrl" -o "$T/l1.ply" --stats
  printf '#VRML V2.0 utf8\nFTransform { children [ FShape { geometry FGeometry { definition "x=u; y=v; z=0;" resolution [4 4] } }\n  FShape { geometry FGeometry { definition "0.5-x*x-y*y-z*z" } } ] }\nFShape { geometry FGeometry { definition "0.5-x*x-y*y-z*z" resolution [8] } }\n' > "$T/mixed.wrl"
  check fvrml-run-ftransform 1 'mixed.wrl:2:1: error: FTransform: an FTransform cannot mix implicit and parametric children' -- "$R" "$T/mixed.wrl" -o "$T/l.ply"
  [ ! -e "$T/l.ply" ] || { echo "FAIL no-output-on-error"; fails=$((fails + 1)); }
  check fvrml-run-keep-going 1 'warning: FTransform: an FTransform cannot mix' -- "$R" "$T/mixed.wrl" -o "$T/l.ply" --keep-going
  check fvrml-run-wrl-stdout 0 'geometry IndexedFaceSet' -- "$R" "$T/ball.wrl"
  for w in "$SRC"/examples/paper/figure1-morphing.wrl "$SRC"/examples/paper/figure6-blends.wrl; do
    check "fvrml-run-wrl $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/out.wrl" --resolution-scale 0.2
    check "fvrml-run-wrl-reads $(basename "$w")" 0 '' -- "$F" check "$T/out.wrl"
    grep -q 'FShape\|FGeometry\|ROUTE Time.fraction_changed TO shape' "$T/out.wrl" && { echo "FAIL FVRML nodes left in $(basename "$w")"; fails=$((fails + 1)); }
  done
  check fvrml-run-bad-backend 2 "unknown backend 'gpu'" -- "$R" "$T/badfield.wrl" --stats --backend gpu
  check fvrml-run-missing 1 'cannot read' -- "$R" "$T/none.wrl" --stats
  if [ -d "$SHARED/corpus" ]; then
    while IFS= read -r -d '' w; do
      head -c 7 "$w" | grep -q BSCRYPT && continue
      check "fvrml-run-corpus $(basename "$w")" 0 '"shapes"' -- "$R" "$w" --stats -o "$T/c.wrl" --resolution-scale 0.3 --keep-going
      check "fvrml-run-corpus-reads $(basename "$w")" 0 '' -- "$F" check "$T/c.wrl"
    done < <(find "$SHARED/corpus" -name '*.wrl' -print0)
  fi
  # A file's meshes follow the scene's order (they once followed the nodes' addresses, which moved with
  # the heap: a backend that allocated more put the shapes of one scene in another order).
  for order in "-2 2 0" "2 0 -2" "0 -2 2"; do
    { echo "#VRML V2.0 utf8"
      for x in $order; do
        echo "Transform { translation $x 0 0 children FShape { geometry FGeometry { definition \"0.3-x*x-y*y-z*z\" bboxSize 2 2 2 resolution [16] } } }"
      done; } > "$T/order.wrl"
    for b in vm sse ${LLVM:+llvm}; do
      "$R" "$T/order.wrl" -o "$T/order.obj" --backend "$b" > /dev/null 2>&1
      got=$(awk '/^v /{ x = $2 + 0; c = x < -1 ? -2 : x > 1 ? 2 : 0; if (c != last) { printf "%s ", c; last = c } }' last=9 "$T/order.obj")
      [ "$got" = "$order " ] || { echo "FAIL shapes out of order ($b): want '$order', got '$got'"; fails=$((fails + 1)); }
    done
  done
  # Every corpus file and example: the same mesh, byte for byte, with the sse and llvm backends as with the VM,
  # the VM's without the row split (every grid point a point) and the others' with it (grid rows).
  while IFS= read -r -d '' w; do
    head -c 7 "$w" | grep -q BSCRYPT && continue
    FSCRIPT_ROW_SPLIT=0 "$R" "$w" -o "$T/vm.ply" --resolution-scale 0.3 --backend vm 2> /dev/null
    check "fvrml-run-sse $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/sse.ply" --resolution-scale 0.3 --backend sse
    cmp -s "$T/vm.ply" "$T/sse.ply" || { echo "FAIL sse mesh differs from vm: $w"; fails=$((fails + 1)); }
    # auto, made to switch tiers after 2,000 points of each kernel: some batches on each.
    check "fvrml-run-auto $(basename "$w")" 0 '' -- env FSCRIPT_AUTO_SWITCH_AFTER=2000 "$R" "$w" -o "$T/auto.ply" --resolution-scale 0.3 --backend auto
    cmp -s "$T/vm.ply" "$T/auto.ply" || { echo "FAIL auto (switched mid-job) mesh differs from vm: $w"; fails=$((fails + 1)); }
    [ -z "$LLVM" ] && continue
    check "fvrml-run-llvm $(basename "$w")" 0 '' -- "$R" "$w" -o "$T/llvm.ply" --resolution-scale 0.3 --backend llvm
    cmp -s "$T/vm.ply" "$T/llvm.ply" || { echo "FAIL llvm mesh differs from vm: $w"; fails=$((fails + 1)); }
  done < <(find "$SRC/examples" "$SHARED/corpus" -name '*.wrl' -print0 2> /dev/null)
fi

# auto: the switch is visible in --stats, and a forced one in the middle of a big job changes no byte.
if [ -n "$R" ]; then
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "sin(x*7)*cos(y*5)+sin(z*6) - 0.2" bboxSize 2 2 2 resolution [40] } }\n' > "$T/tier.wrl"
  "$R" "$T/tier.wrl" -o "$T/tier-vm.ply" --backend vm
  FSCRIPT_AUTO_SWITCH_AFTER=10000 "$R" "$T/tier.wrl" -o "$T/tier-auto.ply" --backend auto --stats 2> "$T/tier.json"
  jcheck "fvrml-run auto: a forced switch, both tiers used" out "
j['tiers']['switched'] >= 1 and j['tiers']['vm_points'] >= 10000 and j['tiers']['native_points'] > 0 and j['tiers']['first_switch_ms'] >= 0
" -- cat "$T/tier.json"
  cmp -s "$T/tier-vm.ply" "$T/tier-auto.ply" || { echo "FAIL auto (switched mid-job) mesh differs from vm"; fails=$((fails + 1)); }
  if [ -n "$LLVM" ]; then
    # With the llvm disk cache, a second run of the same scene is native from its first batch.
    env XDG_CACHE_HOME="$T/xdg-auto" FSCRIPT_AUTO_SWITCH_AFTER=1 "$R" "$T/tier.wrl" -o "$T/tier-d1.ply" --llvm-disk-cache 2> /dev/null
    env XDG_CACHE_HOME="$T/xdg-auto" "$R" "$T/tier.wrl" -o "$T/tier-d2.ply" --llvm-disk-cache --stats 2> "$T/tier-d2.json"
    jcheck "fvrml-run auto: the second run with the disk cache starts native" out "
j['tiers']['cached'] >= 1 and j['tiers']['vm_points'] == 0 and j['tiers']['native_points'] > 0 and j['tiers']['compiles'] == 0
" -- cat "$T/tier-d2.json"
    cmp -s "$T/tier-vm.ply" "$T/tier-d2.ply" || { echo "FAIL auto from the disk cache: mesh differs from vm"; fails=$((fails + 1)); }
  fi
fi

# fvrml-meshdiff: known answers, formats, bad input.
if [ -n "$D" ] && [ -n "$R" ]; then
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1-x^2-y^2-z^2" bboxSize 3 3 3 resolution [24] } }\n' > "$T/r1.wrl"
  printf '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1.1^2-x^2-y^2-z^2" bboxSize 3 3 3 resolution [24] } }\n' > "$T/r11.wrl"
  "$R" "$T/r1.wrl" -o "$T/r1.ply" && "$R" "$T/r11.wrl" -o "$T/r11.stl" && "$R" "$T/r1.wrl" -o "$T/r1.obj"
  # Spheres of radius 1 and 1.1: both distances are 0.1, give or take the meshes' own error.
  jcheck meshdiff-spheres out "near(j['hausdorff'], 0.1, 0.01) and near(j['chamfer'], 0.1, 0.005) and
    near(j['hausdorff_relative'], j['hausdorff'] / j['bbox_diagonal_a']) and j['a']['triangles'] > 1000" -- "$D" "$T/r1.ply" "$T/r11.stl"
  check meshdiff-watertight 0 '"watertight": true' -- "$D" "$T/r1.obj" "$T/r11.stl"
  check meshdiff-euler 0 '"euler": 2' -- "$D" "$T/r1.ply" "$T/r1.obj"
  check meshdiff-missing 1 'cannot read' -- "$D" "$T/none.ply" "$T/r1.ply"
  printf 'not a mesh' > "$T/bad.ply"
  check meshdiff-bad 1 'bad.ply: error: not a PLY file' -- "$D" "$T/bad.ply" "$T/r1.ply"
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//5\n' > "$T/badn.obj"
  check meshdiff-bad-normal 1 'badn.obj: error: OBJ: a face names normal 5 of 1' -- "$D" "$T/badn.obj"
  printf 'v 0 0 0\nvn 0 1\n' > "$T/shortn.obj"
  check meshdiff-short-normal 1 'shortn.obj: error: OBJ line 2: a normal needs three numbers' -- "$D" "$T/shortn.obj"
  check meshdiff-usage 2 '' -- "$D"
  # One mesh: its topology alone, with its components and the inside-out ones.
  jcheck meshdiff-one out "j['a']['components'] == 1 and j['a']['inverted_components'] == 0 and j['a']['watertight'] and 'hausdorff' not in j" \
    -- "$D" "$T/r1.ply"
  jcheck fvrml-run-check out "near(j['hausdorff'], 0.1, 0.01) and near(j['chamfer'], 0.1, 0.005) and j['watertight']" \
    -- "$R" "$T/r1.wrl" --check "$T/r11.stl"
  jcheck fvrml-run-check-self out "j['hausdorff'] < 1e-6 and j['chamfer'] < 1e-6 and j['euler'] == 2" -- "$R" "$T/r1.wrl" --check "$T/r1.ply"
  check fvrml-run-check-missing 1 'none.ply: error: cannot read' -- "$R" "$T/r1.wrl" --check "$T/none.ply"
fi

finish CLI
