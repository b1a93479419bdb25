#!/usr/bin/env bash
# The time model through ROUTEs (docs/scenes.md, the VRML97 TimeSensor rules): fractions at
# given times, cycles restarted, sensors that ended at load.
# usage: time_model.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- The time model through ROUTEs (docs/scenes.md, VRML97 TimeSensor rules) ----
# fractions SCENE NODE SPAN0 SPAN1 TIME:FRACTION...: the shape's fraction at each --time, and the t
# of its NODE (colour, texture) mapped onto the node's timeSpan.
fractions() {
  local scene="$1" node="$2" s0="$3" s1="$4"
  shift 4
  for tf in "$@"; do
    local t=${tf%%:*} f=${tf#*:}
    jcheck "$(basename "$scene") at --time $t: fraction $f" err \
      "near(j['shapes'][0]['fraction'], $f) and near(j['shapes'][0]['$node']['t'], $s0 + $f * ($s1 - $s0), 1e-6)" \
      -- "$R" "$scene" --stats --time "$t"
  done
}
# Figure 3: a 5 s looping TimeSensor routed to the shape's set_fraction. The end of a cycle gives
# 1.0, not 0.0.
fractions "$P/figure3-colour.wrl" colour -3.1415926 3.1415926 0:0 2:0.4 5:1 9.5:0.9 12.5:0.5
# Figure 2: the shape's own single 5 s cycle, restarted by a 7 s loop's cycleTime routed to its
# startTime.
fractions "$P/figure2-texture.wrl" texture 0 0.4 3:0.6 6:1 9.5:0.5 13:1 15:0.2
# A sensor whose single cycle ended exactly at load (time 0) never sends an event; one that ends
# just after load does (a stopTime before the startTime is ignored); the default stopTime 0, after
# a negative startTime, stops it at load.
printf '#VRML V2.0 utf8\nDEF S FShape { startTime -1 stopTime -2 cycleInterval 1 geometry FGeometry { definition "0.5-x*x-y*y-z*z" } }\n' > "$T/ended.wrl"
jcheck "a cycle that ended at load never ran" err "j['shapes'][0]['fraction'] == 0 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 3
sed -i 's/startTime -1/startTime -0.5/' "$T/ended.wrl"
jcheck "a cycle that ended after load holds 1.0" err "j['shapes'][0]['fraction'] == 1 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 3
jcheck "a cycle running at --time 0.25" err "near(j['shapes'][0]['fraction'], 0.75) and j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 0.25
sed -i 's/ stopTime -2//' "$T/ended.wrl"
jcheck "stopTime 0 after a negative startTime stops the sensor at load" err "j['shapes'][0]['fraction'] == 0 and not j['shapes'][0]['active']" \
  -- "$R" "$T/ended.wrl" --stats --time 0.25
jcheck "--fraction overrides the clock" err "near(j['shapes'][0]['fraction'], 0.3)" \
  -- "$R" "$P/figure3-colour.wrl" --stats --time 9.5 --fraction 0.3

finish time_model
