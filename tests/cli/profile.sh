#!/usr/bin/env bash
# fscript profile and fvrml-run --profile on shapes whose cost is known by construction: a union
# where one branch costs ten times the other. Without pruning every point runs it, and the profile
# must say it takes most of the work; with pruning it is needed only near its own small ball, and
# the profile must show its share falling with the points that still run it. Also the picture, the
# JSON in --stats, and bad input.
# usage: profile.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# Lines 8-10 are the heavy branch (about 80 operations), line 7 the light one (7 operations).
cat > "$T/u.wrl" <<'WRL'
#VRML V2.0 utf8
FShape {
  geometry FGeometry {
    resolution [96 96 96]
    bboxSize 2.4 2.4 2.4
    definition "function FRep(x, y, z, t) {
      light = 0.6 - sqrt(x*x + y*y + z*z);
      w = sin(3*x) * cos(5*y) + sin(7*z) * cos(2*x) + sin(4*y) * cos(6*z) + sin(9*x) * sin(8*y) + cos(11*z) * sin(3*y);
      v = cos(3*z) * sin(5*x) + cos(7*y) * sin(2*z) + cos(4*x) * sin(6*y) + cos(9*z) * cos(8*x) + sin(11*y) * cos(3*x);
      heavy = 0.15 - sqrt((x-0.8)*(x-0.8) + (y-0.8)*(y-0.8) + (z-0.8)*(z-0.8)) + 0.01 * (w + v);
      return max(light, heavy);
    }"
  }
}
WRL
# share KEY: the heavy lines' share of KEY (ops, time, runs_at: the most of them) in the JSON report.
cat > "$T/share.py" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
r = r[0] if isinstance(r, list) else r["profile"][0]
heavy = [l for l in r["lines"] if 8 <= l["line"] <= 10]
total = sum(l["ops"] for l in r["lines"])
print(json.dumps({"ops": sum(l["ops"] for l in heavy) / total, "time": sum(l["time"] for l in heavy),
                  "runs_at": max(l["runs_at"] for l in heavy), "light_runs_at": [l["runs_at"] for l in r["lines"] if l["line"] == 7][0],
                  "regions": r["regions"], "decided": r["decided"], "whole": r["whole_operations"],
                  "tape_min": r["tape_min"], "tape_max": r["tape_max"]}))
PY
for b in vm sse; do
  "$F" profile "$T/u.wrl" --backend $b --json --no-prune > "$T/dense.json" || fail "profile --no-prune on $b"
  "$F" profile "$T/u.wrl" --backend $b --json > "$T/pruned.json" || fail "profile on $b"
  dense=$(python3 "$T/share.py" "$T/dense.json") pruned=$(python3 "$T/share.py" "$T/pruned.json")
  # Time shares are measured: on a loaded machine (ctest -j beside other work) one run's clocks can
  # blur them, so the pruned run is taken again, up to twice more, until its time share has fallen.
  for _ in 1 2; do
    python3 -c "import json, sys; sys.exit(json.loads(sys.argv[2])['time'] < json.loads(sys.argv[1])['time'] - 0.2)" \
      "$dense" "$pruned" || break
    "$F" profile "$T/u.wrl" --backend $b --json > "$T/pruned.json" || fail "profile on $b"
    pruned=$(python3 "$T/share.py" "$T/pruned.json")
  done
  n=$((n + 1))
  python3 - "$dense" "$pruned" <<'PY' || fail "profile on $b: dense $dense, pruned $pruned"
import json, sys
d, p = json.loads(sys.argv[1]), json.loads(sys.argv[2])
# Unpruned, every value runs both branches: the heavy one is ten times the light one.
assert d["ops"] > 0.85, "the heavy branch is most of the work without pruning"
assert d["runs_at"] == 1.0 and d["light_runs_at"] == 1.0, "every point runs every line without pruning"
assert d["time"] > 0.6, "and most of the time"
assert d["regions"] == 0 and d["decided"] == 0
# Pruned, the heavy branch is needed only near its own ball: a small share of the points run it.
assert p["runs_at"] < 0.3, "pruning drops the heavy branch from most points"
assert p["light_runs_at"] > 0.7
assert p["ops"] < d["ops"] - 0.1 and p["time"] < d["time"] - 0.2, "its share falls"
assert p["regions"] > 0 and p["decided"] > 0 and p["tape_min"] <= p["tape_max"] < p["whole"], "regions drop the branch"
PY
done
check "profile text: the heavy line first, the pruning figures" 0 \
  "pruning: [0-9]+ octree regions decided.*regions with a tape of their own" -- "$F" profile "$T/u.wrl"
"$F" profile "$T/u.wrl" --no-prune > "$T/dense.txt"
n=$((n + 1))
sed -n 4p "$T/dense.txt" | grep -qE "^ +(8|9) " || { fail "the costliest line first without pruning"; cat "$T/dense.txt"; }
# The picture: two panels of 96 columns, doubled to 192 pixels, 4 pixels apart; the right panel (the
# mean tape length) is brighter at the heavy ball's columns (x, y = 0.8) than at the light ball's edge.
check "profile --picture" 0 "cost picture: .*/u.png" -- "$F" profile "$T/u.wrl" --picture "$T/u.png"
n=$((n + 1))
python3 - "$SRC/tests/clients" "$T/u.png" <<'PY' || fail "profile picture: size and brightness"
import sys
sys.path.insert(0, sys.argv[1])
from png_probe import read_png
w, h, bpp, rows = read_png(sys.argv[2])
assert (w, h) == (2 * 192 + 4, 192), (w, h)
def right(x, y):  # the right panel's pixel at scene (x, y) in [-1.2, 1.2]
    i, j = int((x + 1.2) / 2.4 * 192), int((1.2 - y) / 2.4 * 192)
    return sum(rows[j][(196 + i) * bpp:(196 + i) * bpp + 3])
assert right(0.8, 0.8) > right(-0.55, 0.0) + 100, (right(0.8, 0.8), right(-0.55, 0.0))
PY
# fvrml-run --profile: the same report on standard error, the JSON in --stats.
check "fvrml-run --profile" 0 "regions with a tape of their own" -- "$R" "$T/u.wrl" -o "$T/u.glb" --profile
"$R" "$T/u.wrl" -o "$T/u.ply" --profile --stats 2> "$T/stats.txt" > /dev/null
tail -1 "$T/stats.txt" > "$T/stats.json"
n=$((n + 1))
python3 "$T/share.py" "$T/stats.json" > /dev/null || fail "fvrml-run --profile --stats: the profile in the JSON"
# Profiling counts what the mesher does without changing it: the same mesh, byte for byte.
"$R" "$T/u.wrl" -o "$T/plain.ply" 2> /dev/null
n=$((n + 1))
cmp -s "$T/plain.ply" "$T/u.ply" || fail "fvrml-run --profile: the same mesh as without it"
check "fvrml-run --profile-picture" 0 "cost picture" -- "$R" "$T/u.wrl" -o "$T/u2.glb" --profile-picture "$T/v.png"
n=$((n + 1))
[ -s "$T/v.png" ] || fail "fvrml-run --profile-picture writes the picture"
check "fvrml-run --profile of a PNG meshes it" 0 "regions with a tape of their own" -- \
  "$R" "$T/u.wrl" -o "$T/u.png" --profile --size 64
check "fvrml-run --profile with --serve is refused" 2 "not with --serve" -- "$R" "$T/u.wrl" --profile --serve
# An FTransform: its children's scripts run whole at every point (no region's tape), each line charged.
cat > "$T/group.wrl" <<'WRL'
#VRML V2.0 utf8
FTransform { operation "union" children [
  FShape { geometry FGeometry { resolution [48 48 48] bboxSize 2 2 2 definition "function FRep(x, y, z, t) {
    ball = 0.5 - sqrt(x*x + y*y + z*z);
    return ball;
  }" } }
  FShape { geometry FGeometry { resolution [48 48 48] bboxSize 2 2 2 definition "function FRep(x, y, z, t) {
    g = sin(5*x)*cos(5*y) + sin(5*y)*cos(5*z) + sin(5*z)*cos(5*x);
    return min(g, 0.8 - x*x - y*y - z*z);
  }" } }
] }
WRL
jcheck "profile of an FTransform: both children's lines, every point running them" out "
(lambda l: j[0]['node'] == 'FTransform' and j[0]['mapped'] and set(l) == {4, 8, 9} and
 all(c['runs_at'] == 1.0 for c in l.values()) and l[8]['ops'] > l[4]['ops'] and l[4]['ops'] == l[9]['ops'])(
 {c['line']: c for c in j[0]['lines']})" \
  -- "$F" profile "$T/group.wrl" --json
# Bad input: clear messages, exit 1.
check "profile: a parametric scene has nothing to profile" 1 "no implicit shape to profile" -- \
  "$F" profile "$SRC/examples/paper/figure1-morphing.wrl"
check "profile: a script error at its place" 1 "bad.fs:2:14: error" -- bash -c \
  "printf 'function FRep(x, y, z, t) {\n  return 1 - qq;\n}\n' > '$T/bad.fs'; '$F' profile '$T/bad.fs'"
check "profile: a runtime error at its line, under the budget flags" 1 \
  "spin.fs:3:3: error: loop iteration budget exceeded: more than 100 iterations" -- bash -c \
  "printf 'function FRep(x, y, z, t) {\n  var k = 0;\n  while (k < 1e9) { k = k + 1; }\n  return 1 - x*x;\n}\n' > '$T/spin.fs'; '$F' --max-loop-iterations 100 profile '$T/spin.fs'"
check "profile: a missing file" 1 "error" -- "$F" profile "$T/none.fs"
check "profile: a picture that cannot be written" 1 "error" -- "$F" profile "$T/u.wrl" --picture "$T/no/dir/p.png"
finish profile
