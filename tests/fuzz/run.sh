#!/usr/bin/env bash
# Runs the libFuzzer targets (./dev.sh fuzz calls this after building build-fuzz):
#   tests/fuzz/run.sh BUILD_FUZZ SHARED SECONDS JOBS TARGET...
# Each target runs SECONDS on its regression corpus (tests/fuzz/corpus/T), seeds from the tests,
# examples/ and the shared corpus, and what earlier runs found (BUILD_FUZZ/corpus/T), JOBS at once.
# A finding is saved as BUILD_FUZZ/findings/T-crash-... and fails the run. FUZZ_SEED=N fixes
# libFuzzer's random seed (./dev.sh test does, so that CI explores the same inputs every time).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
bf="$1" shared="$2" seconds="$3" jobs="$4"
shift 4

# shellcheck source=tests/fuzz/lib.sh
source "$here/lib.sh"

run_one() {
  local t="$1" exe="$bf/tests/fuzz/fuzz_$1"
  [ -x "$exe" ] || { echo "fuzz: no target $t (built: $(ls "$bf/tests/fuzz" | grep '^fuzz_' | tr '\n' ' '))"; return 2; }
  seed "$t"
  mkdir -p "$bf/corpus/$t" "$bf/findings" "$bf/logs"
  local dict args=()
  dict=$(dict_for "$t")
  [ -n "$dict" ] && args+=("-dict=$dict")
  [ -n "${FUZZ_SEED:-}" ] && args+=("-seed=$FUZZ_SEED")
  # A target is one process here: -rss_limit_mb catches a leak or a blow-up, -timeout a hang. The
  # timeout counts wall time with JOBS targets sharing the cores (CI runs two on two): a generated
  # program whose inlined calls make 1,200 blocks takes 13 s under this build's sanitizers alone
  # (mostly LLVM's compile of it and the IR verifier after every pass) and 22 s beside another
  # target, slow but no hang.
  nice "$exe" "$bf/corpus/$t" "$here/corpus/$t" "$bf/seeds/$t" "${args[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2560 -timeout=60 -max_len=16384 -print_final_stats=1 \
    -artifact_prefix="$bf/findings/$t-" > "$bf/logs/$t.log" 2>&1
  local st=$?
  local execs speed
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$bf/logs/$t.log" | grep -o '[0-9]*$')
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$bf/logs/$t.log" | grep -o '[0-9]*$')
  if [ "$st" = 0 ]; then
    echo "fuzz $t: ${execs:-?} executions in ${seconds}s (${speed:-?}/s), no finding"
  else
    echo "fuzz $t: FINDING (exit $st); log $bf/logs/$t.log, input in $bf/findings/"
    grep -A3 '==== fuzz finding\|ERROR: AddressSanitizer\|runtime error\|ERROR: libFuzzer' "$bf/logs/$t.log" | head -20
  fi
  return "$st"
}

status=0
pids=()
for t in "$@"; do
  run_one "$t" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$jobs" ]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
exit "$status"
