#!/usr/bin/env bash
# A long campaign of one target (./dev.sh campaign calls this; docs/reliability.md, "Running them"):
#   tests/fuzz/campaign.sh BUILD_FUZZ_UB BUILD_FUZZ SHARED SECONDS WORKERS TARGET
# WORKERS processes of the UBSan-only build share one corpus, BUILD_FUZZ/corpus/TARGET (kept between
# runs, and what the ASan build replays afterwards), beside builds and tests without slowing them.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
ub="$1" bf="$2" shared="$3" seconds="$4" workers="$5" t="$6"

# shellcheck source=tests/fuzz/lib.sh
source "$here/lib.sh"

exe="$ub/tests/fuzz/fuzz_$t"
[ -x "$exe" ] || { echo "campaign: no target $t in $ub/tests/fuzz" >&2; exit 2; }
seed "$t"
mkdir -p "$bf/corpus/$t" "$bf/campaign"
dict=$(dict_for "$t")
args=()
[ -n "$dict" ] && args+=("-dict=$dict")
stamp=$(date +%Y%m%d-%H%M%S)
pids=() logs=()
for w in $(seq 1 "$workers"); do
  log="$bf/campaign/$t-$stamp-$w.log"
  logs+=("$log")
  # -timeout counts wall time, so it is long enough for a worker that builds starve for a while.
  setsid nice -n 19 "$exe" "$bf/corpus/$t" "$here/corpus/$t" "$bf/seeds/$t" "${args[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2560 -timeout=60 -max_len=16384 -print_final_stats=1 \
    -artifact_prefix="$bf/campaign/$t-$stamp-$w-" > "$log" 2>&1 &
  pids+=($!)
done
# setsid makes each worker its own scheduler autogroup, inside which alone nice counts: the
# group's own niceness keeps the workers from taking half of every core from a build. The group is
# made when the worker calls setsid, so wait for that (the worker leads its own session): written
# sooner, the niceness went to this script's group and the workers took 65% of the cores.
for p in "${pids[@]}"; do
  for _ in $(seq 100); do
    [ "$(ps -o sid= -p "$p" 2> /dev/null | tr -d ' ')" = "$p" ] && break
    sleep 0.05
  done
  echo 19 > "/proc/$p/autogroup" 2> /dev/null || true
done
trap 'kill -INT "${pids[@]}" 2> /dev/null' INT TERM
echo "campaign $t: $workers workers for ${seconds}s; logs $bf/campaign/$t-$stamp-*.log (Ctrl-C stops them)"

status=0 total=0
for w in "${!pids[@]}"; do
  wait "${pids[$w]}" || status=1
  n=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "${logs[$w]}" | grep -o '[0-9]*$')
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "${logs[$w]}" | grep -o '[0-9]*$')
  echo "worker $((w + 1)): ${n:-?} executions (${speed:-?}/s)"
  total=$((total + ${n:-0}))
done
echo "campaign $t: $total executions"
if [ "$status" != 0 ]; then
  echo "campaign $t: a worker stopped on a finding or was interrupted; see the logs and $bf/campaign/$t-$stamp-*"
  grep -h -A3 '==== fuzz finding\|ERROR: AddressSanitizer\|runtime error\|ERROR: libFuzzer' "${logs[@]}" | head -20
fi
exit "$status"
