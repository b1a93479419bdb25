#!/usr/bin/env bash
# `emit-ir --gradient`, the VM's listing, and `fscript bench`: figures that agree, the row split.
# usage: bench.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

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

finish bench
