#!/usr/bin/env bash
# `--backend auto`: the switch visible in --stats, a forced switch in the middle of a job changing no byte.
# usage: auto.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

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

finish auto
