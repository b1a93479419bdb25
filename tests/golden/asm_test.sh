#!/usr/bin/env bash
# Precise-output machine-code tests: `fscript emit-asm --backend sse` of each tests/golden/asm/*.fs
# on every instruction-set variant (base: legacy SSE; avx2 and avx512: VEX forms, eight lanes for
# straight-line kernels), compared as text with NAME.ISA.s, so an encoding or code generation
# change shows as a reviewable diff. Addresses of runtime functions (12 hex digits) are masked.
# FSCRIPT_BLESS=1 rewrites the expected files. usage: asm_test.sh FSCRIPT SOURCE_DIR
set -u
F="$1"
SRC="$2"
. "$SRC/tests/support/skip.sh"
fails=0 n=0
for fs in "$SRC"/tests/golden/asm/*.fs; do
  for isa in base avx2 avx512; do
    want="${fs%.fs}.$isa.s"
    flag=$isa
    [ "$isa" = avx512 ] && flag=avx512f
    if [ "$isa" != base ] && ! grep -qw "$flag" /proc/cpuinfo; then  # the tools would run a narrower variant
      fs_skip machine "asm $(basename "$want")" "the CPU has no $isa"
      continue
    fi
    got=$(FSCRIPT_ISA=$isa "$F" emit-asm "$fs" --backend sse 2>&1 | sed -E 's/0x[0-9a-f]{12}\b/0xADDRESS/g')
    n=$((n + 1))
    if [ -n "${FSCRIPT_BLESS:-}" ]; then
      printf '%s\n' "$got" > "$want"
    elif ! diff -u "$want" <(printf '%s\n' "$got") > /tmp/asm_diff.$$ 2>&1; then
      echo "FAIL $(basename "$want"): the listing differs (FSCRIPT_BLESS=1 rewrites it):"
      head -40 /tmp/asm_diff.$$
      fails=$((fails + 1))
    fi
  done
done
rm -f /tmp/asm_diff.$$
echo "$((n - fails)) of $n listings as expected"
[ "$fails" = 0 ]
