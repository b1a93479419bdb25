#!/usr/bin/env bash
# Precise-output machine-code tests: `fscript emit-asm --backend sse` of each tests/golden/asm/*.fs
# on every instruction-set variant (base: legacy SSE; avx2 and avx512: VEX forms, eight lanes for
# straight-line kernels), compared as text with NAME.ISA.s, so an encoding or code generation
# change shows as a reviewable diff. Addresses of runtime functions (12 hex digits) are masked.
# The emitter writes the same VEX code for avx2 and avx512, so avx512 is compared with
# NAME.avx2.s unless a NAME.avx512.s says how it differs. FSCRIPT_BLESS=1 rewrites the expected
# files (an avx512 one only where the code differs). usage: asm_test.sh FSCRIPT SOURCE_DIR
set -u
F="$1"
SRC="$2"
. "$SRC/tests/support/skip.sh"
fails=0 n=0
diffs=$(mktemp)
trap 'rm -f "$diffs"' EXIT
for fs in "$SRC"/tests/golden/asm/*.fs; do
  for isa in base avx2 avx512; do
    want="${fs%.fs}.$isa.s"
    [ "$isa" = avx512 ] && [ ! -f "$want" ] && [ -z "${FSCRIPT_BLESS:-}" ] && want="${fs%.fs}.avx2.s"
    flag=$isa
    [ "$isa" = avx512 ] && flag=avx512f
    if [ "$isa" != base ] && ! grep -qw "$flag" /proc/cpuinfo; then  # the tools would run a narrower variant
      fs_skip machine "asm $(basename "$want")" "the CPU has no $isa"
      continue
    fi
    got=$(FSCRIPT_ISA=$isa "$F" emit-asm "$fs" --backend sse 2>&1 | sed -E 's/0x[0-9a-f]{12}\b/0xADDRESS/g')
    n=$((n + 1))
    if [ -n "${FSCRIPT_BLESS:-}" ]; then
      if [ "$isa" = avx512 ] && [ "$got" = "$(cat "${fs%.fs}.avx2.s")" ]; then
        rm -f "$want"
      else
        printf '%s\n' "$got" > "$want"
      fi
    elif ! diff -u "$want" <(printf '%s\n' "$got") > "$diffs" 2>&1; then
      echo "FAIL $(basename "$fs") on $isa: the listing differs from $(basename "$want") (FSCRIPT_BLESS=1 rewrites it):"
      head -40 "$diffs"
      fails=$((fails + 1))
    fi
  done
done
echo "$((n - fails)) of $n listings as expected"
[ "$fails" = 0 ]
